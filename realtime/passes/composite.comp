#version 460
// beauty = direct + indirect (passes/composite.h).
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, rgba32f) uniform readonly image2D direct_light;
layout(binding = 1, rgba32f) uniform readonly image2D indirect_light;
layout(binding = 2, rgba32f) uniform writeonly image2D beauty;
layout(push_constant) uniform Push { uvec2 size; };

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(px), size))) return;
  vec3 sum = imageLoad(direct_light, px).rgb + imageLoad(indirect_light, px).rgb;
  imageStore(beauty, px, vec4(sum, 1.0));
}
