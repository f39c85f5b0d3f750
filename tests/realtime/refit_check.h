#pragma once
// The BVH bounds SceneGpu refits on the GPU (BvhRefitter) after the deformation and particle
// passes, checked against refit_bvh over the same (GPU) vertices: bit for bit.

#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "giq/realtime/bvh.h"
#include "giq/realtime/scene_gpu.h"
#include "shaders/scene_shared.h"

namespace giq::test {

// The nodes the GPU refitted: the bounds refit_bvh makes over the same (GPU) vertices, exactly.
inline void expect_refit_exact(const realtime::SceneGpu& gpu, const std::string& what) {
  const std::vector<uint8_t> vb = gpu.vertices().download(), nb = gpu.bvh_nodes().download();
  std::vector<glm::vec3> positions(vb.size() / sizeof(realtime::gpu::GpuVertex));
  for (size_t i = 0; i < positions.size(); ++i) std::memcpy(&positions[i], vb.data() + i * sizeof(realtime::gpu::GpuVertex), sizeof(glm::vec3));
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
