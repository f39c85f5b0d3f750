// The parts of an area light (GpuAreaLight, passes/direct_light.h): its triangles and, for a
// stage of glowing particles (range.w > 0), its particles. A stage's are read from the
// octahedra the GPU simulation wrote into the scene's vertex array this frame
// (shaders/particles_vertices.comp: six vertices a particle, on its axes), so they are where
// the drawn particles are and the host lists none of them; another light's triangles from
// the includer's `area_triangles[]`. Needs shaders/scene.glsl and
// passes/direct_light_shared.h.
#ifndef GIQ_AREA_LIGHT_PARTS_GLSL
#define GIQ_AREA_LIGHT_PARTS_GLSL

#include "shaders/particle_octahedron.glsl"

// Particle k of a stage: its centre midway between its +x and -x corners (vertices 0 and 1,
// as scenes::particle_centres reads them).
GpuParticleLight stage_particle(GpuAreaLight l, uint k) {
  uint v = l.range.z + 6u * k;
  GpuParticleLight q;
  q.centre = vec4(0.5 * (scene_vertices[v].position.xyz + scene_vertices[v + 1u].position.xyz), l.particle.w);
  q.radiance = vec4(l.particle.rgb, 0.0);
  return q;
}

// The particles a pass lights particle by particle, and the triangles it integrates one by
// one: a stage's particles unless it asks for its triangles (extent.z), another light's
// triangles.
uint lit_particles(GpuAreaLight l) { return l.extent.z == 0.0 ? l.range.w : 0u; }
uint lit_triangles(GpuAreaLight l) { return lit_particles(l) > 0u ? 0u : l.range.y; }

// Triangle k (below range.y) of the light; a stage's are its particles' faces, eight each.
GpuAreaTriangle area_triangle(GpuAreaLight l, uint k) {
  if (l.range.w == 0u) return area_triangles[l.range.x + k];
  uvec3 f = kParticleFaces[k % 8u] + l.range.z + 6u * (k / 8u);
  GpuAreaTriangle t;
  t.a = vec4(scene_vertices[f.x].position.xyz, l.extent.y);
  t.b = vec4(scene_vertices[f.y].position.xyz, 0.0);
  t.c = vec4(scene_vertices[f.z].position.xyz, 0.0);
  t.radiance = vec4(l.particle.rgb, 0.0);
  return t;
}

#endif
