#pragma once
// Ctrl-C (SIGINT) and SIGTERM during a command that writes outputs: the signal only sets a flag, and the
// command stops at its next frame by throwing Stopped, so that its staged outputs, temporary files and an
// output directory it made are removed on the way out, as for any failure. A second signal ends the process
// at once (the next run removes what that leaves: StagedDirectory, io::removePartialsOfEndedRuns).
#include <exception>

namespace sixway::app {

// Thrown by throwIfStopped; main() ends the process by the same signal once the stack is unwound.
class Stopped : public std::exception {
 public:
  explicit Stopped(int signal) : signal_(signal) {}
  const char* what() const noexcept override;  // "stopped by SIGINT"
  int signal() const { return signal_; }

 private:
  int signal_;
};

// While one lives (one at a time), SIGINT and SIGTERM ask the command to stop instead of ending the process.
// A signal the process started with ignored (a background job of a shell without job control, nohup) stays
// ignored.
class StopOnSignal {
 public:
  StopOnSignal();
  ~StopOnSignal();  // restores the handlers it replaced
  StopOnSignal(const StopOnSignal&) = delete;
  StopOnSignal& operator=(const StopOnSignal&) = delete;
};

// Throws Stopped once SIGINT or SIGTERM has arrived under a StopOnSignal. Commands call it between frames.
void throwIfStopped();

}  // namespace sixway::app
