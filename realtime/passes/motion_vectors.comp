#version 460
// Motion vectors from the G-buffer (passes/gbuffer.h): for each pixel, where the surface
// point it shows was seen in the previous frame. The point's barycentric coordinates in its
// triangle now are applied to the triangle's previous vertices, and the result is projected
// with the previous camera; a pixel that sees the environment follows its direction. One
// pass for both G-buffer builders, from what they already wrote.
#extension GL_GOOGLE_include_directive : require

#include "shaders/scene.glsl"
#include "shaders/camera.glsl"
#include "passes/gbuffer_shared.h"

layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = GIQ_SCENE_BINDING_COUNT + 0) readonly buffer Previous { GpuVertex previous_vertices[]; };
layout(binding = GIQ_SCENE_BINDING_COUNT + 1, rgba32f) uniform readonly image2D gb_position;
layout(binding = GIQ_SCENE_BINDING_COUNT + 2, rgba32ui) uniform readonly uimage2D gb_ids;
layout(binding = GIQ_SCENE_BINDING_COUNT + 3, rgba32f) uniform writeonly image2D out_motion;

layout(push_constant) uniform Push { MotionPush pc; };

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  vec2 size = vec2(imageSize(out_motion));
  if (any(greaterThanEqual(vec2(px), size))) return;
  vec2 centre = vec2(px) + 0.5;
  uvec4 ids = imageLoad(gb_ids, px);
  // What did not move gets exactly 0, not the rounding of a projection back to its pixel:
  // temporal filters would otherwise blend neighbours in with weights of ~1e-5 every frame.
  bool same_camera = pc.current.position == pc.previous.position && pc.current.forward == pc.previous.forward &&
                     pc.current.right == pc.previous.right && pc.current.up == pc.previous.up;
  vec3 previous = vec3(centre, 1.0);
  if (ids.x == 0u) {
    // The direction, seen from the previous camera (from the same point of its image plane
    // when orthographic).
    if (!same_camera) {
      vec3 offset = camera_ray_origin(pc.current, centre, size) - pc.current.position.xyz;
      previous = camera_project(pc.previous, pc.previous.position.xyz + offset + camera_ray_direction(pc.current, centre, size), size);
    }
  } else {
    uvec3 t = scene_triangles[ids.x - 1u].v.xyz;
    vec3 a = scene_vertices[t.x].position.xyz, b = scene_vertices[t.y].position.xyz, c = scene_vertices[t.z].position.xyz;
    vec3 p = imageLoad(gb_position, px).xyz;
    vec3 n = cross(b - a, c - a);
    float nn = dot(n, n);
    // Barycentrics by signed sub-triangle areas; a degenerate triangle keeps its first vertex.
    vec3 w = vec3(1.0, 0.0, 0.0);
    if (nn > 0.0) {
      w.x = dot(cross(c - b, p - b), n) / nn;
      w.y = dot(cross(a - c, p - c), n) / nn;
      w.z = 1.0 - w.x - w.y;
    }
    vec3 pa = previous_vertices[t.x].position.xyz, pb = previous_vertices[t.y].position.xyz,
         pc_ = previous_vertices[t.z].position.xyz;
    if (!same_camera || pa != a || pb != b || pc_ != c) previous = camera_project(pc.previous, w.x * pa + w.y * pb + w.z * pc_, size);
  }
  // w: 1 when the previous position lies in front of the previous camera and inside the image.
  bool inside = previous.z > 0.0 && all(greaterThanEqual(previous.xy, vec2(0.0))) && all(lessThan(previous.xy, size));
  imageStore(out_motion, px, vec4(previous.xy - centre, 0.0, inside ? 1.0 : 0.0));
}
