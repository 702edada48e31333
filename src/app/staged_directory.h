#pragma once
// An output directory written as a whole (`render --out`, `sim --vdb-out`, `bake --out`): a run writes its
// files into a hidden staging directory inside it (.<command>.<pid>.partial) and commit() moves them onto
// their names at the end, so a run interrupted or failed half-way leaves an earlier run's files whole, and a
// finished run leaves only its own.
#include <filesystem>
#include <functional>
#include <set>
#include <string>
#include <vector>

namespace sixway::app {

class StagedDirectory {
 public:
  // Whether a path relative to the directory ("frame_0001.png", "frames/frame_0001.exr") is a file the
  // command writes: the outputs an earlier run may have left.
  using OutputNames = std::function<bool(const std::string&)>;
  // The folders inside the directory that the command writes files into (bake's "frames").
  using OutputFolders = std::vector<std::string>;

  // Claims `directory` (io::claimOutputDirectory: without `force` this run must be the one that makes it)
  // and makes the staging directory `.<command>.<pid>.partial` in it, with `folders` inside. Throws
  // io::InputError naming the directory.
  StagedDirectory(std::filesystem::path directory, const std::string& command, bool force,
                  OutputNames outputNames, OutputFolders folders = {});
  // Unless committed: removes the staging directory, and the directory itself when this run made it and
  // nothing else has appeared there.
  ~StagedDirectory();
  StagedDirectory(const StagedDirectory&) = delete;
  StagedDirectory& operator=(const StagedDirectory&) = delete;

  const std::filesystem::path& directory() const { return directory_; }
  // The staging directory: what the run writes there, commit() moves into `directory()`.
  const std::filesystem::path& staging() const { return staging_; }
  // Where the run writes the file that commit() moves onto `directory()/name`.
  std::filesystem::path stagedPath(const std::string& name) const { return staging_ / name; }
  // Runs `write`; an io::InputError it throws names the file under its final name, not the staging
  // directory.
  void underFinalNames(const std::function<void()>& write) const;
  // All or nothing: first checks that no output name in the directory is a directory or special file, and
  // that each output folder is a directory (throws io::InputError naming it, before any change); then moves
  // every staged file onto its name and removes the outputs of an earlier run that this one did not replace.
  // Other files are never touched.
  void commit();

  // The checks before any work: a directory that holds nothing but the staging directories of runs that were
  // killed (their processes have ended) is removed first, as if it did not exist, since such a run wrote
  // nothing; then io::requireWritableDirectory, and no output name there may be a directory or special file
  // (each output folder must be a directory). Throws io::InputError naming the first problem.
  static void requireWritable(const std::filesystem::path& directory, bool force,
                              const OutputNames& outputNames, const OutputFolders& folders = {});

 private:
  static void requireReplaceableOutputs(const std::filesystem::path& directory,
                                        const OutputNames& outputNames, const OutputFolders& folders);
  // Returns the names moved in, relative to the directory.
  std::set<std::string> moveStagedFilesIn() const;
  void removeEarlierOutputsNotReplaced(const std::set<std::string>& replaced) const;
  void removeStagingOfKilledRuns() const;

  std::filesystem::path directory_;
  std::filesystem::path staging_;
  std::string command_;
  OutputNames outputNames_;
  OutputFolders folders_;
  bool committed_ = false;
  bool madeDirectory_ = false;
};

}  // namespace sixway::app
