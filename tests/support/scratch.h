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

}  // namespace giq::test
