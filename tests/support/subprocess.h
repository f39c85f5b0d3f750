#pragma once
// Test support: running the giq binary (or any command line) as a child process, the way a
// user does, and reading back what it wrote. Shared by the end-to-end CLI tests.

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace giq::test {

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Single-quotes s for /bin/sh.
inline std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// The exit code of a std::system() status; -1 when the child did not exit normally.
inline int exit_code(int system_status) { return WIFEXITED(system_status) ? WEXITSTATUS(system_status) : -1; }

struct Outcome {
  int exit_code = -1;
  std::string out, err;
};

// Runs `command` through the shell with stdout and stderr captured in files under `scratch`
// (removed afterwards), so a test can assert on both streams separately.
inline Outcome run_captured(const std::string& command, const std::filesystem::path& scratch) {
  static int n = 0;
  std::filesystem::create_directories(scratch);
  const std::filesystem::path out = scratch / ("out" + std::to_string(n)), err = scratch / ("err" + std::to_string(n));
  ++n;
  const int status = std::system((command + " >" + shell_quote(out.string()) + " 2>" + shell_quote(err.string())).c_str());
  Outcome r{exit_code(status), slurp(out), slurp(err)};
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return r;
}

}  // namespace giq::test
