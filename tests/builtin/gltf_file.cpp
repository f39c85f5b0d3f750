#include "gltf_file.h"

#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <type_traits>

namespace giq::test {
namespace {

constexpr int kFloat = 5126;
constexpr int kUnsignedByte = 5121;
constexpr int kUnsignedShort = 5123;

// Byte range of an accessor's data, checked against its bufferView and the buffer.
const uint8_t* accessor_data(const GltfFile& f, int index, int component_type, int components,
                             size_t component_size, size_t& count) {
  const auto& a = f.doc.at("accessors").at(index);
  if (a.at("componentType").get<int>() != component_type)
    throw std::runtime_error("accessor " + std::to_string(index) + ": unexpected componentType");
  const std::string type = a.at("type").get<std::string>();
  const int n = type == "SCALAR" ? 1 : type == "VEC3" ? 3 : type == "VEC4" ? 4 : type == "MAT4" ? 16 : 0;
  if (n != components)
    throw std::runtime_error("accessor " + std::to_string(index) + ": unexpected type " + type);
  const auto& view = f.doc.at("bufferViews").at(a.at("bufferView").get<int>());
  if (view.contains("byteStride"))
    throw std::runtime_error("bufferView with byteStride: the writer packs tightly");
  count = a.at("count").get<size_t>();
  const size_t offset = view.value("byteOffset", size_t{0}) + a.value("byteOffset", size_t{0});
  const size_t bytes = count * components * component_size;
  if (a.value("byteOffset", size_t{0}) + bytes > view.at("byteLength").get<size_t>() ||
      offset + bytes > f.buffer.size())
    throw std::runtime_error("accessor " + std::to_string(index) + " overruns its bufferView");
  return f.buffer.data() + offset;
}

// An accessor's elements copied out as T (component_size x components bytes each).
template <class T>
std::vector<T> elements(const GltfFile& f, int accessor, int component_type, int components, size_t component_size) {
  static_assert(std::is_trivially_copyable_v<T>);
  size_t count = 0;
  const uint8_t* p = accessor_data(f, accessor, component_type, components, component_size, count);
  std::vector<T> out(count);
  std::memcpy(out.data(), p, count * sizeof(T));
  return out;
}

}  // namespace

std::string read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<uint8_t> decode_base64(const std::string& text) {
  auto value = [](char c) -> int {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    return -1;
  };
  if (text.size() % 4 != 0) throw std::runtime_error("base64 length not a multiple of 4");
  std::vector<uint8_t> out;
  for (size_t i = 0; i < text.size(); i += 4) {
    uint32_t chunk = 0;
    int pad = 0;
    for (int k = 0; k < 4; ++k) {
      const char c = text[i + k];
      if (c == '=' && i + 4 == text.size() && k >= 2) {
        ++pad;
        chunk <<= 6;
        continue;
      }
      const int v = value(c);
      if (v < 0 || pad) throw std::runtime_error("malformed base64");
      chunk = (chunk << 6) | uint32_t(v);
    }
    out.push_back(uint8_t(chunk >> 16));
    if (pad < 2) out.push_back(uint8_t(chunk >> 8));
    if (pad < 1) out.push_back(uint8_t(chunk));
  }
  return out;
}

GltfFile GltfFile::read(const std::filesystem::path& path) {
  GltfFile f;
  f.doc = nlohmann::json::parse(read_bytes(path));
  const auto& buffers = f.doc.at("buffers");
  if (buffers.size() != 1) throw std::runtime_error("expected one buffer");
  const std::string uri = buffers[0].at("uri").get<std::string>();
  const std::string prefix = "data:application/octet-stream;base64,";
  if (uri.rfind(prefix, 0) != 0) throw std::runtime_error("buffer is not an embedded data URI");
  f.buffer = decode_base64(uri.substr(prefix.size()));
  if (f.buffer.size() != buffers[0].at("byteLength").get<size_t>())
    throw std::runtime_error("buffer byteLength differs from the decoded data");
  return f;
}

std::vector<glm::vec3> GltfFile::vec3s(int accessor) const {
  return elements<glm::vec3>(*this, accessor, kFloat, 3, sizeof(float));
}

std::vector<float> GltfFile::floats(int accessor) const {
  return elements<float>(*this, accessor, kFloat, 1, sizeof(float));
}

std::vector<uint32_t> GltfFile::indices(int accessor) const {
  const auto raw = elements<uint16_t>(*this, accessor, kUnsignedShort, 1, sizeof(uint16_t));
  return {raw.begin(), raw.end()};
}

std::vector<glm::vec4> GltfFile::vec4s(int accessor) const {
  return elements<glm::vec4>(*this, accessor, kFloat, 4, sizeof(float));
}

std::vector<glm::mat4> GltfFile::mat4s(int accessor) const {
  return elements<glm::mat4>(*this, accessor, kFloat, 16, sizeof(float));  // both column-major
}

std::vector<glm::u8vec4> GltfFile::bytes4(int accessor) const {
  return elements<glm::u8vec4>(*this, accessor, kUnsignedByte, 4, 1);
}

int GltfFile::node(const std::string& name) const {
  const auto& nodes = doc.at("nodes");
  for (size_t i = 0; i < nodes.size(); ++i)
    if (nodes[i].value("name", "") == name) return static_cast<int>(i);
  return -1;
}

}  // namespace giq::test
