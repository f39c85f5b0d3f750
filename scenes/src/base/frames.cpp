#include "giq/base/frames.h"

#include <charconv>
#include <cstdio>

namespace giq {

std::string frame_file(int frame) {
  char name[32];
  std::snprintf(name, sizeof name, kFramePattern, frame);
  return name;
}

std::optional<std::pair<int, int>> parse_frame_range(std::string_view text) {
  const size_t colon = text.find(':');
  if (colon == std::string_view::npos) return std::nullopt;
  auto number = [](std::string_view s) -> std::optional<int> {
    int v = 0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (s.empty() || ec != std::errc() || end != s.data() + s.size()) return std::nullopt;
    return v;
  };
  const auto a = number(text.substr(0, colon)), b = number(text.substr(colon + 1));
  if (!a || !b || *a < 0 || *a > *b) return std::nullopt;
  return std::pair{*a, *b};
}

std::string frame_range(int first, int last) { return std::to_string(first) + ":" + std::to_string(last); }

}  // namespace giq
