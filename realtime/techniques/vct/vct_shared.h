// Structures shared by techniques/vct/*.cpp and the VCT shaders.
#ifndef GIQ_VCT_SHARED_H
#define GIQ_VCT_SHARED_H

#include "shaders/camera_shared.h"

#ifdef __cplusplus
namespace giq::realtime::gpu {
using uvec2 = glm::uvec2;
using uint = uint32_t;
#endif

// The voxel cube: `origin` its min corner and voxel edge length (w). Empty voxels of the base level hold GIQ_VCT_EMPTY while voxelising.
#define GIQ_VCT_EMPTY 0xffffffffu
// Anisotropic volumes: +X, -X, +Y, -Y, +Z, -Z (the direction a cone travels).
#define GIQ_VCT_DIRECTIONS 6

struct VctGrid {
  vec4 origin;      // xyz min corner; w voxel edge length
  uint resolution;  // voxels per side of the base level
  uint levels;      // levels of each anisotropic chain
  uint pad0, pad1;
};

// How cones march (cone.glsl).
struct VctCone {
  float aperture;      // diffuse cones' tan(half angle)
  float max_distance;  // world units
  float step_factor;   // step as a fraction of the cone's diameter there
  float start_offset;  // apex offset along the normal, in base voxels
  float guard;         // footprint guard (0: the thesis's log2(diameter / voxel))
  float ao_falloff;    // AO attenuation with cone diameter, per voxel
  uint count;          // diffuse cones
  uint pad;
};

struct VctVoxelizePush {  // voxelize.comp
  VctGrid grid;
  uint triangle_count;
  uint pad0, pad1, pad2;
};

struct VctLightPush {  // voxel_light.comp
  VctGrid grid;
  VctCone cone;
  uint light_count;    // punctual lights
  uint emitter_count;  // VctEmitter entries
  float scale;         // stored value = radiance x scale
  float ray_offset;    // shadow-ray origin offset (world units)
  uint add_bounce;     // 1: add the light the voxel receives from the current mips
  uint pad0, pad1, pad2;
};

struct VctMipPush {  // voxel_mip.comp
  VctGrid grid;
  uint level;        // the anisotropic level written
  uint blend;        // 1: blend with what the level held (the previous frame)
  float new_weight;  // weight of the new voxels in that blend
  uint pad;
};

// An emissive mesh for voxel lighting: a cosine-weighted emitter at its representative point
// (scenes::AreaLight: the area-weighted centroid, a hair in front of a one-sided flat emitter;
// the point every real-time pass shades and shadows the mesh from) with Lambertian intensity
// I(w) = sum over triangles of L A max(n.w, 0).
struct VctEmitter {
  vec4 position;  // xyz representative point; w: how far from it shadow rays stop (a closed
                  // emitter's own extent, which holds that point; 0 otherwise)
  vec4 normal;    // xyz unit mean normal; w: 1 when double-sided; 2 for a closed emitter:
                  // isotropic, a quarter of `power` every way (rsm_shared.h)
  vec4 power;     // rgb: sum of radiance x area (W/sr along the normal); w: total area
};

struct VctConePush {  // cone_trace.comp
  vec4 eye;            // the viewer: gpu_eye() (camera_shared.h)
  VctGrid grid;
  VctCone cone;
  uvec2 size;          // full resolution
  uvec2 low_size;      // the resolution traced at
  float decode_scale;  // radiance = stored / scale: 1 / scale
  uint factor;         // downsample factor k
  uint ao;             // 1: write the ambient occlusion layer
  uint pad;
};

#ifdef __cplusplus
}  // namespace giq::realtime::gpu
#endif
#endif
