#version 460
// Skinning and morph targets in one pass, once a frame (Deformer): each deforming vertex of
// the scene is made from its rest pose, its morph targets' displacements and its joints'
// matrices (glTF 2.0 spec, 3.7.2.2 and 3.7.3), in the same order of operations as
// scenes/src/placement.cpp and scenes/src/pose.cpp do on the CPU in double precision, so the
// two agree to float rounding. As Turánszki 2017 ("Skinning in a Compute Shader") does, the
// vertex's value of the last frame is copied to the previous-vertex buffer before it is
// overwritten: motion vectors of deforming geometry then come with no other pass.
#extension GL_GOOGLE_include_directive : require

#include "shaders/scene_shared.h"
#include "shaders/deform_shared.h"

layout(local_size_x = 64) in;

layout(std430, binding = 0) buffer Vertices { GpuVertex vertices[]; };
layout(std430, binding = 1) writeonly buffer Previous { GpuVertex previous[]; };
layout(std430, binding = 2) buffer Extra { GpuVertexExtra extras[]; };
layout(std430, binding = 3) readonly buffer Rest { GpuRestVertex rest[]; };
layout(std430, binding = 4) readonly buffer Displacements { GpuRestVertex displacements[]; };
layout(std430, binding = 5) readonly buffer Influences { GpuInfluence influences[]; };
layout(std430, binding = 6) readonly buffer Matrices { mat4 matrices[]; };
layout(std430, binding = 7) readonly buffer MorphWeights { float morph_weights[]; };
layout(std430, binding = 8) readonly buffer Meshes { GpuDeformMesh meshes[]; };
// Per slot: x its mesh; y the rest triangle whose face normal replaces a normal that
// collapses (the last one using the vertex; GIQ_DEFORM_NO_TRIANGLE: none).
layout(std430, binding = 9) readonly buffer Slots { uvec2 slots[]; };
layout(std430, binding = 10) readonly buffer RestTriangles { uvec4 rest_triangles[]; };

layout(push_constant) uniform Push {
  uint slot_count;
  uint save_previous;  // 0 on the first frame: previous = current
} pc;

// The sum of a vertex's joints' matrices by their weights (or the mesh's one matrix).
mat4 skin_matrix(GpuDeformMesh m, uint v) {
  if (m.arrays.x == 0u) return matrices[m.frame.x];
  mat4 S = mat4(0.0);
  for (uint set = 0u; set < m.arrays.x; ++set) {
    GpuInfluence f = influences[m.rest.w + set * m.rest.y + v];
    for (int c = 0; c < 4; ++c)
      // A joint outside the skin may be named with weight 0 (checked at load): skipped, as on the CPU.
      if (f.weights[c] != 0.0 && f.joints[c] < m.frame.y) S += f.weights[c] * matrices[m.frame.x + f.joints[c]];
  }
  return S;
}

vec3 morphed_position(GpuDeformMesh m, uint v) {
  vec3 p = rest[m.rest.x + v].position.xyz;
  for (uint t = 0u; t < m.frame.w; ++t) {
    float w = morph_weights[m.frame.z + t];
    if (w != 0.0) p += w * displacements[m.arrays.y + t * m.rest.y + v].position.xyz;
  }
  return p;
}

bool finite3(vec3 v) { return !any(isnan(v)) && !any(isinf(v)); }

// Rest vertex v placed: non-finite positions become 0, as scenes/src/pose.cpp keeps such a
// vertex for its index only.
vec3 placed_position(GpuDeformMesh m, uint v) {
  vec3 p = (skin_matrix(m, v) * vec4(morphed_position(m, v), 1.0)).xyz;
  return finite3(p) ? p : vec3(0.0);
}

// Rest triangle k's corners as the mesh has them at this instant (mirrored: 1 and 2 swapped).
uvec3 corners(GpuDeformMesh m, uint k) {
  uvec3 t = rest_triangles[m.rest.z + k].xyz;
  return (m.slots.w & GIQ_DEFORM_MIRRORED) != 0u ? t.xzy : t;
}

// The face normal of rest triangle k at this instant, (0, 0, 1) where it has no area.
vec3 face_normal(GpuDeformMesh m, uint k) {
  uvec3 t = corners(m, k);
  vec3 a = placed_position(m, t.x), b = placed_position(m, t.y), c = placed_position(m, t.z);
  vec3 n = cross(b - a, c - a);
  float len = length(n);
  return len > 0.0 && !isinf(len) && !isnan(len) ? n / len : vec3(0.0, 0.0, 1.0);
}

// scenes/src/pose.cpp's any_orthogonal.
vec3 any_orthogonal(vec3 n) {
  vec3 a = abs(n.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0);
  return normalize(cross(n, a));
}

void main() {
  uint slot = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * gl_WorkGroupSize.x + gl_LocalInvocationID.x;
  if (slot >= pc.slot_count) return;
  uvec2 item = slots[slot];
  GpuDeformMesh m = meshes[item.x];
  uint local = slot - m.slots.x, dst = m.slots.z + local;
  bool faceted = (m.slots.w & GIQ_DEFORM_FLAT) != 0u;
  uint v = faceted ? corners(m, local / 3u)[local % 3u] : local;

  mat4 S = skin_matrix(m, v);
  vec3 p = (S * vec4(morphed_position(m, v), 1.0)).xyz;
  if (!finite3(p)) p = vec3(0.0);

  // Normals by the cofactor matrix det(L) L^-T, defined for a singular L too, its handedness
  // keeping them outwards (placement.cpp).
  mat3 L = mat3(S);
  float handedness = determinant(L) < 0.0 ? -1.0 : 1.0;
  vec3 n;
  if (faceted) {
    n = face_normal(m, local / 3u);
  } else {
    vec3 r = rest[m.rest.x + v].normal.xyz;
    for (uint t = 0u; t < m.frame.w; ++t) {
      float w = morph_weights[m.frame.z + t];
      if (w != 0.0) r += w * displacements[m.arrays.y + t * m.rest.y + v].normal.xyz;
    }
    n = handedness * (mat3(cross(L[1], L[2]), cross(L[2], L[0]), cross(L[0], L[1])) * r);
    float len = length(n);
    if (len > 0.0 && !isinf(len) && !isnan(len)) n /= len;
    else n = item.y != GIQ_DEFORM_NO_TRIANGLE ? face_normal(m, item.y) : vec3(0.0, 0.0, 1.0);
  }

  // (Member by member: the two buffers' GpuVertex are distinct SPIR-V types.)
  bool save = pc.save_previous != 0u;
  previous[dst].position = save ? vertices[dst].position : vec4(p, 1.0);
  previous[dst].normal = save ? vertices[dst].normal : vec4(n, 0.0);
  vertices[dst].position = vec4(p, 1.0);
  vertices[dst].normal = vec4(n, 0.0);

  if ((m.slots.w & GIQ_DEFORM_TANGENTS) != 0u) {
    vec4 r = rest[m.rest.x + v].tangent;
    vec3 t = r.xyz;
    for (uint k = 0u; k < m.frame.w; ++k) {
      float w = morph_weights[m.frame.z + k];
      if (w != 0.0) t += w * displacements[m.arrays.y + k * m.rest.y + v].tangent.xyz;
    }
    t = L * t;
    t -= n * dot(n, t);  // back into the tangent plane after a non-uniform scale
    float len = length(t);
    t = len > 0.0 && !isinf(len) && !isnan(len) ? t / len : any_orthogonal(n);
    extras[dst].tangent = vec4(t, r.w < 0.0 ? -handedness : handedness);
  }
}
