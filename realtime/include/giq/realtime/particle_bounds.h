#pragma once
// Where each stage of particles is, from the octahedra the GPU simulation wrote into the
// scene's vertex array (shaders/particle_bounds.comp): the centroid, box and extent that a
// scene posed with counted particles (scenes::ParticleDetail::Counted) leaves to the renderer
// that places them, for its area lights (the shadow cube at the centroid, shadow rays that
// stop at the extent) and its bounds; and how near the particles come to each point light, for
// the bounds on irradiance that the host can no longer take from triangles it does not hold
// (techniques/vct/voxel_scale.h). Recorded with the particle passes and read after the
// submission that runs them, which SceneGpu::update waits for anyway: the host evaluates no
// particle.

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "giq/realtime/pipeline.h"
#include "giq/realtime/resources.h"

namespace giq::realtime {

class Context;
class ShaderCompiler;

class ParticleBounds {
 public:
  ParticleBounds(Context& ctx, ShaderCompiler& compiler);

  // A stage's particles in the vertex array: six vertices each from first_vertex on.
  struct Range {
    uint32_t first_vertex = 0, particles = 0;
  };
  // Records the reduction of every range of `vertices` (gpu::GpuVertex), barrier included;
  // `points`: positions (w 1) whose distance to the particles is wanted, w 0 for none.
  void record(VkCommandBuffer cmd, const Buffer& vertices, const std::vector<Range>& ranges,
              const std::vector<glm::vec4>& points = {});

  struct Stage {
    uint32_t particles = 0;
    glm::vec3 centroid{0.0f};  // of the particles' centres
    glm::vec3 lo{0.0f}, hi{0.0f};  // the vertices' box
    float extent = 0.0f;       // the largest distance of a vertex from the centroid
    // Per point of record(): at most the distance from it to the nearest particle's surface
    // (shaders/particle_bounds.comp, octahedron_distance); infinity for a w 0 point.
    std::vector<float> nearest;
  };
  // After the recorded commands ran: one per range of the last record(), in order (an empty
  // range's all zero).
  std::vector<Stage> read() const;

 private:
  Context* ctx_;
  Pipeline pipeline_;
  Buffer chunks_, stages_, partials_, results_, points_, nearest_;
  std::vector<glm::uvec4> stage_rows_;  // per range: first chunk, chunks, particles
  uint32_t points_count_ = 0;
};

}  // namespace giq::realtime
