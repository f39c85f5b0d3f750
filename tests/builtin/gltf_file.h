#pragma once
// Reads a built-in scene's .gltf as plain JSON plus its decoded data: URI buffer, so the
// tests can check the files against the glTF 2.0 specification without the scene loader.

#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace giq::test {

struct GltfFile {
  nlohmann::json doc;
  std::vector<uint8_t> buffer;  // buffers[0], decoded

  static GltfFile read(const std::filesystem::path& path);

  // Accessor data as stored (float VEC3 / float SCALAR / unsigned short SCALAR, and the VEC4
  // and MAT4 kinds of skins and rotations). Each throws
  // std::runtime_error when the accessor is not of that kind or lies outside its bufferView.
  std::vector<glm::vec3> vec3s(int accessor) const;
  std::vector<float> floats(int accessor) const;
  std::vector<uint32_t> indices(int accessor) const;
  std::vector<glm::vec4> vec4s(int accessor) const;     // float VEC4
  std::vector<glm::mat4> mat4s(int accessor) const;     // float MAT4
  std::vector<glm::u8vec4> bytes4(int accessor) const;  // unsigned byte VEC4

  // Index of the node called `name`; -1 when there is none.
  int node(const std::string& name) const;
};

// RFC 4648 base64 decoding (throws std::runtime_error on a malformed string).
std::vector<uint8_t> decode_base64(const std::string& text);

std::string read_bytes(const std::filesystem::path& path);

}  // namespace giq::test
