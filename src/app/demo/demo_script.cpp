#include "app/demo/demo_script.h"

#include <array>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "io/error.h"
#include "io/file_access.h"

namespace sixway::app::demo {
namespace {

// Per command: the argument patterns it accepts; "#" a number, "*" any word, anything else that word.
const std::map<std::string, std::vector<std::vector<std::string>>>& grammar() {
  static const std::map<std::string, std::vector<std::vector<std::string>>> g = {
      {"wait", {{"#"}}},
      {"orbit", {{"#", "#"}}},
      {"zoom", {{"#"}}},
      {"pan", {{"#", "#"}}},
      {"mode", {{"*"}}},
      {"view", {{"*"}}},
      {"split", {{"on"}, {"off"}}},
      {"shadows", {{"on"}, {"off"}}},
      {"light",
       {{"add", "directional", "#", "#", "#"},
        {"add", "point", "#", "#", "#"},
        {"move", "#", "#", "#", "#"},
        {"color", "#", "#", "#", "#"},
        {"intensity", "#", "#"},
        {"remove", "#"}}},
      {"obstacle", {{"#", "#", "#", "#"}}},
      {"pause", {{}}},
      {"resume", {{}}},
      {"step", {{}}},
      {"reset", {{}}},
      {"inlet", {{"#"}}},
      {"exposure", {{"#"}}},
      {"vsync", {{"on"}, {"off"}}},
      {"resize", {{"#", "#"}}},
      {"screenshot", {{"*"}, {"*", "window"}}},
      {"record", {{"stop"}, {"*"}}},
      {"scene", {{"*"}}},
      {"quit", {{}}},
  };
  return g;
}

constexpr float kMaxScriptNumber = 1e6f;
constexpr int kMaxWaitFrames = 1000000;  // 4.6 hours at 60 frames per second

// A number a float holds (1e20 is one; 1e39 and "nan" are not, and fail the pattern).
bool isNumber(const std::string& word) {
  std::istringstream in(word);
  float value = 0;
  in >> value;
  return !in.fail() && in.eof();
}

bool matches(const std::vector<std::string>& words, const std::vector<std::string>& pattern) {
  if (words.size() != pattern.size()) return false;
  for (size_t i = 0; i < words.size(); ++i) {
    if (pattern[i] == "#" && !isNumber(words[i])) return false;
    if (pattern[i] != "#" && pattern[i] != "*" && pattern[i] != words[i]) return false;
  }
  return true;
}

std::string usage(const std::string& name) {
  std::string text;
  for (const auto& pattern : grammar().at(name)) {
    text += text.empty() ? "" : " | ";
    text += name;
    for (const std::string& p : pattern) text += " " + (p == "#" ? std::string("N") : p == "*" ? "WORD" : p);
  }
  return text;
}

}  // namespace

float ScriptCommand::number(size_t i) const {
  return std::stof(words.at(i));
}

std::vector<ScriptCommand> loadScript(const std::filesystem::path& path) {
  io::requireRegularFile(path);
  std::ifstream in(path);
  std::vector<ScriptCommand> commands;
  std::string text;
  for (int line = 1; std::getline(in, text); ++line) {
    if (const size_t hash = text.find('#'); hash != std::string::npos) text.resize(hash);
    std::istringstream words(text);
    ScriptCommand c;
    c.line = line;
    if (!(words >> c.name)) continue;
    for (std::string w; words >> w;) c.words.push_back(w);
    const auto known = grammar().find(c.name);
    const std::string where = "line " + std::to_string(line) + ": ";
    if (known == grammar().end())
      throw io::InputError(path.string(), where + "unknown command \"" + c.name + "\"");
    bool ok = false;
    for (const auto& pattern : known->second) ok = ok || matches(c.words, pattern);
    if (!ok) throw io::InputError(path.string(), where + "expected " + usage(c.name));
    // Numbers that a frame cannot use (a wait of 1e20 frames, a move to 1e30 m) are typos: one line each.
    for (const std::string& w : c.words)
      if (isNumber(w) && !(std::abs(std::stof(w)) <= kMaxScriptNumber))
        throw io::InputError(path.string(), where + "numbers must be within ±1e6 (got " + w + ")");
    if (c.name == "wait" && (c.number(0) < 1 || c.number(0) > kMaxWaitFrames))
      throw io::InputError(path.string(), where + "wait takes 1 to " + std::to_string(kMaxWaitFrames) +
                                              " frames (got " + c.words[0] + ")");
    commands.push_back(std::move(c));
  }
  return commands;
}

std::vector<ScriptCommand> ScriptRunner::beforeFrame() {
  std::vector<ScriptCommand> due;
  while (waiting_ == 0 && next_ < commands_.size()) {
    const ScriptCommand& c = commands_[next_++];
    if (c.name == "wait")
      waiting_ = int(c.number(0));
    else
      due.push_back(c);
  }
  if (waiting_ > 0) --waiting_;
  return due;
}

}  // namespace sixway::app::demo
