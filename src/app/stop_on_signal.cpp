#include "app/stop_on_signal.h"

#include <signal.h>
#include <unistd.h>

#include <atomic>

namespace sixway::app {
namespace {

constexpr int kSignals[] = {SIGINT, SIGTERM};
std::atomic<int> received{0};
struct sigaction previous[2];

void onSignal(int signal) {
  received.store(signal);
  static const char note[] = "\nsixway: stopping after this frame (signal again to stop at once)\n";
  [[maybe_unused]] const ssize_t written = ::write(STDERR_FILENO, note, sizeof(note) - 1);
}

}  // namespace

const char* Stopped::what() const noexcept {
  return signal_ == SIGINT ? "stopped by SIGINT" : signal_ == SIGTERM ? "stopped by SIGTERM" : "stopped";
}

StopOnSignal::StopOnSignal() {
  received.store(0);
  struct sigaction action {};
  action.sa_handler = onSignal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART | SA_RESETHAND;  // the second signal finds the default action: the end
  for (int i = 0; i < 2; ++i) {
    sigaction(kSignals[i], nullptr, &previous[i]);
    if (previous[i].sa_handler != SIG_IGN) sigaction(kSignals[i], &action, nullptr);
  }
}

StopOnSignal::~StopOnSignal() {
  for (int i = 0; i < 2; ++i) sigaction(kSignals[i], &previous[i], nullptr);
}

void throwIfStopped() {
  if (const int signal = received.load()) throw Stopped(signal);
}

}  // namespace sixway::app
