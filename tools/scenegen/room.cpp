#include "room.h"

namespace giq::scenegen {

void add_room(GltfWriter& gltf, const std::string& prefix, glm::dvec3 lo, glm::dvec3 hi,
              BoxFace shared, int walls, int floor) {
  const glm::dvec3 inside = (lo + hi) * 0.5;
  const std::array<Quad, 6> q = box_quads(lo, hi);
  auto face = [&](BoxFace f, const std::string& name, int material) {
    MeshData m;
    add_quad_facing_point(m, q[f], inside);
    gltf.add_mesh_node(prefix + "_" + name, m, material);
  };
  face(kYLo, "floor", floor);
  face(kYHi, "ceiling", walls);
  face(kZLo, "front_wall", walls);
  face(kZHi, "back_wall", walls);
  face(shared == kXHi ? kXLo : kXHi, "end_wall", walls);
}

void add_thin_wall(GltfWriter& gltf, glm::dvec3 lo, glm::dvec3 hi, const std::string& lo_face,
                   const std::string& hi_face, const std::string& edges, int material) {
  const glm::dvec3 centre = (lo + hi) * 0.5;
  const std::array<Quad, 6> w = box_quads(lo, hi);
  MeshData side_lo, side_hi, narrow;
  add_quad_away_from(side_lo, w[kXLo], centre);
  add_quad_away_from(side_hi, w[kXHi], centre);
  for (BoxFace f : {kYLo, kYHi, kZLo, kZHi}) add_quad_away_from(narrow, w[f], centre);
  gltf.add_mesh_node(lo_face, side_lo, material);
  gltf.add_mesh_node(hi_face, side_hi, material);
  gltf.add_mesh_node(edges, narrow, material);
}

}  // namespace giq::scenegen
