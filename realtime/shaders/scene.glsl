// The scene's storage buffers (bindings 0..9, see scene_shared.h) and accessors.
#ifndef GIQ_SCENE_GLSL
#define GIQ_SCENE_GLSL

#include "scene_shared.h"

layout(std430, binding = GIQ_BINDING_VERTICES) readonly buffer SceneVertices { GpuVertex scene_vertices[]; };
layout(std430, binding = GIQ_BINDING_TRIANGLES) readonly buffer SceneTriangles { GpuTriangle scene_triangles[]; };
layout(std430, binding = GIQ_BINDING_MATERIALS) readonly buffer SceneMaterials { GpuMaterial scene_materials[]; };
layout(std430, binding = GIQ_BINDING_BVH_NODES) readonly buffer SceneBvhNodes { GpuBvhNode bvh_nodes[]; };
layout(std430, binding = GIQ_BINDING_BVH_PRIMS) readonly buffer SceneBvhPrims { uint bvh_prims[]; };
layout(std430, binding = GIQ_BINDING_LIGHTS) readonly buffer SceneLights { GpuLight scene_lights[]; };
layout(std430, binding = GIQ_BINDING_EMISSIVE) readonly buffer SceneEmissive { GpuEmissive scene_emissive[]; };
layout(std430, binding = GIQ_BINDING_VERTEX_EXTRA) readonly buffer SceneVertexExtra { GpuVertexExtra scene_vertex_extra[]; };
layout(std430, binding = GIQ_BINDING_TEXTURES) readonly buffer SceneTextures { GpuTexture scene_textures[]; };
layout(std430, binding = GIQ_BINDING_DECODE) readonly buffer SceneDecode { float scene_decode[]; };

void triangle_vertices(uint tri, out vec3 a, out vec3 b, out vec3 c) {
  uvec4 v = scene_triangles[tri].v;
  a = scene_vertices[v.x].position.xyz;
  b = scene_vertices[v.y].position.xyz;
  c = scene_vertices[v.z].position.xyz;
}

#endif
