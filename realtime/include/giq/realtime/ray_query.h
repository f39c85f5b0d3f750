#pragma once
// Traces a batch of rays through the GPU BVH (shaders/ray_query.comp): the same traversal
// every technique uses, exposed so it can be checked against another ray tracer.

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "giq/realtime/pipeline.h"

namespace giq::realtime {

class Context;
class SceneGpu;
class ShaderCompiler;

struct QueryRay {
  glm::vec4 org_tmax;  // origin (local frame), tmax
  glm::vec4 dir_any;   // direction (need not be unit); w = 1 for an any-hit query
};
struct QueryHit {
  uint32_t triangle;  // global triangle index, 0xffffffff = miss
  float t, u, v;
};

class RayQuery {
 public:
  RayQuery(Context& ctx, ShaderCompiler& compiler, const SceneGpu& scene);
  std::vector<QueryHit> trace(const std::vector<QueryRay>& rays);

 private:
  Context& ctx_;
  const SceneGpu& scene_;
  Pipeline pipeline_;
};

}  // namespace giq::realtime
