#pragma once
// One glTF primitive as instanced by one node, flattened to triangles in the scene's local
// frame. Renderers read these arrays directly.

#include <glm/glm.hpp>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "giq/scenes/deformation.h"

namespace giq::scenes {

// The shape an emissive mesh declares for its light (extras.giq.area_light on the glTF mesh):
// real-time techniques then use that shape's representative point for glossy reflections
// (Scene::AreaLight, docs/scene-format.md). `Mesh`: none declared; the triangles themselves.
enum class AreaShape { Mesh, Sphere, Disc, Rectangle, Tube };
// The names the extras use: "mesh", "sphere", "disc", "rectangle", "tube".
inline constexpr const char* kAreaShapeNames[] = {"mesh", "sphere", "disc", "rectangle", "tube"};
inline const char* name(AreaShape s) { return kAreaShapeNames[int(s)]; }

struct Mesh {
  std::string name;  // the node's name (or "node<i>"), which leak regions refer to
  int node = -1;     // glTF node index
  int mesh = -1;     // glTF mesh index
  int primitive = 0;
  // Value of the `objectId` layer for this mesh's pixels: glTF node index + 1 (0 = no hit).
  uint32_t object_id = 0;
  int material = 0;  // index into Scene::materials (always valid; a default one is added)
  int emitter = -1;  // >= 0: the particles of Scene::emitters[emitter] in one stage of life (node -1)
  // A stage's particle count: six vertices and eight triangles each where the scene places
  // them, none where it only counts them (ParticleDetail::Counted).
  uint32_t particles = 0;
  // Particles: each vertex where it was one frame (1 / Sequence::fps) earlier, for motion
  // vectors, since a particle is not at the same vertex index from frame to frame; empty for
  // other meshes.
  std::vector<glm::vec3> previous_positions;
  AreaShape area_shape = AreaShape::Mesh;  // as declared on the glTF mesh

  std::vector<glm::vec3> positions;   // local frame
  std::vector<glm::vec3> normals;     // unit; flat normals generated when the file has none
  std::vector<glm::vec4> tangents;    // xyz unit, w = bitangent sign; empty when absent
  // Texture coordinates of the material's first and second mapping (TEXCOORD_n with
  // KHR_texture_transform applied; Material::uv2_slots says which textures read uvs2); empty
  // when absent.
  std::vector<glm::vec2> uvs, uvs2;
  std::vector<glm::vec4> colors;      // COLOR_0, linear RGBA multiplying the base colour; empty when absent
  std::vector<glm::uvec3> triangles;  // vertex indices; degenerate triangles removed
  // A skinned or morphing mesh: how its vertices are made from its rest pose at this instant
  // (deformation.h); empty for a rigid one.
  std::optional<Deformation> deformation;

  size_t triangle_count() const { return triangles.size(); }
  // Texture coordinates at barycentrics (b1, b2) of triangle t in the first or second mapping,
  // (0, 0) where the mesh has none; the GPU's triangle_uv interpolates the same way.
  glm::vec2 uv_at(const glm::uvec3& t, float b1, float b2, bool second = false) const {
    const std::vector<glm::vec2>& set = second ? uvs2 : uvs;
    if (set.empty()) return glm::vec2(0.0f);
    return (1.0f - b1 - b2) * set[t.x] + b1 * set[t.y] + b2 * set[t.z];
  }
  // COLOR_0 at barycentrics (b1, b2) of triangle t, white without vertex colours; the GPU's
  // triangle_color (realtime/shaders/textures.glsl) interpolates the same way.
  glm::vec4 color_at(const glm::uvec3& t, float b1, float b2) const {
    if (colors.empty()) return glm::vec4(1.0f);
    return (1.0f - b1 - b2) * colors[t.x] + b1 * colors[t.y] + b2 * colors[t.z];
  }
};

}  // namespace giq::scenes
