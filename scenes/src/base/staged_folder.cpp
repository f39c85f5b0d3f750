#include "giq/base/staged_folder.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <system_error>

#include "giq/base/error.h"

namespace giq {
namespace fs = std::filesystem;
namespace {

constexpr std::string_view kStagingPrefix = ".giq-staging-";

bool plain_file_name(const std::string& name) {
  return !name.empty() && name != "." && name != ".." && name.find('/') == std::string::npos &&
         name.find('\0') == std::string::npos;
}

void fsync_folder(const fs::path& p) {
  const int fd = ::open(p.c_str(), O_RDONLY | O_DIRECTORY);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

}  // namespace

StagedFolder::StagedFolder(fs::path folder, std::string manifest)
    : folder_(std::move(folder)), manifest_(std::move(manifest)) {
  std::error_code ec;
  created_ = !fs::exists(folder_, ec);
  fs::create_directories(folder_, ec);
  if (ec) throw InputError(folder_.string(), "", "cannot create the output folder: " + ec.message());
  lock_fd_ = ::open(folder_.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (lock_fd_ < 0)
    throw InputError(folder_.string(), "", std::string("cannot open the output folder: ") + std::strerror(errno));
  if (::flock(lock_fd_, LOCK_EX | LOCK_NB) != 0) {
    const int err = errno;
    ::close(lock_fd_);
    lock_fd_ = -1;
    if (err == EWOULDBLOCK)
      throw InputError(folder_.string(), "",
                       "another giq process is writing to this folder; expected a folder no other run uses");
    throw InputError(folder_.string(), "", std::string("cannot lock the output folder: ") + std::strerror(err));
  }
  // Holding the lock, any staging folder here belongs to a run that was killed.
  for (const fs::directory_entry& e : fs::directory_iterator(folder_, ec))
    if (e.path().filename().string().starts_with(kStagingPrefix)) fs::remove_all(e.path(), ec);
  staging_ = folder_ / (std::string(kStagingPrefix) + std::to_string(::getpid()));
  fs::create_directory(staging_, ec);
  if (ec) {
    ::close(lock_fd_);
    lock_fd_ = -1;
    throw InputError(folder_.string(), "", "cannot write in the output folder: " + ec.message());
  }
}

StagedFolder::~StagedFolder() {
  std::error_code ignored;
  if (!staging_.empty()) fs::remove_all(staging_, ignored);
  // A run that failed before publishing leaves no empty folder it made.
  if (!published_ && created_ && fs::is_empty(folder_, ignored)) fs::remove(folder_, ignored);
  if (lock_fd_ >= 0) ::close(lock_fd_);  // closing releases the flock
}

void StagedFolder::publish(const std::vector<std::string>& previous) {
  std::vector<fs::path> staged;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(staging_, ec))
    if (e.path().filename() != manifest_) staged.push_back(e.path());
  if (ec) throw InputError(staging_.string(), "", "cannot list the staged outputs: " + ec.message());

  auto remove = [&](const fs::path& p) {
    std::error_code rec;
    fs::remove(p, rec);
    if (rec) throw InputError(p.string(), "", "cannot replace the previous run's file: " + rec.message());
  };
  // The manifest first: from here until the new one lands, the folder claims nothing.
  remove(folder_ / manifest_);
  for (const std::string& name : previous) {
    if (!plain_file_name(name) || name == manifest_) continue;
    if (fs::exists(staging_ / name)) continue;  // replaced by rename below
    remove(folder_ / name);
  }
  auto move = [&](const fs::path& from) {
    const fs::path to = folder_ / from.filename();
    if (::rename(from.c_str(), to.c_str()) != 0)
      throw InputError(to.string(), "", std::string("cannot write: ") + std::strerror(errno));
  };
  for (const fs::path& p : staged) move(p);
  if (fs::exists(staging_ / manifest_)) move(staging_ / manifest_);
  published_ = true;
  fsync_folder(folder_);
}

}  // namespace giq
