#pragma once
// A folder of outputs that one run replaces as a whole: `giq score --out DIR` writes
// metrics.json plus the maps and the strip it names, and a reader of DIR must never see
// metrics.json beside files of another run (a second score into the same folder, or a disk
// full halfway through a re-score).
//
// The folder is locked (flock(2) on the folder itself, so a killed writer never leaves a stale
// lock) for the object's lifetime; a second writer is refused with an InputError. Files are
// written into a hidden staging folder inside it (same file system, so publishing is
// renames only and cannot run out of space). publish() then removes the previous run's
// manifest, then the previous run's files this run does not write again, renames every staged
// file into place and the manifest last. At every moment, a manifest in the folder describes
// exactly the files beside it; a run that throws before publish() leaves the previous run
// untouched.

#include <filesystem>
#include <string>
#include <vector>

namespace giq {

class StagedFolder {
 public:
  // Creates `folder` if missing, takes its lock and makes an empty staging folder in it
  // (removing staging folders that killed runs left). `manifest` is the file name published
  // last ("metrics.json"). Destroyed unpublished, it removes the staging folder, and the
  // folder too when it made it and it is empty.
  StagedFolder(std::filesystem::path folder, std::string manifest);
  ~StagedFolder();
  StagedFolder(const StagedFolder&) = delete;
  StagedFolder& operator=(const StagedFolder&) = delete;

  // Where the run writes its files (plain files, no subfolders).
  const std::filesystem::path& staging() const { return staging_; }

  // `previous` names the files the previous run's manifest listed; only plain file names are
  // honoured (a name with a separator or "..", as a hostile manifest could carry, is skipped),
  // so nothing outside the folder is ever removed.
  void publish(const std::vector<std::string>& previous);

 private:
  std::filesystem::path folder_, staging_;
  std::string manifest_;
  int lock_fd_ = -1;
  bool created_ = false, published_ = false;
};

}  // namespace giq
