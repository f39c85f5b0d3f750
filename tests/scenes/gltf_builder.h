#pragma once
// Test support: a glTF document written from C++ (JSON and one binary buffer), for tests that
// need files no generator script holds.

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace giq::test {

// A glTF document under construction: buffer 0 holds `bin`.
struct Doc {
  nlohmann::json j = {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"materials", {{{"pbrMetallicRoughness", {{"baseColorFactor", {1, 1, 1, 1}}}}}}},
      {"bufferViews", nlohmann::json::array()},
      {"accessors", nlohmann::json::array()}};
  std::vector<unsigned char> bin;

  size_t append(const void* data, size_t size) {
    while (bin.size() % 4) bin.push_back(0);
    const size_t at = bin.size();
    bin.insert(bin.end(), static_cast<const unsigned char*>(data),
               static_cast<const unsigned char*>(data) + size);
    return at;
  }
  int view(nlohmann::json v) {
    j["bufferViews"].push_back(std::move(v));
    return int(j["bufferViews"].size()) - 1;
  }
  int accessor(nlohmann::json a) {
    j["accessors"].push_back(std::move(a));
    return int(j["accessors"].size()) - 1;
  }
  void primitive(nlohmann::json attributes, int indices, nlohmann::json extensions = nullptr) {
    nlohmann::json p = {
        {"attributes", std::move(attributes)}, {"indices", indices}, {"material", 0}};
    if (!extensions.is_null()) p["extensions"] = std::move(extensions);
    j["meshes"] = {{{"primitives", {p}}}};
  }
  void require(const char* ext) {
    j["extensionsUsed"].push_back(ext);
    j["extensionsRequired"].push_back(ext);
  }

  // .gltf with an external .bin, or .glb with buffer 0 as its BIN chunk.
  std::filesystem::path write(const std::filesystem::path& dir, const std::string& name, bool glb) {
    while (bin.size() % 4) bin.push_back(0);
    j["buffers"][0]["byteLength"] = bin.size();
    const std::filesystem::path path = dir / name;
    if (!glb) {
      j["buffers"][0]["uri"] = name + ".bin";
      std::ofstream(dir / (name + ".bin"), std::ios::binary)
          .write(reinterpret_cast<const char*>(bin.data()), std::streamsize(bin.size()));
      std::ofstream(path) << j.dump();
      return path;
    }
    std::string text = j.dump();
    while (text.size() % 4) text += ' ';
    std::vector<unsigned char> out;
    auto put32 = [&](uint32_t v) {
      for (int k = 0; k < 4; ++k) out.push_back(static_cast<unsigned char>(v >> (8 * k)));
    };
    put32(0x46546C67u), put32(2), put32(uint32_t(12 + 8 + text.size() + 8 + bin.size()));
    put32(uint32_t(text.size())), put32(0x4E4F534Au);
    out.insert(out.end(), text.begin(), text.end());
    put32(uint32_t(bin.size())), put32(0x004E4942u);
    out.insert(out.end(), bin.begin(), bin.end());
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(out.data()), std::streamsize(out.size()));
    return path;
  }
};

}  // namespace giq::test
