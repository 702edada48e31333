#pragma once
// An output directory written as a whole (`render --out`, `sim --vdb-out`): a run writes its files into a
// hidden staging directory inside it (.<command>.<pid>.partial) and commit() moves them onto their names at
// the end, so a run interrupted or failed half-way leaves an earlier run's files whole, and a finished run
// leaves only its own.
#include <filesystem>
#include <functional>
#include <set>
#include <string>

namespace sixway::app {

class StagedDirectory {
 public:
  // Whether a file name is one the command writes: the outputs an earlier run may have left.
  using OutputNames = std::function<bool(const std::string&)>;

  // Claims `directory` (io::claimOutputDirectory: without `force` this run must be the one that makes it)
  // and makes the staging directory `.<command>.<pid>.partial` in it. Throws io::InputError naming the
  // directory.
  StagedDirectory(std::filesystem::path directory, const std::string& command, bool force,
                  OutputNames outputNames);
  // Unless committed: removes the staging directory, and the directory itself when this run made it.
  ~StagedDirectory();
  StagedDirectory(const StagedDirectory&) = delete;
  StagedDirectory& operator=(const StagedDirectory&) = delete;

  const std::filesystem::path& directory() const { return directory_; }
  // Where the run writes the file that commit() moves onto `directory()/name`.
  std::filesystem::path stagedPath(const std::string& name) const { return staging_ / name; }
  // Runs `write`; an io::InputError it throws names the file under its final name, not the staging
  // directory.
  void underFinalNames(const std::function<void()>& write) const;
  // All or nothing: first checks that no output name in the directory is a directory or special file
  // (throws io::InputError naming it, before any change); then moves every staged file onto its name and
  // removes the outputs of an earlier run that this one did not replace. Other files are never touched.
  void commit();

  // Throws io::InputError naming the first entry of `directory` whose name `outputNames` accepts and that is
  // a directory or special file: a run would have to replace or remove it. Nothing when `directory` does not
  // exist.
  static void requireReplaceableOutputs(const std::filesystem::path& directory,
                                        const OutputNames& outputNames);

 private:
  // Returns the names moved in.
  std::set<std::string> moveStagedFilesIn() const;
  void removeEarlierOutputsNotReplaced(const std::set<std::string>& replaced) const;
  void removeStagingOfKilledRuns() const;

  std::filesystem::path directory_;
  std::filesystem::path staging_;
  std::string command_;
  OutputNames outputNames_;
  bool committed_ = false;
  bool madeDirectory_ = false;
};

}  // namespace sixway::app
