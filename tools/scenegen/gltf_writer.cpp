#include "gltf_writer.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>
#include <zlib.h>

#include "giq/base/frames.h"

namespace giq::scenegen {
namespace {

static_assert(std::endian::native == std::endian::little,
              "glTF buffers are little-endian; this writer copies native floats");

// glTF 2.0 §5.1.3 / §5.12 constants.
constexpr int kFloat = 5126;
constexpr int kUnsignedByte = 5121;
constexpr int kUnsignedShort = 5123;
constexpr int kUnsignedInt = 5125;
constexpr int kArrayBuffer = 34962;
constexpr int kElementArrayBuffer = 34963;

constexpr const char* kLightsPunctual = "KHR_lights_punctual";
constexpr const char* kEmissiveStrength = "KHR_materials_emissive_strength";
constexpr const char* kSpecular = "KHR_materials_specular";

// Values this close to zero are rounding noise of the double-precision construction (a
// quaternion's 1e-17); writing them as 0 keeps the files readable and the same everywhere.
float clean(double v) {
  if (std::abs(v) < 1e-12) return 0.0f;
  return static_cast<float>(v);
}

Json vec3(glm::dvec3 v) {
  return Json::array({clean(v.x), clean(v.y), clean(v.z)});
}

std::string base64(const std::vector<uint8_t>& bytes) {
  // RFC 4648 §4, with padding: the encoding data URIs use (RFC 2397).
  static constexpr char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const size_t n = std::min<size_t>(3, bytes.size() - i);
    uint32_t chunk = uint32_t(bytes[i]) << 16;
    if (n > 1) chunk |= uint32_t(bytes[i + 1]) << 8;
    if (n > 2) chunk |= uint32_t(bytes[i + 2]);
    out += kAlphabet[(chunk >> 18) & 63];
    out += kAlphabet[(chunk >> 12) & 63];
    out += n > 1 ? kAlphabet[(chunk >> 6) & 63] : '=';
    out += n > 2 ? kAlphabet[chunk & 63] : '=';
  }
  return out;
}

glm::dquat canonical(glm::dquat q) {
  q = glm::normalize(q);
  return q.w < 0.0 ? -q : q;
}

void write_pose(Json& node, const Pose& pose) {
  const glm::dquat q = canonical(pose.rotation);
  if (!(q.x == 0.0 && q.y == 0.0 && q.z == 0.0))
    node["rotation"] = Json::array({clean(q.x), clean(q.y), clean(q.z), clean(q.w)});
  if (pose.translation != glm::dvec3(0.0)) node["translation"] = vec3(pose.translation);
}

Json view_json(const ViewSpec& v) {
  Json j;
  j["name"] = v.name;
  j["eye"] = vec3(v.eye);
  j["target"] = vec3(v.target);
  j["up"] = vec3(v.up);
  j["yfov_deg"] = clean(v.yfov_deg);
  return j;
}

// An 8-bit RGBA PNG (ISO/IEC 15948): signature, IHDR, one IDAT of rows with the Sub filter
// (as encoders commonly choose for photographs and gradients), IEND.
std::vector<uint8_t> encode_png(int width, int height, const std::vector<uint8_t>& rgba) {
  const size_t row = size_t(width) * 4;
  std::vector<uint8_t> raw;
  raw.reserve(size_t(height) * (row + 1));
  for (int y = 0; y < height; ++y) {
    const uint8_t* r = rgba.data() + size_t(y) * row;
    raw.push_back(1);  // Sub: each byte minus the byte 4 to its left
    for (size_t i = 0; i < row; ++i) raw.push_back(uint8_t(r[i] - (i >= 4 ? r[i - 4] : 0)));
  }
  uLongf packed_size = compressBound(uLong(raw.size()));
  std::vector<uint8_t> packed(packed_size);
  if (compress2(packed.data(), &packed_size, raw.data(), uLong(raw.size()), 6) != Z_OK) throw std::runtime_error("zlib failed");
  packed.resize(packed_size);
  std::vector<uint8_t> out = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  auto be32 = [&](uint32_t v) {
    for (int k = 3; k >= 0; --k) out.push_back(uint8_t(v >> (8 * k)));
  };
  auto chunk = [&](const char* type, const std::vector<uint8_t>& data) {
    be32(uint32_t(data.size()));
    const size_t start = out.size();
    out.insert(out.end(), type, type + 4);
    out.insert(out.end(), data.begin(), data.end());
    be32(uint32_t(crc32(0, out.data() + start, uInt(out.size() - start))));
  };
  std::vector<uint8_t> ihdr;
  for (uint32_t v : {uint32_t(width), uint32_t(height)})
    for (int k = 3; k >= 0; --k) ihdr.push_back(uint8_t(v >> (8 * k)));
  ihdr.insert(ihdr.end(), {8, 6, 0, 0, 0});  // 8-bit RGBA, deflate, adaptive filtering, no interlace
  chunk("IHDR", ihdr);
  chunk("IDAT", packed);
  chunk("IEND", {});
  return out;
}

}  // namespace

glm::dquat look_rotation(glm::dvec3 eye, glm::dvec3 target, glm::dvec3 up) {
  const glm::dvec3 f = glm::normalize(target - eye);
  const glm::dvec3 r = glm::normalize(glm::cross(f, up));
  const glm::dvec3 u = glm::cross(r, f);
  // Columns: where the camera's local +X, +Y and +Z go (glTF 2.0 §3.10.3: the camera looks
  // along its local -Z with +Y up).
  return canonical(glm::quat_cast(glm::dmat3(r, u, -f)));
}

glm::dquat rotation_from_minus_z(glm::dvec3 direction) {
  const glm::dvec3 a(0.0, 0.0, -1.0);
  const glm::dvec3 b = glm::normalize(direction);
  const double c = glm::dot(a, b);
  if (c < -1.0 + 1e-9) return {0.0, 1.0, 0.0, 0.0};  // half turn about +Y
  // Half-way quaternion: (1 + a.b, a x b), normalised, rotates a onto b.
  const glm::dvec3 axis = glm::cross(a, b);
  return canonical(glm::dquat(1.0 + c, axis.x, axis.y, axis.z));
}

int GltfWriter::add_buffer_view(const void* data, size_t bytes, std::optional<int> target) {
  // glTF 2.0 §3.6.2.4: an accessor's offset must be a multiple of its component size; 4-byte
  // aligned views satisfy every component type used here.
  while (buffer_.size() % 4 != 0) buffer_.push_back(0);
  Json view;
  view["buffer"] = 0;
  view["byteOffset"] = buffer_.size();
  view["byteLength"] = bytes;
  if (target) view["target"] = *target;
  const auto* p = static_cast<const uint8_t*>(data);
  buffer_.insert(buffer_.end(), p, p + bytes);
  buffer_views_.push_back(std::move(view));
  return static_cast<int>(buffer_views_.size() - 1);
}

int GltfWriter::add_accessor(const void* data, size_t bytes, int component_type, size_t count,
                             const char* type, std::optional<int> target, Json min, Json max) {
  Json acc;
  acc["bufferView"] = add_buffer_view(data, bytes, target);
  acc["componentType"] = component_type;
  acc["count"] = count;
  acc["type"] = type;
  if (!min.is_null()) acc["min"] = std::move(min);
  if (!max.is_null()) acc["max"] = std::move(max);
  accessors_.push_back(std::move(acc));
  return static_cast<int>(accessors_.size() - 1);
}

int GltfWriter::add_vec3_accessor(const std::vector<glm::dvec3>& values, std::optional<int> target,
                                  bool bounds) {
  std::vector<float> data;
  data.reserve(values.size() * 3);
  glm::vec3 lo(std::numeric_limits<float>::infinity()), hi(-lo);
  for (const glm::dvec3& v : values) {
    const glm::vec3 f(clean(v.x), clean(v.y), clean(v.z));
    data.insert(data.end(), {f.x, f.y, f.z});
    lo = glm::min(lo, f);
    hi = glm::max(hi, f);
  }
  Json min, max;
  // Bounds of the float data as stored, so they match it exactly (§3.6.2.5).
  if (bounds) {
    min = Json::array({lo.x, lo.y, lo.z});
    max = Json::array({hi.x, hi.y, hi.z});
  }
  return add_accessor(data.data(), data.size() * sizeof(float), kFloat, values.size(), "VEC3",
                      target, std::move(min), std::move(max));
}

int GltfWriter::add_material(const MaterialSpec& spec) {
  Json m;
  m["name"] = spec.name;
  Json pbr;
  pbr["baseColorFactor"] = Json::array(
      {clean(spec.base_color.r), clean(spec.base_color.g), clean(spec.base_color.b), 1.0f});
  pbr["metallicFactor"] = clean(spec.metallic);
  pbr["roughnessFactor"] = clean(spec.roughness);
  if (spec.base_color_texture >= 0) pbr["baseColorTexture"] = {{"index", spec.base_color_texture}};
  if (spec.metallic_roughness_texture >= 0) pbr["metallicRoughnessTexture"] = {{"index", spec.metallic_roughness_texture}};
  m["pbrMetallicRoughness"] = std::move(pbr);
  if (spec.normal_texture >= 0) m["normalTexture"] = {{"index", spec.normal_texture}};
  if (spec.double_sided) m["doubleSided"] = true;
  Json ext = Json::object();
  const double peak = std::max({spec.emission.r, spec.emission.g, spec.emission.b});
  if (peak > 0.0) {
    if (peak > 1.0) {
      m["emissiveFactor"] = vec3(spec.emission / peak);
      ext[kEmissiveStrength] = {{"emissiveStrength", clean(peak)}};
      extensions_.insert(kEmissiveStrength);
    } else {
      m["emissiveFactor"] = vec3(spec.emission);
    }
  }
  if (spec.specular_factor) {
    ext[kSpecular] = {{"specularFactor", clean(*spec.specular_factor)}};
    extensions_.insert(kSpecular);
  }
  if (!ext.empty()) m["extensions"] = std::move(ext);
  materials_.push_back(std::move(m));
  material_specs_.push_back(spec);
  return static_cast<int>(materials_.size() - 1);
}

int GltfWriter::add_texture(const std::string& name, int width, int height, const std::vector<uint8_t>& rgba) {
  if (width < 1 || height < 1 || rgba.size() != size_t(width) * size_t(height) * 4)
    throw std::logic_error(name + ": texel count does not match the size");
  const std::vector<uint8_t> png = encode_png(width, height, rgba);
  Json image;
  image["name"] = name;
  image["bufferView"] = add_buffer_view(png.data(), png.size(), std::nullopt);
  image["mimeType"] = "image/png";
  images_.push_back(std::move(image));
  Json texture;
  texture["sampler"] = 0;
  texture["source"] = images_.size() - 1;
  textures_.push_back(std::move(texture));
  return static_cast<int>(textures_.size() - 1);
}

int GltfWriter::add_node(Json node, int parent, const Pose& pose) {
  Pose world = pose;
  if (parent >= 0) {
    const Pose& p = world_poses_.at(parent);
    world = {p.rotation * pose.translation + p.translation, p.rotation * pose.rotation};
  }
  world_poses_.push_back(world);
  nodes_.push_back(std::move(node));
  const int index = static_cast<int>(nodes_.size() - 1);
  if (parent < 0) {
    roots_.push_back(index);
  } else {
    nodes_.at(parent)["children"].push_back(index);
  }
  return index;
}

int GltfWriter::add_mesh(const std::string& name, const MeshData& mesh, int material,
                         const Pose& pose, Json extra_attributes) {
  if (mesh.positions.empty()) throw std::logic_error(name + ": no vertices");
  if (!mesh.uvs.empty() && mesh.uvs.size() != mesh.positions.size()) throw std::logic_error(name + ": one UV a vertex");
  Json attributes;
  attributes["POSITION"] = add_vec3_accessor(mesh.positions, kArrayBuffer, true);
  attributes["NORMAL"] = add_vec3_accessor(mesh.normals, kArrayBuffer, false);
  if (!mesh.uvs.empty()) {
    std::vector<float> uv;
    for (const glm::dvec2& t : mesh.uvs) uv.insert(uv.end(), {clean(t.x), clean(t.y)});
    attributes["TEXCOORD_0"] = add_accessor(uv.data(), uv.size() * sizeof(float), kFloat, mesh.uvs.size(), "VEC2", kArrayBuffer);
  }
  for (auto& [key, value] : extra_attributes.items()) attributes[key] = value;
  // 16-bit indices where they suffice (the small built-in scenes), 32-bit otherwise.
  int index_accessor;
  if (mesh.positions.size() <= 65535) {
    const std::vector<uint16_t> indices(mesh.indices.begin(), mesh.indices.end());
    index_accessor = add_accessor(indices.data(), indices.size() * sizeof(uint16_t), kUnsignedShort, indices.size(), "SCALAR",
                                  kElementArrayBuffer);
  } else {
    index_accessor = add_accessor(mesh.indices.data(), mesh.indices.size() * sizeof(uint32_t), kUnsignedInt, mesh.indices.size(),
                                  "SCALAR", kElementArrayBuffer);
  }
  Json primitive;
  primitive["attributes"] = std::move(attributes);
  primitive["indices"] = index_accessor;
  primitive["material"] = material;
  Json m;
  m["name"] = name;
  m["primitives"] = Json::array({std::move(primitive)});
  meshes_.push_back(std::move(m));

  NodeFacts facts;
  facts.name = name;
  facts.material = materials_.at(material)["name"].get<std::string>();
  facts.triangles = mesh.triangle_count();
  facts.world_lo = glm::dvec3(std::numeric_limits<double>::infinity());
  facts.world_hi = -facts.world_lo;
  for (const glm::dvec3& p : mesh.positions) {
    const glm::dvec3 w = pose.rotation * p + pose.translation;
    facts.world_lo = glm::min(facts.world_lo, w);
    facts.world_hi = glm::max(facts.world_hi, w);
  }
  facts_.push_back(facts);
  return static_cast<int>(meshes_.size() - 1);
}

int GltfWriter::add_mesh_node(const std::string& name, const MeshData& mesh, int material,
                              const Pose& pose) {
  Json node;
  node["name"] = name;
  node["mesh"] = add_mesh(name, mesh, material, pose, Json::object());
  write_pose(node, pose);
  return add_node(std::move(node), -1, pose);
}

int GltfWriter::add_skinned_mesh_node(const std::string& name, const MeshData& mesh,
                                      const SkinWeights& weights, int material, int skin) {
  const size_t n = mesh.positions.size();
  if (weights.joints.size() != n || weights.weights.size() != n)
    throw std::logic_error(name + ": one joint set and one weight set a vertex");
  const size_t joint_count = skins_.at(skin)["joints"].size();
  std::vector<uint8_t> joints;
  std::vector<float> w;
  for (size_t v = 0; v < n; ++v) {
    const glm::dvec4& wv = weights.weights[v];
    if (std::abs(wv.x + wv.y + wv.z + wv.w - 1.0) > 1e-9 || glm::any(glm::lessThan(wv, glm::dvec4(0.0))))
      throw std::logic_error(name + ": weights must be non-negative and sum to 1");
    for (int k = 0; k < 4; ++k) {
      if (weights.joints[v][k] >= joint_count) throw std::logic_error(name + ": joint index beyond the skin");
      joints.push_back(weights.joints[v][k]);
      w.push_back(clean(wv[k]));
    }
  }
  Json attributes;
  attributes["JOINTS_0"] = add_accessor(joints.data(), joints.size(), kUnsignedByte, n, "VEC4", kArrayBuffer);
  attributes["WEIGHTS_0"] = add_accessor(w.data(), w.size() * sizeof(float), kFloat, n, "VEC4", kArrayBuffer);
  Json node;
  node["name"] = name;
  node["mesh"] = add_mesh(name, mesh, material, {}, std::move(attributes));
  node["skin"] = skin;
  return add_node(std::move(node), -1, {});
}

int GltfWriter::add_skin(const std::string& name, const std::vector<int>& joints) {
  if (joints.empty() || joints.size() > 256) throw std::logic_error(name + ": 1 to 256 joints");
  std::vector<float> inverse_bind;
  for (int j : joints) {
    const Pose& world = world_poses_.at(j);
    const glm::dmat4 m = glm::inverse(glm::translate(glm::dmat4(1.0), world.translation) * glm::mat4_cast(world.rotation));
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) inverse_bind.push_back(clean(m[c][r]));  // column-major (§3.6.2.2)
  }
  Json skin;
  skin["name"] = name;
  skin["inverseBindMatrices"] =
      add_accessor(inverse_bind.data(), inverse_bind.size() * sizeof(float), kFloat, joints.size(), "MAT4", std::nullopt);
  skin["skeleton"] = joints.front();
  skin["joints"] = joints;
  skins_.push_back(std::move(skin));
  return static_cast<int>(skins_.size() - 1);
}

void GltfWriter::declare_area_light(int node, const std::string& shape) {
  if (shape != "sphere" && shape != "disc" && shape != "rectangle" && shape != "tube")
    throw std::logic_error("area light shape " + shape);
  meshes_.at(nodes_.at(node).at("mesh").get<size_t>())["extras"] = {{"giq", {{"area_light", shape}}}};
}

int GltfWriter::add_camera_node(const ViewSpec& view, double aspect_ratio, double znear) {
  Json perspective;
  perspective["aspectRatio"] = clean(aspect_ratio);
  perspective["yfov"] = clean(glm::radians(view.yfov_deg));
  perspective["znear"] = clean(znear);
  Json camera;
  camera["name"] = view.name;
  camera["type"] = "perspective";
  camera["perspective"] = std::move(perspective);
  cameras_.push_back(std::move(camera));

  Json node;
  node["name"] = view.name;
  node["camera"] = cameras_.size() - 1;
  const Pose pose{view.eye, look_rotation(view.eye, view.target, view.up)};
  write_pose(node, pose);
  camera_views_.push_back(view);
  return add_node(std::move(node), -1, pose);
}

int GltfWriter::add_light_node(const LightSpec& light, const Pose& pose, int parent) {
  Json l;
  l["name"] = light.name;
  l["type"] = light.kind == LightKind::Point ? "point" : "directional";
  l["color"] = vec3(light.color);
  l["intensity"] = clean(light.intensity);
  lights_.push_back(std::move(l));
  extensions_.insert(kLightsPunctual);

  Json node;
  node["name"] = light.name;
  write_pose(node, pose);
  node["extensions"] = {{kLightsPunctual, {{"light", lights_.size() - 1}}}};
  const int index = add_node(std::move(node), parent, pose);
  const Pose& world = world_poses_.back();
  light_facts_.push_back({light, world.translation, world.rotation * glm::dvec3(0.0, 0.0, -1.0)});
  return index;
}

int GltfWriter::add_group_node(const std::string& name, const Pose& pose, int parent) {
  Json node;
  node["name"] = name;
  write_pose(node, pose);
  return add_node(std::move(node), parent, pose);
}

int GltfWriter::add_animation(const std::string& name,
                              const std::vector<TranslationTrack>& tracks,
                              const std::vector<RotationTrack>& rotations) {
  Json samplers = Json::array(), channels = Json::array();
  // The key times' accessor first, then the values', as each channel is added.
  auto input = [&](const std::vector<double>& key_times, size_t values) {
    if (key_times.empty() || key_times.size() != values ||
        !std::is_sorted(key_times.begin(), key_times.end(), std::less_equal<double>()))
      throw std::logic_error(name + ": key times must be strictly increasing, one per value");
    std::vector<float> times;
    for (double t : key_times) times.push_back(clean(t));
    // §3.11: sampler input accessors must declare min and max.
    return add_accessor(times.data(), times.size() * sizeof(float), kFloat, times.size(), "SCALAR", std::nullopt,
                        Json::array({times.front()}), Json::array({times.back()}));
  };
  auto channel = [&](int node, int input_accessor, Interpolation interpolation, const char* path, int output) {
    Json sampler;
    sampler["input"] = input_accessor;
    sampler["interpolation"] = interpolation == Interpolation::Linear ? "LINEAR" : "STEP";
    sampler["output"] = output;
    Json c;
    c["sampler"] = samplers.size();
    c["target"] = {{"node", node}, {"path", path}};
    samplers.push_back(std::move(sampler));
    channels.push_back(std::move(c));
  };
  for (const TranslationTrack& track : tracks) {
    const int times = input(track.times, track.values.size());
    channel(track.node, times, track.interpolation, "translation", add_vec3_accessor(track.values, std::nullopt, false));
  }
  for (const RotationTrack& track : rotations) {
    const int times = input(track.times, track.values.size());
    // Each key in the hemisphere of the one before, so slerp turns the short way between them
    // in every reader (q and -q are the same rotation).
    std::vector<float> q;
    glm::dquat previous(1.0, 0.0, 0.0, 0.0);
    for (glm::dquat v : track.values) {
      v = glm::normalize(v);
      if (glm::dot(v, previous) < 0.0) v = -v;
      previous = v;
      q.insert(q.end(), {clean(v.x), clean(v.y), clean(v.z), clean(v.w)});
    }
    channel(track.node, times, track.interpolation, "rotation",
            add_accessor(q.data(), q.size() * sizeof(float), kFloat, track.values.size(), "VEC4", std::nullopt));
  }
  Json animation;
  animation["name"] = name;
  animation["channels"] = std::move(channels);
  animation["samplers"] = std::move(samplers);
  animations_.push_back(std::move(animation));
  return static_cast<int>(animations_.size() - 1);
}

void GltfWriter::add_view(const ViewSpec& view) {
  extra_views_.push_back(view);
}

void GltfWriter::set_sequence(int frames, double fps, int animation, std::optional<MeasurementWindows> windows) {
  Json s;
  s["frames"] = frames;
  s["fps"] = clean(fps);
  s["animation"] = animation;
  if (windows) {
    s["step_frame"] = windows->step_frame;
    s["flicker_frames"] = frame_range(windows->flicker_frames.first, windows->flicker_frames.second);
    s["lag_frames"] = frame_range(windows->lag_frames.first, windows->lag_frames.second);
  }
  sequence_ = std::move(s);
  windows_ = windows;
}

void GltfWriter::add_leak_region(const std::string& node_name) {
  leak_regions_.push_back(node_name);
}

void GltfWriter::add_emitter(const EmitterSpec& emitter) {
  emitters_.push_back(emitter);
}

Json GltfWriter::document(const std::string* buffer_uri) const {
  std::set<std::string> node_names, view_names;
  for (const Json& n : nodes_)
    if (!node_names.insert(n["name"].get<std::string>()).second)
      throw std::logic_error("duplicate node name " + n["name"].get<std::string>());
  for (const auto* views : {&camera_views_, &extra_views_})
    for (const ViewSpec& v : *views)
      if (!view_names.insert(v.name).second) throw std::logic_error("duplicate view " + v.name);
  for (const std::string& r : leak_regions_)
    if (!node_names.count(r)) throw std::logic_error("leak region names no node: " + r);

  Json doc;
  doc["asset"] = {{"version", "2.0"}, {"generator", "giq-scenegen"}};
  if (!extensions_.empty()) doc["extensionsUsed"] = extensions_;
  if (!lights_.empty()) doc["extensions"] = {{kLightsPunctual, {{"lights", lights_}}}};

  Json giq = Json::object();
  if (!extra_views_.empty()) {
    giq["views"] = Json::array();
    for (const ViewSpec& v : extra_views_) giq["views"].push_back(view_json(v));
  }
  if (sequence_) giq["sequence"] = *sequence_;
  if (!leak_regions_.empty()) giq["leak_regions"] = leak_regions_;
  for (const EmitterSpec& e : emitters_) {
    if (!node_names.count(e.node)) throw std::logic_error("emitter on no node: " + e.node);
    Json j;
    j["name"] = e.name;
    j["node"] = e.node;
    j["rate"] = clean(e.rate);
    j["lifetime"] = clean(e.lifetime);
    j["speed"] = clean(e.speed);
    j["spread_deg"] = clean(e.spread_deg);
    j["gravity"] = vec3(e.gravity);
    j["drag"] = clean(e.drag);
    j["size"] = clean(e.size);
    j["color"] = vec3(e.color);
    j["emission"] = vec3(e.emission);
    if (!e.strength.empty()) {
      j["strength"] = Json::array();
      for (glm::dvec2 k : e.strength) j["strength"].push_back(Json::array({clean(k.x), clean(k.y)}));
    }
    j["stages"] = e.stages;
    j["seed"] = e.seed;
    giq["emitters"].push_back(std::move(j));
  }
  doc["extras"] = {{"giq", std::move(giq)}};

  doc["scene"] = 0;
  doc["scenes"] = Json::array({{{"nodes", roots_}}});
  doc["nodes"] = nodes_;
  // glTF arrays must not be empty when present (minItems 1): write only what the scene has.
  if (!meshes_.empty()) doc["meshes"] = meshes_;
  if (!materials_.empty()) doc["materials"] = materials_;
  if (!cameras_.empty()) doc["cameras"] = cameras_;
  if (!animations_.empty()) doc["animations"] = animations_;
  if (!skins_.empty()) doc["skins"] = skins_;
  if (!images_.empty()) {
    doc["images"] = images_;
    doc["textures"] = textures_;
    doc["samplers"] = Json::array({{{"magFilter", 9729}, {"minFilter", 9987}, {"wrapS", 10497}, {"wrapT", 10497}}});
  }
  doc["accessors"] = accessors_;
  doc["bufferViews"] = buffer_views_;
  Json buffer = {{"byteLength", buffer_.size()}};
  if (buffer_uri) buffer["uri"] = *buffer_uri;
  doc["buffers"] = Json::array({std::move(buffer)});
  return doc;
}

std::string GltfWriter::dump() const {
  const std::string uri = "data:application/octet-stream;base64," + base64(buffer_);
  return document(&uri).dump(2) + "\n";
}

std::vector<uint8_t> GltfWriter::dump_glb() const {
  std::string json = document(nullptr).dump();
  while (json.size() % 4) json += ' ';  // §4.4.3.1: the JSON chunk is padded with spaces
  std::vector<uint8_t> bin = buffer_;
  while (bin.size() % 4) bin.push_back(0);
  std::vector<uint8_t> out;
  auto le32 = [&](uint32_t v) {
    for (int k = 0; k < 4; ++k) out.push_back(uint8_t(v >> (8 * k)));
  };
  le32(0x46546C67);  // "glTF"
  le32(2);
  le32(uint32_t(12 + 8 + json.size() + 8 + bin.size()));
  le32(uint32_t(json.size()));
  le32(0x4E4F534A);  // "JSON"
  out.insert(out.end(), json.begin(), json.end());
  le32(uint32_t(bin.size()));
  le32(0x004E4942);  // "BIN"
  out.insert(out.end(), bin.begin(), bin.end());
  return out;
}

}  // namespace giq::scenegen
