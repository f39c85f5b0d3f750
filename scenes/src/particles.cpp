// The particle simulation of particles.h, in double precision: what the reference renders.

#include "giq/scenes/particles.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "orthonormal_basis.h"

namespace giq::scenes {
namespace {

uint32_t pcg_hash(uint32_t v) {
  const uint32_t state = v * 747796405u + 2891336453u;
  const uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

// floor(x) + 1 clamped to [0, 2^32]: the first id born after time x * rate.
uint64_t first_after(double x) { return x < 0.0 ? 0 : uint64_t(std::min(std::floor(x), 4294967295.0)) + 1; }

// phi1(z) = (e^z - 1) / z and phi2(z) = (e^z - 1 - z) / z^2, by their series where the
// closed forms would cancel.
double phi1(double z) { return std::abs(z) < 1e-3 ? 1.0 + z * (0.5 + z * (1.0 / 6.0 + z / 24.0)) : std::expm1(z) / z; }
double phi2(double z) { return std::abs(z) < 1e-3 ? 0.5 + z * (1.0 / 6.0 + z * (1.0 / 24.0 + z / 120.0)) : (std::expm1(z) - z) / (z * z); }

}  // namespace

double Emitter::stage_strength(int stage) const {
  const double life = (stage + 0.5) / double(stages);
  if (strength.empty()) return 1.0;
  if (life <= strength.front().life) return strength.front().strength;
  for (size_t k = 1; k < strength.size(); ++k)
    if (life <= strength[k].life) {
      const StrengthKey &a = strength[k - 1], &b = strength[k];
      const double f = b.life > a.life ? (life - a.life) / (b.life - a.life) : 1.0;
      return a.strength + f * (b.strength - a.strength);
    }
  return strength.back().strength;
}

AliveRange alive_range(const Emitter& e, double t) {
  AliveRange r;
  if (!(e.rate > 0.0)) return r;
  r.end = first_after(e.rate * t);
  r.first = std::min(r.end, first_after(e.rate * (t - e.lifetime)));
  return r;
}

std::vector<uint64_t> stage_starts(const Emitter& e, double t) {
  std::vector<uint64_t> out;
  for (int s = 1; s < e.stages; ++s) out.push_back(e.rate > 0.0 ? first_after(e.rate * (t - s * e.lifetime / e.stages)) : 0);
  return out;
}

AliveRange stage_range(const AliveRange& alive, const std::vector<uint64_t>& starts, int s) {
  const size_t i = size_t(s);
  AliveRange r;
  r.end = i == 0 ? alive.end : std::clamp(starts[i - 1], alive.first, alive.end);
  r.first = i < starts.size() ? std::clamp(starts[i], alive.first, r.end) : alive.first;
  return r;
}

uint32_t particle_random(uint32_t seed, uint32_t id, uint32_t k) { return pcg_hash(k ^ pcg_hash(id ^ pcg_hash(seed))); }

double particle_unit(uint32_t seed, uint32_t id, uint32_t k) { return double(particle_random(seed, id, k) >> 8) * 0x1p-24; }

ParticleBirth particle_birth(const Emitter& e, uint32_t id) {
  ParticleBirth birth;
  if (e.choice.empty()) return birth;
  // Where: a triangle by area (words 0), a uniform point on it (1, 2).
  const uint32_t r = particle_random(e.seed, id, 0);
  const size_t k = size_t(std::lower_bound(e.choice.begin(), e.choice.end(), r) - e.choice.begin());
  const glm::dvec3 &a = e.surface[3 * k], &b = e.surface[3 * k + 1], &c = e.surface[3 * k + 2];
  const double s = std::sqrt(particle_unit(e.seed, id, 1)), u = particle_unit(e.seed, id, 2);
  birth.position = a + s * ((b - a) + u * (c - b));
  // Which way: uniform in the cone about the face's normal (3, 4).
  const glm::dvec3 n = glm::normalize(glm::cross(b - a, c - a));
  glm::dvec3 tx, ty;
  orthonormal_basis(n, tx, ty);
  // sin from 1 - cos (x (2 - x) = 1 - cos^2), which does not cancel near the cone's axis.
  const double x = particle_unit(e.seed, id, 3) * (1.0 - std::cos(e.spread)), cos_theta = 1.0 - x, sin_theta = std::sqrt(x * (2.0 - x));
  const double phi = 2.0 * std::numbers::pi * particle_unit(e.seed, id, 4);
  birth.velocity = e.speed * (cos_theta * n + sin_theta * (std::cos(phi) * tx + std::sin(phi) * ty));
  return birth;
}

Particle particle_at(const Emitter& e, uint32_t id, const ParticleBirth& birth, double t, const std::vector<uint64_t>& starts) {
  Particle p;
  p.id = id;
  p.age = t - double(id) / e.rate;
  p.stage = int(std::count_if(starts.begin(), starts.end(), [&](uint64_t s) { return id < s; }));
  const double z = -e.drag * p.age;
  p.velocity = birth.velocity * std::exp(z) + e.gravity * (p.age * phi1(z));
  p.position = birth.position + birth.velocity * (p.age * phi1(z)) + e.gravity * (p.age * p.age * phi2(z));
  return p;
}

Particle particle_at(const Emitter& e, uint32_t id, double t) { return particle_at(e, id, particle_birth(e, id), t, stage_starts(e, t)); }

}  // namespace giq::scenes
