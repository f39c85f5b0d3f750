#pragma once
// The scene's triangles in an Embree 3 BVH: one triangle geometry per Mesh (geometry ID =
// mesh index), robust traversal, and alpha-mask cut-outs as Embree filter functions, attached
// only to the meshes whose material asks for them.
//
// Positions are copied into the renderer's frame, the scene's local frame shifted by the
// centre of its bounds: small coordinates keep the ray-offset and intersection errors
// proportional to the scene's size wherever the scene was built.

#include <embree3/rtcore.h>
#include <glm/glm.hpp>

#include <cstdint>
#include <limits>
#include <vector>

#include "giq/scenes/scene.h"

namespace giq::reference {

struct Hit {
  float t = std::numeric_limits<float>::infinity();
  uint32_t mesh = RTC_INVALID_GEOMETRY_ID;
  uint32_t triangle = 0;
  float b1 = 0.0f, b2 = 0.0f;  // barycentrics of vertices 1 and 2
  bool valid() const { return mesh != RTC_INVALID_GEOMETRY_ID; }
};

// What every hit needs of its triangle beyond the vertices, computed once at build: the unit
// geometric normal (glTF front face: counter-clockwise winding), the area and the distance
// that rays leaving it are lifted by (ray_offset.h). A degenerate triangle has area 0 and a
// non-finite normal; Embree never reports hits on one.
struct TriangleShape {
  glm::vec3 normal{0.0f};
  float area = 0.0f;
  float offset = 0.0f;
};

// A ray as the integrators traced it, for giq-bench-reference's raw Embree rate
// (EmbreeScene::record).
struct TracedRay {
  glm::vec3 origin{0.0f}, dir{0.0f};
  float tfar = 0.0f;
  enum Kind : uint8_t { Camera, Bounce, Shadow } kind = Bounce;
};

class EmbreeScene {
 public:
  // While `log` is set, every ray any EmbreeScene traces is appended to it: for a render with
  // one thread only (the log is not synchronised), so that a benchmark can trace the same
  // rays again with nothing else around them. Null stops it.
  static void record(std::vector<TracedRay>* log);

  // alpha_mask: whether to install the cut-out filters (the scene's FeatureSet says).
  EmbreeScene(const scenes::Scene& scene, glm::vec3 centre, bool alpha_mask);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  Hit intersect(glm::vec3 origin, glm::vec3 dir, float tfar = std::numeric_limits<float>::infinity()) const;
  // A camera ray: glTF 2.0, 3.9.5 "Double Sided": a single-sided surface is not rendered from
  // behind (back-face culling), so a camera ray passes through the back of one. Rays of light
  // transport still meet it there (black, reflecting and emitting nothing), so that
  // visibility stays the same in both directions.
  Hit intersect_camera(glm::vec3 origin, glm::vec3 dir) const;
  bool occluded(glm::vec3 origin, glm::vec3 dir, float tfar) const;
  // The same for eight rays at once (Embree's packet queries, "rtcIntersect8"), the rays of
  // lane_integrator.h's eight paths; lanes whose `valid` is 0 are skipped. The hit is in
  // `rays.hit`, and an occluded ray's tfar becomes -inf. `camera`: some ray has kCameraRay
  // set in its id, and those are camera rays (intersect_camera).
  void intersect(const int* valid, RTCRayHit8& rays, bool camera) const;
  void occluded(const int* valid, RTCRay8& rays) const;

  // Per mesh, vertex positions in the renderer's frame.
  const std::vector<std::vector<glm::vec3>>& positions() const { return positions_; }
  // Per mesh, per triangle, from those positions.
  const std::vector<std::vector<TriangleShape>>& shapes() const { return shapes_; }

  static constexpr unsigned kCameraRay = 1u << 31;

  struct AlphaMask;  // what a filter function needs to look up a texel's coverage

 private:
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  std::vector<std::vector<glm::vec3>> positions_;
  std::vector<std::vector<TriangleShape>> shapes_;
  std::vector<AlphaMask*> masks_;
  std::vector<char> single_sided_;  // per mesh: its material is single-sided

  // Whether a camera ray along d culls its hit on that triangle: the back of a single-sided
  // surface.
  bool culled(uint32_t mesh, uint32_t triangle, glm::vec3 d) const;
};

}  // namespace giq::reference
