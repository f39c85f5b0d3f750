#version 460
// One LPV propagation step (Afanasev 2021, chapter III and appendix "LPVPropagation.hlsl";
// Kaplanyan and Dachsbacher 2010): every cell gathers from its 6 face neighbours. A neighbour
// at cell - d sends light along d; the flux it sends through each of the 5 faces of this cell
// that it does not share (the far face, solid angle 0.4006696846 sr from the neighbour's
// centre, and 4 side faces, 0.4234413544 sr each: the appendix's constants; together exactly
// the shared face's 2.0943951 sr) is its intensity towards the face's centre times the solid
// angle, re-emitted in this cell as a cosine lobe along the face's normal: flux / pi x
// cos_lobe_sh(face normal). The 30 (evaluation direction, re-projection lobe) pairs are built
// on the CPU (lpv.cpp) with each neighbour's own orthonormal frame, see lpv.cpp for what the
// appendix's code gets wrong there. The result is the next step's input and is added to the
// accumulated volume.
#extension GL_GOOGLE_include_directive : require

#include "techniques/lpv/lpv_shared.h"
#include "techniques/lpv/lpv_sh.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

layout(std430, binding = 0) readonly buffer Source { vec4 src[]; };
layout(std430, binding = 1) writeonly buffer Destination { vec4 dst[]; };
layout(std430, binding = 2) buffer Accumulated { vec4 accumulated[]; };
// Per neighbour n (0..5) and face f (0..4): [2 (5 n + f)] = solid angle / pi x dir_to_sh(the
// face centre's direction), [2 (5 n + f) + 1] = cos_lobe_sh(the face's normal); [60 + n].xyz = d.
layout(std430, binding = 3) readonly buffer Faces { vec4 faces[]; };

layout(push_constant) uniform Push { LpvGrid grid; };

void main() {
  ivec3 c = ivec3(gl_GlobalInvocationID);
  int res = int(grid.resolution);
  if (any(greaterThanEqual(c, ivec3(res)))) return;
  vec4 r = vec4(0.0), g = vec4(0.0), b = vec4(0.0);
  for (int n = 0; n < 6; ++n) {
    ivec3 nb = c - ivec3(faces[60 + n].xyz);
    if (any(lessThan(nb, ivec3(0))) || any(greaterThanEqual(nb, ivec3(res)))) continue;
    int i = 3 * lpv_cell_index(nb, res);
    vec4 nr = src[i], ng = src[i + 1], nbb = src[i + 2];
    for (int f = 0; f < 5; ++f) {
      vec4 eval = faces[2 * (5 * n + f)], lobe = faces[2 * (5 * n + f) + 1];
      r += dot(nr, eval) * lobe;
      g += dot(ng, eval) * lobe;
      b += dot(nbb, eval) * lobe;
    }
  }
  int o = 3 * lpv_cell_index(c, res);
  dst[o] = r;
  dst[o + 1] = g;
  dst[o + 2] = b;
  accumulated[o] += r;
  accumulated[o + 1] += g;
  accumulated[o + 2] += b;
}
