#pragma once
// What tests read back from the scene on the GPU (SceneGpu): its vertices, and the BVH it
// holds after the deformation and particle passes (the CPU's tree refitted there by
// BvhRefitter, the particles' built there by LinearBvh), checked against the GPU's vertices,
// bit for bit.

#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "giq/realtime/bvh.h"
#include "giq/realtime/scene_gpu.h"
#include "shaders/scene_shared.h"

namespace giq::test {

// A GpuVertex array (SceneGpu::vertices(), previous_vertices()) as the GPU holds it.
inline std::vector<realtime::gpu::GpuVertex> vertex_rows(const realtime::Buffer& buffer) {
  const std::vector<uint8_t> bytes = buffer.download();
  std::vector<realtime::gpu::GpuVertex> rows(bytes.size() / sizeof(realtime::gpu::GpuVertex));
  std::memcpy(rows.data(), bytes.data(), rows.size() * sizeof(realtime::gpu::GpuVertex));
  return rows;
}

// The tree the GPU holds, walked from its root: every triangle of the scene in exactly one
// leaf; every leaf's box exactly its triangles' over the GPU's vertices and every interior
// box exactly its children's (min and max round nothing, so refit_bvh and the GPU's builds
// agree to the bit); no deeper than the traversal's stack. The CPU's tree is the part of it
// from node cpu_tree_offset() on, node for node. A leaf with an empty box (a tree without
// triangles yet) may repeat triangle 0.
inline void expect_tree_exact(const realtime::SceneGpu& gpu, const std::string& what) {
  using realtime::BvhNode;
  const std::vector<uint8_t> nb = gpu.bvh_nodes().download(), pb = gpu.bvh_prims().download();
  std::vector<BvhNode> nodes(nb.size() / sizeof(BvhNode));
  std::memcpy(nodes.data(), nb.data(), nodes.size() * sizeof(BvhNode));
  std::vector<uint32_t> prims(pb.size() / sizeof(uint32_t));
  std::memcpy(prims.data(), pb.data(), prims.size() * sizeof(uint32_t));
  std::vector<glm::vec3> positions;
  for (const realtime::gpu::GpuVertex& v : vertex_rows(gpu.vertices())) positions.emplace_back(v.position);
  // The triangles as the GPU holds them: the host's and the particles' the GPU wrote.
  const std::vector<uint8_t> tb = gpu.triangles().download();
  ASSERT_GE(tb.size(), gpu.triangle_count() * sizeof(realtime::gpu::GpuTriangle)) << what;
  std::vector<glm::uvec3> triangles(gpu.triangle_count());
  for (size_t t = 0; t < triangles.size(); ++t) {
    realtime::gpu::GpuTriangle r;
    std::memcpy(&r, tb.data() + t * sizeof(r), sizeof(r));
    triangles[t] = glm::uvec3(r.v);
  }

  const realtime::Bvh& cpu = gpu.bvh();
  const uint32_t offset = gpu.cpu_tree_offset();
  for (size_t i = 0; i < cpu.nodes.size(); ++i) {
    const BvhNode& n = nodes.at(offset + i);
    ASSERT_TRUE(n.count == cpu.nodes[i].count && n.index == cpu.nodes[i].index + (n.count == 0 ? offset : 0)) << what << ", node " << i;
  }

  std::vector<int> seen(triangles.size(), 0);
  std::vector<std::pair<uint32_t, int>> stack{{0u, 1}};
  const glm::vec3 inf(std::numeric_limits<float>::infinity());
  // Leaves are checked as they are visited; interior nodes afterwards, in the reverse of the
  // visiting order, which puts every node after its children.
  std::vector<std::pair<glm::vec3, glm::vec3>> box(nodes.size(), {inf, -inf});
  std::vector<uint32_t> order;
  while (!stack.empty()) {
    const auto [i, depth] = stack.back();
    stack.pop_back();
    ASSERT_LT(i, nodes.size()) << what;
    ASSERT_LE(depth, realtime::Bvh::kMaxDepth) << what << ", node " << i;
    order.push_back(i);
    const BvhNode& n = nodes[i];
    if (n.count == 0) {
      stack.push_back({i + 1, depth + 1});
      stack.push_back({n.index, depth + 1});
      continue;
    }
    glm::vec3 lo = inf, hi = -inf;
    const bool empty = n.lo == inf && n.hi == -inf;
    for (uint32_t k = n.index; k < n.index + n.count; ++k) {
      ASSERT_LT(k, prims.size()) << what << ", node " << i;
      const uint32_t t = prims[k];
      ASSERT_LT(t, triangles.size()) << what << ", node " << i;
      if (empty) {
        EXPECT_EQ(t, 0u) << what << ", node " << i;
        continue;
      }
      ++seen[t];
      for (int c = 0; c < 3; ++c) lo = glm::min(lo, positions.at(triangles[t][c])), hi = glm::max(hi, positions.at(triangles[t][c]));
    }
    box[i] = {lo, hi};
    ASSERT_TRUE(n.lo == lo && n.hi == hi) << what << ", leaf " << i;
  }
  for (size_t k = order.size(); k-- > 0;) {
    const uint32_t i = order[k];
    const BvhNode& n = nodes[i];
    if (n.count > 0) continue;
    box[i] = {glm::min(box[i + 1].first, box[n.index].first), glm::max(box[i + 1].second, box[n.index].second)};
    ASSERT_TRUE(n.lo == box[i].first && n.hi == box[i].second) << what << ", node " << i;
  }
  for (size_t t = 0; t < seen.size(); ++t) ASSERT_EQ(seen[t], 1) << what << ", triangle " << t << " in " << seen[t] << " leaves";
}

}  // namespace giq::test
