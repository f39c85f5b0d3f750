// Structures shared by techniques/gi1/gi1.cpp and the GI-1.0 shaders.
#ifndef GIQ_GI1_SHARED_H
#define GIQ_GI1_SHARED_H

#include "shaders/camera_shared.h"

#ifdef __cplusplus
namespace giq::realtime::gpu {
using uvec4 = glm::uvec4;
using uint = uint32_t;
#endif

// A screen probe is an 8x8 map of the hemisphere around its normal (Boissé et al. 2022,
// section 2.1): one probe per 8x8 tile of pixels, one ray per cell when it is traced.
#define GIQ_GI1_PROBE 8u
#define GIQ_GI1_CELLS 64u
// Spherical-harmonic coefficients of a probe: bands 0 to 2 (section 2.4.2).
#define GIQ_GI1_SH 9u
// A world-cache tile is an 8x8 grid of cells with its mip levels 4x4, 2x2 and 1x1
// (section 2.2.3): 85 cells, the finest 64 first.
#define GIQ_GI1_TILE 8u
#define GIQ_GI1_TILE_CELLS 85u
#define GIQ_GI1_NONE 0xffffffffu
// GpuGi1Probe::info.y
#define GIQ_GI1_SPAWNED 1u      // traced this frame
#define GIQ_GI1_REPROJECTED 2u  // carries last frame's radiance (history)
#define GIQ_GI1_PATCHED 4u  // spawned on an empty tile with rays moved from another (Algorithm 2)
// GpuGi1Frame::counts.w
#define GIQ_GI1_RAY_LENGTH_BIT 1u
#define GIQ_GI1_ADAPTIVE_SAMPLING 2u
#define GIQ_GI1_FEEDBACK 4u
#define GIQ_GI1_HISTORY 8u  // the previous frame's probes and irradiance exist
#define GIQ_GI1_RAY_GUIDING 16u
#define GIQ_GI1_NEAR_FIELD 32u  // screen-space near field (section 3, gi1_near_field.comp)
#define GIQ_GI1_SIDE_CACHE 64u  // the persistent side cache (section 2.1.8, gi1_side_*.comp)
#define GIQ_GI1_LIGHT_SAMPLING 128u  // lights sampled at the hits through the light grid (section 2.3)
// Radiance is added into the world cache's cells as integers, each sample in units of
// 1 / GIQ_GI1_QUANTUM of the largest sample the cell received this frame (gi1_hash.glsl).
#define GIQ_GI1_QUANTUM 65535.0
#define GIQ_GI1_MAX_CELL_SAMPLES 65536u

// The frame's constants, one buffer every pass reads (gi1.cpp fills it each frame).
struct GpuGi1Frame {
  GpuCamera camera;    // this frame's
  GpuCamera previous;  // the previous frame's (the feedback's reprojection)
  vec4 environment;    // rgb constant environment radiance, w its map's texture or -1
  uvec4 size;          // xy the image, zw screen tiles per axis
  uvec4 spawn;         // xy temporal upscale per axis, zw spawn tiles per axis
  uvec4 jitter;        // x the pixel inside its tile a probe spawns on (Halton), y the tile inside
                       // its spawn tile that spawns, both packed as x | y << 16; z the frame;
                       // w the technique's `seed`
  uvec4 counts;        // x punctual lights, y area lights, z spawn slots, w GIQ_GI1_* switches
  uvec4 cache;  // x buckets, y tiles per bucket, z frames an unused tile lives, w samples a cell
                // averages
  vec4 pixel;   // x a pixel's size per unit of distance along the view (perspective), y its
                // size at any distance (orthographic), z world cells are this many pixels,
                // w the smallest world cell
  vec4 params;  // x the albedo cap of the feedback; y 1: the shadow-preserving hysteresis
                // (Algorithm 3), 0: new radiance replaces the history; z the frames the
                // denoiser's history holds at most; w its spatial radius in pixels
  uvec4 mask;   // x mip levels of the probe mask (gi1_mask.glsl)
  vec4 near;    // the near field: x its radius in pixels, y steps per side of its slice
  uvec4 side;   // the side cache: x its entries (0: off), y this frame + 1 (an entry's stamp)
  vec4 grid;    // the light grid (section 2.3.2): xyz its lowest corner, w its cells' side
  uvec4 grid_cells;  // xyz its cells per axis, w the lights a cell lists at most
  uvec4 lights;      // x the lights the grid ranks (punctual, then area, then the environment
                     // where it shines), y candidates per hit (section 2.3.1), z the most
                     // candidates a stored reservoir carries into the next frame (0: no reuse
                     // this frame), w the reservoir grid's slots
};

// A screen tile's probe.
struct GpuGi1Probe {
  uvec4 info;     // x its pixel (x | y << 16) or GIQ_GI1_NONE; y GIQ_GI1_* flags; z for a
                  // carried probe, the previous frame's tile it came from, else GIQ_GI1_NONE
  vec4 position;  // xyz where it sits; w its view depth
  vec4 normal;    // xyz its normal; w its cell size (Algorithm 6)
};

// Counters, and the indirect dispatches they size (VkDispatchIndirectCommand at offsets 0 and
// 16): zeroed at the start of every frame.
struct GpuGi1Counters {
  uvec4 probe_groups;  // xyz the per-probe passes' work groups (gi1_patch.comp); w probes traced
  uvec4 tile_groups;   // xyz the world-cache update's work groups (gi1_args.comp); w tiles
                       // that received samples (gi1_trace.comp)
  uvec4 tiles;         // x tiles left without a probe, y tiles that took rays from another
};

// A probe ray's world-cache query: the cell its hit falls in and the light leaving the hit.
struct GpuGi1Query {
  uvec4 cell;     // x the world-cache tile, or GIQ_GI1_NONE: the ray missed, hit the back of a
                  // one-sided surface, or found its bucket full; y the finest cell in it (0..63)
  vec4 radiance;  // rgb this frame's sample of the light leaving the hit towards the probe, or
                  // what a miss saw (the environment); w the hit distance (1e30: a miss, small
                   // enough that filters can sum a few)
};

// A light-sampling reservoir (section 2.3.1), kept per cell of the reservoir grid
// (gi1_reservoir.glsl) from one frame to the next.
struct GpuGi1Reservoir {
  vec4 point;   // xyz the point on an area light or the environment's direction; w in the
                 // trace's stash (gi1_reservoir_store.comp) the grid slot, as float bits
  uvec4 info;    // x the cell's fingerprint (0: empty), y the light, z its triangle (area
                 // lights: its index in the light), w the candidates it stands for (M)
  vec4 weight;   // x its unbiased contribution weight W (unshadowed), yzw the surface normal
};

// Per spawn slot: the side-cache entries the blend writes (section 2.1.8), each GIQ_GI1_NONE or
// an entry the slot won (gi1_reconstruct.comp claims, the lowest claim wins).
struct GpuGi1SideWrite {
  uint evicted;  // receives the tile's carried probe, which the new probe did not reuse
  uint fresh;    // receives the new probe: the entry that matched it best in the reconstruction
};

#ifdef __cplusplus
}  // namespace giq::realtime::gpu
#endif
#endif
