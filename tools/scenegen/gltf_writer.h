#pragma once
// A small glTF 2.0 writer for the built-in scenes: one self-contained .gltf with every byte of
// geometry, images and animation in one embedded base64 buffer, so any glTF viewer opens it as
// it is, or the same as one binary .glb (large scenes).
//
// Output is deterministic: the JSON keeps insertion order, numbers are single-precision floats
// printed in their shortest round-trip form (glTF 2.0 §3.6.2.5: float min/max "represent
// single precision floats"), the buffer is little-endian float32/uint16 data, and nothing
// depends on time, locale or addresses. Each bufferView holds one accessor, tightly packed and
// 4-byte aligned, so no byteStride is needed (§3.6.2.4: byteStride only when accessors share a
// vertex bufferView).

#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "geometry.h"

namespace giq::scenegen {

// JSON with insertion-ordered objects and float numbers, so every value is written exactly as a
// glTF reader will hold it.
using Json = nlohmann::basic_json<nlohmann::ordered_map, std::vector, std::string, bool,
                                  std::int64_t, std::uint64_t, float>;

// Node transform; the rotation is applied before the translation, as in glTF.
struct Pose {
  glm::dvec3 translation{0.0};
  glm::dquat rotation{1.0, 0.0, 0.0, 0.0};  // w, x, y, z
};

struct MaterialSpec {
  std::string name;
  glm::dvec3 base_color{1.0};
  double metallic = 0.0;
  double roughness = 1.0;
  // KHR_materials_specular specularFactor; 0 makes the material pure Lambert. Unset: the
  // extension is not written (glTF's default dielectric specular layer).
  std::optional<double> specular_factor;
  // Emitted radiance. Written as emissiveFactor normalised to a maximum of 1 times
  // KHR_materials_emissive_strength (the maximum), since emissiveFactor is limited to [0, 1].
  glm::dvec3 emission{0.0};
  // Textures (GltfWriter::add_texture) read through TEXCOORD_0; -1 = none.
  int base_color_texture = -1, metallic_roughness_texture = -1, normal_texture = -1;
  bool double_sided = false;
};

enum class LightKind { Directional, Point };

struct LightSpec {
  std::string name;
  LightKind kind = LightKind::Point;
  glm::dvec3 color{1.0};
  double intensity = 1.0;  // W/sr (point) or W/m^2 (directional), as giq reads them
};

// A view as written to extras.giq.views (or as a camera node).
struct ViewSpec {
  std::string name;
  glm::dvec3 eye{0.0};
  glm::dvec3 target{0.0, 0.0, -1.0};
  glm::dvec3 up{0.0, 1.0, 0.0};
  double yfov_deg = 45.0;
};

enum class Interpolation { Linear, Step };

// One animated translation: node, key times (seconds, increasing) and values.
struct TranslationTrack {
  int node = -1;
  Interpolation interpolation = Interpolation::Linear;
  std::vector<double> times;
  std::vector<glm::dvec3> values;
};

// One animated rotation (LINEAR keys are interpolated by slerp, glTF 2.0 Appendix C).
struct RotationTrack {
  int node = -1;
  Interpolation interpolation = Interpolation::Linear;
  std::vector<double> times;
  std::vector<glm::dquat> values;
};

// Joint influences of a skinned mesh, per vertex: four indices into the skin's joint list and
// their weights (non-negative, summing to 1; unused slots weigh 0).
struct SkinWeights {
  std::vector<std::array<uint8_t, 4>> joints;
  std::vector<glm::dvec4> weights;
};

// A particle emitter as extras.giq.emitters declares it (docs/scene-format.md); the node is
// named, the emitting surface is its mesh.
struct EmitterSpec {
  std::string name, node;
  double rate = 1.0, lifetime = 1.0, speed = 0.0, spread_deg = 0.0;
  glm::dvec3 gravity{0.0, -9.81, 0.0};
  double drag = 0.0, size = 0.01;
  glm::dvec3 color{1.0}, emission{0.0};
  std::vector<glm::dvec2> strength;  // (life fraction, strength) keys
  int stages = 8;
  uint32_t seed = 0;
};

// What the documentation says about a mesh node (filled as nodes are added).
struct NodeFacts {
  std::string name;
  std::string material;
  size_t triangles = 0;
  glm::dvec3 world_lo{0.0}, world_hi{0.0};  // bounds at rest, after the node's pose
};

struct LightFacts {
  LightSpec spec;
  glm::dvec3 position{0.0};   // world, at rest (t = 0 before any animation)
  glm::dvec3 direction{0.0};  // world direction the light travels (directional lights)
};

class GltfWriter {
 public:
  int add_material(const MaterialSpec& spec);
  // An 8-bit RGBA image (rows top first) stored in the buffer as a PNG, sampled bilinearly
  // with REPEAT wrapping; returns the texture index.
  int add_texture(const std::string& name, int width, int height, const std::vector<uint8_t>& rgba);
  // A node with its own mesh (named like the node) of one triangle primitive.
  int add_mesh_node(const std::string& name, const MeshData& mesh, int material,
                    const Pose& pose = {});
  // A perspective camera node looking from eye to target (glTF cameras look along local -Z).
  int add_camera_node(const ViewSpec& view, double aspect_ratio, double znear);
  // A KHR_lights_punctual light on a node; a directional light shines along the node's -Z.
  int add_light_node(const LightSpec& light, const Pose& pose, int parent = -1);
  // A node that only carries a transform (to be animated, with children).
  int add_group_node(const std::string& name, const Pose& pose, int parent = -1);
  // One glTF animation with one translation channel per translation track and one rotation
  // channel per rotation track.
  int add_animation(const std::string& name, const std::vector<TranslationTrack>& tracks,
                    const std::vector<RotationTrack>& rotations = {});
  // A skin over these joint nodes (glTF 2.0 §3.7.3): each joint's inverse bind matrix is the
  // inverse of its world transform at rest, so a mesh written in world coordinates at rest is
  // its own bind pose.
  int add_skin(const std::string& name, const std::vector<int>& joints);
  // A node with a skinned mesh (world coordinates at rest) of one triangle primitive.
  int add_skinned_mesh_node(const std::string& name, const MeshData& mesh,
                            const SkinWeights& weights, int material, int skin);
  // meshes[].extras.giq.area_light of a mesh node's mesh: "sphere", "disc", "rectangle", "tube".
  void declare_area_light(int node, const std::string& shape);

  // extras.giq
  void add_view(const ViewSpec& view);
  // The windows, where given, are extras.giq.sequence's step_frame, flicker_frames and
  // lag_frames (docs/scene-format.md).
  struct MeasurementWindows {
    int step_frame = 0;
    std::pair<int, int> flicker_frames, lag_frames;
  };
  void set_sequence(int frames, double fps, int animation, std::optional<MeasurementWindows> windows = std::nullopt);
  void add_leak_region(const std::string& node_name);
  void add_emitter(const EmitterSpec& emitter);

  // The finished document (validates names first; throws std::logic_error on a broken scene).
  std::string dump() const;
  // The same as a binary glTF (glTF 2.0 §4.4: JSON chunk, BIN chunk holding the buffer).
  std::vector<uint8_t> dump_glb() const;

  const std::vector<NodeFacts>& node_facts() const { return facts_; }
  const std::vector<MaterialSpec>& material_specs() const { return material_specs_; }
  const std::vector<LightFacts>& light_facts() const { return light_facts_; }
  const std::vector<ViewSpec>& camera_views() const { return camera_views_; }
  const std::vector<ViewSpec>& extra_views() const { return extra_views_; }
  const std::vector<std::string>& leak_regions() const { return leak_regions_; }
  const std::vector<EmitterSpec>& emitters() const { return emitters_; }
  int sequence_frames() const { return sequence_ ? (*sequence_)["frames"].get<int>() : 1; }
  double sequence_fps() const { return sequence_ ? (*sequence_)["fps"].get<double>() : 0.0; }
  const std::optional<MeasurementWindows>& sequence_windows() const { return windows_; }

 private:
  // Appends bytes to the buffer as one 4-byte aligned bufferView; returns its index.
  int add_buffer_view(const void* data, size_t bytes, std::optional<int> target);
  int add_accessor(const void* data, size_t bytes, int component_type, size_t count,
                   const char* type, std::optional<int> target, Json min = {}, Json max = {});
  int add_vec3_accessor(const std::vector<glm::dvec3>& values, std::optional<int> target,
                        bool bounds);
  int add_node(Json node, int parent, const Pose& pose);
  // The mesh of one triangle primitive with these extra attributes, its facts recorded.
  int add_mesh(const std::string& name, const MeshData& mesh, int material, const Pose& pose,
               Json extra_attributes);
  Json document(const std::string* buffer_uri) const;

  std::vector<uint8_t> buffer_;
  std::vector<Json> buffer_views_, accessors_, meshes_, materials_, nodes_, cameras_, lights_,
      animations_, images_, textures_, skins_;
  std::vector<int> roots_;
  std::set<std::string> extensions_;
  std::vector<NodeFacts> facts_;
  std::vector<MaterialSpec> material_specs_;
  std::vector<LightFacts> light_facts_;
  std::vector<Pose> world_poses_;  // per node, at rest
  std::vector<ViewSpec> camera_views_, extra_views_;
  std::vector<std::string> leak_regions_;
  std::vector<EmitterSpec> emitters_;
  std::optional<Json> sequence_;
  std::optional<MeasurementWindows> windows_;
};

// Quaternion turning glTF's camera frame (looking along -Z, up +Y) to look from eye to target.
glm::dquat look_rotation(glm::dvec3 eye, glm::dvec3 target, glm::dvec3 up);
// Quaternion turning -Z (the direction a glTF directional light shines) onto `direction`.
glm::dquat rotation_from_minus_z(glm::dvec3 direction);

}  // namespace giq::scenegen
