#pragma once
// What tests read back from the scene on the GPU (SceneGpu): its vertices, and the BVH bounds
// it refits there (BvhRefitter) after the deformation and particle passes, checked against
// refit_bvh over the same (GPU) vertices, bit for bit.

#include <gtest/gtest.h>

#include <cstring>
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

// The nodes the GPU refitted: the bounds refit_bvh makes over the same (GPU) vertices, exactly.
inline void expect_refit_exact(const realtime::SceneGpu& gpu, const std::string& what) {
  const std::vector<uint8_t> nb = gpu.bvh_nodes().download();
  std::vector<glm::vec3> positions;
  for (const realtime::gpu::GpuVertex& v : vertex_rows(gpu.vertices())) positions.emplace_back(v.position);
  realtime::Bvh expected = gpu.bvh();
  refit_bvh(expected, positions, gpu.geometry().triangles);
  ASSERT_GE(nb.size(), expected.nodes.size() * sizeof(realtime::BvhNode)) << what;
  for (size_t i = 0; i < expected.nodes.size(); ++i) {
    realtime::BvhNode n;
    std::memcpy(&n, nb.data() + i * sizeof(realtime::BvhNode), sizeof(realtime::BvhNode));
    ASSERT_TRUE(n.lo == expected.nodes[i].lo && n.hi == expected.nodes[i].hi && n.index == expected.nodes[i].index &&
                n.count == expected.nodes[i].count)
        << what << ", node " << i;
  }
}

}  // namespace giq::test
