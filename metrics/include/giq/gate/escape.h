#pragma once
// Escaping text that comes from files (scene names, node names, parameters, messages) before
// it goes into XML (JUnit) or HTML (the report), and base64 for data URIs.

#include <cstdint>
#include <string>
#include <string_view>

namespace giq::gate {

// &, <, >, " and ' as entities; control characters that XML 1.0 forbids (all below U+0020
// except tab, newline, carriage return) are replaced by U+FFFD, so the output always parses.
// HTML5 accepts the same escapes in text and in quoted attribute values.
std::string xml_escape(std::string_view text);
inline std::string html_escape(std::string_view text) {
  return xml_escape(text);
}

// RFC 4648 section 4 base64 with padding.
std::string base64(std::string_view bytes);

}  // namespace giq::gate
