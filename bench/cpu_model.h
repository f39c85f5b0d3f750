#pragma once
// The host CPU's model name, as /proc/cpuinfo gives it: benchmark results name the machine
// they were measured on.

#include <fstream>
#include <string>

namespace giq::bench {

inline std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown CPU";
}

}  // namespace giq::bench
