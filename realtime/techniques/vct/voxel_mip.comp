#version 460
// One level of the six anisotropic mip chains (Crassin et al. 2011, "Interactive Indirect
// Illumination Using Voxel Cone Tracing"; Afanasev 2021 ch. IV uses their six
// directional textures, VoxelConeTracingPS.hlsl). Chain D holds what a cone travelling along
// D sees: the 2x2x2 children are composited front to back in pairs along D (near + (1 - near
// alpha) far, premultiplied radiance) and the four pairs averaged. Level 0 of the chains
// (half the base resolution) is built from the isotropic base level, level l from level l-1
// of the same chain. At level 0 the new value may be blended with the previous frame's
// (Turánszki 2017 part 2: "interpolating with old values so that abrupt changes in lighting ...
// don't cause much flickering").
#extension GL_GOOGLE_include_directive : require

#include "techniques/vct/vct_shared.h"
#include "techniques/vct/voxel.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(binding = 0) uniform sampler3D base;
layout(binding = 1) uniform sampler3D chain0;
layout(binding = 2) uniform sampler3D chain1;
layout(binding = 3) uniform sampler3D chain2;
layout(binding = 4) uniform sampler3D chain3;
layout(binding = 5) uniform sampler3D chain4;
layout(binding = 6) uniform sampler3D chain5;
layout(binding = 7, r32ui) uniform uimage3D out0;
layout(binding = 8, r32ui) uniform uimage3D out1;
layout(binding = 9, r32ui) uniform uimage3D out2;
layout(binding = 10, r32ui) uniform uimage3D out3;
layout(binding = 11, r32ui) uniform uimage3D out4;
layout(binding = 12, r32ui) uniform uimage3D out5;
layout(push_constant) uniform Push { VctMipPush pc; };

vec4 child(int d, ivec3 p, int level) {
  switch (d) {
    case 0: return texelFetch(chain0, p, level);
    case 1: return texelFetch(chain1, p, level);
    case 2: return texelFetch(chain2, p, level);
    case 3: return texelFetch(chain3, p, level);
    case 4: return texelFetch(chain4, p, level);
    default: return texelFetch(chain5, p, level);
  }
}

uint load_out(int d, ivec3 p) {
  switch (d) {
    case 0: return imageLoad(out0, p).x;
    case 1: return imageLoad(out1, p).x;
    case 2: return imageLoad(out2, p).x;
    case 3: return imageLoad(out3, p).x;
    case 4: return imageLoad(out4, p).x;
    default: return imageLoad(out5, p).x;
  }
}

void store_out(int d, ivec3 p, uint v) {
  switch (d) {
    case 0: imageStore(out0, p, uvec4(v)); break;
    case 1: imageStore(out1, p, uvec4(v)); break;
    case 2: imageStore(out2, p, uvec4(v)); break;
    case 3: imageStore(out3, p, uvec4(v)); break;
    case 4: imageStore(out4, p, uvec4(v)); break;
    default: imageStore(out5, p, uvec4(v)); break;
  }
}

void main() {
  int level = int(pc.level);
  int size = int(pc.grid.resolution) >> (level + 1);
  ivec3 cell = ivec3(gl_GlobalInvocationID);
  if (any(greaterThanEqual(cell, ivec3(size)))) return;
  ivec3 first = 2 * cell;
  // The isotropic base is shared by all six directions: fetch its eight children once.
  vec4 base_children[8];
  if (level == 0)
    for (int i = 0; i < 8; ++i) base_children[i] = texelFetch(base, first + ivec3(i & 1, (i >> 1) & 1, i >> 2), 0);
  for (int d = 0; d < GIQ_VCT_DIRECTIONS; ++d) {
    int axis = d / 2;
    bool positive = (d % 2) == 0;
    // Along +axis the child with the smaller coordinate is in front.
    int near_o = positive ? 0 : 1;
    vec4 sum = vec4(0.0);
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        ivec3 o_near, o_far;
        o_near[axis] = near_o;
        o_far[axis] = 1 - near_o;
        o_near[(axis + 1) % 3] = o_far[(axis + 1) % 3] = i;
        o_near[(axis + 2) % 3] = o_far[(axis + 2) % 3] = j;
        vec4 n, f;
        if (level == 0) {
          n = base_children[o_near.x + 2 * o_near.y + 4 * o_near.z];
          f = base_children[o_far.x + 2 * o_far.y + 4 * o_far.z];
        } else {
          n = child(d, first + o_near, level - 1);
          f = child(d, first + o_far, level - 1);
        }
        sum += n + (1.0 - n.a) * f;
      }
    vec4 v = 0.25 * sum;
    if (pc.blend != 0u) v = mix(unpack_voxel(load_out(d, cell)), v, pc.new_weight);
    store_out(d, cell, pack_voxel(v));
  }
}
