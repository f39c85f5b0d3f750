#pragma once
// Flat-shaded triangle meshes built from quads and boxes, in double precision until they are
// written. Every face gets its own vertices carrying the face's geometric normal, so a renderer
// that interpolates vertex normals still shades each face flat.

#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace giq::scenegen {

using Quad = std::array<glm::dvec3, 4>;

struct MeshData {
  std::vector<glm::dvec3> positions;
  std::vector<glm::dvec3> normals;  // unit
  std::vector<uint32_t> indices;    // triangles, counter-clockwise seen from the normal's side
  std::vector<glm::dvec2> uvs;      // TEXCOORD_0 per vertex, or empty

  size_t triangle_count() const { return indices.size() / 3; }
};

// Appends the quad a-b-c-d (a polygon in that cyclic order) facing `facing`: the winding is
// chosen so the geometric normal has a positive dot product with `facing`, which for a room seen
// from inside is a direction into the room and for a solid a direction out of it. A planar quad
// becomes 4 vertices and 2 triangles sharing its normal; a non-planar one (the published Cornell
// box has one) becomes two triangles of 3 vertices each, each with its own normal. Throws
// std::invalid_argument for a degenerate quad or a facing in the quad's plane.
void add_quad(MeshData& mesh, glm::dvec3 a, glm::dvec3 b, glm::dvec3 c, glm::dvec3 d,
              glm::dvec3 facing);

// Same, with the facing taken as the direction from the quad's centroid towards `inside`.
void add_quad_facing_point(MeshData& mesh, const Quad& quad, glm::dvec3 inside);

// Same, with the facing taken as the direction from `centre` to the quad's centroid (faces of a
// solid around `centre`).
void add_quad_away_from(MeshData& mesh, const Quad& quad, glm::dvec3 centre);

// Axis-aligned box [lo, hi] with its six faces facing outwards (a closed solid).
void add_box(MeshData& mesh, glm::dvec3 lo, glm::dvec3 hi);

// The six faces of the axis-aligned box [lo, hi] as unoriented quads, in the order
// y = lo (floor), y = hi (ceiling), x = lo, x = hi, z = lo, z = hi. Orient them with
// add_quad_facing_point (a room seen from inside) or add_quad_away_from (a solid).
enum BoxFace { kYLo = 0, kYHi, kXLo, kXHi, kZLo, kZHi };
std::array<Quad, 6> box_quads(glm::dvec3 lo, glm::dvec3 hi);

// The axis-aligned rectangle [lo, hi] with one coordinate equal in lo and hi (the plane it lies
// in), with the rectangle [hole_lo, hole_hi] (strictly inside, same plane) cut out, as four quads
// around the hole, facing `facing`.
void add_rect_with_hole(MeshData& mesh, glm::dvec3 lo, glm::dvec3 hi, glm::dvec3 hole_lo,
                        glm::dvec3 hole_hi, glm::dvec3 facing);

// Centroid of a quad's corners.
glm::dvec3 centroid(const Quad& quad);

}  // namespace giq::scenegen
