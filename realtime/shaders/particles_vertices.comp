#version 460
// The alive particles as the scene's geometry: each particle of this frame's alive list
// written as the scene library's octahedron (scenes/particle_geometry.cpp: six vertices on the
// axes at the emitter's size, normals along them, eight faces) into the scene's vertex,
// triangle and index arrays, in its stage mesh at the place the scene library gives it
// (particle ids ascending within a stage), and where it was one frame earlier, by the same
// closed form at its age less a frame, into the previous vertices (motion vectors; before its
// birth too, as the scene library does). A glowing stage's faces are also written as emissive
// triangles, with their CDF in closed form (GpuParticleStage). The vertices are the ones the
// GPU simulated, so every pass draws and traces this system's particles (SceneGpu builds
// their tree over them), and the host computes none of them.
#extension GL_GOOGLE_include_directive : require

#include "shaders/scene_shared.h"
#include "shaders/particles_bindings.glsl"
#include "shaders/particle_motion.glsl"
#include "shaders/particle_octahedron.glsl"

layout(local_size_x = GIQ_PARTICLES_GROUP) in;

layout(std430, binding = 10) writeonly buffer Vertices { vec4 vertices[]; };  // GpuVertex rows: position, normal
layout(std430, binding = 11) writeonly buffer Previous { vec4 previous[]; };
layout(std430, binding = 12) readonly buffer Stages { GpuParticleStage stages[]; };
layout(std430, binding = 13) writeonly buffer Triangles { GpuTriangle triangles[]; };
layout(std430, binding = 14) writeonly buffer Indices { uint indices[]; };
layout(std430, binding = 15) writeonly buffer Emissive { GpuEmissive emissive[]; };
layout(push_constant) uniform Push { float frame_seconds; };

// Eight invocations a particle, one a face (and the first six a vertex each), so that the
// invocations of a subgroup write neighbouring records together: a particle's records lie
// side by side, and the particles of the alive list mostly do too. One invocation writing a
// particle's 1.1 kB strided its stores a record apart across the subgroup. The groups run over
// two dimensions (particles_count.comp), since 2^22 particles need more than 65535 of them.
void main() {
  uint group = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
  uint i = group * (GIQ_PARTICLES_GROUP / 8u) + gl_LocalInvocationID.x / 8u;
  uint f = gl_LocalInvocationID.x % 8u;
  if (i >= counters[GIQ_PARTICLES_OUT]) return;
  uint slot = alive_out[i];
  vec4 position = particles[slot].position;  // w: age
  uint stage = floatBitsToUint(particles[slot].velocity.w);
  vec4 birth = particles[slot].birth_position;
  uint id = floatBitsToUint(birth.w);
  GpuParticleStage st = stages[stage];
  uint place = id - st.first.y;  // the particle's place in its stage
  uint first = st.first.x + 6u * place;
  if (f < 6u) {
    vec3 was, v;
    particle_state(birth.xyz, particles[slot].birth_velocity.xyz, position.w - frame_seconds, was, v);
    float size = emitter.motion.w;
    vec3 axis = kParticleAxes[f];
    uint row = 2u * (first + f);
    vertices[row] = vec4(position.xyz + size * axis, 1.0);
    vertices[row + 1u] = vec4(axis, 0.0);
    previous[row] = vec4(was + size * axis, 1.0);
    previous[row + 1u] = vec4(axis, 0.0);
  }
  uint tri = st.first.z + 8u * place + f;
  uvec3 v = kParticleFaces[f] + first;
  uint e = st.first.w == 0u ? 0u : st.first.w + 8u * place + f;  // emissive index + 1
  triangles[tri].v = uvec4(v, st.triangle.x);
  triangles[tri].extra = uvec4(e, st.triangle.y, st.triangle.z, 0u);
  indices[3u * tri] = v.x;
  indices[3u * tri + 1u] = v.y;
  indices[3u * tri + 2u] = v.z;
  if (e == 0u) return;
  uint j = 8u * place + f;  // the stage's j-th emissive triangle
  emissive[e - 1u].triangle = uvec4(tri, 0u, 0u, 0u);
  emissive[e - 1u].radiance = st.radiance;
  emissive[e - 1u].sampling = vec4(e == st.triangle.w ? 1.0 : min(st.sampling.x + float(j + 1u) * st.sampling.y, 1.0), st.sampling.y, 0.0, 0.0);
}
