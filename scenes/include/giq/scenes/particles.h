#pragma once
// Particle emitters (a scene's extras.giq.emitters, docs/scene-format.md) and the particles they
// have alive at any instant, by a simulation that needs no history, so that any frame can be
// rendered alone, in any order, on any rank:
//   - particle i of an emitter is born at i / rate and lives `lifetime` seconds; which ids are
//     alive, and in which stage of life, is decided on integers (alive_range, stage_starts),
//     so every renderer agrees on it exactly;
//   - where and how it is emitted follows from counter-based random numbers of (seed, i)
//     (particle_random): a point on the emitting surface chosen by area, a direction in a cone
//     about that surface's normal;
//   - it then moves under gravity and linear drag in closed form (particle_at).
// The scene library evaluates this in double precision and adds the particles to every posed
// scene as geometry (Scene::at): each an octahedron (a small sphere of eight triangles, the
// same from every side, so its light does not depend on the camera) whose material is its
// emitter's at its stage of life. The reference renders those triangles; the real-time
// module's GPU particle system evaluates the same expressions in float.

#include <glm/glm.hpp>
#include <cstdint>
#include <string>
#include <vector>

namespace giq::scenes {

// Emission strength at a fraction of life; piecewise linear between keys, held beyond them.
struct StrengthKey {
  double life = 0.0;  // fraction of the lifetime, in [0, 1]
  double strength = 1.0;
};

// A particle's octahedron: six vertices on the axes, normals pointing out along them (a small
// sphere's), eight faces counter-clockwise from outside (the GPU's copy is
// realtime/shaders/particle_octahedron.glsl).
inline constexpr uint32_t kParticleVertices = 6, kParticleTriangles = 8;
inline const glm::dvec3 kParticleAxes[kParticleVertices] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
inline const glm::uvec3 kParticleFaces[kParticleTriangles] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                                                               {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};

// The most particles one emitter may have alive at once: with eight triangles each, the most
// triangles a scene may hold.
inline constexpr uint32_t kMaxParticles = 1u << 22;

struct Emitter {
  std::string name;
  int node = -1;  // the glTF node whose meshes' surface emits, as posed at t = 0
  double rate = 0.0;      // particles per second
  double lifetime = 1.0;  // seconds
  double speed = 0.0;     // initial speed (m/s), along a direction in the cone
  double spread = 0.0;    // the cone's half angle about the surface normal (radians)
  glm::dvec3 gravity{0.0, -9.81, 0.0};  // m/s^2, in the scene's frame
  double drag = 0.0;      // 1/s: dv/dt = gravity - drag * v
  double size = 0.01;     // the octahedron's circumradius (m)
  glm::vec3 color{1.0f};  // base colour (Lambertian)
  glm::vec3 emission{0.0f};            // emitted radiance at strength 1
  std::vector<StrengthKey> strength;   // over life; empty: 1 throughout
  int stages = 8;         // a particle's emission is its stage's: the strength at the stage's middle
  uint32_t seed = 0;
  uint32_t max_particles = 0;  // the most alive at once, at least floor(rate * lifetime) + 1

  // Fixed at load. The emitting surface in the scene's local frame: three corners per
  // triangle, and its choice by area in 32-bit fixed point (triangle k is chosen when the
  // random word r <= choice[k] and r > choice[k - 1]), so that integer comparisons choose the
  // same triangle on every device.
  std::vector<glm::dvec3> surface;
  std::vector<uint32_t> choice;
  int first_material = -1;  // `stages` consecutive materials in Scene::materials
  uint32_t object_id = 0;   // of the particles' pixels: glTF node count + 1 + emitter index

  double stage_strength(int stage) const;  // strength at the stage's middle of life
  // The area of each face of a particle's octahedron: an equilateral triangle of side
  // size sqrt(2).
  double face_area() const { return 0.5 * 1.7320508075688772 * size * size; }
};

// The ids alive at time t: born at id / rate <= t, dying at id / rate + lifetime > t.
struct AliveRange {
  uint64_t first = 0, end = 0;  // [first, end)
  uint64_t count() const { return end - first; }
};
AliveRange alive_range(const Emitter& e, double t);
// stage_starts(e, t)[s - 1] for s in 1..stages-1: an alive particle is in stage s or later
// when its id is below that (born at least s lifetime / stages ago).
std::vector<uint64_t> stage_starts(const Emitter& e, double t);
// The ids of stage s among the `alive` ones, given their `starts` (stage_starts): those below
// starts[s - 1] (every alive id for s = 0) and at or above starts[s] (down to the first alive
// one for the last stage). Stage s - 1's ids come right after stage s's.
AliveRange stage_range(const AliveRange& alive, const std::vector<uint64_t>& starts, int s);

// The k-th 32-bit random word of particle `id` (PCG hashes, Jarzynski and Olano 2020, "Hash
// Functions for GPU Rendering", JCGT 9(3)), and the same as a float in [0, 1) (its top 24
// bits).
uint32_t particle_random(uint32_t seed, uint32_t id, uint32_t k);
double particle_unit(uint32_t seed, uint32_t id, uint32_t k);

struct Particle {
  uint32_t id = 0;
  glm::dvec3 position{0.0}, velocity{0.0};
  double age = 0.0;  // seconds
  int stage = 0;
};
// Where and how particle `id` is emitted: the point and the velocity its random words choose
// (0 for an emitter without a surface).
struct ParticleBirth {
  glm::dvec3 position{0.0}, velocity{0.0};
};
ParticleBirth particle_birth(const Emitter& e, uint32_t id);
// Particle `id`, emitted as `birth`, at time t (at any age, even outside its life), in its
// stage among `starts` (stage_starts(e, t)), moved in closed form. Under constant gravity g
// and linear drag k, with a = age: v(a) = v0 e^(-k a) + g a phi1(-k a) and
// p(a) = p0 + v0 a phi1(-k a) + g a^2 phi2(-k a), where phi1(z) = (e^z - 1) / z and
// phi2(z) = (e^z - 1 - z) / z^2 (1 and 1/2 at z = 0: free fall without drag).
Particle particle_at(const Emitter& e, uint32_t id, const ParticleBirth& birth, double t, const std::vector<uint64_t>& starts);
// The same from the id alone: its birth and the stage starts at t worked out for it.
Particle particle_at(const Emitter& e, uint32_t id, double t);

struct Mesh;
// The centres of the particles in a mesh that Scene::at made for a stage of an emitter's
// particles (Mesh::emitter >= 0), read back from their octahedra (each Emitter::size in
// circumradius, eight consecutive triangles), in the mesh's order: renderers that treat a
// particle as one small light rather than eight triangles (the real-time direct light).
std::vector<glm::vec3> particle_centres(const Mesh& m);

}  // namespace giq::scenes
