#include "embree_scene.h"

#include <stdexcept>
#include <string>

namespace giq::reference {

struct EmbreeScene::AlphaMask {
  const scenes::Mesh* mesh;
  const scenes::Material* material;
  const scenes::Texture* texture;  // base colour texture, or null

  // glTF 2.0, "Alpha Coverage": MASK renders a fragment when alpha >= alphaCutoff, alpha being
  // baseColorFactor.a times the base colour texture's alpha times COLOR_0's.
  bool transparent(uint32_t triangle, float b1, float b2) const {
    float alpha = material->base_color.a;
    const glm::uvec3 t = mesh->triangles[triangle];
    if (texture != nullptr && !mesh->uvs.empty()) {
      const glm::vec2 uv = (1.0f - b1 - b2) * mesh->uvs[t.x] + b1 * mesh->uvs[t.y] + b2 * mesh->uvs[t.z];
      alpha *= texture->sample(uv).a;
    }
    alpha *= mesh->color_at(t, b1, b2).a;
    return alpha < material->alpha_cutoff;
  }
};

namespace {

// Rejects hits on cut-out texels; serves both intersection and occlusion queries
// (Embree 3 API, "rtcSetGeometryIntersectFilterFunction").
void alpha_filter(const RTCFilterFunctionNArguments* args) {
  const auto* mask = static_cast<const EmbreeScene::AlphaMask*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const uint32_t prim = RTCHitN_primID(args->hit, args->N, i);
    const float u = RTCHitN_u(args->hit, args->N, i), v = RTCHitN_v(args->hit, args->N, i);
    if (mask->transparent(prim, u, v)) args->valid[i] = 0;
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
      shapes_[m].push_back({c / len, 0.5f * len});
    }
    RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    // Embree reads vertex buffers with 16-byte loads: the last vertex needs 4 bytes of padding,
    // which the spare capacity reserved above provides.
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, pos.data(), 0, sizeof(glm::vec3), pos.size());
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, mesh.triangles.data(), 0, sizeof(glm::uvec3),
                               mesh.triangles.size());
    const scenes::Material& mat = scene.materials.at(size_t(mesh.material));
    if (alpha_mask && mat.alpha_mode == scenes::AlphaMode::Mask) {
      const scenes::Texture* tex = mat.base_color_texture >= 0 ? &scene.textures.at(size_t(mat.base_color_texture)) : nullptr;
      masks_.push_back(new AlphaMask{&mesh, &mat, tex});
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

Hit EmbreeScene::intersect(glm::vec3 o, glm::vec3 d, float tfar) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh;
  rh.ray.org_x = o.x, rh.ray.org_y = o.y, rh.ray.org_z = o.z;
  rh.ray.dir_x = d.x, rh.ray.dir_y = d.y, rh.ray.dir_z = d.z;
  rh.ray.tnear = 0.0f;
  rh.ray.tfar = tfar;
  rh.ray.time = 0.0f;
  rh.ray.mask = 0xffffffffu;
  rh.ray.id = 0;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &ctx, &rh);
  Hit h;
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return h;
  h.t = rh.ray.tfar;
  h.mesh = rh.hit.geomID;
  h.triangle = rh.hit.primID;
  h.b1 = rh.hit.u, h.b2 = rh.hit.v;
  return h;
}

bool EmbreeScene::occluded(glm::vec3 o, glm::vec3 d, float tfar) const {
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

void EmbreeScene::intersect(const int* valid, RTCRayHit8& rays) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  rtcIntersect8(valid, scene_, &ctx, &rays);
}

void EmbreeScene::occluded(const int* valid, RTCRay8& rays) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  rtcOccluded8(valid, scene_, &ctx, &rays);
}

}  // namespace giq::reference
