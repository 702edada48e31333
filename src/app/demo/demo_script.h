#pragma once
// A scripted session of the demo (`sixway-demo --script FILE`): one command per line, run in order; `wait N`
// lets N frames go by. The commands are the ones a user gives with the mouse, the keyboard and the panel
// (docs/demo.md lists them). A script is checked whole when it is loaded, so a typo fails before the window
// opens.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace sixway::app::demo {

struct ScriptCommand {
  int line = 0;                    // in the file, from 1
  std::string name;                // e.g. "orbit"
  std::vector<std::string> words;  // the arguments
  // The argument `i` as a number (checked when the script was loaded).
  float number(size_t i) const;
};

// Throws io::InputError naming the file and the line for an unknown command or wrong arguments.
std::vector<ScriptCommand> loadScript(const std::filesystem::path& path);

// Hands out the commands up to the next `wait` and counts the frames a wait lets go by.
class ScriptRunner {
 public:
  explicit ScriptRunner(std::vector<ScriptCommand> commands) : commands_(std::move(commands)) {}
  // The commands to run before this frame (none while waiting); the runner then counts this frame.
  std::vector<ScriptCommand> beforeFrame();
  bool finished() const { return next_ >= commands_.size() && waiting_ == 0; }

 private:
  std::vector<ScriptCommand> commands_;
  size_t next_ = 0;
  int waiting_ = 0;  // frames still to let go by
};

}  // namespace sixway::app::demo
