// The demo's Dear ImGui panel (everything the keyboard and mouse do, plus the stage-time graph) and the help
// overlay with the shortcuts.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "app/demo/demo_app.h"
#include "app/demo/live_scene.h"
#include "render/sixway.h"

#ifndef SIXWAY_SCENES_DIR
#error "SIXWAY_SCENES_DIR: the shipped scenes, listed in the panel"
#endif

namespace sixway::app::demo {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> shippedScenes() {
  std::vector<fs::path> scenes;
  std::error_code ignored;
  for (const auto& entry : fs::directory_iterator(SIXWAY_SCENES_DIR, ignored))
    if (entry.path().extension() == ".json") scenes.push_back(entry.path());
  std::sort(scenes.begin(), scenes.end());
  return scenes;
}

// Runs an action of the panel; its error goes to the status line.
template <typename Action>
void attempt(Demo& demo, Action action, void (Demo::*say)(std::string, bool)) {
  try {
    action();
  } catch (const std::exception& e) {
    (demo.*say)(e.what(), true);
  }
}

}  // namespace

void Demo::drawPanel() {
  const auto act = [&](auto action) { attempt(*this, action, &Demo::say); };
  ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(360, 0), ImGuiCond_FirstUseEver);
  ImGui::Begin("sixway");
  ImGui::Text("%s", context_->properties().deviceName);
  ImGui::Text("%.1f frames/s   frame %d   t = %.2f s", history_.framesPerSecond(), live_->frame(),
              live_->seconds());
  if (!status_.empty())
    ImGui::TextColored(statusIsError_ ? ImVec4(1, 0.4f, 0.4f, 1) : ImVec4(0.6f, 1, 0.6f, 1), "%s",
                       status_.c_str());

  if (ImGui::CollapsingHeader("Simulation", ImGuiTreeNodeFlags_DefaultOpen)) {
    if (ImGui::BeginCombo("scene", scenePath_.filename().string().c_str())) {
      for (const fs::path& scene : shippedScenes())
        if (ImGui::Selectable(scene.filename().string().c_str(), scene == scenePath_))
          act([&] { loadScene(scene); });
      ImGui::EndCombo();
    }
    if (ImGui::Button(paused_ ? "resume (space)" : "pause (space)")) paused_ = !paused_;
    ImGui::SameLine();
    if (ImGui::Button("step (N)")) step();
    ImGui::SameLine();
    if (ImGui::Button("reset (R)")) act([&] { reset(); });
    float inlet = live_->inletStrength();
    if (ImGui::SliderFloat("inlet strength", &inlet, 0.0f, live_->maxInletStrength(), "%.2f"))
      act([&] { setInletStrength(inlet); });
    if (live_->obstacleCount() > 0) {
      int selected = int(selectedObstacle_);
      if (ImGui::SliderInt("obstacle (Tab)", &selected, 0, int(live_->obstacleCount()) - 1))
        selectedObstacle_ = size_t(selected);
      glm::vec3 p = live_->obstaclePosition(selectedObstacle_);
      if (ImGui::DragFloat3("drag to (ctrl+drag)", &p.x, 0.01f))
        act([&] { dragObstacle(selectedObstacle_, p); });
    }
  }

  if (ImGui::CollapsingHeader("View", ImGuiTreeNodeFlags_DefaultOpen)) {
    int mode = int(mode_);
    const modes::RenderMode modes[] = {modes::RenderMode::Neural, modes::RenderMode::Reference,
                                       modes::RenderMode::Traditional, modes::RenderMode::Guide,
                                       modes::RenderMode::GuideLit};
    for (int i = 0; i < 5; ++i) {
      char label[32];
      std::snprintf(label, sizeof(label), "%s (%d)", modes::renderModeName(modes[i]), i + 1);
      if (ImGui::RadioButton(label, mode == int(modes[i]))) act([&] { setMode(modes[i]); });
      if (i % 3 != 2 && i != 4) ImGui::SameLine();
    }
    const auto& channels = render::sixWayChannelNames();
    const std::string current = view_ == ViewKind::Frame   ? "frame"
                                : view_ == ViewKind::Guide ? "guiding map"
                                                           : "lightmap: " + channels[size_t(channel_)];
    if (ImGui::BeginCombo("shows (F, G, L)", current.c_str())) {
      if (ImGui::Selectable("frame", view_ == ViewKind::Frame)) setView(ViewKind::Frame);
      if (ImGui::Selectable("guiding map", view_ == ViewKind::Guide)) setView(ViewKind::Guide);
      for (int c = 0; c < render::kSixWayChannels; ++c)
        if (ImGui::Selectable(("lightmap: " + channels[size_t(c)]).c_str(),
                              view_ == ViewKind::Channel && channel_ == c))
          setView(ViewKind::Channel, c);
      ImGui::EndCombo();
    }
    bool split = split_;
    if (ImGui::Checkbox("neural | reference (C)", &split)) setSplit(split);
    if (split_ && splitPsnr_) {
      ImGui::SameLine();
      ImGui::Text("PSNR %.2f dB", *splitPsnr_);
    }
    ImGui::SliderFloat("exposure (+/-)", &exposure_, 0.05f, 20.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
    ImGui::Checkbox("obstacle shadows (S)", &shadows_);
    ImGui::SameLine();
    ImGui::Checkbox("vsync (V)", &vsync_);
    if (ImGui::Button("screenshot (P)")) screenshotRequested_ = true;
    ImGui::SameLine();
    if (ImGui::Button("with panel (shift+P)")) act([&] { windowScreenshot(nextScreenshotPath()); });
    ImGui::SameLine();
    if (ImGui::Button(recording_ ? "stop recording (O)" : "record (O)"))
      act([&] { recording_ ? stopRecording() : startRecording(nextRecordingPath()); });
  }

  if (ImGui::CollapsingHeader("Lights", ImGuiTreeNodeFlags_DefaultOpen)) {
    for (size_t i = 0; i < lights_.size(); ++i) {
      scene::Light& light = lights_[i];
      ImGui::PushID(int(i));
      const bool point = std::holds_alternative<scene::PointLight>(light.source);
      char title[48];
      std::snprintf(title, sizeof(title), "%zu: %s%s", i, point ? "point" : "directional",
                    i == selectedLight_ ? "  (selected)" : "");
      if (ImGui::TreeNode(title)) {
        if (ImGui::IsItemClicked()) selectedLight_ = i;
        if (point) {
          ImGui::DragFloat3("position (shift+drag)", &std::get<scene::PointLight>(light.source).position.x,
                            0.01f);
        } else {
          glm::vec3 direction = std::get<scene::DirectionalLight>(light.source).direction;
          if (ImGui::DragFloat3("toward the light", &direction.x, 0.01f))
            act([&] { placeLight(i, direction); });
        }
        ImGui::ColorEdit3("colour", &light.color.x);
        ImGui::DragFloat("intensity", &light.intensity, 0.02f, 0.0f, 100.0f);
        ImGui::Checkbox("casts obstacle shadows", &light.shadows);
        if (ImGui::Button("remove")) act([&] { removeLight(i); });
        ImGui::TreePop();
      }
      ImGui::PopID();
    }
    if (ImGui::Button("add point light (A)"))
      act([&] {
        scene::Light light;
        light.source = scene::PointLight{camera_.target + glm::vec3(0.3f)};
        addLight(light);
      });
    ImGui::SameLine();
    if (ImGui::Button("add directional"))
      act([&] {
        scene::Light light;
        light.source = scene::DirectionalLight{glm::normalize(glm::vec3(0.4f, 1.0f, 0.3f))};
        addLight(light);
      });
  }

  if (ImGui::CollapsingHeader("GPU time per stage (ms)", ImGuiTreeNodeFlags_DefaultOpen) &&
      !history_.empty()) {
    const std::vector<float> totals = history_.totals();
    const float top = std::max(1.0f, *std::max_element(totals.begin(), totals.end()));
    char overlay[48];
    std::snprintf(overlay, sizeof(overlay), "%.2f ms", history_.last().total());
    ImGui::PlotLines("total", totals.data(), int(totals.size()), 0, overlay, 0.0f, top, ImVec2(0, 40));
    for (int s = 0; s < int(Stage::Count); ++s) {
      const std::vector<float> series = history_.series(Stage(s));
      std::snprintf(overlay, sizeof(overlay), "%.2f ms", series.back());
      ImGui::PlotLines(stageName(Stage(s)), series.data(), int(series.size()), 0, overlay, 0.0f, top,
                       ImVec2(0, 24));
    }
  }
  ImGui::End();
}

void Demo::drawHelp() {
  const ImGuiViewport* viewport = ImGui::GetMainViewport();
  ImGui::SetNextWindowPos(ImVec2(viewport->WorkSize.x - 10, 10), ImGuiCond_Always, ImVec2(1, 0));
  ImGui::SetNextWindowBgAlpha(0.6f);
  ImGui::Begin("help (H)", &showHelp_, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoMove);
  static const char* lines[][2] = {{"left drag", "orbit the camera"},
                                   {"right/middle drag", "pan"},
                                   {"wheel", "zoom"},
                                   {"ctrl + left drag", "drag the selected obstacle"},
                                   {"shift + left drag", "drag the selected point light"},
                                   {"Tab / ]", "select the next obstacle / light"},
                                   {"1 2 3 4 5", "neural, reference, traditional, guide, guide-lit"},
                                   {"F / G / L", "frame / guiding map / next lightmap channel"},
                                   {"C", "split screen neural | reference (PSNR)"},
                                   {"space / N / R", "pause / step / reset the simulation"},
                                   {"A / Delete", "add a point light / remove the selected light"},
                                   {"S / V", "obstacle shadows / vsync"},
                                   {"+ / -", "exposure"},
                                   {"P / shift+P / O", "screenshot / with the panel / record frames"},
                                   {"H / Esc", "this help / quit"}};
  if (ImGui::BeginTable("keys", 2)) {
    for (const auto& line : lines) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(line[0]);
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(line[1]);
    }
    ImGui::EndTable();
  }
  ImGui::End();
}

}  // namespace sixway::app::demo
