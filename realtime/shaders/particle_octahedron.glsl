// A particle's octahedron on the GPU, as scenes/particles.h lays it out (kParticleAxes,
// kParticleFaces): six vertices on the axes, normals along them, eight faces counter-clockwise
// from outside. Written by shaders/particles_vertices.comp, read back by
// passes/area_light_parts.glsl.
#ifndef GIQ_PARTICLE_OCTAHEDRON_GLSL
#define GIQ_PARTICLE_OCTAHEDRON_GLSL

const vec3 kParticleAxes[6] = vec3[6](vec3(1, 0, 0), vec3(-1, 0, 0), vec3(0, 1, 0), vec3(0, -1, 0), vec3(0, 0, 1), vec3(0, 0, -1));
const uvec3 kParticleFaces[8] = uvec3[8](uvec3(0, 2, 4), uvec3(2, 1, 4), uvec3(1, 3, 4), uvec3(3, 0, 4),
                                         uvec3(2, 0, 5), uvec3(1, 2, 5), uvec3(3, 1, 5), uvec3(0, 3, 5));

#endif
