#include "gltf_document.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <optional>
#include <system_error>

#include "giq/base/error.h"
#include "giq/base/json.h"
#include "giq/base/hash.h"
#include "gltf_bytes.h"

namespace giq::scenes::gltf {

const nlohmann::json* member(const nlohmann::json& o, const char* key) {
  if (!o.is_object()) return nullptr;
  auto it = o.find(key);
  return it == o.end() ? nullptr : &*it;
}

uint64_t unsigned_property(const Document& d, const nlohmann::json& o, const char* key, const std::string& where,
                           bool required, uint64_t fallback) {
  const nlohmann::json* v = member(o, key);
  if (!v) {
    if (required) throw InputError(d.file, where + "." + key, "missing; expected a non-negative integer");
    return fallback;
  }
  if (v->is_number_unsigned()) return v->get<uint64_t>();
  if (v->is_number_float()) {
    const double x = v->get<double>();
    if (x >= 0.0 && x < 9.0e15 && x == double(uint64_t(x))) return uint64_t(x);
  }
  throw InputError(d.file, where + "." + key, "is " + v->dump() + "; expected a non-negative integer");
}

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Extensions giq implements. Anything else in extensionsRequired changes the image in a way
// giq would get wrong, so it is refused (glTF 2.0 spec, 3.12 "Specifying Extensions"); anything
// else in extensionsUsed alone is ignored, as the specification allows, with a warning that
// says what is then approximated.
constexpr const char* kImplemented[] = {"KHR_lights_punctual",     "KHR_materials_emissive_strength", "KHR_materials_specular",
                                        "KHR_materials_ior",       "KHR_materials_unlit",             "KHR_texture_transform",
                                        "KHR_mesh_quantization",   "EXT_mesh_gpu_instancing",         "KHR_materials_pbrSpecularGlossiness",
                                        kMeshoptExtension,         "KHR_draco_mesh_compression"};

// What ignoring an optional extension means for the image ("" = nothing visible: metadata).
struct Ignored {
  const char* name;
  const char* effect;
};
constexpr Ignored kIgnored[] = {
    {"KHR_materials_transmission", "transmissive surfaces render opaque"},
    {"KHR_materials_diffuse_transmission", "surfaces transmit no diffuse light"},
    {"KHR_materials_volume", "volumes absorb and scatter nothing"},
    {"KHR_materials_clearcoat", "materials have no clear-coat layer"},
    {"KHR_materials_sheen", "materials have no sheen lobe"},
    {"KHR_materials_iridescence", "materials have no thin-film iridescence"},
    {"KHR_materials_anisotropy", "specular highlights are isotropic"},
    {"KHR_materials_dispersion", "refraction has no dispersion"},
    {"KHR_materials_variants", "every primitive keeps its default material"},
    {"KHR_animation_pointer", "only node transforms animate"},
    {"KHR_texture_basisu", "textures use their core PNG or JPEG image"},
    {"EXT_texture_webp", "textures use their core PNG or JPEG image"},
    {"EXT_texture_avif", "textures use their core PNG or JPEG image"},
    {"MSFT_texture_dds", "textures use their core PNG or JPEG image"},
    {"KHR_xmp_json_ld", ""},
    {"KHR_xmp", ""},
};

// The data-URI prefixes tinygltf 2.7 decodes (tiny_gltf.h, IsDataURI); anything else would be
// taken for a file name.
constexpr const char* kDataUriPrefixes[] = {
    "data:application/octet-stream;base64,", "data:application/gltf-buffer;base64,",
    "data:image/png;base64,",  "data:image/jpeg;base64,", "data:image/bmp;base64,",
    "data:image/gif;base64,",  "data:text/plain;base64,"};

std::vector<unsigned char> read_file(const std::string& file, const fs::path& path,
                                     const std::string& field) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec))
    throw InputError(file, field, "'" + path.string() + "' does not exist or is not a regular file");
  // glTF files and their buffers are limited to 4 GiB (uint32 lengths in .glb); checking
  // before reading keeps a stray huge file from being loaded into memory first.
  if (fs::file_size(path, ec) > std::numeric_limits<uint32_t>::max() || ec)
    throw InputError(file, field, "'" + path.string() + "' is larger than 4 GiB or its size cannot be read");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(file, field, "cannot open '" + path.string() + "' for reading");
  // One read of the whole file (a byte-wise stream iterator took a second for 120 MB).
  std::vector<unsigned char> bytes(size_t(fs::file_size(path, ec)));
  in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(bytes.size()));
  if (ec || in.bad() || size_t(in.gcount()) != bytes.size() || in.peek() != std::char_traits<char>::eof())
    throw InputError(file, field, "error while reading '" + path.string() + "' (did it change while being read?)");
  return bytes;
}

uint32_t le32(const std::vector<unsigned char>& b, size_t at) {
  return uint32_t(b[at]) | uint32_t(b[at + 1]) << 8 | uint32_t(b[at + 2]) << 16 | uint32_t(b[at + 3]) << 24;
}

// glTF 2.0 spec, 4.4 "Binary glTF Layout": 12-byte header, a JSON chunk, an optional BIN chunk.
// The checks are also the preconditions tinygltf's own GLB reader relies on.
void read_glb_layout(Document& d) {
  const auto& b = d.bytes;
  const std::string& f = d.file;
  if (b.size() < 20) throw InputError(f, "glb header", "file has " + std::to_string(b.size()) + " bytes; a .glb needs at least 20");
  if (le32(b, 4) != 2) throw InputError(f, "glb header.version", "container version " + std::to_string(le32(b, 4)) + "; expected 2");
  const uint64_t length = le32(b, 8);
  if (length != b.size())
    throw InputError(f, "glb header.length", "declares " + std::to_string(length) + " bytes but the file has " + std::to_string(b.size()));
  const uint64_t json_len = le32(b, 12);
  if (le32(b, 16) != 0x4E4F534Au) throw InputError(f, "glb chunk[0].chunkType", "first chunk must be JSON (0x4E4F534A)");
  if (json_len < 1 || 20 + json_len > length)
    throw InputError(f, "glb chunk[0].chunkLength", "JSON chunk of " + std::to_string(json_len) + " bytes does not fit in a " + std::to_string(length) + "-byte file");
  if ((20 + json_len) % 4 != 0) throw InputError(f, "glb chunk[0].chunkLength", "JSON chunk must end on a 4-byte boundary");
  d.json_offset = 20;
  d.json_size = size_t(json_len);
  const uint64_t bin_at = 20 + json_len;
  if (bin_at == length) return;
  if (bin_at + 8 > length) throw InputError(f, "glb chunk[1]", "truncated chunk header after the JSON chunk");
  const uint64_t bin_len = le32(b, size_t(bin_at));
  if (le32(b, size_t(bin_at + 4)) != 0x004E4942u) throw InputError(f, "glb chunk[1].chunkType", "second chunk must be BIN (0x004E4942)");
  if (bin_len < 4 || bin_len % 4 != 0 || bin_at + 8 + bin_len > length)
    throw InputError(f, "glb chunk[1].chunkLength", "BIN chunk of " + std::to_string(bin_len) + " bytes does not fit the file or is not a positive multiple of 4");
  d.bin_size = size_t(bin_len);
}

const json& array_of_objects(const Document& d, const char* key) {
  static const json empty = json::array();
  const json* a = member(d.json, key);
  if (!a) return empty;
  if (!a->is_array()) throw InputError(d.file, key, "must be an array");
  for (size_t i = 0; i < a->size(); ++i)
    if (!(*a)[i].is_object()) throw InputError(d.file, std::string(key) + "[" + std::to_string(i) + "]", "must be a JSON object");
  return *a;
}

int base64_value(unsigned char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+') return 62;
  if (c == '/') return 63;
  return -1;
}

// Strict RFC 4648 base64: alphabet only, length a multiple of 4, padding only at the end.
bool base64_decode(std::string_view s, std::vector<unsigned char>& out) {
  out.clear();
  if (s.size() % 4 != 0) return false;
  out.reserve(s.size() / 4 * 3);
  for (size_t i = 0; i < s.size(); i += 4) {
    int v[4];
    int pad = 0;
    for (int k = 0; k < 4; ++k) {
      const unsigned char c = s[i + k];
      if (c == '=' && i + 4 == s.size() && k >= 2) {
        v[k] = 0, ++pad;
        continue;
      }
      if (pad > 0) return false;
      v[k] = base64_value(c);
      if (v[k] < 0) return false;
    }
    const uint32_t n = uint32_t(v[0]) << 18 | uint32_t(v[1]) << 12 | uint32_t(v[2]) << 6 | uint32_t(v[3]);
    out.push_back(static_cast<unsigned char>(n >> 16));
    if (pad < 2) out.push_back(static_cast<unsigned char>(n >> 8));
    if (pad < 1) out.push_back(static_cast<unsigned char>(n));
  }
  return true;
}

// Percent-decoding as tinygltf applies it to file URIs (tiny_gltf.h, dlib::urldecode, which
// also maps '+' to a space), so the path checked here is the path tinygltf asks for. Unlike
// tinygltf, a malformed escape is an error.
bool uri_decode(const std::string& s, std::string& out) {
  out.clear();
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '+') {
      out += ' ';
    } else if (s[i] == '%') {
      if (i + 2 >= s.size()) return false;
      auto hex = [](char c) { return std::isxdigit(static_cast<unsigned char>(c)) != 0; };
      if (!hex(s[i + 1]) || !hex(s[i + 2])) return false;
      out += static_cast<char>(std::stoi(s.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      out += s[i];
    }
  }
  return out.find('\0') == std::string::npos;
}

bool has_scheme(const std::string& uri) {
  // RFC 3986, 3.1: scheme = ALPHA *( ALPHA / DIGIT / "+" / "-" / "." ) ":"
  if (uri.empty() || !std::isalpha(static_cast<unsigned char>(uri[0]))) return false;
  for (char c : uri) {
    if (c == ':') return true;
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '+' && c != '-' && c != '.') return false;
  }
  return false;
}

bool inside(const fs::path& folder, const fs::path& p) {
  auto [f, q] = std::mismatch(folder.begin(), folder.end(), p.begin(), p.end());
  return f == folder.end() && q != p.end();
}

// Resolves one URI. Data URIs are decoded into `data`; file URIs must name a regular file
// inside the scene folder after normalisation and symlink resolution, and are read into
// d.files. Returns the canonical path for files, "" for data URIs.
std::string resolve_uri(Document& d, const std::string& uri, const std::string& field,
                        std::vector<unsigned char>& data) {
  if (uri.rfind("data:", 0) == 0) {
    for (const char* prefix : kDataUriPrefixes) {
      const size_t n = std::strlen(prefix);
      if (uri.compare(0, n, prefix) == 0) {
        if (!base64_decode(std::string_view(uri).substr(n), data))
          throw InputError(d.file, field, "data URI payload is not valid base64");
        return "";
      }
    }
    throw InputError(d.file, field, "unsupported data URI '" + uri.substr(0, std::min<size_t>(uri.find(','), 48)) +
                                        "'; expected base64 with an application/octet-stream, application/gltf-buffer or image media type");
  }
  if (has_scheme(uri))
    throw InputError(d.file, field, "URI '" + uri + "' has a scheme; only relative file paths and data: URIs are read");
  std::string decoded;
  if (!uri_decode(uri, decoded)) throw InputError(d.file, field, "URI '" + uri + "' has a malformed percent escape");
  if (decoded.empty()) throw InputError(d.file, field, "empty URI");
  if (decoded[0] == '/' || decoded[0] == '\\' || fs::path(decoded).is_absolute())
    throw InputError(d.file, field, "absolute URI '" + uri + "' refused; URIs must be relative to the scene's folder");
  std::error_code ec;
  const fs::path target = fs::weakly_canonical(d.folder / decoded, ec);
  if (ec || !inside(d.folder, target))
    throw InputError(d.file, field, "URI '" + uri + "' resolves outside the scene's folder '" + d.folder.string() + "'; refused");
  auto it = d.files.find(target.string());
  if (it == d.files.end()) {
    // Files saved under their URI's undecoded name ("a%20b.png" on disk for the URI
    // "a%20b.png", which names "a b.png") are common where models pass through web tools: read
    // in the decoded file's place, with a warning, when only the literal one exists.
    std::error_code lec;
    const fs::path literal = decoded != uri ? fs::weakly_canonical(d.folder / uri, lec) : fs::path();
    const bool fallback = !literal.empty() && !lec && !fs::exists(target, ec) && inside(d.folder, literal) && fs::is_regular_file(literal, lec);
    it = d.files.emplace(target.string(), read_file(d.file, fallback ? literal : target, field)).first;
    if (fallback)
      d.warnings.push_back(field + ": no file '" + decoded + "' (the URI percent-decoded, as glTF URIs are); read '" + uri +
                           "' instead, the file named exactly as the URI is written");
  }
  data = it->second;
  return target.string();
}

std::vector<std::string> string_array(const Document& d, const char* key) {
  std::vector<std::string> out;
  const json* a = member(d.json, key);
  if (!a) return out;
  if (!a->is_array()) throw InputError(d.file, key, "must be an array of strings");
  for (size_t i = 0; i < a->size(); ++i) {
    if (!(*a)[i].is_string()) throw InputError(d.file, std::string(key) + "[" + std::to_string(i) + "]", "must be a string");
    out.push_back((*a)[i].get<std::string>());
  }
  return out;
}

void check_extensions(Document& d) {
  auto implemented = [](const std::string& name) {
    return std::any_of(std::begin(kImplemented), std::end(kImplemented), [&](const char* s) { return name == s; });
  };
  const std::vector<std::string> required = string_array(d, "extensionsRequired");
  for (size_t i = 0; i < required.size(); ++i)
    if (!implemented(required[i])) {
      std::string list;
      for (const char* s : kImplemented) list += (list.empty() ? "" : ", ") + std::string(s);
      throw InputError(d.file, "extensionsRequired[" + std::to_string(i) + "]",
                       "extension '" + required[i] + "' is required by the file but not supported; supported: " + list);
    }
  for (const std::string& name : string_array(d, "extensionsUsed")) {
    if (implemented(name)) continue;
    const auto known = std::find_if(std::begin(kIgnored), std::end(kIgnored), [&](const Ignored& k) { return name == k.name; });
    if (known == std::end(kIgnored))
      d.warnings.push_back("extensionsUsed: " + name + " is not implemented and was ignored; whatever it adds is not rendered");
    else if (*known->effect)
      d.warnings.push_back("extensionsUsed: " + name + " is not implemented and was ignored: " + known->effect);
  }
}

// Buffers, buffer views and image sources: everything tinygltf copies or indexes while
// parsing, checked so it cannot read out of bounds.
void check_binary_data(Document& d, Hasher& hash) {
  const json& buffers = array_of_objects(d, "buffers");
  std::vector<uint64_t> buffer_length(buffers.size());
  d.placeholder_buffers.assign(buffers.size(), false);
  for (size_t i = 0; i < buffers.size(); ++i) {
    const std::string where = "buffers[" + std::to_string(i) + "]";
    const uint64_t declared = unsigned_property(d, buffers[i], "byteLength", where, true);
    if (declared < 1) throw InputError(d.file, where + ".byteLength", "is 0; expected at least 1");
    buffer_length[i] = declared;
    const json* uri = member(buffers[i], "uri");
    if (!uri) {
      if (d.binary && i == 0) {
        if (declared > d.bin_size)
          throw InputError(d.file, where + ".byteLength", "declares " + std::to_string(declared) + " bytes but the .glb BIN chunk has " + std::to_string(d.bin_size));
        continue;
      }
      // No data: a placeholder that only compressed views may name (checked below).
      d.placeholder_buffers[i] = true;
      continue;
    }
    if (!uri->is_string()) throw InputError(d.file, where + ".uri", "must be a string");
    std::vector<unsigned char> data;
    const std::string path = resolve_uri(d, uri->get<std::string>(), where + ".uri", data);
    if (data.size() != declared) {
      const std::string what = stand_in(data);
      throw InputError(d.file, where + ".byteLength", "declares " + std::to_string(declared) + " bytes but '" + uri->get<std::string>().substr(0, 64) +
                                                          "' holds " + std::to_string(data.size()) + "; they must be equal" +
                                                          (what.empty() ? "" : "; " + what));
    }
    if (!path.empty()) hash.add(path.substr(d.folder.string().size())).add(data.data(), data.size());
  }
  const json& views = array_of_objects(d, "bufferViews");
  for (size_t i = 0; i < views.size(); ++i) {
    const std::string where = "bufferViews[" + std::to_string(i) + "]";
    const uint64_t b = unsigned_property(d, views[i], "buffer", where, true);
    if (b >= buffers.size())
      throw InputError(d.file, where + ".buffer", "is " + std::to_string(b) + "; the file has " + std::to_string(buffers.size()) + " buffers");
    const json* ext = member(views[i], "extensions");
    if (d.placeholder_buffers[b] && !(ext && member(*ext, kMeshoptExtension)))
      throw InputError(d.file, where + ".buffer", "names buffers[" + std::to_string(b) + "], which has no uri and holds no data; only a view compressed with " +
                                                      kMeshoptExtension + " may (and only the first buffer of a .glb may name the BIN chunk)");
    const uint64_t offset = unsigned_property(d, views[i], "byteOffset", where, false, 0);
    const uint64_t length = unsigned_property(d, views[i], "byteLength", where, true);
    if (length < 1) throw InputError(d.file, where + ".byteLength", "is 0; expected at least 1");
    if (offset > buffer_length[b] || length > buffer_length[b] - offset)
      throw InputError(d.file, where, "bytes [" + std::to_string(offset) + ", " + std::to_string(offset + length) + ") exceed buffers[" +
                                          std::to_string(b) + "] of " + std::to_string(buffer_length[b]) + " bytes");
    const uint64_t stride = unsigned_property(d, views[i], "byteStride", where, false, 4);
    if (stride < 4 || stride > 252 || stride % 4 != 0)
      throw InputError(d.file, where + ".byteStride", "is " + std::to_string(stride) + "; expected a multiple of 4 in [4, 252]");
  }
  const json& images = array_of_objects(d, "images");
  for (size_t i = 0; i < images.size(); ++i) {
    const std::string where = "images[" + std::to_string(i) + "]";
    const json* uri = member(images[i], "uri");
    const bool has_view = member(images[i], "bufferView") != nullptr;
    if ((uri != nullptr) == has_view) throw InputError(d.file, where, "needs exactly one of 'uri' and 'bufferView'");
    if (has_view) {
      const uint64_t v = unsigned_property(d, images[i], "bufferView", where, true);
      if (v >= views.size())
        throw InputError(d.file, where + ".bufferView", "is " + std::to_string(v) + "; the file has " + std::to_string(views.size()) + " buffer views");
      continue;
    }
    if (!uri->is_string()) throw InputError(d.file, where + ".uri", "must be a string");
    std::vector<unsigned char> data;
    const std::string path = resolve_uri(d, uri->get<std::string>(), where + ".uri", data);
    if (data.empty()) throw InputError(d.file, where + ".uri", "image data is empty");
    if (!path.empty()) hash.add(path.substr(d.folder.string().size())).add(data.data(), data.size());
  }
}

// The shape of the arrays and accessor fields, checked here so that a malformed document
// is reported at its glTF path rather than in the parser's words.
void check_structure(const Document& d) {
  for (const char* key : {"accessors", "animations", "buffers", "bufferViews", "cameras", "images", "materials", "meshes",
                          "nodes", "samplers", "scenes", "skins", "textures"})
    array_of_objects(d, key);
  const size_t n_views = array_of_objects(d, "bufferViews").size();
  const json& accessors = array_of_objects(d, "accessors");
  for (size_t i = 0; i < accessors.size(); ++i) {
    const std::string where = "accessors[" + std::to_string(i) + "]";
    const uint64_t ct = unsigned_property(d, accessors[i], "componentType", where, true);
    if (ct < 5120 || ct > 5126 || ct == 5124)
      throw InputError(d.file, where + ".componentType", "is " + std::to_string(ct) + "; expected 5120, 5121, 5122, 5123, 5125 or 5126");
    const json* type = member(accessors[i], "type");
    static const char* kTypes[] = {"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4"};
    if (!type || !type->is_string() ||
        std::none_of(std::begin(kTypes), std::end(kTypes), [&](const char* t) { return type->get<std::string>() == t; }))
      throw InputError(d.file, where + ".type", std::string(type ? "is " + type->dump() : "missing") + "; expected SCALAR, VEC2, VEC3, VEC4, MAT2, MAT3 or MAT4");
    unsigned_property(d, accessors[i], "count", where, true);
    unsigned_property(d, accessors[i], "byteOffset", where, false);
    if (member(accessors[i], "bufferView")) {
      const uint64_t v = unsigned_property(d, accessors[i], "bufferView", where, true);
      if (v >= n_views)
        throw InputError(d.file, where + ".bufferView", "is " + std::to_string(v) + "; the file has " + std::to_string(n_views) + " buffer views");
    }
  }
  const json& meshes = array_of_objects(d, "meshes");
  for (size_t m = 0; m < meshes.size(); ++m) {
    const std::string mw = "meshes[" + std::to_string(m) + "].primitives";
    const json* prims = member(meshes[m], "primitives");
    if (!prims || !prims->is_array() || prims->empty()) throw InputError(d.file, mw, "missing or empty; expected an array of primitives");
    for (size_t p = 0; p < prims->size(); ++p) {
      const std::string pw = mw + "[" + std::to_string(p) + "]";
      const json& prim = (*prims)[p];
      if (!prim.is_object()) throw InputError(d.file, pw, "must be a JSON object");
      const json* attrs = member(prim, "attributes");
      if (!attrs || !attrs->is_object()) throw InputError(d.file, pw + ".attributes", "missing or not an object");
      for (const auto& [name, value] : attrs->items()) {
        const uint64_t a = unsigned_property(d, *attrs, name.c_str(), pw + ".attributes", true);
        if (a >= accessors.size())
          throw InputError(d.file, pw + ".attributes." + name, "is " + std::to_string(a) + "; the file has " + std::to_string(accessors.size()) + " accessors");
      }
      if (member(prim, "indices")) {
        const uint64_t a = unsigned_property(d, prim, "indices", pw, true);
        if (a >= accessors.size())
          throw InputError(d.file, pw + ".indices", "is " + std::to_string(a) + "; the file has " + std::to_string(accessors.size()) + " accessors");
      }
    }
  }
}

// tinygltf file-system callbacks: only files already read and checked above exist.
bool fs_exists(const std::string& path, void* user) {
  const auto* d = static_cast<const Document*>(user);
  std::error_code ec;
  const fs::path p = fs::weakly_canonical(path, ec);
  return !ec && d->files.count(p.string()) != 0;
}
std::string fs_expand(const std::string& path, void*) { return path; }  // no shell expansion
bool fs_read(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  const auto* d = static_cast<const Document*>(user);
  std::error_code ec;
  const fs::path p = fs::weakly_canonical(path, ec);
  auto it = ec ? d->files.end() : d->files.find(p.string());
  if (it == d->files.end()) {
    if (err) *err += "refused: not a checked file of this scene";
    return false;
  }
  *out = it->second;
  return true;
}
bool fs_write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "giq never writes through the glTF loader";
  return false;
}

bool stash_image(tinygltf::Image*, const int index, std::string*, std::string*, int, int,
                 const unsigned char* bytes, int size, void* user) {
  auto* d = static_cast<Document*>(user);
  if (index < 0) return false;
  if (d->encoded_images.size() <= size_t(index)) d->encoded_images.resize(size_t(index) + 1);
  d->encoded_images[size_t(index)].assign(bytes, bytes + std::max(size, 0));
  return true;
}

// The document with its JSON replaced by `text`: the text itself, or for a .glb the
// container rebuilt around it (glTF 2.0 spec, 4.4: JSON chunk padded with spaces to 4 bytes,
// the BIN chunk kept as it is).
std::vector<unsigned char> with_json(const Document& d, std::string text) {
  if (!d.binary) return std::vector<unsigned char>(text.begin(), text.end());
  while (text.size() % 4) text += ' ';
  const size_t bin_at = d.json_offset + d.json_size;  // the BIN chunk's header, if any
  std::vector<unsigned char> out;
  auto put32 = [&](uint32_t v) {
    for (int k = 0; k < 4; ++k) out.push_back(static_cast<unsigned char>(v >> (8 * k)));
  };
  const size_t total = 12 + 8 + text.size() + (d.bytes.size() - bin_at);
  put32(0x46546C67u), put32(2), put32(uint32_t(total));
  put32(uint32_t(text.size())), put32(0x4E4F534Au);
  out.insert(out.end(), text.begin(), text.end());
  out.insert(out.end(), d.bytes.begin() + std::ptrdiff_t(bin_at), d.bytes.end());
  return out;
}

// What glTF allows but tinygltf 2.7 refuses, patched in the copy it parses; nothing patched
// is read from that copy (the views and accessors concerned are decoded instead):
//  - a buffer without data (a placeholder) would be refused, or in a .glb given the BIN
//    chunk: it gets three zero bytes;
//  - an indices accessor without a buffer view (a Draco-compressed primitive's) would be
//    refused: it gets a one-byte view of such a buffer.
// The patched JSON, or nothing when the document needs no patch (the usual case: no copy).
std::optional<json> patch_for_tinygltf(const Document& d) {
  std::vector<size_t> viewless;
  const json* meshes = member(d.json, "meshes");
  const json* accessors = member(d.json, "accessors");
  if (meshes && accessors)
    for (const json& mesh : *meshes) {
      const json* prims = member(mesh, "primitives");
      if (!prims) continue;
      for (const json& prim : *prims) {
        const json* ext = member(prim, "extensions");
        const json* idx = member(prim, "indices");
        if (!ext || !member(*ext, "KHR_draco_mesh_compression") || !idx || !idx->is_number_unsigned()) continue;
        const size_t a = idx->get<size_t>();
        if (a < accessors->size() && !member((*accessors)[a], "bufferView")) viewless.push_back(a);
      }
    }
  const bool placeholders = std::find(d.placeholder_buffers.begin(), d.placeholder_buffers.end(), true) != d.placeholder_buffers.end();
  if (!placeholders && viewless.empty()) return std::nullopt;
  const json kEmpty = {{"uri", "data:application/octet-stream;base64,AAAA"}, {"byteLength", 3}};
  json j = d.json;
  for (size_t i = 0; i < d.placeholder_buffers.size(); ++i)
    if (d.placeholder_buffers[i]) j["buffers"][i] = kEmpty;
  if (!viewless.empty()) {
    j["buffers"].push_back(kEmpty);
    j["bufferViews"].push_back({{"buffer", j["buffers"].size() - 1}, {"byteLength", 1}});
    for (size_t a : viewless) j["accessors"][a]["bufferView"] = j["bufferViews"].size() - 1;
  }
  return j;
}

}  // namespace

Document read_document(const fs::path& path) {
  Document d;
  d.file = path.string();
  d.bytes = read_file(d.file, path, "");
  std::error_code ec;
  d.folder = fs::canonical(fs::absolute(path, ec).parent_path(), ec);
  if (ec) throw InputError(d.file, "", "cannot resolve the scene's folder: " + ec.message());
  d.binary = d.bytes.size() >= 4 && std::memcmp(d.bytes.data(), "glTF", 4) == 0;
  if (!d.binary) {
    // A file that is neither binary glTF nor JSON is refused with what it is, not in the JSON
    // parser's words; JSON named .glb still loads.
    std::string ext = path.extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    const bool glb = ext == ".glb";
    const std::string what = stand_in(d.bytes);
    if (!what.empty())
      throw InputError(d.file, glb ? "glb header.magic" : "JSON",
                       what + (glb ? "; expected binary glTF, beginning with the 4 bytes \"glTF\"" : "; expected a glTF 2.0 JSON object"));
    size_t at = d.bytes.size() >= 3 && std::memcmp(d.bytes.data(), "\xEF\xBB\xBF", 3) == 0 ? 3 : 0;  // a UTF-8 byte-order mark
    while (at < d.bytes.size() && std::isspace(d.bytes[at])) ++at;
    if (glb && (at == d.bytes.size() || d.bytes[at] != '{')) {
      std::string begins;
      for (size_t i = 0; i < std::min<size_t>(d.bytes.size(), 4); ++i) {
        char c[8];
        std::snprintf(c, sizeof c, std::isprint(d.bytes[i]) ? "%c" : "\\x%02x", d.bytes[i]);
        begins += c;
      }
      throw InputError(d.file, "glb header.magic", "begins with \"" + begins + "\"; expected binary glTF, beginning with the 4 bytes \"glTF\"");
    }
  }
  if (d.binary) {
    read_glb_layout(d);
  } else {
    d.json_offset = 0;
    d.json_size = d.bytes.size();
  }
  std::string text(reinterpret_cast<const char*>(d.bytes.data()) + d.json_offset, d.json_size);
  if (const size_t replaced = repair_strings(text)) {
    d.strings_repaired = true;
    d.warnings.push_back("JSON: " + std::to_string(replaced) + " byte" + (replaced == 1 ? "" : "s") +
                         " in strings replaced by U+FFFD: not UTF-8, control characters or backslashes that start no escape; glTF's JSON is UTF-8");
  }
  // Depth-limited before tinygltf sees it: its conversion of `extras` recurses.
  d.json = parse_json(text, d.file);
  if (!d.json.is_object()) throw InputError(d.file, "JSON", "top level must be an object");
  const json* asset = member(d.json, "asset");
  const json* version = asset ? member(*asset, "version") : nullptr;
  if (!version || !version->is_string() || version->get<std::string>().rfind("2.", 0) != 0)
    throw InputError(d.file, "asset.version", std::string(version ? "is " + version->dump() : "missing") + "; expected \"2.0\"");
  check_extensions(d);
  Hasher hash;
  hash.add(d.bytes.data(), d.bytes.size());
  check_structure(d);
  check_binary_data(d, hash);
  d.content_hash = hash.hex();
  return d;
}

tinygltf::Model parse_model(Document& d) {
  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks(tinygltf::FsCallbacks{&fs_exists, &fs_expand, &fs_read, &fs_write, &d});
  loader.SetImageLoader(&stash_image, &d);
  tinygltf::Model model;
  std::string err, warn;
  const std::string base = d.folder.string();
  const std::vector<unsigned char>* bytes = &d.bytes;
  std::vector<unsigned char> rewritten;
  // Patched, or with its strings repaired: tinygltf parses the JSON giq parsed, not the file's.
  const std::optional<json> patched = patch_for_tinygltf(d);
  if (patched || d.strings_repaired) {
    rewritten = with_json(d, (patched ? *patched : d.json).dump());
    bytes = &rewritten;
  }
  const bool ok =
      d.binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, bytes->data(), unsigned(bytes->size()), base)
               : loader.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(bytes->data()),
                                            unsigned(bytes->size()), base);
  if (!ok) {
    std::string first = err.substr(0, err.find('\n'));
    if (first.empty()) first = "rejected by the glTF parser";
    throw InputError(d.file, "glTF", first);
  }
  d.encoded_images.resize(model.images.size());
  return model;
}

}  // namespace giq::scenes::gltf
