#pragma once
// Test support: an empty scratch folder of this test process's own under the system's
// temporary folder, and the bytes of a file.

#include <unistd.h>

#include <filesystem>
#include <string>

#include "support/subprocess.h"  // slurp

namespace giq::test {

// <tmp>/giq_<name>_<pid>, emptied.
inline std::filesystem::path fresh_dir(const std::string& name) {
  const std::filesystem::path d =
      std::filesystem::temp_directory_path() / ("giq_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

// fresh_dir(name) for the life of the object, removed afterwards: a suite's folder, held in a
// function-local static.
struct ScratchDir {
  explicit ScratchDir(const std::string& name) : path(fresh_dir(name)) {}
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  std::filesystem::path path;
};

}  // namespace giq::test
