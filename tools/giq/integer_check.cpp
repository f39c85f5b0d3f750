#include "integer_check.h"

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>

namespace giq::cli {

CLI::Validator integer_in(long double lo, long double hi) {
  std::ostringstream range;
  range << std::fixed;
  range.precision(0);
  range << "an integer in [" << lo << ", " << hi << "]";
  const std::string expected = range.str();
  return CLI::Validator(
      [lo, hi, expected](std::string& text) -> std::string {
        size_t digits = text.size() > 0 && (text[0] == '-' || text[0] == '+') ? 1 : 0;
        bool plain = digits < text.size();
        for (size_t i = digits; i < text.size(); ++i) plain = plain && text[i] >= '0' && text[i] <= '9';
        // long double holds every integer up to 2^64 exactly: the comparison is exact there.
        const long double v = plain ? std::strtold(text.c_str(), nullptr) : 0.0L;
        if (!plain || v < lo || v > hi) return "'" + text + "' is not " + expected;
        return {};
      },
      expected);
}

}  // namespace giq::cli
