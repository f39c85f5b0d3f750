// `sunroom`: a closed room with thick walls, lit only by the sun through one window, so most
// of what the camera sees is indirect light; one glossy metal box.

#include <cmath>
#include <numbers>

#include "scenes.h"
#include "text.h"

namespace giq::scenegen {
namespace {

// Interior [0, W] x [0, H] x [0, D]; walls, floor slab and roof kThickness thick all round.
constexpr double kW = 5.0, kH = 3.0, kD = 5.0;
constexpr double kThickness = 0.2;
// The window: an opening through the z = 0 wall.
const glm::dvec3 kWindowLo{1.5, 1.0, 0.0}, kWindowHi{3.5, 2.2, 0.0};
// Direction the sunlight travels: in through the window, down onto the floor.
const glm::dvec3 kSunDirection{0.3, -0.7, 1.0};
constexpr double kSunIrradiance = 10.0;  // W/m^2 on a surface facing the sun
// Linear F0 of copper as tabulated by Hoffman, "Physics and Math of Shading", SIGGRAPH 2015
// course notes; the glossy object.
const glm::dvec3 kCopper{0.955, 0.637, 0.538};
constexpr double kCopperRoughness = 0.2;
const glm::dvec3 kBoxHalfSize{0.3, 0.45, 0.3};
const glm::dvec3 kBoxPosition{1.2, 0.0, 3.0};  // centre of its base
constexpr double kBoxTurnDeg = 30.0;           // about +y

}  // namespace

BuiltinScene make_sunroom() {
  BuiltinScene s;
  s.name = "sunroom";
  s.purpose =
      "Indirect light that dominates: a closed room with thick walls lit only by a directional "
      "sun through one window. Only the sunlit patch on the floor (and the window reveal) is "
      "lit directly; everything else the camera sees is lit by bounced light, and a glossy "
      "copper box adds a specular lobe.";
  GltfWriter& g = s.gltf;
  const int plaster = g.add_material({"plaster", glm::dvec3(0.8), 0.0, 1.0, 0.0, {}});
  const int oak = g.add_material({"oak_floor", {0.55, 0.38, 0.22}, 0.0, 1.0, 0.0, {}});
  const int outside = g.add_material({"exterior", glm::dvec3(0.5), 0.0, 1.0, 0.0, {}});
  // Default KHR_materials_specular (the extension is not written): a plain glTF metal.
  const int copper = g.add_material({"copper", kCopper, 1.0, kCopperRoughness, {}, {}});

  // Interior surfaces, facing into the room.
  const glm::dvec3 lo(0.0), hi(kW, kH, kD);
  const glm::dvec3 inside = (lo + hi) * 0.5;
  const std::array<Quad, 6> in = box_quads(lo, hi);
  auto inner = [&](BoxFace f, const std::string& name, int material) {
    MeshData m;
    add_quad_facing_point(m, in[f], inside);
    g.add_mesh_node(name, m, material);
  };
  inner(kYLo, "floor", oak);
  inner(kYHi, "ceiling", plaster);
  inner(kXLo, "wall_west", plaster);
  inner(kXHi, "wall_east", plaster);
  inner(kZHi, "wall_back", plaster);
  MeshData window_wall;
  add_rect_with_hole(window_wall, lo, {kW, kH, 0.0}, kWindowLo, kWindowHi, {0.0, 0.0, 1.0});
  g.add_mesh_node("window_wall", window_wall, plaster);

  // The window's reveal: four faces through the wall's thickness, facing into the opening.
  const glm::dvec3 reveal_lo{kWindowLo.x, kWindowLo.y, -kThickness};
  const glm::dvec3 reveal_hi{kWindowHi.x, kWindowHi.y, 0.0};
  const std::array<Quad, 6> r = box_quads(reveal_lo, reveal_hi);
  MeshData reveal;
  for (BoxFace f : {kYLo, kYHi, kXLo, kXHi})
    add_quad_facing_point(reveal, r[f], (reveal_lo + reveal_hi) * 0.5);
  g.add_mesh_node("window_reveal", reveal, plaster);

  // The outside of the shell, facing out, with the same opening: walls, floor slab and roof
  // are solid, so neither the sun nor a shadow-map texel can slip through an edge.
  const glm::dvec3 out_lo(-kThickness), out_hi = hi + glm::dvec3(kThickness);
  const std::array<Quad, 6> out = box_quads(out_lo, out_hi);
  MeshData exterior;
  for (BoxFace f : {kYLo, kYHi, kXLo, kXHi, kZHi}) add_quad_away_from(exterior, out[f], inside);
  add_rect_with_hole(exterior, out_lo, {out_hi.x, out_hi.y, out_lo.z},
                     {kWindowLo.x, kWindowLo.y, out_lo.z}, {kWindowHi.x, kWindowHi.y, out_lo.z},
                     {0.0, 0.0, -1.0});
  g.add_mesh_node("exterior", exterior, outside);

  MeshData box;
  add_box(box, {-kBoxHalfSize.x, 0.0, -kBoxHalfSize.z},
          {kBoxHalfSize.x, 2.0 * kBoxHalfSize.y, kBoxHalfSize.z});
  const glm::dquat turn = glm::angleAxis(glm::radians(kBoxTurnDeg), glm::dvec3(0.0, 1.0, 0.0));
  g.add_mesh_node("copper_box", box, copper, {kBoxPosition, turn});

  const glm::dvec3 sun = glm::normalize(kSunDirection);
  g.add_light_node({"sun", LightKind::Directional, glm::dvec3(1.0), kSunIrradiance},
                   {glm::dvec3(kW * 0.5, kH + 2.0, -3.0), rotation_from_minus_z(sun)});

  const double aspect = 16.0 / 9.0;
  // From the back corner: the sunlit patch, the copper box and the window.
  g.add_camera_node({"interior", {4.6, 1.8, 4.7}, {2.2, 0.6, 1.8}, {0.0, 1.0, 0.0}, 60.0}, aspect,
                    0.01);
  g.add_view({"window", {2.5, 1.6, 4.7}, {2.5, 1.3, 0.0}, {0.0, 1.0, 0.0}, 60.0});
  // From the window wall toward the back wall and ceiling: almost only indirect light.
  g.add_view({"back", {2.5, 1.5, 0.4}, {2.5, 2.0, 5.0}, {0.0, 1.0, 0.0}, 60.0});

  // Irradiance on the floor: E cos(theta), cos(theta) = -sun.y.
  const double floor_irradiance = kSunIrradiance * -sun.y;
  s.notes = {
      "Room: " + num(kW) + " m (x) by " + num(kH) + " m (y) by " + num(kD) +
          " m (z) inside; walls, floor slab and roof " + num(kThickness) +
          " m thick, modelled as a closed solid (inner faces, outer faces and the window's "
          "reveal), so the sun reaches the interior only through the window.",
      "Window: x " + num(kWindowLo.x) + "-" + num(kWindowHi.x) + " m, y " + num(kWindowLo.y) + "-" +
          num(kWindowHi.y) + " m in the z = 0 wall.",
      "Sun: directional, irradiance " + num(kSunIrradiance) +
          " W/m^2 (white) on a surface "
          "facing it, travelling along " +
          vec(sun) + "; the floor patch it lights receives " + num(floor_irradiance, 2) +
          " W/m^2, so the floor (albedo 0.55, 0.38, 0.22) there has "
          "radiance up to " +
          num(floor_irradiance * 0.55 / std::numbers::pi, 2) +
          " in red, against the unlit walls' indirect light.",
      "Glossy object: `copper_box`, metallic 1, roughness " + num(kCopperRoughness) +
          ", base colour " + vec(kCopper, 3) +
          " (copper's linear F0 as tabulated in Hoffman, "
          "\"Physics and Math of Shading\", SIGGRAPH 2015), turned " +
          num(kBoxTurnDeg) +
          " degrees about +y. Every other material is Lambert (KHR_materials_specular factor 0).",
  };
  return s;
}

}  // namespace giq::scenegen
