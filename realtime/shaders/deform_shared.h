// The deformation pass's buffers (Deformer, shaders/deform.comp): one layout for the C++ that
// fills them and the GLSL that reads them (std430, 16-byte rows).
#ifndef GIQ_DEFORM_SHARED_H
#define GIQ_DEFORM_SHARED_H

#ifdef __cplusplus
#include <cstdint>
#include <glm/glm.hpp>
namespace giq::realtime::gpu {
using vec4 = glm::vec4;
using uvec4 = glm::uvec4;
#endif

// GpuDeformMesh::slots.w bits.
#define GIQ_DEFORM_FLAT 1u       // no rest normals: vertex 3k + c is corner c of rest triangle k, with the face's normal
#define GIQ_DEFORM_MIRRORED 2u   // this instant: corners 1 and 2 swapped (scenes::Deformation::mirrored)
#define GIQ_DEFORM_TANGENTS 4u   // rest tangents, written to the scene's vertex extras
#define GIQ_DEFORM_NO_TRIANGLE 0xffffffffu

// One rest vertex, or one morph target's displacement of it.
struct GpuRestVertex {
  vec4 position;  // xyz
  vec4 normal;    // xyz
  vec4 tangent;   // xyz, w the bitangent sign (rest vertices only)
};

// One JOINTS_k/WEIGHTS_k pair of one vertex.
struct GpuInfluence {
  uvec4 joints;  // indices into the mesh's matrices
  vec4 weights;
};

// One deforming mesh. Its emitted vertices are slots slots.x .. slots.x + slots.y - 1 of the
// pass, written to the scene's vertices from slots.z on.
struct GpuDeformMesh {
  uvec4 slots;   // x first slot, y count, z first scene vertex, w GIQ_DEFORM_* bits
  uvec4 rest;    // x first rest vertex, y rest vertices, z first rest triangle, w first influence
  uvec4 frame;   // x first matrix, y matrices, z first morph weight, w morph targets
  uvec4 arrays;  // x influence sets (set k of vertex i at rest.w + k * rest.y + i),
                 // y first displacement (target t of vertex i at y + t * rest.y + i)
};

#ifdef __cplusplus
}  // namespace giq::realtime::gpu
#endif
#endif
