#include "giq/base/suggest.h"

#include <algorithm>
#include <cctype>

namespace giq {
namespace {

// Optimal string alignment distance (Damerau-Levenshtein without repeated edits of a
// substring), case-insensitive.
size_t distance(std::string_view a, std::string_view b) {
  auto lower = [](char c) { return char(std::tolower(static_cast<unsigned char>(c))); };
  std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
  for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (size_t i = 1; i <= a.size(); ++i)
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t cost = lower(a[i - 1]) == lower(b[j - 1]) ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && lower(a[i - 1]) == lower(b[j - 2]) && lower(a[i - 2]) == lower(b[j - 1]))
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}

}  // namespace

std::string nearest_name(std::string_view typed, const std::vector<std::string>& known) {
  // Names far longer than anything typed are not typos of it; keep the table small.
  if (typed.empty() || typed.size() > 256) return "";
  std::string best;
  size_t best_distance = 0;
  for (const std::string& k : known) {
    if (k.empty() || k.size() > 256) continue;
    const size_t dist = distance(typed, k);
    const size_t limit = std::max<size_t>(1, std::max(typed.size(), k.size()) / 3);
    if (dist > limit || dist == 0) continue;
    if (best.empty() || dist < best_distance) best = k, best_distance = dist;
  }
  return best;
}

std::string did_you_mean(std::string_view typed, const std::vector<std::string>& known) {
  const std::string n = nearest_name(typed, known);
  return n.empty() ? "" : "; did you mean '" + n + "'?";
}

}  // namespace giq
