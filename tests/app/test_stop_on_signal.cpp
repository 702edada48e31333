// app::StopOnSignal: SIGINT and SIGTERM become a Stopped exception at the command's next check, once; a
// signal the process was started with ignored stays ignored; the handlers are restored afterwards.
#include "app/stop_on_signal.h"

#include <gtest/gtest.h>
#include <signal.h>

namespace sixway::test {
namespace {

void (*handlerOf(int signal))(int) {
  struct sigaction action {};
  sigaction(signal, nullptr, &action);
  return action.sa_handler;
}

int stoppedBy() {
  try {
    app::throwIfStopped();
  } catch (const app::Stopped& e) {
    return e.signal();
  }
  return 0;
}

TEST(StopOnSignalTest, ASignalStopsAtTheNextCheck) {
  for (const int signal : {SIGINT, SIGTERM}) {
    {
      const app::StopOnSignal stop;
      EXPECT_EQ(stoppedBy(), 0);
      raise(signal);
      EXPECT_EQ(stoppedBy(), signal);
      EXPECT_EQ(handlerOf(signal), SIG_DFL);  // a second signal ends the process
    }
    EXPECT_EQ(handlerOf(signal), SIG_DFL);
  }
}

TEST(StopOnSignalTest, AnIgnoredSignalStaysIgnored) {
  signal(SIGINT, SIG_IGN);
  {
    const app::StopOnSignal stop;
    EXPECT_EQ(handlerOf(SIGINT), SIG_IGN);
    raise(SIGINT);
    EXPECT_EQ(stoppedBy(), 0);
  }
  EXPECT_EQ(handlerOf(SIGINT), SIG_IGN);
  signal(SIGINT, SIG_DFL);
}

TEST(StopOnSignalTest, EachRunStartsAfresh) {
  {
    const app::StopOnSignal stop;
    raise(SIGTERM);
  }
  const app::StopOnSignal stop;
  EXPECT_EQ(stoppedBy(), 0);
}

}  // namespace
}  // namespace sixway::test
