// What each built-in scene must contain, read from the files themselves (no scene loader):
// the published Cornell numbers, the leak scene's sealed rooms, the sunroom's window and sun,
// the movinglight path, the dynamic scene's skin, lamp and fountain.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <map>
#include <numbers>

#include "gltf_file.h"

namespace fs = std::filesystem;
using giq::test::GltfFile;
using nlohmann::json;

namespace {

GltfFile scene(const std::string& name) {
  return GltfFile::read(fs::path(GIQ_SCENES_DIR) / (name + ".gltf"));
}

glm::dvec3 vec3(const json& j) {
  return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()};
}

glm::dquat rotation(const json& node) {
  if (!node.contains("rotation")) return {1.0, 0.0, 0.0, 0.0};
  const json& r = node["rotation"];  // glTF order x, y, z, w
  return {r[3].get<double>(), r[0].get<double>(), r[1].get<double>(), r[2].get<double>()};
}

glm::dvec3 translation(const json& node) {
  return node.contains("translation") ? vec3(node["translation"]) : glm::dvec3(0.0);
}

struct Surface {
  std::vector<glm::dvec3> positions, normals;  // world space (root nodes)
  std::vector<uint32_t> indices;
  int material = -1;
  double area() const {
    double a = 0.0;
    for (size_t t = 0; t < indices.size(); t += 3)
      a += 0.5 * glm::length(glm::cross(positions[indices[t + 1]] - positions[indices[t]],
                                        positions[indices[t + 2]] - positions[indices[t]]));
    return a;
  }
  glm::dvec3 lo() const {
    glm::dvec3 l(INFINITY);
    for (auto p : positions) l = glm::min(l, p);
    return l;
  }
  glm::dvec3 hi() const {
    glm::dvec3 h(-INFINITY);
    for (auto p : positions) h = glm::max(h, p);
    return h;
  }
};

Surface surface(const GltfFile& f, const std::string& name) {
  const int index = f.node(name);
  if (index < 0) throw std::runtime_error("no node " + name);
  const json& node = f.doc["nodes"][index];
  const json& prim = f.doc["meshes"][node.at("mesh").get<int>()]["primitives"][0];
  const glm::dquat q = rotation(node);
  const glm::dvec3 t = translation(node);
  Surface s;
  for (glm::vec3 p : f.vec3s(prim["attributes"]["POSITION"].get<int>()))
    s.positions.push_back(q * glm::dvec3(p) + t);
  for (glm::vec3 n : f.vec3s(prim["attributes"]["NORMAL"].get<int>()))
    s.normals.push_back(q * glm::dvec3(n));
  s.indices = f.indices(prim["indices"].get<int>());
  s.material = prim.at("material").get<int>();
  return s;
}

// Every face of `s` faces towards `point` (a room's inside) or, with away, away from it.
void expect_facing(const Surface& s, glm::dvec3 point, bool away, const std::string& what) {
  for (size_t i = 0; i < s.positions.size(); ++i) {
    const double d = glm::dot(s.normals[i], point - s.positions[i]);
    EXPECT_GT(away ? -d : d, 0.0) << what << " vertex " << i;
  }
}

const json& material(const GltfFile& f, const Surface& s) {
  return f.doc["materials"][s.material];
}

double specular_factor(const json& m) {
  return m.value("/extensions/KHR_materials_specular/specularFactor"_json_pointer, 1.0);
}

constexpr double kMm = 0.001;
// Float storage of metre values below 10 m: relative 2^-24, i.e. < 1e-6 m.
constexpr double kPositionTolerance = 1e-6;

}  // namespace

TEST(CornellFile, HasThePublishedDimensionsAndLight) {
  const GltfFile f = scene("cornell");
  glm::dvec3 lo(INFINITY), hi(-INFINITY);
  for (const char* name : {"floor", "ceiling", "back_wall", "red_wall", "green_wall", "short_block",
                           "tall_block", "light"}) {
    const Surface s = surface(f, name);
    lo = glm::min(lo, s.lo());
    hi = glm::max(hi, s.hi());
  }
  // Published extremes: x 0..556.0 (ceiling), y 0..548.8, z 0..559.2 mm.
  EXPECT_NEAR(glm::length(lo), 0.0, kPositionTolerance);
  EXPECT_NEAR(hi.x, 556.0 * kMm, kPositionTolerance);
  EXPECT_NEAR(hi.y, 548.8 * kMm, kPositionTolerance);
  EXPECT_NEAR(hi.z, 559.2 * kMm, kPositionTolerance);

  const Surface light = surface(f, "light");
  EXPECT_NEAR(light.area(), 0.130 * 0.105, 1e-7);  // (343 - 213) x (332 - 227) mm
  for (glm::dvec3 n : light.normals) EXPECT_NEAR(n.y, -1.0, 1e-7);
  EXPECT_LT(light.hi().y, 548.8 * kMm);  // just below the ceiling
  EXPECT_GT(light.lo().y, 548.8 * kMm - 0.002);
  const json& m = material(f, light);
  const glm::dvec3 radiance =
      vec3(m["emissiveFactor"]) *
      m["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"].get<double>();
  EXPECT_NEAR(radiance.r, 17.0, 1e-5);
  EXPECT_NEAR(radiance.g, 12.0, 1e-5);
  EXPECT_NEAR(radiance.b, 4.0, 1e-5);
  EXPECT_FALSE(m.value("doubleSided", false));

  for (const json& mat : f.doc["materials"]) {
    EXPECT_EQ(mat["pbrMetallicRoughness"]["metallicFactor"].get<double>(), 0.0);
    EXPECT_EQ(mat["pbrMetallicRoughness"]["roughnessFactor"].get<double>(), 1.0);
    EXPECT_EQ(specular_factor(mat), 0.0) << mat["name"];
  }
  EXPECT_FALSE(f.doc["extensionsUsed"].dump().find("KHR_lights_punctual") != std::string::npos);
}

TEST(CornellFile, WallsFaceInBlocksFaceOutAndRedIsOnTheLeft) {
  const GltfFile f = scene("cornell");
  const glm::dvec3 inside(0.278, 0.274, 0.280);
  for (const char* name : {"floor", "ceiling", "back_wall", "red_wall", "green_wall", "light"})
    expect_facing(surface(f, name), inside, false, name);
  for (const char* name : {"short_block", "tall_block"}) {
    const Surface s = surface(f, name);
    expect_facing(s, (s.lo() + s.hi()) * 0.5, true, name);
  }
  EXPECT_EQ(material(f, surface(f, "red_wall"))["name"], "red");
  EXPECT_EQ(material(f, surface(f, "green_wall"))["name"], "green");

  // The published camera: at (278, 273, -800) mm looking +z, 35 mm lens on 25 mm film.
  const json& cam = f.doc["nodes"][f.node("front")];
  const glm::dvec3 eye = translation(cam);
  EXPECT_NEAR(eye.x, 0.278, kPositionTolerance);
  EXPECT_NEAR(eye.y, 0.273, kPositionTolerance);
  EXPECT_NEAR(eye.z, -0.800, kPositionTolerance);
  const glm::dquat q = rotation(cam);
  EXPECT_NEAR(glm::length(q * glm::dvec3(0, 0, -1) - glm::dvec3(0, 0, 1)), 0.0, 1e-6);
  // The camera's right (+X) is world -x: the red wall (x = 552.8 mm) appears on the left.
  EXPECT_NEAR(glm::length(q * glm::dvec3(1, 0, 0) - glm::dvec3(-1, 0, 0)), 0.0, 1e-6);
  EXPECT_GT(surface(f, "red_wall").lo().x, 0.5);
  const double yfov =
      f.doc["cameras"][cam["camera"].get<int>()]["perspective"]["yfov"].get<double>();
  EXPECT_NEAR(yfov, 2.0 * std::atan(12.5 / 35.0), 1e-6);
}

TEST(LeakFile, ThinWallSeparatesSealedRoomsLightAndCamera) {
  const GltfFile f = scene("leak");
  const Surface a = surface(f, "thin_wall_A"), b = surface(f, "thin_wall_B");
  const double thickness = b.lo().x - a.hi().x;
  EXPECT_GT(thickness, 0.0);
  EXPECT_LE(thickness, 0.02 + kPositionTolerance);
  expect_facing(a, {-1.0, 1.0, 2.0}, false, "thin_wall_A");  // faces room A (x < 0)
  expect_facing(b, {1.0, 1.0, 2.0}, false, "thin_wall_B");   // faces room B (x > 0)
  // The edges close the box: the wall is a solid, not a quad.
  const Surface edges = surface(f, "thin_wall_edges");
  EXPECT_NEAR(edges.lo().x, a.lo().x, kPositionTolerance);
  EXPECT_NEAR(edges.hi().x, b.hi().x, kPositionTolerance);
  EXPECT_NEAR(edges.area(), 2.0 * thickness * (b.hi().y + b.hi().z), 1e-6);

  // Sealed: every room surface that meets the thin wall runs on past its face (to x = 0), and
  // the rooms' floor and ceiling meet the wall's bottom and top.
  for (const char* room : {"roomA", "roomB"}) {
    const bool is_a = room[4] == 'A';
    for (const char* part : {"_floor", "_ceiling", "_front_wall", "_back_wall"}) {
      const Surface s = surface(f, std::string(room) + part);
      if (is_a) {
        EXPECT_GE(s.hi().x, a.hi().x) << room << part;
      } else {
        EXPECT_LE(s.lo().x, b.lo().x) << room << part;
      }
    }
    EXPECT_EQ(surface(f, std::string(room) + "_floor").lo().y, a.lo().y);
    EXPECT_EQ(surface(f, std::string(room) + "_ceiling").hi().y, a.hi().y);
  }

  // The only light is a point light in room A; the default view's camera is in room B.
  ASSERT_EQ(f.doc["extensions"]["KHR_lights_punctual"]["lights"].size(), 1u);
  EXPECT_EQ(f.doc["extensions"]["KHR_lights_punctual"]["lights"][0]["type"], "point");
  EXPECT_LT(translation(f.doc["nodes"][f.node("light_A")]).x, a.lo().x);
  const int camera = f.node("roomB");
  ASSERT_GE(camera, 0);
  EXPECT_TRUE(f.doc["nodes"][camera].contains("camera"));
  EXPECT_GT(translation(f.doc["nodes"][camera]).x, b.hi().x);
  // Room B's side of the wall is in front of the camera.
  const glm::dvec3 forward = rotation(f.doc["nodes"][camera]) * glm::dvec3(0, 0, -1);
  EXPECT_LT(forward.x, 0.0);

  std::set<std::string> regions;
  for (const auto& r : f.doc["extras"]["giq"]["leak_regions"]) regions.insert(r.get<std::string>());
  EXPECT_EQ(regions, (std::set<std::string>{"roomB_floor", "roomB_ceiling", "roomB_front_wall",
                                            "roomB_back_wall", "roomB_end_wall", "thin_wall_B"}));
}

TEST(SunroomFile, SunEntersOnlyThroughTheWindowOfAThickWalledRoom) {
  const GltfFile f = scene("sunroom");
  const auto& lights = f.doc["extensions"]["KHR_lights_punctual"]["lights"];
  ASSERT_EQ(lights.size(), 1u);
  EXPECT_EQ(lights[0]["type"], "directional");
  const glm::dvec3 sun = rotation(f.doc["nodes"][f.node("sun")]) * glm::dvec3(0, 0, -1);

  const Surface floor = surface(f, "floor"), reveal = surface(f, "window_reveal");
  const Surface exterior = surface(f, "exterior");
  // Walls have thickness: the outside is beyond the inside on every side.
  EXPECT_LT(exterior.lo().x, floor.lo().x - 0.1);
  EXPECT_GT(exterior.hi().x, floor.hi().x + 0.1);
  EXPECT_LT(exterior.lo().y, floor.lo().y - 0.1);
  // The sun ray through the window's centre lands on the floor inside the room.
  const glm::dvec3 window_centre = (reveal.lo() + reveal.hi()) * 0.5;
  ASSERT_LT(sun.y, 0.0);
  const glm::dvec3 landing = window_centre + sun * (-window_centre.y / sun.y);
  EXPECT_GT(landing.x, floor.lo().x);
  EXPECT_LT(landing.x, floor.hi().x);
  EXPECT_GT(landing.z, floor.lo().z);
  EXPECT_LT(landing.z, floor.hi().z);

  // One glossy object; every other material is pure Lambert.
  int glossy = 0;
  for (const json& m : f.doc["materials"]) {
    const double roughness = m["pbrMetallicRoughness"].value("roughnessFactor", 1.0);
    if (roughness < 1.0) {
      ++glossy;
      EXPECT_NEAR(roughness, 0.2, 1e-6);
    } else {
      EXPECT_EQ(specular_factor(m), 0.0) << m["name"];
    }
  }
  EXPECT_EQ(glossy, 1);
}

namespace {

// Translation of an animated node at time t (glTF 2.0 §3.11: LINEAR interpolates between the
// keys around t, STEP holds the previous key; before the first and after the last key the
// end values hold).
glm::dvec3 sample(const GltfFile& f, const json& sampler, double t) {
  const auto times = f.floats(sampler["input"].get<int>());
  const auto values = f.vec3s(sampler["output"].get<int>());
  if (t <= times.front()) return values.front();
  if (t >= times.back()) return values.back();
  size_t k = 0;
  while (times[k + 1] <= t) ++k;
  if (sampler["interpolation"] == "STEP") return values[k];
  const double s = (t - times[k]) / (times[k + 1] - times[k]);
  return glm::mix(glm::dvec3(values[k]), glm::dvec3(values[k + 1]), s);
}

}  // namespace

TEST(MovingLightFile, LightFollowsTheDocumentedPath) {
  const GltfFile f = scene("movinglight");
  const json& seq = f.doc["extras"]["giq"]["sequence"];
  EXPECT_EQ(seq["frames"], 60);
  EXPECT_EQ(seq["fps"].get<double>(), 30.0);
  const json& anim = f.doc["animations"][seq["animation"].get<int>()];

  const int light = f.node("moving_light"), rig = f.node("light_rig");
  ASSERT_GE(light, 0);
  ASSERT_GE(rig, 0);
  EXPECT_EQ(f.doc["nodes"][rig]["children"], json::array({light}));
  auto position = [&](int frame) {
    glm::dvec3 rig_t = translation(f.doc["nodes"][rig]),
               light_t = translation(f.doc["nodes"][light]);
    for (const json& ch : anim["channels"]) {
      EXPECT_EQ(ch["target"]["path"], "translation");
      const glm::dvec3 v = sample(f, anim["samplers"][ch["sampler"].get<int>()], frame / 30.0);
      if (ch["target"]["node"] == rig) rig_t = v;
      if (ch["target"]["node"] == light) light_t = v;
    }
    return rig_t + light_t;  // the rig is not rotated
  };
  // Circle of radius 0.15 m around (0.278, 0.45, 0.2796) m, one turn over frames 0..30; jump to
  // (0.47, 0.12, 0.15) m between frames 29 and 30, held to the end.
  const glm::dvec3 centre(0.278, 0.45, 0.2796);
  auto circle = [&](int frame) {
    const double a = 2.0 * std::numbers::pi * frame / 30.0;
    return centre + 0.15 * glm::dvec3(std::cos(a), 0.0, std::sin(a));
  };
  for (int frame : {0, 7, 15, 29})
    EXPECT_NEAR(glm::length(position(frame) - circle(frame)), 0.0, kPositionTolerance) << frame;
  for (int frame : {30, 45, 59})
    EXPECT_NEAR(glm::length(position(frame) - glm::dvec3(0.47, 0.12, 0.15)), 0.0,
                kPositionTolerance)
        << frame;

  // Same power as the cornell ceiling light: I = A L / 4, A = 0.13 m x 0.105 m.
  const json& l = f.doc["extensions"]["KHR_lights_punctual"]["lights"][0];
  EXPECT_EQ(l["type"], "point");
  const glm::dvec3 radiant = vec3(l["color"]) * l["intensity"].get<double>();
  const glm::dvec3 expected = 0.130 * 0.105 * glm::dvec3(17.0, 12.0, 4.0) / 4.0;
  EXPECT_NEAR(glm::length(radiant - expected), 0.0, 1e-7);
  EXPECT_LT(f.node("light"), 0) << "the ceiling light is off in movinglight";
}

namespace {

// A node's transform at rest as a matrix (translation, rotation; the writer writes no scale).
glm::dmat4 local_matrix(const json& node) {
  return glm::translate(glm::dmat4(1.0), translation(node)) * glm::mat4_cast(rotation(node));
}

}  // namespace

// The walker's skin (glTF 2.0 §3.7.3): its joints are walker_root and its descendants; each
// inverse bind matrix is the inverse of its joint's world transform at rest, so the mesh as
// written is the bind pose and stands where the root stands; every vertex's weights sum to 1
// over at most two joints, the same joint or a parent and its child (a bend, not a tear).
TEST(DynamicFile, WalkerSkinIsItsOwnBindPoseAndBlendsOnlyNeighbours) {
  const GltfFile f = scene("dynamic");
  const int walker = f.node("walker");
  ASSERT_GE(walker, 0);
  const json& node = f.doc["nodes"][walker];
  ASSERT_TRUE(node.contains("skin"));
  EXPECT_FALSE(node.contains("translation") || node.contains("rotation")) << "a skinned node's transform is ignored";
  const json& skin = f.doc["skins"][node["skin"].get<int>()];
  const std::vector<int> joints = skin["joints"].get<std::vector<int>>();
  ASSERT_EQ(joints.size(), 10u);
  EXPECT_EQ(joints[0], f.node("walker_root"));
  EXPECT_EQ(skin["skeleton"], joints[0]);

  std::map<int, int> parent;
  for (size_t i = 0; i < f.doc["nodes"].size(); ++i)
    for (const json& c : f.doc["nodes"][i].value("children", json::array())) parent[c.get<int>()] = int(i);
  auto world = [&](int n) {
    glm::dmat4 m = local_matrix(f.doc["nodes"][n]);
    for (auto it = parent.find(n); it != parent.end(); it = parent.find(it->second))
      m = local_matrix(f.doc["nodes"][it->second]) * m;
    return m;
  };
  const std::vector<glm::mat4> inverse_bind = f.mat4s(skin["inverseBindMatrices"].get<int>());
  ASSERT_EQ(inverse_bind.size(), joints.size());
  for (size_t j = 0; j < joints.size(); ++j) {
    if (j > 0) {
      EXPECT_TRUE(parent.count(joints[j]) && std::count(joints.begin(), joints.end(), parent[joints[j]])) << j;
    }
    // Float storage of matrices with entries below 10: ~1e-6 each.
    const glm::dmat4 product = world(joints[j]) * glm::dmat4(inverse_bind[j]);
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) EXPECT_NEAR(product[c][r], c == r ? 1.0 : 0.0, 1e-5) << "joint " << j;
  }

  const json& attributes = f.doc["meshes"][node["mesh"].get<int>()]["primitives"][0]["attributes"];
  const auto indices = f.bytes4(attributes["JOINTS_0"].get<int>());
  const auto weights = f.vec4s(attributes["WEIGHTS_0"].get<int>());
  const auto positions = f.vec3s(attributes["POSITION"].get<int>());
  ASSERT_EQ(indices.size(), positions.size());
  ASSERT_EQ(weights.size(), positions.size());
  glm::dvec3 lo(INFINITY), hi(-INFINITY);
  for (size_t v = 0; v < positions.size(); ++v) {
    lo = glm::min(lo, glm::dvec3(positions[v])), hi = glm::max(hi, glm::dvec3(positions[v]));
    const glm::dvec4 w(weights[v]);
    // glTF 2.0 §3.7.3.3: the sum within the float rounding of its terms.
    EXPECT_NEAR(w.x + w.y + w.z + w.w, 1.0, 4e-7) << v;
    EXPECT_EQ(w.z, 0.0);
    EXPECT_EQ(w.w, 0.0);
    const int a = joints.at(indices[v].x), b = joints.at(indices[v].y);
    if (w.y > 0.0) {
      EXPECT_TRUE(a == b || parent[a] == b || parent[b] == a) << "vertex " << v;
    }
  }
  // At rest the figure stands on the floor at the root's place, 1.8 m tall.
  const glm::dvec3 root = translation(f.doc["nodes"][joints[0]]);
  EXPECT_NEAR(lo.y, 0.0, kPositionTolerance);
  EXPECT_NEAR(hi.y, 1.8, kPositionTolerance);
  EXPECT_LT(glm::length(glm::dvec2((lo + hi).x / 2 - root.x, (lo + hi).z / 2 - root.z)), 0.1);
}

// The lamp jumps once, by a STEP key half-way between frames 29 and 30, and declares itself a
// rectangle; the fountain emits from the nozzle on the basin, inside the main room.
TEST(DynamicFile, LampStepsOnceAndTheFountainIsInTheRoom) {
  const GltfFile f = scene("dynamic");
  const int lamp = f.node("lamp");
  ASSERT_GE(lamp, 0);
  EXPECT_EQ(f.doc["meshes"][f.doc["nodes"][lamp]["mesh"].get<int>()]["extras"]["giq"]["area_light"], "rectangle");
  const json& seq = f.doc["extras"]["giq"]["sequence"];
  EXPECT_EQ(seq["frames"], 120);
  const json& anim = f.doc["animations"][seq["animation"].get<int>()];
  int lamp_channels = 0;
  for (const json& ch : anim["channels"]) {
    if (ch["target"]["node"] != lamp) continue;
    ++lamp_channels;
    const json& sampler = anim["samplers"][ch["sampler"].get<int>()];
    EXPECT_EQ(sampler["interpolation"], "STEP");
    EXPECT_EQ(f.floats(sampler["input"].get<int>()), (std::vector<float>{0.0f, float(29.5 / 30.0)}));
    for (int frame : {0, 29})
      EXPECT_NEAR(glm::length(sample(f, sampler, frame / 30.0) - glm::dvec3(3.6, 2.4, 3.0)), 0.0, kPositionTolerance);
    for (int frame : {30, 119})
      EXPECT_NEAR(glm::length(sample(f, sampler, frame / 30.0) - glm::dvec3(5.4, 2.4, 2.4)), 0.0, kPositionTolerance);
  }
  EXPECT_EQ(lamp_channels, 1);

  const json& emitters = f.doc["extras"]["giq"]["emitters"];
  ASSERT_EQ(emitters.size(), 1u);
  EXPECT_EQ(emitters[0]["node"], "nozzle");
  const Surface nozzle = surface(f, "nozzle"), basin = surface(f, "basin");
  for (size_t i = 0; i < nozzle.positions.size(); ++i) {
    EXPECT_NEAR(glm::length(nozzle.normals[i] - glm::dvec3(0.0, 1.0, 0.0)), 0.0, 1e-6);
    EXPECT_GT(nozzle.positions[i].y, basin.hi().y);
    EXPECT_LT(nozzle.positions[i].y, basin.hi().y + 0.01);
  }
  // Inside the main room, short of the thin wall at x = 8 +- 0.01.
  EXPECT_LT(basin.hi().x, 7.99);
  EXPECT_LT(surface(f, "thin_wall_room").hi().x, 8.0);
  EXPECT_GT(surface(f, "thin_wall_closet").lo().x, 8.0);
}
