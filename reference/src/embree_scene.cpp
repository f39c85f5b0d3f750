#include "embree_scene.h"

#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

#include "giq/reference/ray_offset.h"

namespace giq::reference {

struct EmbreeScene::AlphaMask {
  const scenes::Scene* scene;
  const scenes::Mesh* mesh;
};

namespace {

// A number in [0, 1) that is a function of the ray and the triangle only: BLEND's stochastic
// transparency decides with it (a ray passes a surface of coverage c when it is >= c). Rays of
// different samples differ, so the decisions are independent across samples, and the same
// ray gives the same decision in every integrator and thread. splitmix64's finaliser
// (Steele, Lea and Flood 2014) over the ray's float bits.
float ray_number(const RTCFilterFunctionNArguments* args, unsigned i, uint32_t prim) {
  auto bits = [](float f) {
    uint32_t b;
    std::memcpy(&b, &f, 4);
    return uint64_t(b);
  };
  auto mix = [](uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  };
  const unsigned n = args->N;
  uint64_t h = mix(bits(RTCRayN_org_x(args->ray, n, i)) | bits(RTCRayN_org_y(args->ray, n, i)) << 32);
  h = mix(h ^ (bits(RTCRayN_org_z(args->ray, n, i)) | bits(RTCRayN_dir_x(args->ray, n, i)) << 32));
  h = mix(h ^ (bits(RTCRayN_dir_y(args->ray, n, i)) | bits(RTCRayN_dir_z(args->ray, n, i)) << 32));
  h = mix(h ^ prim);
  return float(h >> 40) * 0x1p-24f;
}

// Rejects hits where the surface is not (alpha coverage): cut-out texels of MASK, and BLEND
// with probability 1 - alpha; serves both intersection and occlusion queries (Embree 3 API,
// "rtcSetGeometryIntersectFilterFunction").
void alpha_filter(const RTCFilterFunctionNArguments* args) {
  const auto* mask = static_cast<const EmbreeScene::AlphaMask*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const uint32_t prim = RTCHitN_primID(args->hit, args->N, i);
    const float u = RTCHitN_u(args->hit, args->N, i), v = RTCHitN_v(args->hit, args->N, i);
    const float c = mask->scene->coverage(*mask->mesh, mask->mesh->triangles[prim], u, v);
    if (c >= 1.0f) continue;
    if (c <= 0.0f || ray_number(args, i, prim) >= c) args->valid[i] = 0;
  }
}

void check(RTCDevice device, const char* what) {
  const RTCError e = rtcGetDeviceError(device);
  if (e != RTC_ERROR_NONE) throw std::runtime_error(std::string("Embree failed: ") + what + " (error " + std::to_string(int(e)) + ")");
}

}  // namespace

EmbreeScene::EmbreeScene(const scenes::Scene& scene, glm::vec3 centre, bool alpha_mask) {
  device_ = rtcNewDevice(nullptr);
  if (device_ == nullptr) throw std::runtime_error("Embree failed: cannot create a device");
  scene_ = rtcNewScene(device_);
  // Robust mode: watertight triangle tests, so rays cannot slip through shared edges.
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
  single_sided_.assign(scene.meshes.size(), 0);
  for (size_t m = 0; m < scene.meshes.size(); ++m)
    single_sided_[m] = !scene.materials.at(size_t(scene.meshes[m].material)).double_sided;
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
  positions_.resize(scene.meshes.size());
  shapes_.resize(scene.meshes.size());
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const scenes::Mesh& mesh = scene.meshes[m];
    std::vector<glm::vec3>& pos = positions_[m];
    pos.reserve(mesh.positions.size() + 1);
    for (const glm::vec3& p : mesh.positions) pos.push_back(p - centre);
    if (mesh.triangles.empty()) continue;
    shapes_[m].reserve(mesh.triangles.size());
    for (const glm::uvec3& t : mesh.triangles) {
      const glm::vec3 c = glm::cross(pos[t.y] - pos[t.x], pos[t.z] - pos[t.x]);
      const float len = glm::length(c);
      shapes_[m].push_back({c / len, 0.5f * len, ray_offset(pos[t.x], pos[t.y], pos[t.z])});
    }
    RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    // Embree reads vertex buffers with 16-byte loads: the last vertex needs 4 bytes of padding,
    // which the spare capacity reserved above provides.
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, pos.data(), 0, sizeof(glm::vec3), pos.size());
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, mesh.triangles.data(), 0, sizeof(glm::uvec3),
                               mesh.triangles.size());
    const scenes::Material& mat = scene.materials.at(size_t(mesh.material));
    if (alpha_mask && mat.alpha_mode != scenes::AlphaMode::Opaque) {
      masks_.push_back(new AlphaMask{&scene, &mesh});
      rtcSetGeometryUserData(g, masks_.back());
      rtcSetGeometryIntersectFilterFunction(g, alpha_filter);
      rtcSetGeometryOccludedFilterFunction(g, alpha_filter);
    }
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(scene_, g, unsigned(m));
    rtcReleaseGeometry(g);
    check(device_, "adding a mesh");
  }
  rtcCommitScene(scene_);
  check(device_, "building the BVH");
}

EmbreeScene::~EmbreeScene() {
  rtcReleaseScene(scene_);
  rtcReleaseDevice(device_);
  for (AlphaMask* m : masks_) delete m;
}

namespace {

RTCRayHit make_ray(glm::vec3 o, glm::vec3 d, float tfar, unsigned id) {
  RTCRayHit rh;
  rh.ray.org_x = o.x, rh.ray.org_y = o.y, rh.ray.org_z = o.z;
  rh.ray.dir_x = d.x, rh.ray.dir_y = d.y, rh.ray.dir_z = d.z;
  rh.ray.tnear = 0.0f;
  rh.ray.tfar = tfar;
  rh.ray.time = 0.0f;
  rh.ray.mask = 0xffffffffu;
  rh.ray.id = id;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return rh;
}

Hit to_hit(const RTCRayHit& rh) {
  Hit h;
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return h;
  h.t = rh.ray.tfar;
  h.mesh = rh.hit.geomID;
  h.triangle = rh.hit.primID;
  h.b1 = rh.hit.u, h.b2 = rh.hit.v;
  return h;
}

}  // namespace

namespace {
std::vector<TracedRay>* g_log = nullptr;
}  // namespace

void EmbreeScene::record(std::vector<TracedRay>* log) { g_log = log; }

Hit EmbreeScene::intersect(glm::vec3 o, glm::vec3 d, float tfar) const {
  if (g_log != nullptr) g_log->push_back({o, d, tfar, TracedRay::Bounce});
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh = make_ray(o, d, tfar, 0);
  rtcIntersect1(scene_, &ctx, &rh);
  return to_hit(rh);
}

bool EmbreeScene::culled(uint32_t mesh, uint32_t triangle, glm::vec3 d) const {
  return single_sided_[mesh] && glm::dot(shapes_[mesh][triangle].normal, d) > 0.0f;
}

// A culled hit is skipped by tracing the ray again from just beyond it (tnear is inclusive,
// and the same triangle gives the same t again), rather than by a filter function: Embree
// would check every hit of every ray for a context filter, a few per cent of the reference's
// time, to cull only the camera's.
Hit EmbreeScene::intersect_camera(glm::vec3 o, glm::vec3 d) const {
  if (g_log != nullptr) g_log->push_back({o, d, std::numeric_limits<float>::infinity(), TracedRay::Camera});
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh = make_ray(o, d, std::numeric_limits<float>::infinity(), kCameraRay);
  for (;;) {
    rtcIntersect1(scene_, &ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID || !culled(rh.hit.geomID, rh.hit.primID, d)) return to_hit(rh);
    rh.ray.tnear = std::nextafter(rh.ray.tfar, std::numeric_limits<float>::infinity());
    rh.ray.tfar = std::numeric_limits<float>::infinity();
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  }
}

bool EmbreeScene::occluded(glm::vec3 o, glm::vec3 d, float tfar) const {
  if (g_log != nullptr) g_log->push_back({o, d, tfar, TracedRay::Shadow});
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRay r;
  r.org_x = o.x, r.org_y = o.y, r.org_z = o.z;
  r.dir_x = d.x, r.dir_y = d.y, r.dir_z = d.z;
  r.tnear = 0.0f;
  r.tfar = tfar;
  r.time = 0.0f;
  r.mask = 0xffffffffu;
  r.id = 0;
  r.flags = 0;
  rtcOccluded1(scene_, &ctx, &r);
  return r.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
}

void EmbreeScene::intersect(const int* valid, RTCRayHit8& rays, bool camera) const {
  if (g_log != nullptr)
    for (int l = 0; l < 8; ++l)
      if (valid[l] != 0)
        g_log->push_back({{rays.ray.org_x[l], rays.ray.org_y[l], rays.ray.org_z[l]},
                          {rays.ray.dir_x[l], rays.ray.dir_y[l], rays.ray.dir_z[l]},
                          rays.ray.tfar[l],
                          (rays.ray.id[l] & kCameraRay) != 0 ? TracedRay::Camera : TracedRay::Bounce});
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  rtcIntersect8(valid, scene_, &ctx, &rays);
  if (!camera) return;
  // Camera rays that met a culled back go on from just beyond it (intersect_camera), in
  // packets of those lanes; tnear is given back its 0 afterwards.
  bool retraced = false;
  for (;;) {
    alignas(32) int again[8];
    bool any = false;
    for (int l = 0; l < 8; ++l) {
      again[l] = 0;
      if (valid[l] == 0 || (rays.ray.id[l] & kCameraRay) == 0 || rays.hit.geomID[l] == RTC_INVALID_GEOMETRY_ID) continue;
      const glm::vec3 d(rays.ray.dir_x[l], rays.ray.dir_y[l], rays.ray.dir_z[l]);
      if (!culled(rays.hit.geomID[l], rays.hit.primID[l], d)) continue;
      again[l] = -1, any = true;
      rays.ray.tnear[l] = std::nextafter(rays.ray.tfar[l], std::numeric_limits<float>::infinity());
      rays.ray.tfar[l] = std::numeric_limits<float>::infinity();
      rays.hit.geomID[l] = RTC_INVALID_GEOMETRY_ID;
    }
    if (!any) break;
    retraced = true;
    rtcIntersect8(again, scene_, &ctx, &rays);
  }
  if (retraced)
    for (int l = 0; l < 8; ++l) rays.ray.tnear[l] = 0.0f;
}

void EmbreeScene::occluded(const int* valid, RTCRay8& rays) const {
  if (g_log != nullptr)
    for (int l = 0; l < 8; ++l)
      if (valid[l] != 0)
        g_log->push_back({{rays.org_x[l], rays.org_y[l], rays.org_z[l]}, {rays.dir_x[l], rays.dir_y[l], rays.dir_z[l]},
                          rays.tfar[l], TracedRay::Shadow});
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  rtcOccluded8(valid, scene_, &ctx, &rays);
}

}  // namespace giq::reference
