// sixway-demo: the interactive window (docs/demo.md). Every failure ends in one line on stderr and exit 1.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>

#include "app/demo/demo_app.h"
#include "app/options.h"
#include "app/shipped_weights.h"

int main(int argc, char** argv) {
  namespace demo = sixway::app::demo;
  CLI::App app("sixway-demo: live smoke lit by neural six-way lightmaps, in a window");
  demo::DemoOptions options;
  options.scene = SIXWAY_SCENES_DIR "/plume.json";
  std::string script;
  bool noVsync = false;
  sixway::app::CommonOptions common;
  app.add_option("--scene", options.scene, "Scene JSON (default assets/scenes/plume.json)");
  app.add_option("--script", script, "Run the commands of this file, then quit (docs/demo.md, Scripts)");
  app.add_option("--weights", options.weights, sixway::app::kWeightsHelp);
  app.add_flag("--fp16", options.fp16, "Neural: fp16 feature maps");
  app.add_flag("--no-vsync", noVsync, "Present without waiting for the display");
  app.add_option("--width", options.width, "Window width")->check(CLI::Range(64, 8192));
  app.add_option("--height", options.height, "Window height")->check(CLI::Range(64, 8192));
  app.add_option("--screenshots", options.screenshots,
                 "Directory of screenshots and recordings (default out/screenshots)");
  common.addTo(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);              // --help
    std::fprintf(stderr, "sixway-demo: error: %s\n", e.what());  // one line, CLI11's exit code
    return e.get_exit_code();
  }
  try {
    if (!script.empty()) options.script = script;
    options.weights = sixway::app::resolveWeights(options.weights);
    options.vsync = !noVsync;
    options.device = common.deviceOptions();
    demo::Demo demo(options);
    return demo.run();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sixway-demo: error: %s\n", e.what());
    return 1;
  }
}
