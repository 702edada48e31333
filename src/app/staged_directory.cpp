#include "app/staged_directory.h"

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <fstream>
#include <regex>
#include <set>
#include <vector>

#include "io/error.h"
#include "io/file_access.h"
#include "io/report.h"

namespace sixway::app {
namespace {

namespace fs = std::filesystem;

// Whether process `pid` has ended: it no longer exists, or it is a zombie (it has exited and only its exit
// status waits for its parent; a parent that killed it on a timeout may never collect it).
bool processEnded(long pid) {
  if (pid <= 0) return false;
  if (::kill(pid_t(pid), 0) != 0) return errno == ESRCH;
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  std::getline(stat, line);
  const size_t command = line.rfind(')');  // the state follows the command name, which may hold spaces
  return command != std::string::npos && line.compare(command, 3, ") Z") == 0;
}

std::set<std::string> namesIn(const fs::path& directory) {
  std::set<std::string> names;
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(directory, error)) names.insert(entry.path().filename());
  return names;
}

}  // namespace

StagedDirectory::StagedDirectory(fs::path directory, const std::string& command, bool force,
                                 OutputNames outputNames)
    : directory_(std::move(directory)), command_(command), outputNames_(std::move(outputNames)) {
  staging_ = directory_ / ("." + command_ + "." + std::to_string(getpid()) + ".partial");
  madeDirectory_ = io::claimOutputDirectory(directory_, force);
  std::error_code error;
  fs::remove_all(staging_, error);  // left by a killed run of a process with this id
  if (!error) fs::create_directory(staging_, error);
  if (error)
    throw io::InputError(directory_.string(), "cannot create the output directory: " + error.message());
}

StagedDirectory::~StagedDirectory() {
  if (committed_) return;
  std::error_code ignored;
  fs::remove_all(staging_, ignored);
  if (madeDirectory_) fs::remove(directory_, ignored);  // only if empty: a failed first run leaves nothing
}

void StagedDirectory::underFinalNames(const std::function<void()>& write) const {
  try {
    write();
  } catch (const io::InputError& e) {
    std::string message = e.what();
    const std::string staged = staging_.string() + "/";
    if (message.starts_with(staged)) message.replace(0, staged.size(), (directory_ / "").string());
    throw io::InputError(message.substr(0, message.find(": ")), message.substr(message.find(": ") + 2));
  }
}

void StagedDirectory::requireReplaceableOutputs(const fs::path& directory, const OutputNames& outputNames) {
  for (const std::string& name : namesIn(directory))
    if (outputNames(name)) io::requireReplaceable(directory / name);
}

void StagedDirectory::commit() {
  requireReplaceableOutputs(directory_, outputNames_);
  removeEarlierOutputsNotReplaced(moveStagedFilesIn());
  std::error_code ignored;
  fs::remove(staging_, ignored);
  committed_ = true;
  removeStagingOfKilledRuns();
}

std::set<std::string> StagedDirectory::moveStagedFilesIn() const {
  const std::set<std::string> staged = namesIn(staging_);
  for (const std::string& name : staged) {
    std::error_code error;
    fs::rename(staging_ / name, directory_ / name, error);
    if (error)
      throw io::InputError((directory_ / name).string(), "cannot move the new file in: " + error.message());
  }
  return staged;
}

void StagedDirectory::removeEarlierOutputsNotReplaced(const std::set<std::string>& replaced) const {
  std::error_code error;
  std::vector<fs::path> earlier;
  for (const auto& entry : fs::directory_iterator(directory_, error)) {
    const std::string name = entry.path().filename();
    if (!replaced.contains(name) && outputNames_(name) && entry.is_regular_file(error))
      earlier.push_back(entry.path());
  }
  for (const fs::path& path : earlier) fs::remove(path, error);
}

// A run killed half-way leaves its hidden staging directory; the next run of the command into the directory
// removes it once its process has ended.
void StagedDirectory::removeStagingOfKilledRuns() const {
  const std::regex name("\\." + command_ + "\\.([0-9]{1,9})\\.partial");
  io::removeNumberedEntries(directory_, name, fs::file_type::directory, processEnded);
}

}  // namespace sixway::app
