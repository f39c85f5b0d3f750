#include "text.h"

#include <cmath>
#include <cstdio>

namespace giq::scenegen {

std::string num(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  std::string s(buf);
  if (s.find('.') != std::string::npos) {
    while (s.back() == '0') s.pop_back();
    if (s.back() == '.') s.pop_back();
  }
  if (s == "-0") s = "0";
  return s;
}

std::string vec(glm::dvec3 v, int decimals) {
  return "(" + num(v.x, decimals) + ", " + num(v.y, decimals) + ", " + num(v.z, decimals) + ")";
}

}  // namespace giq::scenegen
