#include "gltf_bytes.h"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <string_view>

namespace giq::scenes::gltf {

std::string stand_in(const std::vector<unsigned char>& bytes) {
  if (bytes.empty()) return "the file is empty";
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), std::min<size_t>(bytes.size(), 256));
  // git-lfs's pointer format (docs/spec.md in git-lfs): its first line names the spec.
  if (text.starts_with("version https://git-lfs.github.com/spec/"))
    return "the file is a Git LFS pointer, not the data itself: fetch it with 'git lfs pull'";
  const size_t first = text.find_first_not_of(" \t\r\n");
  if (first != std::string_view::npos && text[first] == '<') {
    std::string lower(text.substr(first, 64));
    for (char& c : lower) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (lower.starts_with("<!doctype html") || lower.starts_with("<html") || lower.starts_with("<?xml"))
      return "the file is an HTML or XML page, not the data itself (a web page saved in place of the file?)";
  }
  return "";
}

size_t repair_strings(std::string& text) {
  std::string out;     // built only once something is replaced
  size_t copied = 0;   // text before this is in `out`
  size_t replaced = 0;
  bool in_string = false;
  const auto byte = [&](size_t i) { return i < text.size() ? static_cast<unsigned char>(text[i]) : 0u; };
  for (size_t i = 0; i < text.size();) {
    const unsigned char c = byte(i);
    const bool escape = in_string && c == '\\';
    if (escape && std::strchr("\"\\/bfnrtu", int(byte(i + 1))) != nullptr && byte(i + 1) != 0) {
      i += 2;  // an escape (a \u's digits are the parser's to judge)
      continue;
    }
    if (!escape && (!in_string || (c >= 0x20 && c < 0x80))) {
      if (c == '"') in_string = !in_string;
      ++i;
      continue;
    }
    // A sequence's length from its lead byte, and the range its second byte must fall in.
    size_t n = 0;
    unsigned lo = 0x80, hi = 0xBF;
    if (c >= 0xC2 && c <= 0xDF) n = 2;
    else if (c >= 0xE0 && c <= 0xEF) n = 3, lo = c == 0xE0 ? 0xA0 : 0x80, hi = c == 0xED ? 0x9F : 0xBF;
    else if (c >= 0xF0 && c <= 0xF4) n = 4, lo = c == 0xF0 ? 0x90 : 0x80, hi = c == 0xF4 ? 0x8F : 0xBF;
    bool ok = n > 0 && byte(i + 1) >= lo && byte(i + 1) <= hi;
    for (size_t k = 2; ok && k < n; ++k) ok = byte(i + k) >= 0x80 && byte(i + k) <= 0xBF;
    if (ok) {
      i += n;
      continue;
    }
    out.append(text, copied, i - copied);
    out += "\xEF\xBF\xBD";
    copied = ++i;
    ++replaced;
  }
  if (replaced) text = out.append(text, copied, std::string::npos);
  return replaced;
}

}  // namespace giq::scenes::gltf
