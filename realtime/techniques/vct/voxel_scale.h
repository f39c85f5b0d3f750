#pragma once
// The scale that maps voxel radiance into the [0, 1] range of 8-bit voxels: a power of two
// below the reciprocal of an upper bound on the radiance any voxel can reflect this frame, so
// that no voxel clips, however bright the lights (the values the GPU stores are normalised;
// the scale itself is a float32 on the CPU, which reaches 3e38). The bound sums, over the
// lights, the largest irradiance each can deliver to a surface of the scene, times the
// largest diffuse BRDF (1/pi):
//   directional: its irradiance;
//   point/spot: intensity / d^2, d the distance from the light to the nearest triangle (no
//     surface is closer), or to the nearest particle, which the GPU drew where the host may
//     hold none (SceneGpu::particle_light_distances); but at least half a voxel. A surface
//     nearer than that clips its voxels (at most those within half a voxel of the light,
//     where no cone resolves the light's falloff anyway) rather than have one lamp in its
//     bulb, or a spark passing through a lamp, scale the rest of the scene down to black;
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
// `voxel`: the voxels' side; `particle_distance`: per light of the scene, at most its
// distance to the particles (empty: none).
float voxel_radiance_scale(const scenes::Scene& scene, const std::vector<gpu::VctEmitter>& emitters,
                           int bounces, float voxel, const std::vector<float>& particle_distance = {});

}  // namespace giq::realtime
