// `cornell`: the Cornell box with its ceiling light; and the box itself, shared with
// `movinglight`.

#include <cmath>

#include "cornell_box.h"
#include "scenes.h"
#include "text.h"

namespace giq::scenegen {
namespace cornell {
namespace {

// A point inside the box: walls face it.
constexpr glm::dvec3 kInside = mm(278.0, 274.4, 279.6);

MeshData wall(const Quad& q) {
  MeshData m;
  add_quad_facing_point(m, q, kInside);
  return m;
}

// A block from its published faces (top and four sides; it stands on the floor, so no bottom),
// each facing away from the block's centre.
MeshData block(const std::array<Quad, 5>& faces) {
  glm::dvec3 centre(0.0);
  for (const Quad& q : faces) centre += centroid(q);
  centre /= double(faces.size());
  MeshData m;
  for (const Quad& q : faces) add_quad_away_from(m, q, centre);
  return m;
}

}  // namespace

double yfov_deg() {
  return glm::degrees(2.0 * std::atan(kFilmMm / 2.0 / kFocalLengthMm));
}

void add_box(GltfWriter& gltf, bool ceiling_light) {
  // Pure Lambert: KHR_materials_specular factor 0 removes glTF's dielectric specular layer.
  const int white = gltf.add_material({"white", kWhite, 0.0, 1.0, 0.0, {}});
  const int red = gltf.add_material({"red", kRed, 0.0, 1.0, 0.0, {}});
  const int green = gltf.add_material({"green", kGreen, 0.0, 1.0, 0.0, {}});

  // Published "Cornell Box Data" quads, vertex order as published (orientation is computed).
  gltf.add_mesh_node(
      "floor",
      wall({mm(552.8, 0.0, 0.0), mm(0.0, 0.0, 0.0), mm(0.0, 0.0, 559.2), mm(549.6, 0.0, 559.2)}),
      white);
  gltf.add_mesh_node("ceiling",
                     wall({mm(556.0, 548.8, 0.0), mm(556.0, 548.8, 559.2), mm(0.0, 548.8, 559.2),
                           mm(0.0, 548.8, 0.0)}),
                     white);
  gltf.add_mesh_node("back_wall",
                     wall({mm(549.6, 0.0, 559.2), mm(0.0, 0.0, 559.2), mm(0.0, 548.8, 559.2),
                           mm(556.0, 548.8, 559.2)}),
                     white);
  // The red wall is the published quad, which is not planar (one corner lies 3.2 mm off the
  // plane of the other three): it becomes two triangles with their own normals.
  gltf.add_mesh_node("red_wall",
                     wall({mm(552.8, 0.0, 0.0), mm(549.6, 0.0, 559.2), mm(556.0, 548.8, 559.2),
                           mm(556.0, 548.8, 0.0)}),
                     red);
  gltf.add_mesh_node(
      "green_wall",
      wall({mm(0.0, 0.0, 559.2), mm(0.0, 0.0, 0.0), mm(0.0, 548.8, 0.0), mm(0.0, 548.8, 559.2)}),
      green);
  gltf.add_mesh_node("short_block",
                     block({{{mm(130.0, 165.0, 65.0), mm(82.0, 165.0, 225.0),
                              mm(240.0, 165.0, 272.0), mm(290.0, 165.0, 114.0)},
                             {mm(290.0, 0.0, 114.0), mm(290.0, 165.0, 114.0),
                              mm(240.0, 165.0, 272.0), mm(240.0, 0.0, 272.0)},
                             {mm(130.0, 0.0, 65.0), mm(130.0, 165.0, 65.0), mm(290.0, 165.0, 114.0),
                              mm(290.0, 0.0, 114.0)},
                             {mm(82.0, 0.0, 225.0), mm(82.0, 165.0, 225.0), mm(130.0, 165.0, 65.0),
                              mm(130.0, 0.0, 65.0)},
                             {mm(240.0, 0.0, 272.0), mm(240.0, 165.0, 272.0),
                              mm(82.0, 165.0, 225.0), mm(82.0, 0.0, 225.0)}}}),
                     white);
  gltf.add_mesh_node("tall_block",
                     block({{{mm(423.0, 330.0, 247.0), mm(265.0, 330.0, 296.0),
                              mm(314.0, 330.0, 456.0), mm(472.0, 330.0, 406.0)},
                             {mm(423.0, 0.0, 247.0), mm(423.0, 330.0, 247.0),
                              mm(472.0, 330.0, 406.0), mm(472.0, 0.0, 406.0)},
                             {mm(472.0, 0.0, 406.0), mm(472.0, 330.0, 406.0),
                              mm(314.0, 330.0, 456.0), mm(314.0, 0.0, 456.0)},
                             {mm(314.0, 0.0, 456.0), mm(314.0, 330.0, 456.0),
                              mm(265.0, 330.0, 296.0), mm(265.0, 0.0, 296.0)},
                             {mm(265.0, 0.0, 296.0), mm(265.0, 330.0, 296.0),
                              mm(423.0, 330.0, 247.0), mm(423.0, 0.0, 247.0)}}}),
                     white);

  if (ceiling_light) {
    // Emits downwards only (single-sided). Its published reflectance is ~0.78, flat.
    const int light = gltf.add_material({"light", glm::dvec3(0.78), 0.0, 1.0, 0.0, kLightRadiance});
    const double y = kLightMin.y - kLightDrop;
    MeshData quad;
    add_quad(quad, {kLightMin.x, y, kLightMin.z}, {kLightMax.x, y, kLightMin.z},
             {kLightMax.x, y, kLightMax.z}, {kLightMin.x, y, kLightMax.z}, {0.0, -1.0, 0.0});
    gltf.add_mesh_node("light", quad, light);
  }

  // The published camera: at (278, 273, -800) mm looking +z; yfov = 2 atan(film / 2 / focal).
  gltf.add_camera_node(
      {"front", mm(278.0, 273.0, -800.0), mm(278.0, 273.0, 0.0), {0.0, 1.0, 0.0}, yfov_deg()}, 1.0,
      0.01);
  // From inside the open front near the green wall, into the corner of the red wall, the back
  // wall and the ceiling: the colour bleeding the front view sees only at grazing angles.
  gltf.add_view({"corner", mm(80.0, 300.0, 40.0), mm(500.0, 420.0, 520.0), {0.0, 1.0, 0.0}, 55.0});
}

}  // namespace cornell

BuiltinScene make_cornell() {
  BuiltinScene s;
  s.name = "cornell";
  s.purpose =
      "The classic Cornell box, the scene every GI technique is first compared on: diffuse "
      "interreflection and colour bleeding from one small area light. Its only light is the "
      "emissive ceiling quad, so it also tests how a technique treats an emissive-mesh area "
      "light.";
  using namespace cornell;
  s.notes = {
      "Geometry: the published \"Cornell Box Data\" of the Cornell Program of Computer Graphics "
      "(https://www.graphics.cornell.edu/online/box/data.html), millimetres converted to metres; "
      "the box is open toward the camera, as published. The red wall's published quad is not "
      "planar (one corner lies 3.2 mm off the plane of the other three) and is written as two "
      "triangles with their own normals.",
      "The light quad is the published rectangle (x " + num(kLightMin.x * 1000.0) + "-" +
          num(kLightMax.x * 1000.0) + " mm, z " + num(kLightMin.z * 1000.0) + "-" +
          num(kLightMax.z * 1000.0) + " mm), lowered " + num(kLightDrop * 1000.0) +
          " mm below the ceiling so the two never share a plane; it is single-sided and faces "
          "down.",
      "Reflectances and light radiance: the RGB fits used by the cornell-box scene of Bitterli's "
      "\"Rendering Resources\" (2016, for pbrt-v3 and Mitsuba): white " +
          vec(kWhite) + ", red " + vec(kRed) + ", green " + vec(kGreen) + ", light radiance " +
          vec(kLightRadiance) +
          ". All materials are pure Lambert (metallic 0, roughness 1, KHR_materials_specular "
          "specularFactor 0).",
      "The view `front` is the published camera at (278, 273, -800) mm looking +z with up +y (" +
          num(kFocalLengthMm) + " mm focal length on a " + num(kFilmMm) +
          " mm square film: yfov = 2 atan(" + num(kFilmMm / 2.0) + "/" + num(kFocalLengthMm) +
          ") = " + num(yfov_deg(), 4) +
          " degrees, square aspect). glTF is right-handed: looking "
          "+z, +x is to the left, so the red wall (x = 552.8 mm) is on the left as in the "
          "photograph.",
  };
  cornell::add_box(s.gltf, true);
  return s;
}

}  // namespace giq::scenegen
