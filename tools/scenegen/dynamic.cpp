// `dynamic`: a room where things move the way they do in games: a skinned figure walks, a
// fountain throws glowing particles that light the walls, and a rectangle light over a glossy
// floor jumps once (the step for lag). A sealed closet behind a thin wall next to the
// fountain is a leak region.

#include <cmath>

#include "room.h"
#include "scenes.h"
#include "text.h"
#include "walker.h"

namespace giq::scenegen {
namespace {

constexpr int kFrames = 120;
constexpr double kFps = 30.0;
// The main room [0, kW] x [0, kH] x [0, kD]; the closet [kW, kW + kClosetW] behind a thin
// wall centred on x = kW.
constexpr double kW = 8.0, kH = 3.0, kD = 6.0;
constexpr double kClosetW = 1.6;
constexpr double kWallThickness = 0.02;
// The lamp: a rectangle facing down, kLampSize wide in x and z, that jumps from kLampA to
// kLampB half-way between frames 29 and 30 (so every reader's STEP convention gives frame 30
// the new place), as `movinglight`'s light does.
const glm::dvec2 kLampSize{1.2, 0.6};
const glm::dvec3 kLampA{3.6, 2.4, 3.0}, kLampB{5.4, 2.4, 2.4};
const glm::dvec3 kLampRadiance{12.0, 11.0, 9.5};
constexpr int kStepFrame = 30;
// Polished tiles: a dielectric (glTF's default 4 % specular) of roughness 0.2, the glossy
// floor whose reflection of the lamp the representative-point method approximates.
const glm::dvec3 kTile{0.3, 0.3, 0.32};
constexpr double kTileRoughness = 0.2;
// The fountain: a stone basin whose top carries the nozzle, 1 m from the thin wall.
const glm::dvec3 kBasinLo{6.7, 0.0, 1.1}, kBasinHi{7.3, 0.5, 1.7};
constexpr double kNozzleHalf = 0.1;

}  // namespace

BuiltinScene make_dynamic() {
  BuiltinScene s;
  s.name = "dynamic";
  s.purpose =
      "Moving content, for flicker and lag where games show them: a skinned figure walks a "
      "circle, a fountain throws particles that glow and light the walls next to it, and a "
      "rectangle light over a glossy floor jumps once, at frame 30, the step whose response "
      "measures lag. 120 frames at 30 fps. A sealed closet behind a 2 cm wall next to the "
      "fountain is a leak region: its truth is black in every frame.";
  GltfWriter& g = s.gltf;
  const int plaster = g.add_material({"plaster", glm::dvec3(0.8), 0.0, 1.0, 0.0, {}});
  const int tiles = g.add_material({"tiles", kTile, 0.0, kTileRoughness, {}, {}});
  const int boards = g.add_material({"boards", glm::dvec3(0.5), 0.0, 1.0, 0.0, {}});
  const int stone = g.add_material({"stone", glm::dvec3(0.6), 0.0, 1.0, 0.0, {}});
  const int cloth = g.add_material({"cloth", {0.25, 0.45, 0.7}, 0.0, 1.0, 0.0, {}});
  const int lamp_material = g.add_material({"lamp", glm::dvec3(0.8), 0.0, 1.0, 0.0, kLampRadiance});

  add_room(g, "room", {0.0, 0.0, 0.0}, {kW, kH, kD}, kXHi, plaster, tiles);
  add_room(g, "closet", {kW, 0.0, 0.0}, {kW + kClosetW, kH, kD}, kXLo, plaster, boards);
  const double half = kWallThickness / 2.0;
  add_thin_wall(g, {kW - half, 0.0, 0.0}, {kW + half, kH, kD}, "thin_wall_room", "thin_wall_closet",
                "thin_wall_edges", plaster);

  // The lamp, in its node's frame: centred on the origin, facing down.
  MeshData lamp;
  add_quad(lamp, {-kLampSize.x / 2, 0.0, -kLampSize.y / 2}, {kLampSize.x / 2, 0.0, -kLampSize.y / 2},
           {kLampSize.x / 2, 0.0, kLampSize.y / 2}, {-kLampSize.x / 2, 0.0, kLampSize.y / 2}, {0.0, -1.0, 0.0});
  const int lamp_node = g.add_mesh_node("lamp", lamp, lamp_material, {kLampA});
  g.declare_area_light(lamp_node, "rectangle");

  MeshData basin, nozzle;
  add_box(basin, kBasinLo, kBasinHi);
  g.add_mesh_node("basin", basin, stone);
  const glm::dvec3 top = {(kBasinLo.x + kBasinHi.x) / 2, kBasinHi.y + 0.002, (kBasinLo.z + kBasinHi.z) / 2};
  add_quad(nozzle, top + glm::dvec3(-kNozzleHalf, 0.0, -kNozzleHalf), top + glm::dvec3(kNozzleHalf, 0.0, -kNozzleHalf),
           top + glm::dvec3(kNozzleHalf, 0.0, kNozzleHalf), top + glm::dvec3(-kNozzleHalf, 0.0, kNozzleHalf), {0.0, 1.0, 0.0});
  g.add_mesh_node("nozzle", nozzle, stone);
  // Particles rise about 0.45 m and die (at 0.7 s) before they fall to the floor, glowing
  // orange, brightest a tenth into their life.
  EmitterSpec fountain;
  fountain.name = "fountain";
  fountain.node = "nozzle";
  fountain.rate = 300.0;
  fountain.lifetime = 0.7;
  fountain.speed = 3.0;
  fountain.spread_deg = 15.0;
  fountain.drag = 0.3;
  fountain.size = 0.015;
  fountain.color = glm::dvec3(0.9);
  fountain.emission = {40.0, 16.0, 4.0};
  fountain.strength = {{0.0, 0.0}, {0.1, 1.0}, {1.0, 0.1}};
  fountain.stages = 4;
  fountain.seed = 7;
  g.add_emitter(fountain);

  // The figure walks beside the lamp's first place, out of the line from the camera to the
  // fountain.
  const WalkSpec walk{{4.5, 0.0, 4.0}, 0.8, kFrames / kFps, 1.0, kFrames};
  Walker walker = add_walker(g, walk, cloth);

  TranslationTrack jump{lamp_node, Interpolation::Step, {0.0, (kStepFrame - 0.5) / kFps}, {kLampA, kLampB}};
  std::vector<TranslationTrack> translations = walker.translations;
  translations.push_back(jump);
  const int animation = g.add_animation("dynamic", translations, walker.rotations);
  // Flicker from frame 12, after the histories' warm-up, to the frame before the step's
  // window; lag from two frames before the step to 13 after it. Not longer: the walker and the
  // particles keep moving, so the error once settled keeps drifting (by about as much as
  // `ddgi`'s whole response to the step), and over every later frame lag90 would measure the
  // drift (docs/metrics.md, "Lag").
  g.set_sequence(kFrames, kFps, animation, GltfWriter::MeasurementWindows{kStepFrame, {12, kStepFrame - 3}, {kStepFrame - 2, kStepFrame + 13}});

  const double aspect = 16.0 / 9.0;
  // From the wall opposite the fountain, pitched down so that the lamp and, after the step, its
  // reflection in the floor are both in the square gate image.
  g.add_camera_node({"room", {0.3, 1.7, 3.0}, {6.0, 0.0, 2.5}, {0.0, 1.0, 0.0}, 65.0}, aspect, 0.01);
  g.add_view({"closet", {kW + kClosetW - 0.2, 1.6, kD - 0.4}, {kW, 0.9, 1.5}, {0.0, 1.0, 0.0}, 65.0});
  // The lamp's reflection in the glossy floor, near grazing (from frame 30).
  g.add_view({"floor", {1.2, 1.0, 2.6}, {5.4, 0.0, 2.4}, {0.0, 1.0, 0.0}, 65.0});
  for (const char* name : {"closet_floor", "closet_ceiling", "closet_front_wall", "closet_back_wall", "closet_end_wall",
                           "thin_wall_closet"})
    g.add_leak_region(name);

  const double lamp_area = kLampSize.x * kLampSize.y;
  s.notes = {
      "Rooms: the main room is " + num(kW) + " m (x) by " + num(kH) + " m (y) by " + num(kD) +
          " m (z); the closet beyond x = " + num(kW) + " is " + num(kClosetW) + " m wide, behind a wall " +
          num(kWallThickness * 100.0) + " cm thick modelled as a closed box. Both rooms run on to the wall's middle "
          "plane, as in `leak`, so the closet is sealed and its truth is exactly black.",
      "Floor: `tiles`, a dielectric of roughness " + num(kTileRoughness) + " with glTF's default specular layer (F0 = 0.04).",
      "Lamp: an emissive rectangle of " + num(kLampSize.x) + " m x " + num(kLampSize.y) + " m (" + num(lamp_area, 2) +
          " m^2) facing down, declared `area_light: rectangle`, radiance " + vec(kLampRadiance) + "; at " + vec(kLampA) +
          " m for frames 0-" + std::to_string(kStepFrame - 1) + ", then (a STEP key at t = " + num((kStepFrame - 0.5) / kFps, 6) +
          " s, half-way between frames) at " + vec(kLampB) + " m. The step frame for lag is t0 = " +
          std::to_string(kStepFrame) + ".",
      "Fountain (`extras.giq.emitters`): the 0.2 m square `nozzle` on a stone basin at " + vec(top) + " m emits " +
          num(fountain.rate) + " particles a second, each living " + num(fountain.lifetime) + " s, at " +
          num(fountain.speed) + " m/s within " + num(fountain.spread_deg) + " degrees of vertical, drag " +
          num(fountain.drag) + " /s: octahedra of circumradius " + num(fountain.size) +
          " m emitting up to " + vec(fountain.emission) + " in " + std::to_string(fountain.stages) +
          " stages of life (strength 0 at birth, 1 at a tenth of the life, 0.1 at death), about " +
          num(std::floor(fountain.rate * fountain.lifetime)) + " alive at once. They die before they reach the floor.",
      "Walker: a skinned mesh (`walker`, " + std::to_string(walker.triangles) + " triangles, " +
          std::to_string(walker.joints.size()) + " joints; where two bones meet a vertex follows both, elsewhere one) " +
          num(walker.height, 2) + " m tall, walking once round a circle of radius " + num(walk.radius) +
          " m about " + vec(walk.centre) + " m in " + num(walk.lap_seconds) + " s (" + num(walker.speed, 3) +
          " m/s), one stride a second: hips swing +-" + num(walker.hip_swing_deg, 1) + " degrees, knees bend up to " +
          num(walker.knee_bend_deg, 1) + " degrees (no foot planting: the swinging toe dips up to 2 cm into the floor). Keys every frame "
          "(LINEAR; rotations slerp).",
      "Sequence: " + std::to_string(kFrames) + " frames at " + num(kFps) + " fps (animation " +
          std::to_string(animation) + ", `dynamic`).",
  };
  return s;
}

}  // namespace giq::scenegen
