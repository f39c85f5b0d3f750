// Particle k of a stage of glowing particles (GpuAreaLight::range.w > 0): its octahedron's
// centre, midway between its +x and -x corners (vertices 0 and 1 of the six that
// shaders/particles_vertices.comp writes, as scenes::particle_centres reads them), in the
// scene's vertex array, so the light is where the GPU simulation put the particle this frame
// and the host keeps no list of them. Needs shaders/scene.glsl and
// passes/direct_light_shared.h.
#ifndef GIQ_PARTICLE_LIGHT_GLSL
#define GIQ_PARTICLE_LIGHT_GLSL

GpuParticleLight stage_particle(GpuAreaLight l, uint k) {
  uint v = l.range.z + 6u * k;
  GpuParticleLight q;
  q.centre = vec4(0.5 * (scene_vertices[v].position.xyz + scene_vertices[v + 1u].position.xyz), l.particle.w);
  q.radiance = vec4(l.particle.rgb, 0.0);
  return q;
}

#endif
