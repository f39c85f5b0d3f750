#pragma once
// Reading a glTF file and everything it references, before tinygltf sees any of it: the
// .glb container, URI resolution confined to the scene's folder, data URIs, declared sizes
// against actual sizes, and the content hash. tinygltf then parses the checked bytes through
// file-system callbacks that can only return what was read and checked here.

#include <tiny_gltf.h>

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace giq::scenes::gltf {

struct Document {
  std::string file;                  // the path as given, for messages
  std::filesystem::path folder;      // canonical folder every URI must stay inside
  std::vector<unsigned char> bytes;  // the .gltf or .glb file
  bool binary = false;
  size_t json_offset = 0, json_size = 0;  // the JSON text inside `bytes`
  size_t bin_size = 0;                    // GLB BIN chunk payload size (0 = none)
  nlohmann::json json;
  // Referenced external files by canonical path, as tinygltf will be given them.
  std::map<std::string, std::vector<unsigned char>> files;
  std::string content_hash;
  // Encoded image bytes by images[] index, handed over by tinygltf's image callback and
  // decoded later, once per colour space (see gltf_materials.cpp).
  std::vector<std::vector<unsigned char>> encoded_images;
  // Optional extensions the file uses that giq ignores, with what that approximates.
  std::vector<std::string> warnings;
  // Buffers without data (no uri, and not a .glb's BIN chunk): placeholders that only views
  // compressed with EXT_meshopt_compression may name (gltf_meshopt.cpp decodes those views).
  std::vector<bool> placeholder_buffers;
  // The JSON had bytes in its strings that were replaced before parsing (repair_strings,
  // gltf_bytes.h): tinygltf then parses `json` as dumped, not the file's bytes.
  bool strings_repaired = false;
};

// The extension whose compressed buffer views gltf_meshopt.cpp decodes.
inline constexpr const char* kMeshoptExtension = "EXT_meshopt_compression";

// The member `key` of object `o`, or nullptr.
const nlohmann::json* member(const nlohmann::json& o, const char* key);
// A non-negative integer property of `o` (at glTF path `where`), or `fallback` when absent
// and not required. Throws InputError naming where.key.
uint64_t unsigned_property(const Document& d, const nlohmann::json& o, const char* key, const std::string& where,
                           bool required, uint64_t fallback = 0);

// Reads `path`, checks the container, the JSON and every buffer and image URI, and computes
// the content hash. Throws InputError.
Document read_document(const std::filesystem::path& path);

// Parses the checked document with tinygltf. Throws InputError.
tinygltf::Model parse_model(Document& doc);

}  // namespace giq::scenes::gltf
