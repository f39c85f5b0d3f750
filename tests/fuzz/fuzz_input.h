#pragma once
// What every harness shares: the fuzzed bytes as a file (giq's readers take paths, and the
// glTF loader resolves URIs against the file's folder), and the policy a finding breaks.
//
// Policy: a reader either succeeds or throws giq::InputError, which the CLI prints as one line
// with exit 2. Any other exception would be exit 3 ("internal error") on the user's input, so
// the harness aborts on it and libFuzzer records the input like a crash.

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>

#include "giq/base/error.h"
#include "giq/base/hash.h"

namespace giq::fuzz {

// The identity the seed checkpoints are written with and the checkpoint harness reads with.
inline constexpr const char* kCheckpointIdentity = "fuzz-identity";

// A folder of this process's own (libFuzzer's -fork and -jobs run several processes), in
// memory where the machine has /dev/shm.
inline const std::filesystem::path& work_folder() {
  static const std::filesystem::path folder = [] {
    std::error_code ec;
    const std::filesystem::path base =
        std::filesystem::is_directory("/dev/shm", ec) ? std::filesystem::path("/dev/shm") : std::filesystem::temp_directory_path();
    std::filesystem::path f = base / ("giq-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(f);
    return f;
  }();
  return folder;
}

// Writes the input to <work folder>/<name> and returns the path.
inline std::filesystem::path input_file(const uint8_t* data, size_t size, const std::string& name) {
  const std::filesystem::path p = work_folder() / name;
  std::FILE* f = std::fopen(p.c_str(), "wb");
  if (!f) std::abort();
  if (size && std::fwrite(data, 1, size, f) != size) std::abort();
  std::fclose(f);
  return p;
}

// A file that ends with a 64-bit FNV-1a checksum of everything before it (checkpoints, shard
// parts) refuses almost every mutation at that check. An input that starts with the byte 0x01
// (such files start with 'g') stands for the file without its checksum: it is dropped and the
// right checksum appended, so the mutations also reach the fields behind the check. Other
// inputs are the file's bytes as they are.
inline std::filesystem::path checksummed_input_file(const uint8_t* data, size_t size, const std::string& name) {
  std::string bytes(reinterpret_cast<const char*>(data), size);
  if (!bytes.empty() && bytes[0] == '\x01') {
    bytes.erase(0, 1);
    const uint64_t hash = giq::Hasher().add(bytes).value();
    bytes.append(reinterpret_cast<const char*>(&hash), sizeof hash);
  }
  return input_file(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size(), name);
}

// Runs `read`; InputError is the expected outcome of bad input, anything else a finding.
template <class F>
void expect_success_or_input_error(F&& read) {
  try {
    read();
  } catch (const giq::InputError&) {
  } catch (const std::exception& e) {
    std::fprintf(stderr, "giq fuzz: not an InputError: %s\n", e.what());
    std::abort();
  }
}

}  // namespace giq::fuzz
