// Structures shared by techniques/vct/*.cpp and the VCT shaders.
#ifndef GIQ_VCT_SHARED_H
#define GIQ_VCT_SHARED_H

#include "shaders/camera_shared.h"

#ifdef __cplusplus
namespace giq::realtime::gpu {
using uvec4 = glm::uvec4;
#endif

// The voxel cube: `origin` its min corner and voxel edge length (w); size.x voxels per side
// of the base level. Empty voxels of the base level hold GIQ_VCT_EMPTY while voxelising.
#define GIQ_VCT_EMPTY 0xffffffffu
// Anisotropic volumes: +X, -X, +Y, -Y, +Z, -Z (the direction a cone travels).
#define GIQ_VCT_DIRECTIONS 6

struct VctGrid {
  vec4 origin;  // xyz min corner; w voxel edge length
  uvec4 size;   // x voxels per side (base); y anisotropic levels; z, w per pass
};

// voxelize.comp: size.z triangle count, size.w column slices (workgroups per triangle).
// voxel_light.comp: size.z punctual lights, size.w emitters; params.x = encode scale (stored
// value = radiance * scale), params.y = shadow-ray origin offset (world units), params.z =
// diffuse cone count, params.w = 1 to add the light the voxel's surface receives from the
// current mips (one more bounce); cone = aperture, max distance, step factor, start offset;
// guard.x = footprint guard (cone.glsl).
// voxel_mip.comp: size.z target anisotropic level, size.w 1 = blend with the previous frame;
// params.x = weight of the new voxels.
struct VctVoxelPush {
  VctGrid grid;
  vec4 params;
  vec4 cone;
  vec4 guard;
};

// An emissive mesh for voxel lighting: a cosine-weighted emitter at its area-weighted
// centroid (Lambertian: intensity(w) = sum over triangles of L A max(n.w, 0)).
struct VctEmitter {
  vec4 position;  // xyz centroid; w: first shadow layer (unused: voxels trace shadow rays)
  vec4 normal;    // xyz unit mean normal; w: 1 when double-sided
  vec4 power;     // rgb: sum of radiance x area (W/sr along the normal); w: total area
};

struct VctConePush {
  vec4 eye;         // xyz camera position
  VctGrid grid;     // size.z cone count, size.w flags (1: AO)
  vec4 viewport;    // x full width, y full height, z low width, w low height
  vec4 cone;        // x diffuse aperture (tan of the half angle), y max distance (world),
                    // z step factor, w start offset (voxels)
  vec4 params;      // x decode scale (radiance = stored / scale), y k, z AO falloff,
                    // w footprint guard (cone.glsl)
};

#ifdef __cplusplus
}  // namespace giq::realtime::gpu
#endif
#endif
