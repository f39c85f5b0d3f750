#pragma once
// A bounding volume hierarchy over triangles, built on the CPU with the binned surface area
// heuristic (Wald 2007, "On fast Construction of SAH-based Bounding Volume Hierarchies") and
// flattened depth-first for the GPU traversal in shaders/bvh.glsl.

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace giq::realtime {

struct BvhNode {
  glm::vec3 lo{0.0f};
  uint32_t index = 0;  // interior: right child; leaf: first entry of Bvh::prims
  glm::vec3 hi{0.0f};
  uint32_t count = 0;  // 0 = interior (left child = this node + 1)
};
static_assert(sizeof(BvhNode) == 32);

struct Bvh {
  std::vector<BvhNode> nodes;   // nodes[0] is the root; empty for an empty scene
  std::vector<uint32_t> prims;  // triangle indices, grouped by leaf
  int depth = 0;                // levels; the GPU traversal stack holds kMaxDepth
  static constexpr int kMaxDepth = 64;
};

struct BvhOptions {
  int bins = 16;
  int max_leaf_size = 4;
  // SAH costs of a traversal step and of a triangle test (relative).
  float traversal_cost = 1.0f;
  float intersection_cost = 1.0f;
};

Bvh build_bvh(const std::vector<glm::vec3>& positions, const std::vector<glm::uvec3>& triangles,
              const BvhOptions& options = {});

// The same tree over moved vertices (the same triangles, deformed): every node's bounds
// recomputed bottom-up, the topology kept. A refit costs one pass over the triangles and the
// nodes; the tree was chosen for the old positions, so its SAH cost grows with the motion.
void refit_bvh(Bvh& bvh, const std::vector<glm::vec3>& positions, const std::vector<glm::uvec3>& triangles);
// The same where only some triangles moved (`moved[t]` nonzero): only the leaves that hold one
// and the nodes above them are recomputed, the rest kept, which gives refit_bvh's tree to the
// bit (a box is the min and max of its triangles' vertices, in any order). The nodes
// recomputed go to `refitted`, ascending. A pass over the prims and the nodes to find them,
// the arithmetic only where something moved.
void refit_bvh(Bvh& bvh, const std::vector<glm::vec3>& positions, const std::vector<glm::uvec3>& triangles,
               const std::vector<uint8_t>& moved, std::vector<uint32_t>& refitted);

// The tree's expected cost of a random ray by the surface area heuristic: the traversal and
// intersection costs of every node weighted by its area relative to the root's.
double sah_cost(const Bvh& bvh, const BvhOptions& options = {});

// The watertight ray/triangle test of shaders/bvh.glsl on the CPU (Woop, Benthin, Wald 2013,
// "Watertight Ray/Triangle Intersection", JCGT 2(1)), for tests that explain GPU answers.
// Returns false when the ray misses the triangle in (0, tmax).
struct BvhHit {
  uint32_t triangle = ~0u;
  float t = 0.0f;
  float u = 0.0f, v = 0.0f;  // barycentric weights of the triangle's second and third vertex
};
bool intersect_triangle(glm::vec3 org, glm::vec3 dir, glm::vec3 a, glm::vec3 b, glm::vec3 c, float tmax, BvhHit& hit);

}  // namespace giq::realtime
