#pragma once
// A scene's files as bytes, before they are parsed as glTF, JSON or images: what stands in
// for the data where a user's copy went wrong, and JSON strings repaired where an exporter
// wrote them in another encoding.

#include <cstddef>
#include <string>
#include <vector>

namespace giq::scenes::gltf {

// What a file holds instead of the data it stands for, when that is a common mistake: nothing
// ("the file is empty"), a Git LFS pointer (a repository cloned without its LFS objects), or
// an HTML page (a web page saved in place of the file); empty when none of them.
std::string stand_in(const std::vector<unsigned char>& bytes);

// Replaces, in JSON text, every byte of its strings that is not part of a well-formed UTF-8
// sequence (RFC 3629, section 4: no overlong forms, no surrogates, nothing above U+10FFFF), and
// every raw control character and every backslash that starts no escape (RFC 8259, section 7),
// by U+FFFD, and returns how many it replaced. Bytes outside strings are left to the parser.
// Exporters write names in legacy encodings (whose two-byte characters may end in 0x5C, a
// backslash); names are all such strings hold that giq reads, so the file is not refused.
size_t repair_strings(std::string& text);

}  // namespace giq::scenes::gltf
