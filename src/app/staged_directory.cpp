#include "app/staged_directory.h"

#include <algorithm>
#include <regex>
#include <set>
#include <vector>

#include "io/error.h"
#include "io/file_access.h"
#include "io/report.h"
#include "platform/platform.h"

namespace sixway::app {
namespace {

namespace fs = std::filesystem;

// A run's staging directory, `.<command>.<pid>.partial`; the first group is the process id.
const std::regex& stagingName() {
  static const std::regex name(R"(\.[a-z]+\.([0-9]{1,9})\.partial)");
  return name;
}

std::set<std::string> namesIn(const fs::path& directory) {
  std::set<std::string> names;
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(directory, error)) names.insert(entry.path().filename());
  return names;
}

// Where outputs lie: the directory itself ("") and its output folders.
std::vector<std::string> placesOf(const StagedDirectory::OutputFolders& folders) {
  std::vector<std::string> places{""};
  places.insert(places.end(), folders.begin(), folders.end());
  return places;
}

// The name of file `name` in `place`, relative to the directory: what OutputNames is asked about.
std::string relativeName(const std::string& place, const std::string& name) {
  return place.empty() ? name : place + "/" + name;
}

// Whether `directory` holds staging directories of runs whose processes have ended, and nothing else.
bool holdsOnlyKilledRuns(const fs::path& directory) {
  std::error_code error;
  bool any = false;
  for (const auto& entry : fs::directory_iterator(directory, error)) {
    std::smatch match;
    const std::string name = entry.path().filename();
    if (!std::regex_match(name, match, stagingName()) ||
        entry.symlink_status(error).type() != fs::file_type::directory ||
        !platform::processEnded(std::stol(match[1])))
      return false;
    any = true;
  }
  return any && !error;
}

}  // namespace

StagedDirectory::StagedDirectory(fs::path directory, const std::string& command, bool force,
                                 OutputNames outputNames, OutputFolders folders)
    : directory_(std::move(directory)),
      command_(command),
      outputNames_(std::move(outputNames)),
      folders_(std::move(folders)) {
  staging_ = directory_ / ("." + command_ + "." + std::to_string(platform::processId()) + ".partial");
  madeDirectory_ = io::claimOutputDirectory(directory_, force);
  std::error_code error;
  fs::remove_all(staging_, error);  // left by a killed run of a process with this id
  if (!error) fs::create_directory(staging_, error);
  for (const std::string& folder : folders_)
    if (!error) fs::create_directory(staging_ / folder, error);
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
    if (!message.starts_with(staged)) throw;
    message.replace(0, staged.size(), (directory_ / "").string());
    const size_t colon = message.find(": ");
    throw io::InputError(message.substr(0, colon), message.substr(colon + 2));
  }
}

void StagedDirectory::requireWritable(const fs::path& directory, bool force, const OutputNames& outputNames,
                                      const OutputFolders& folders) {
  std::error_code error;
  if (fs::symlink_status(directory, error).type() == fs::file_type::directory &&
      holdsOnlyKilledRuns(directory)) {
    io::removeNumberedEntries(directory, stagingName(), fs::file_type::directory, platform::processEnded);
    fs::remove(directory, error);  // only if empty: another run may have claimed it meanwhile
  }
  io::requireWritableDirectory(directory, force);
  requireReplaceableOutputs(directory, outputNames, folders);
}

void StagedDirectory::requireReplaceableOutputs(const fs::path& directory, const OutputNames& outputNames,
                                                const OutputFolders& folders) {
  for (const std::string& folder : folders) {
    std::error_code error;
    const fs::file_type type = fs::status(directory / folder, error).type();
    if (!error && type != fs::file_type::directory)
      throw io::InputError((directory / folder).string(),
                           "is " + io::describeFileType(type) + ", not a directory; not replaced");
  }
  for (const std::string& place : placesOf(folders))
    for (const std::string& name : namesIn(directory / place))
      if (outputNames(relativeName(place, name))) io::requireReplaceable(directory / place / name);
}

void StagedDirectory::commit() {
  requireReplaceableOutputs(directory_, outputNames_, folders_);
  removeEarlierOutputsNotReplaced(moveStagedFilesIn());
  std::error_code ignored;
  fs::remove_all(staging_, ignored);
  committed_ = true;
  removeStagingOfKilledRuns();
}

std::set<std::string> StagedDirectory::moveStagedFilesIn() const {
  std::set<std::string> moved;
  for (const std::string& place : placesOf(folders_)) {
    std::error_code error;
    if (!place.empty() && !fs::is_directory(directory_ / place, error)) {
      fs::create_directory(directory_ / place, error);
      if (error)
        throw io::InputError((directory_ / place).string(), "cannot create the folder: " + error.message());
    }
    for (const std::string& name : namesIn(staging_ / place)) {
      if (place.empty() && std::ranges::count(folders_, name) > 0) continue;  // moved file by file
      const fs::path target = directory_ / place / name;
      fs::rename(staging_ / place / name, target, error);
      if (error) throw io::InputError(target.string(), "cannot move the new file in: " + error.message());
      moved.insert(relativeName(place, name));
    }
  }
  return moved;
}

void StagedDirectory::removeEarlierOutputsNotReplaced(const std::set<std::string>& replaced) const {
  std::error_code error;
  std::vector<fs::path> earlier;
  for (const std::string& place : placesOf(folders_))
    for (const auto& entry : fs::directory_iterator(directory_ / place, error)) {
      const std::string name = relativeName(place, entry.path().filename());
      if (!replaced.contains(name) && outputNames_(name) && entry.is_regular_file(error))
        earlier.push_back(entry.path());
    }
  for (const fs::path& path : earlier) fs::remove(path, error);
}

// A run killed half-way leaves its hidden staging directory; the next run of the command into the directory
// removes it once its process has ended.
void StagedDirectory::removeStagingOfKilledRuns() const {
  const std::regex name("\\." + command_ + "\\.([0-9]{1,9})\\.partial");
  io::removeNumberedEntries(directory_, name, fs::file_type::directory, platform::processEnded);
}

}  // namespace sixway::app
