#pragma once
// The progress of `sixway dataset` on the terminal: one line redrawn in place (\r) with a bar, the sequence
// and frame, the elapsed time and an ETA when stdout is a terminal; plain lines (each tenth of the work and
// each finished sequence) when it is not, so that a batch job's log stays readable.
#include <chrono>
#include <cstdio>
#include <string>

namespace sixway::app {

class DatasetProgress {
 public:
  // `totalFrames`: the frames that all of this worker's sequences simulate.
  DatasetProgress(int sequences, long totalFrames);

  // Frame `frame` of `frames` of the sequence numbered `sequence` (the `ordinal`-th of this worker's) is
  // done.
  void frameDone(int sequence, int ordinal, int frame, int frames);
  // More frames to do (a sequence simulated again).
  void addFrames(long frames) { totalFrames_ += frames; }
  // A line of its own, e.g. "wrote shard_00003.safetensors", that the bar does not overwrite.
  void note(const std::string& line);
  // Ends the bar's line, e.g. before an error message.
  void endLine();
  double elapsedSeconds() const;

 private:
  std::string status(int sequence, int ordinal, int frame, int frames) const;

  int sequences_;
  long totalFrames_, doneFrames_ = 0;
  int lastTenth_ = 0;
  bool terminal_;
  bool barShown_ = false;
  std::chrono::steady_clock::time_point start_;
};

// "1:05:03", "4:07"
std::string formatDuration(double seconds);

}  // namespace sixway::app
