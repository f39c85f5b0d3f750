// `leak`: two sealed rooms sharing one thin wall; the light is in room A, the camera in room B,
// where the truth is exactly black. Any light a technique puts in room B leaked.

#include "room.h"
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
  add_thin_wall(g, {-kHalf, 0.0, 0.0}, {kHalf, kRoomHeight, kRoomDepth}, "thin_wall_A", "thin_wall_B",
                "thin_wall_edges", walls);

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
