#version 460
// Empties the base level before voxelisation: a compute fill rather than vkCmdClearColorImage,
// which on GPUs whose graphics units are few (the H100) takes the slow path for a 256^3
// volume.
#extension GL_GOOGLE_include_directive : require
#include "techniques/vct/vct_shared.h"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(binding = 0, r32ui) uniform writeonly uimage3D voxel_ids;

void main() {
  ivec3 p = ivec3(gl_GlobalInvocationID);
  if (any(greaterThanEqual(p, imageSize(voxel_ids)))) return;
  imageStore(voxel_ids, p, uvec4(GIQ_VCT_EMPTY));
}
