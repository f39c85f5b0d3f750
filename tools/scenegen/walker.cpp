#include "walker.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <numbers>
#include <stdexcept>
#include <tuple>

namespace giq::scenegen {
namespace {

// The skin's joints, in the order of skins[].joints (the vertices' JOINTS_0 indices).
enum Joint : uint8_t { kRoot, kPelvis, kSpine, kHead, kThighL, kShinL, kThighR, kShinR, kArmL, kArmR, kJoints };

// The bind pose, in the figure's own frame: feet on y = 0, facing +z, its left along +x.
constexpr double kPelvisHeight = 0.95;
constexpr double kHipHeight = 0.92, kKneeHeight = 0.47, kShoulderHeight = 1.45;
constexpr double kHipX = 0.1, kShoulderX = 0.24;
constexpr double kLegLength = kHipHeight;  // hip to sole
constexpr double kHeadTop = 1.8;

// Two joints and the weight of the second: one vertex's influences.
struct Influence {
  Joint a, b;
  double wb;
};

// Appends triangles over the vertices i0-i1-i2-i3 (a planar quad in cyclic order), wound so
// that their normal points along `n`.
void add_face(MeshData& m, uint32_t i0, uint32_t i1, uint32_t i2, uint32_t i3, glm::dvec3 n) {
  const glm::dvec3 c = glm::cross(m.positions[i1] - m.positions[i0], m.positions[i2] - m.positions[i0]);
  if (glm::dot(c, n) < 0.0) std::swap(i1, i3);
  m.indices.insert(m.indices.end(), {i0, i1, i2, i0, i2, i3});
}

uint32_t add_vertex(MeshData& m, SkinWeights& w, glm::dvec3 p, glm::dvec3 n, Influence f) {
  m.positions.push_back(p);
  m.normals.push_back(n);
  w.joints.push_back({f.a, f.b, 0, 0});
  w.weights.emplace_back(1.0 - f.wb, f.wb, 0.0, 0.0);
  return static_cast<uint32_t>(m.positions.size() - 1);
}

// A box-section tube along y through `levels` (increasing), centred on (x, z) with half sizes
// (hx, hz), its ends capped; each level's vertices take that level's influences. Every side
// keeps its own vertices (flat shaded), shared along its length so it bends smoothly.
void add_tube(MeshData& m, SkinWeights& w, double x, double z, double hx, double hz,
              const std::vector<double>& levels, const std::function<Influence(double)>& influence) {
  const std::array<glm::dvec2, 4> corner = {glm::dvec2{x - hx, z - hz}, {x + hx, z - hz}, {x + hx, z + hz}, {x - hx, z + hz}};
  for (int side = 0; side < 4; ++side) {
    const glm::dvec2 c0 = corner[side], c1 = corner[(side + 1) % 4];
    const glm::dvec2 mid = (c0 + c1) * 0.5 - glm::dvec2(x, z);
    const glm::dvec3 n = glm::normalize(glm::dvec3(mid.x, 0.0, mid.y));
    uint32_t previous0 = 0, previous1 = 0;
    for (size_t i = 0; i < levels.size(); ++i) {
      const double y = levels[i];
      const uint32_t v0 = add_vertex(m, w, {c0.x, y, c0.y}, n, influence(y));
      const uint32_t v1 = add_vertex(m, w, {c1.x, y, c1.y}, n, influence(y));
      if (i > 0) add_face(m, previous0, previous1, v1, v0, n);
      previous0 = v0, previous1 = v1;
    }
  }
  for (const double y : {levels.front(), levels.back()}) {
    const glm::dvec3 n(0.0, y == levels.front() ? -1.0 : 1.0, 0.0);
    uint32_t v[4];
    for (int k = 0; k < 4; ++k) v[k] = add_vertex(m, w, {corner[k].x, y, corner[k].y}, n, influence(y));
    add_face(m, v[0], v[1], v[2], v[3], n);
  }
}

// A box moving rigidly with one joint.
void add_rigid_box(MeshData& m, SkinWeights& w, glm::dvec3 lo, glm::dvec3 hi, Joint joint) {
  MeshData box;
  add_box(box, lo, hi);
  const auto base = static_cast<uint32_t>(m.positions.size());
  for (size_t i = 0; i < box.positions.size(); ++i) add_vertex(m, w, box.positions[i], box.normals[i], {joint, joint, 0.0});
  for (uint32_t i : box.indices) m.indices.push_back(base + i);
}

// The figure's surface in its bind pose.
void build_body(MeshData& m, SkinWeights& w) {
  // Torso, waist bending between pelvis and spine.
  add_tube(m, w, 0.0, 0.0, 0.17, 0.1, {0.9, 1.0, 1.1, 1.2, 1.3, 1.4, 1.5},
           [](double y) { return Influence{kPelvis, kSpine, glm::smoothstep(1.0, 1.1, y)}; });
  add_rigid_box(m, w, {-0.1, 1.55, -0.11}, {0.1, kHeadTop, 0.11}, kHead);
  add_tube(m, w, 0.0, 0.0, 0.045, 0.045, {1.48, 1.56}, [](double y) { return Influence{kSpine, kHead, glm::smoothstep(1.5, 1.56, y)}; });
  // Legs: the hip blends pelvis into thigh, the knee thigh into shin.
  const std::vector<double> leg = {0.05, 0.2, 0.35, 0.41, 0.47, 0.53, 0.59, 0.7, 0.8, 0.87, 0.93, 0.98};
  for (const auto& [x, thigh, shin] : {std::tuple{kHipX, kThighL, kShinL}, std::tuple{-kHipX, kThighR, kShinR}}) {
    add_tube(m, w, x, 0.0, 0.065, 0.07, leg, [thigh, shin](double y) {
      if (y > 0.59) return Influence{thigh, kPelvis, glm::smoothstep(0.86, 0.98, y)};
      return Influence{shin, thigh, glm::smoothstep(kKneeHeight - 0.06, kKneeHeight + 0.06, y)};
    });
    add_rigid_box(m, w, {x - 0.06, 0.0, -0.06}, {x + 0.06, 0.07, 0.18}, shin);
  }
  // Arms hang from the shoulders, which blend spine into arm.
  const std::vector<double> arm = {0.78, 0.95, 1.1, 1.25, 1.35, 1.42, 1.48};
  for (const auto& [x, joint] : {std::pair{kShoulderX, kArmL}, std::pair{-kShoulderX, kArmR}})
    add_tube(m, w, x, 0.0, 0.045, 0.05, arm, [joint](double y) { return Influence{joint, kSpine, glm::smoothstep(1.36, 1.47, y)}; });
}

glm::dquat about_x(double angle) { return glm::angleAxis(angle, glm::dvec3(1.0, 0.0, 0.0)); }

}  // namespace

Walker add_walker(GltfWriter& gltf, const WalkSpec& walk, int material) {
  if (!(walk.radius > 0.0 && walk.lap_seconds > 0.0 && walk.stride_seconds > 0.0 && walk.keys > 1))
    throw std::logic_error("walker: radius, lap, stride and keys must be positive");
  constexpr double kTau = 2.0 * std::numbers::pi;
  Walker out;
  out.speed = kTau * walk.radius / walk.lap_seconds;
  // While a foot stands, the hip passes over it by half a stride: the leg sweeps 2 A with
  // 2 L sin A = speed x stride / 2.
  const double swing = std::asin(out.speed * walk.stride_seconds / (4.0 * kLegLength));
  const double knee = 2.0 * swing;
  out.hip_swing_deg = glm::degrees(swing);
  out.knee_bend_deg = glm::degrees(knee);
  out.height = kHeadTop;

  // Where the root is and which way it faces at time t: on the circle, along its tangent.
  auto root_pose = [&](double t) {
    const double phi = kTau * t / walk.lap_seconds;
    const glm::dvec3 tangent(-std::sin(phi), 0.0, std::cos(phi));
    return Pose{walk.centre + walk.radius * glm::dvec3(std::cos(phi), 0.0, std::sin(phi)),
                glm::angleAxis(std::atan2(tangent.x, tangent.z), glm::dvec3(0.0, 1.0, 0.0))};
  };
  const Pose rest = root_pose(0.0);
  std::vector<int>& j = out.joints;
  j.resize(kJoints);
  j[kRoot] = gltf.add_group_node("walker_root", rest);
  j[kPelvis] = gltf.add_group_node("walker_pelvis", {{0.0, kPelvisHeight, 0.0}}, j[kRoot]);
  j[kSpine] = gltf.add_group_node("walker_spine", {{0.0, 0.1, 0.0}}, j[kPelvis]);
  j[kHead] = gltf.add_group_node("walker_head", {{0.0, 0.5, 0.0}}, j[kSpine]);
  j[kThighL] = gltf.add_group_node("walker_thigh_l", {{kHipX, kHipHeight - kPelvisHeight, 0.0}}, j[kPelvis]);
  j[kShinL] = gltf.add_group_node("walker_shin_l", {{0.0, kKneeHeight - kHipHeight, 0.0}}, j[kThighL]);
  j[kThighR] = gltf.add_group_node("walker_thigh_r", {{-kHipX, kHipHeight - kPelvisHeight, 0.0}}, j[kPelvis]);
  j[kShinR] = gltf.add_group_node("walker_shin_r", {{0.0, kKneeHeight - kHipHeight, 0.0}}, j[kThighR]);
  j[kArmL] = gltf.add_group_node("walker_arm_l", {{kShoulderX, kShoulderHeight - kPelvisHeight - 0.1, 0.0}}, j[kSpine]);
  j[kArmR] = gltf.add_group_node("walker_arm_r", {{-kShoulderX, kShoulderHeight - kPelvisHeight - 0.1, 0.0}}, j[kSpine]);
  const int skin = gltf.add_skin("walker", j);

  // The mesh in world coordinates at rest, which is the skin's bind pose.
  MeshData body;
  SkinWeights weights;
  build_body(body, weights);
  for (size_t i = 0; i < body.positions.size(); ++i) {
    body.positions[i] = rest.rotation * body.positions[i] + rest.translation;
    body.normals[i] = rest.rotation * body.normals[i];
  }
  out.mesh_node = gltf.add_skinned_mesh_node("walker", body, weights, material, skin);
  out.triangles = body.triangle_count();

  // One key a frame over the lap. The gait: hips swing +-A (sin), each knee bends while its
  // leg swings forward (cos^2 of the half cycle), the arms swing against the legs and the
  // pelvis dips 15 mm at the ends of each step.
  TranslationTrack root{j[kRoot], Interpolation::Linear, {}, {}}, pelvis{j[kPelvis], Interpolation::Linear, {}, {}};
  RotationTrack turn{j[kRoot], Interpolation::Linear, {}, {}};
  std::vector<RotationTrack> limbs;
  for (Joint joint : {kThighL, kShinL, kThighR, kShinR, kArmL, kArmR}) limbs.push_back({j[joint], Interpolation::Linear, {}, {}});
  const double omega = kTau / walk.stride_seconds;
  for (int k = 0; k <= walk.keys; ++k) {
    const double t = walk.lap_seconds * k / walk.keys;
    const Pose p = root_pose(t);
    const double s = std::sin(omega * t), c = std::cos(omega * t);
    root.values.push_back(p.translation);
    turn.values.push_back(p.rotation);
    pelvis.values.push_back({0.0, kPelvisHeight - 0.0075 * (1.0 - std::cos(2.0 * omega * t)), 0.0});
    // A positive turn about +x swings a hanging limb backwards (-z).
    const double angles[] = {-swing * s, knee * std::pow(std::max(0.0, c), 2.0),
                             swing * s,  knee * std::pow(std::max(0.0, -c), 2.0),
                             0.6 * swing * s, -0.6 * swing * s};
    for (size_t l = 0; l < limbs.size(); ++l) limbs[l].values.push_back(about_x(angles[l]));
    for (auto* track : {&root.times, &pelvis.times, &turn.times}) track->push_back(t);
    for (RotationTrack& l : limbs) l.times.push_back(t);
  }
  out.translations = {root, pelvis};
  out.rotations = {turn};
  out.rotations.insert(out.rotations.end(), limbs.begin(), limbs.end());
  return out;
}

}  // namespace giq::scenegen
