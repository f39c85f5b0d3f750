#version 460
// Reflective shadow map layer by ray casting instead of rasterisation (passes/rsm.h): one ray
// per texel centre through the BVH, from the layer's near plane to its far plane, as the
// rasteriser clips (shaders/texel_ray.glsl). The closest surface gives the texel rsm.frag
// would write (rsm_texel.glsl); texels that see nothing, and those of the array beyond this
// layer's size, are cleared. For GPUs whose graphics units are the bottleneck (giq/realtime/pass_builder.h).
#extension GL_GOOGLE_include_directive : require

#include "shaders/bvh.glsl"
#include "shaders/surface.glsl"
#include "shaders/lights.glsl"
#include "passes/rsm_shared.h"
#include "passes/rsm.glsl"
#include "passes/rsm_albedo.glsl"
#include "passes/rsm_texel.glsl"
#include "shaders/texel_ray.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = GIQ_SCENE_BINDING_COUNT + 0) readonly buffer Emitters { GpuRsmEmitter emitters[]; };
layout(std430, binding = GIQ_SCENE_BINDING_COUNT + 1) readonly buffer Layers { GpuRsmLayer layers[]; };
layout(binding = GIQ_SCENE_BINDING_COUNT + 2, rgba32ui) uniform writeonly uimage2DArray out_surface;
layout(binding = GIQ_SCENE_BINDING_COUNT + 3, rgba16f) uniform writeonly image2DArray out_flux;

layout(push_constant) uniform Push { RsmLayerPush pc; };

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(px, imageSize(out_surface).xy))) return;
  RsmTexel t;
  t.surface = uvec4(0u);
  t.flux = vec4(0.0);
  if (px.x < int(pc.size) && px.y < int(pc.size)) {
    vec3 o, d;
    float tmax;
    texel_ray(layers[pc.layer].clip_to_world, vec2(px) + 0.5, float(pc.size), o, d, tmax);
    GpuRsmEmitter e = emitters[pc.emitter];
    // An area light's own triangles are left out of its maps, as rsm.frag leaves them.
    RayHit hit = trace_ray(o, d, tmax, false, false, e.layers.zw);
    if (hit.triangle != 0xffffffffu)
      t = rsm_texel(e, hit.triangle, texel_plane_point(o, d, hit.triangle, o + hit.t * d), pc.flux_scale);
  }
  ivec3 at = ivec3(px, int(pc.layer));
  imageStore(out_surface, at, t.surface);
  imageStore(out_flux, at, t.flux);
}
