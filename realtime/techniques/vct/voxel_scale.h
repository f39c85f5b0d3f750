#pragma once
// The scale that maps voxel radiance into the [0, 1] range of 8-bit voxels: a power of two
// below the reciprocal of an upper bound on the radiance any voxel can reflect this frame, so
// that no voxel clips, however bright the lights (the values the GPU stores are normalised;
// the scale itself is a float32 on the CPU, which reaches 3e38). The bound sums, over the
// lights, the largest irradiance each can deliver to a surface of the scene, times the
// largest diffuse BRDF (1/pi):
//   directional: its irradiance;
//   point/spot: intensity / d_min^2, d_min the distance from the light to the nearest
//     triangle (no surface is closer);
//   emissive mesh: P / (A / pi) = pi times its area-weighted mean radiance (the cosine
//     emitter's on-axis limit in voxel_light.comp).

#include <vector>

#include "giq/scenes/scene.h"
#include "techniques/vct/vct_shared.h"

namespace giq::realtime {

// One cosine-weighted emitter per emissive mesh (the meshes' order, as DirectLightPass
// builds its area lights).
std::vector<gpu::VctEmitter> voxel_emitters(const scenes::Scene& scene);

// The largest power of two <= 1 / (bound on the voxel radiance after `bounces` bounces); 1
// when nothing emits. A power of two changes only when the bound changes by a factor 2, so a
// moving light rarely restarts the temporal blend, and a light 2^k times brighter stores
// exactly the same codes (its radiances are exactly 2^k times larger).
float voxel_radiance_scale(const scenes::Scene& scene, const std::vector<gpu::VctEmitter>& emitters,
                           int bounces);

}  // namespace giq::realtime
