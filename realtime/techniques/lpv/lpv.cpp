// `lpv`: Light Propagation Volumes (Afanasev 2021 ch. III; Kaplanyan and Dachsbacher 2010):
// the frame's reflective shadow maps (passes/rsm.h) injected into a grid (lpv_inject.comp,
// lpv_resolve.comp), propagation steps (lpv_propagate.comp) and the per-pixel lookup
// (lpv_lookup.comp) into the frame's indirect target.
//
// What the thesis's propagation shader (Afanasev 2021, appendix "LPVPropagation.hlsl") gets wrong,
// and what is done here instead:
//   1. The side faces are built from cellDirections[face] (face = 0..3) instead of
//      cellDirections[neighbourCell]: every neighbour uses the same four side faces whatever
//      the direction it propagates in. Here each neighbour's side faces surround its own
//      direction d.
//   2. getEvalSideDirection puts the big component (2/sqrt 5) on z and multiplies component-wise
//      by the orientation, which is a unit vector towards a side face only for d = +-z; for d
//      along x or y it is (+-0.447, 0, 0), (0, +-0.447, 0) or zero. Here the direction is
//      2/sqrt5 d + 1/sqrt5 s for the side axis s of an orthonormal frame around d.
//   3. getReprojSideDirection returns (d.x s.x, d.y s.y, 0): the zero vector for d = +-z (its
//      cosine lobe degenerates to the constant term) and not the face normal otherwise. Here the
//      re-projection lobe is along the side face's normal s.
// The solid angles are the appendix's (far face 0.4006696846 sr, side face 0.4234413544 sr,
// each divided by pi), which sum to the shared face's 2.0943951 sr: a step moves all the flux
// that leaves through a face. As in the appendix, the intensity towards a face is not clamped:
// 2-band SH rings negative behind a lobe, and the negative flux it sends backwards is what keeps
// a step's total flux at what entered the cell (clamping it adds light: +8% on the Cornell
// box's mean at 50 steps).
#include <algorithm>
#include <cmath>

#include "giq/realtime/context.h"
#include "giq/realtime/resources.h"
#include "giq/realtime/shader.h"
#include "giq/realtime/timer.h"
#include "passes/cube_grid.h"
#include "passes/deferred_gi.h"
#include "techniques/lpv/lpv_shared.h"

namespace giq::realtime {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Afanasev 2021, appendix "LPVPropagation.hlsl".
constexpr float kDirectFaceSolidAngle = 0.4006696846f;
constexpr float kSideFaceSolidAngle = 0.4234413544f;

glm::vec4 dir_to_sh(glm::vec3 d) {
  const float c0 = 0.282094792f, c1 = 0.488602512f;
  return {c0, -c1 * d.y, c1 * d.z, -c1 * d.x};
}
glm::vec4 cos_lobe_sh(glm::vec3 n) {
  const float c0 = 0.886226925f, c1 = 1.02332671f;
  return {c0, -c1 * n.y, c1 * n.z, -c1 * n.x};
}

// Per neighbour direction (the appendix's order) and face: evaluation SH (solid angle / pi
// included) and re-projection lobe; then the 6 directions (see lpv_propagate.comp).
std::vector<glm::vec4> face_table() {
  const glm::vec3 dirs[6] = {{0, 0, 1}, {1, 0, 0}, {0, 0, -1}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}};
  std::vector<glm::vec4> t(66);
  for (int n = 0; n < 6; ++n) {
    const glm::vec3 d = dirs[n];
    const glm::vec3 s1 = std::abs(d.x) > 0.5f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    const glm::vec3 s2 = glm::cross(d, s1);
    t[2 * (5 * n)] = float(kDirectFaceSolidAngle / kPi) * dir_to_sh(d);
    t[2 * (5 * n) + 1] = cos_lobe_sh(d);
    const glm::vec3 sides[4] = {s1, -s1, s2, -s2};
    for (int f = 0; f < 4; ++f) {
      const glm::vec3 eval =
          0.894427191f * d + 0.447213595f * sides[f];  // towards the side face's centre
      t[2 * (5 * n + 1 + f)] = float(kSideFaceSolidAngle / kPi) * dir_to_sh(eval);
      t[2 * (5 * n + 1 + f) + 1] = cos_lobe_sh(sides[f]);
    }
    t[60 + n] = glm::vec4(d, 0.0f);
  }
  return t;
}

class Lpv : public IndirectLight {
 public:
  Lpv(const TechniqueCreateInfo& ci, DeferredGi& /*frame*/)
      : res_(uint32_t(ci.parameters.get_int("lpv_grid"))),
        steps_(ci.parameters.get_int("propagation_steps")),
        placement_(ci.parameters.get_int("lpv_placement")),
        downsample_(uint32_t(ci.parameters.get_int("rsm_downsample"))),
        intensity_(float(ci.parameters.get("intensity"))) {
    const uint64_t cells = uint64_t(res_) * res_ * res_;
    inject_ = Buffer(ci.ctx, cells * 12 * sizeof(int32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    for (auto& v : volume_)
      v = Buffer(ci.ctx, cells * 3 * sizeof(glm::vec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    accumulated_ =
        Buffer(ci.ctx, cells * 3 * sizeof(glm::vec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    faces_ = Buffer::storage(ci.ctx, face_table());
    const auto s = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, i = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    inject_pipeline_ =
        Pipeline::compute(ci.ctx, ci.compiler.compile("techniques/lpv/lpv_inject.comp"),
                          {i, i, s, s, s}, sizeof(gpu::LpvGrid));
    resolve_pipeline_ =
        Pipeline::compute(ci.ctx, ci.compiler.compile("techniques/lpv/lpv_resolve.comp"), {s, s, s},
                          sizeof(gpu::LpvGrid));
    propagate_pipeline_ =
        Pipeline::compute(ci.ctx, ci.compiler.compile("techniques/lpv/lpv_propagate.comp"),
                          {s, s, s, s}, sizeof(gpu::LpvGrid));
    auto bindings = GBufferPass::receiver_bindings();
    bindings.insert(bindings.end(), {s, i});
    lookup_pipeline_ = Pipeline::compute(
        ci.ctx,
        ci.compiler.compile("techniques/lpv/lpv_lookup.comp", feature_defines(ci.scene.features)),
        bindings, sizeof(gpu::LpvLookupPush));
  }

  void record(const FrameInput& in, DeferredGi& frame) override {
    ReflectiveShadowMaps& rsm = frame.rsm();
    Image& indirect = frame.indirect_target();
    const gpu::LpvGrid grid = make_grid(in, rsm);
    const uint32_t cells = res_ * res_ * res_;

    in.timer.begin(in.cmd, "lpv_inject");
    vkCmdFillBuffer(in.cmd, inject_.handle(), 0, VK_WHOLE_SIZE, 0);
    full_barrier(in.cmd);
    inject_pipeline_.bind(in.cmd);
    inject_pipeline_.push_descriptors(
        in.cmd, {Descriptor::storage_image(rsm.surface()), Descriptor::storage_image(rsm.flux()),
                 Descriptor::storage(rsm.layer_buffer()),
                 Descriptor::storage(rsm.emitter_buffer()), Descriptor::storage(inject_)});
    inject_pipeline_.push_constants(in.cmd, grid);
    const uint32_t blocks = (rsm.extent() + downsample_ - 1) / downsample_;
    if (rsm.layer_count() > 0)
      vkCmdDispatch(in.cmd, (blocks + 7) / 8, (blocks + 7) / 8, rsm.layer_count());
    full_barrier(in.cmd);
    resolve_pipeline_.bind(in.cmd);
    resolve_pipeline_.push_descriptors(
        in.cmd, {Descriptor::storage(inject_), Descriptor::storage(volume_[0]),
                 Descriptor::storage(accumulated_)});
    resolve_pipeline_.push_constants(in.cmd, grid);
    vkCmdDispatch(in.cmd, (cells * 3 + 63) / 64, 1, 1);
    full_barrier(in.cmd);
    in.timer.end(in.cmd);

    in.timer.begin(in.cmd, "lpv_propagate");
    propagate_pipeline_.bind(in.cmd);
    propagate_pipeline_.push_constants(in.cmd, grid);
    const uint32_t groups = (res_ + 3) / 4;
    for (int step = 0; step < steps_; ++step) {
      propagate_pipeline_.push_descriptors(
          in.cmd,
          {Descriptor::storage(volume_[step % 2]), Descriptor::storage(volume_[(step + 1) % 2]),
           Descriptor::storage(accumulated_), Descriptor::storage(faces_)});
      vkCmdDispatch(in.cmd, groups, groups, groups);
      compute_barrier(in.cmd);
    }
    full_barrier(in.cmd);
    in.timer.end(in.cmd);

    in.timer.begin(in.cmd, "lpv_lookup");
    indirect.transition(in.cmd, VK_IMAGE_LAYOUT_GENERAL);
    lookup_pipeline_.bind(in.cmd);
    auto d = frame.gbuffer().receiver_descriptors();
    d.push_back(Descriptor::storage(accumulated_));
    d.push_back(Descriptor::storage_image(indirect));
    lookup_pipeline_.push_descriptors(in.cmd, d);
    gpu::LpvLookupPush lookup{};
    lookup.grid = grid;
    lookup.size = glm::uvec2(frame.width(), frame.height());
    lookup_pipeline_.push_constants(in.cmd, lookup);
    lookup_pipeline_.dispatch_2d(in.cmd, frame.width(), frame.height());
    full_barrier(in.cmd);
    in.timer.end(in.cmd);
  }

 private:
  // Cubic cells: the grid spans the scene's largest extent (plus a cell on each side, so that
  // the half-cell normal offsets stay inside), centred on the scene, on the camera or half a
  // grid ahead of it (the last two snapped to whole cells, so that a moving camera does not
  // make the injection crawl). Grids that follow the camera are for scenes larger than them;
  // sized from the scene, they cover it only when the camera is inside or near it.
  gpu::LpvGrid make_grid(const FrameInput& in, const ReflectiveShadowMaps& rsm) const {
    const CubeGrid fitted = fit_cube_grid(in.scene.bounds, res_);
    const float cell = fitted.cell;
    glm::vec3 origin = fitted.origin;
    if (placement_ != 0) {
      const float ahead = placement_ == 2 ? 0.5f * cell * float(res_) : 0.0f;
      const glm::vec3 c = in.camera.position + in.camera.forward * ahead;
      origin = glm::floor((c - 0.5f * cell * float(res_)) / cell) * cell;
    }
    // Fixed point for the injection sums: no cell's SH coefficient can exceed the total flux
    // of all RSM texels / pi x 1.0233 (the cosine lobe's largest coefficient), bounded by the
    // light's brightest channel x 4 pi / 6 per cube face or x window area per ortho layer;
    // 2^30 units for that bound keep every int32 sum from overflowing.
    double bound = 0.0;
    for (const auto& l : rsm.layers())
      bound += double(l.params.z) *
               (l.params.x == GIQ_RSM_ORTHO ? double(l.axes.w) * l.axes.w : 4.0 * kPi / 6.0);
    const double coefficient = bound / kPi * 1.02332671;
    const float scale = coefficient > 0.0 ? float(std::ldexp(1.0, 30) / coefficient) : 0.0f;
    gpu::LpvGrid grid{};
    grid.origin = glm::vec4(origin, cell);
    grid.resolution = res_;
    grid.rsm_layers = rsm.layer_count();
    grid.rsm_downsample = downsample_;
    grid.emitter_count = rsm.emitter_count();
    grid.injection_scale = scale;
    grid.intensity = intensity_;
    return grid;
  }

  uint32_t res_;
  int steps_;
  int placement_;  // 0 scene, 1 camera-centred, 2 half a grid ahead of the camera
  uint32_t downsample_;
  float intensity_;
  Buffer inject_, volume_[2], accumulated_, faces_;
  Pipeline inject_pipeline_, resolve_pipeline_, propagate_pipeline_, lookup_pipeline_;
};

}  // namespace

TechniqueInfo lpv_technique() {
  FrameNeeds needs;
  needs.reflective_shadow_maps = true;
  return deferred_technique<Lpv>(
      "lpv",
      "Light Propagation Volumes (Afanasev 2021 ch. III): RSM VPLs (brightest texel of each 4x4 block) injected as "
      "2-band SH into a grid, propagated to the 6 face neighbours, trilinear cosine-lobe lookup",
      needs,
      {{"rsm_downsample", 4, 1, 8, true,
        "k: one VPL per k x k RSM block, by the brightest-texel scheme (Afanasev 2021, III.3.2: k = 4)"},
       {"lpv_grid", 32, 4, 128, true, "cells per side of the propagation volume"},
       {"propagation_steps", 50, 0, 100, true,
        "propagation steps (Afanasev 2021: 50, 1-100); 0 = the injected light only"},
       {"lpv_placement", 0, 0, 2, true,
        "0: the grid fits the scene's bounds; 1: centred on the camera; 2: half a grid ahead of it"},
       {"intensity", 1, 0, 100, false, "multiplier of the indirect light (1 = physical units)"}},
      {"lpv_grid", {8, 16, 24, 32, 48, 64}});
}

}  // namespace giq::realtime
