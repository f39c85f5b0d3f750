// `leak`: two sealed rooms sharing one thin wall; the light is in room A, the camera in room B,
// where the truth is exactly black. Any light a technique puts in room B leaked.

#include "scenes.h"
#include "text.h"

namespace giq::scenegen {
namespace {

constexpr double kRoomWidth = 4.0;   // x, each room
constexpr double kRoomHeight = 2.5;  // y
constexpr double kRoomDepth = 4.0;   // z
constexpr double kWallThickness = 0.01;
constexpr double kHalf = kWallThickness / 2.0;  // the thin wall spans x in [-kHalf, kHalf]
const glm::dvec3 kLightPosition{-1.0, 1.6, 2.0};
// Room A well lit: the thin wall's A side, about 1 m away, receives about I / d^2 = 10 W/m^2.
constexpr double kLightIntensity = 10.0;

// Adds a room's floor, ceiling and three outer walls as nodes `<prefix>_floor` etc.; the face on
// the thin wall's side is left out. Floors, ceilings and the front and back walls run on to
// x = 0, under, over and beside the thin wall, so every seam between a room and the wall is
// covered by a surface behind it: no ray finds a crack between two quads that merely touch.
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

}  // namespace

BuiltinScene make_leak() {
  BuiltinScene s;
  s.name = "leak";
  s.purpose =
      "Leaking: two closed rooms share one thin wall. A point light shines in room A only; the "
      "camera of the default view is in room B, which no light can reach, so its true image is "
      "exactly black and every bit of light a technique shows there went through the wall. "
      "Room B's surfaces are declared leak regions (METRICS.md \"Leaking\").";
  GltfWriter& g = s.gltf;
  const int walls = g.add_material({"plaster", glm::dvec3(0.8), 0.0, 1.0, 0.0, {}});
  const int floor = g.add_material({"floor", glm::dvec3(0.5), 0.0, 1.0, 0.0, {}});

  const double far = kHalf + kRoomWidth;
  add_room(g, "roomA", {-far, 0.0, 0.0}, {0.0, kRoomHeight, kRoomDepth}, kXHi, walls, floor);
  add_room(g, "roomB", {0.0, 0.0, 0.0}, {far, kRoomHeight, kRoomDepth}, kXLo, walls, floor);

  // The thin wall is a closed box: its two large faces are separate nodes (room B's side is a
  // leak region) and its four narrow faces one more.
  const glm::dvec3 wall_lo{-kHalf, 0.0, 0.0}, wall_hi{kHalf, kRoomHeight, kRoomDepth};
  const glm::dvec3 wall_centre = (wall_lo + wall_hi) * 0.5;
  const std::array<Quad, 6> w = box_quads(wall_lo, wall_hi);
  MeshData side_a, side_b, edges;
  add_quad_away_from(side_a, w[kXLo], wall_centre);
  add_quad_away_from(side_b, w[kXHi], wall_centre);
  for (BoxFace f : {kYLo, kYHi, kZLo, kZHi}) add_quad_away_from(edges, w[f], wall_centre);
  g.add_mesh_node("thin_wall_A", side_a, walls);
  g.add_mesh_node("thin_wall_B", side_b, walls);
  g.add_mesh_node("thin_wall_edges", edges, walls);

  g.add_light_node({"light_A", LightKind::Point, glm::dvec3(1.0), kLightIntensity},
                   {kLightPosition});

  const double aspect = 16.0 / 9.0;
  g.add_camera_node({"roomB", {3.7, 1.7, 3.6}, {0.0, 0.7, 1.6}, {0.0, 1.0, 0.0}, 60.0}, aspect,
                    0.01);
  g.add_view({"roomA", {-3.7, 1.7, 3.6}, {0.0, 0.9, 1.6}, {0.0, 1.0, 0.0}, 60.0});
  // Close to where the thin wall meets room B's floor: where voxel and grid techniques leak.
  g.add_view({"roomB_seam", {1.0, 0.6, 2.0}, {0.0, 0.15, 2.0}, {0.0, 1.0, 0.0}, 60.0});

  for (const char* name : {"roomB_floor", "roomB_ceiling", "roomB_front_wall", "roomB_back_wall",
                           "roomB_end_wall", "thin_wall_B"})
    g.add_leak_region(name);

  const double distance = -kHalf - kLightPosition.x;
  s.notes = {
      "Rooms: " + num(kRoomWidth) + " m (x) by " + num(kRoomHeight) + " m (y) by " +
          num(kRoomDepth) + " m (z) inside each, either side of a thin wall " +
          num(kWallThickness * 100.0) + " cm thick (x from " + num(-kHalf) + " to " + num(kHalf) +
          " m), modelled as a closed box.",
      "Sealed: each room's floor, ceiling, front and back walls run on to x = 0, under, over "
      "and beside the thin wall, so the seams are backed by surfaces and the truth in room B "
      "is exactly zero.",
      "Light: one point light, radiant intensity " + num(kLightIntensity) + " W/sr, white, at " +
          vec(kLightPosition) + " m in room A; the thin wall's A side, " + num(distance, 3) +
          " m away, receives I / d^2 = " + num(kLightIntensity / (distance * distance), 2) +
          " W/m^2 at its closest point.",
      "Materials: Lambert (KHR_materials_specular factor 0), walls and ceilings 0.8, floors 0.5.",
  };
  return s;
}

}  // namespace giq::scenegen
