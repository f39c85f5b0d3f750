#pragma once
// Tangents for a normal-mapped primitive that has none. glTF 2.0 (3.7.2.1, "Meshes"): "When
// tangents are not specified, client implementations SHOULD calculate tangents using default
// MikkTSpace algorithms with the specified vertex positions, normals, and texture coordinates
// associated with the normal texture." Blender, Unity and Unreal do by default, and normal
// maps are baked in that space, so the reference and the real-time module must too: per-
// triangle dp/du frames would shade a curved, normal-mapped surface differently from the tool
// that baked the map and the engine that draws it. The rules are MikkTSpace's (Mikkelsen
// 2008, "Simulation of Wrinkled Surfaces Revisited", and the defaults of its reference
// implementation):
// - vertices equal in position, normal and texture coordinate are one vertex;
// - around each vertex, triangles form groups by walking across shared edges, only between
//   triangles whose UV mapping has the same orientation (so a mirrored UV seam splits);
// - a group's tangent is the sum of its triangles' dp/du directions projected into the
//   vertex's tangent plane, weighted by the triangle's angle at the vertex (measured in that
//   plane), normalised; triangles without UV area add nothing and take their orientation from
//   a neighbour.
// glTF's UV origin is the image's top-left corner (v runs down the image) while the normal
// map's +Y is up the image: the bitangent sign is +1 where the UV triangle winds clockwise
// (MikkTSpace's sign negated, as Blender's exporter and three.js do for glTF).

#include <glm/glm.hpp>
#include <cstdint>
#include <vector>

namespace giq::scenes {

struct GeneratedTangents {
  // One per vertex of the result: xyz unit, w the bitangent's sign (bitangent = w n x t).
  std::vector<glm::vec4> tangents;
  // Where a vertex's corners need different tangents (a mirrored seam), the vertex is split:
  // vertex i of the result is input vertex source[i]. The first n are the input's own, so a
  // mesh that needs no split keeps its indices.
  std::vector<uint32_t> source;
  std::vector<glm::uvec3> triangles;  // the input's, re-indexed
};

// `normals` unit (one per position), `uvs` the normal texture's mapping (one per position).
GeneratedTangents generate_tangents(const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& normals,
                                    const std::vector<glm::vec2>& uvs, const std::vector<glm::uvec3>& triangles);

}  // namespace giq::scenes
