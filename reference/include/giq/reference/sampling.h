#pragma once
// Sampling helpers of the reference path tracer: a counter-based random number generator and
// the warps from the unit square to the domains the integrator samples. All pure functions.
//
// Determinism: a random number is a function of (pixel, sample index, dimension, seed) only,
// never of a generator's state, so a pixel renders the same whatever thread runs it, in
// whatever order, and a render resumed after sample n continues exactly as if uninterrupted.

#include <glm/glm.hpp>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>

#include "giq/reference/sobol.h"

namespace giq::reference {

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr float kInvPi = 0.318309886183790671538f;

// MurmurHash3's 64-bit finaliser (Appleby, "fmix64"): every input bit affects every output bit.
constexpr uint64_t mix64(uint64_t k) {
  k ^= k >> 33;
  k *= 0xff51afd7ed558ccdull;
  k ^= k >> 33;
  k *= 0xc4ceb9fe1a85ec53ull;
  k ^= k >> 33;
  return k;
}

// A float in [0, 1) from the top 24 bits of a hash (exactly representable, never 1).
constexpr float to_unit_float(uint64_t h) { return float(h >> 40) * 0x1p-24f; }

// The random number for (pixel, sample, dimension, seed): two rounds of mixing over the packed
// 128-bit key, so neighbouring keys give uncorrelated values.
constexpr float sample_1d(uint32_t pixel, uint32_t sample, uint32_t dimension, uint64_t seed) {
  const uint64_t a = (uint64_t(pixel) << 32) | sample;
  const uint64_t b = (uint64_t(dimension) << 32) ^ seed;
  return to_unit_float(mix64(mix64(a ^ 0x9e3779b97f4a7c15ull) ^ mix64(b + 0x632be59bd9b4e019ull)));
}

// The random numbers of one camera path, in groups of four: the pixel jitter, then per
// bounce a light group (point on the light, light pick, alias choice) and a BSDF group
// (direction, lobe, roulette). The first two numbers of a group are the best stratified.
//
// Independent: every number a hash of (pixel, sample, dimension, seed), so samples are
// independent and a pixel's sample variance estimates the variance of its mean.
// Sobol (block > 0): sample i belongs to block i / block; each block is an independently
// scrambled Sobol net of `block` points per group, so blocks are independent replicates of a
// randomised quasi-Monte Carlo estimate (Owen 1997, "Monte Carlo variance of scrambled net
// quadrature") and the variance of a pixel's mean is estimated from its block means.
class PathSampler {
 public:
  PathSampler() = default;
  PathSampler(uint32_t pixel, uint32_t sample, uint64_t seed, uint32_t block)
      : pixel_(pixel), sample_(sample), seed_(seed), block_(block) {
    if (block_ != 0) {
      bits_ = std::countr_zero(block_);
      key_ = mix64(mix64(((uint64_t(pixel) << 32) | (sample / block)) ^ 0x9e3779b97f4a7c15ull) ^ mix64(seed ^ 0x2545f4914f6cdd1dull));
    }
  }

  // The numbers of one group, computed when asked for: a path that has no use for a group's
  // third or fourth number (no specular lobe to choose, no roulette yet) does not pay for it.
  class Group {
   public:
    [[gnu::always_inline]] float operator[](int k) const {
      if (independent_) return sample_1d(pixel_, sample_, independent_dimension(group_, k), seed_);
      return float(sobol_[k] >> 8) * 0x1p-24f;
    }

    // The independent sampler's dimension of number k of a group: the layout it has always
    // had (2 for the pixel, then per bounce light pick, light point (2), lobe, direction (2),
    // roulette, alias), so its renders keep their bits across the change to groups.
    static constexpr uint32_t independent_dimension(uint32_t group, int k) {
      if (group == 0) return k < 2 ? uint32_t(k) : 0x80000000u + uint32_t(k);  // 2 and 3 are unused
      constexpr uint32_t light[4] = {1, 2, 0, 7}, bsdf[4] = {4, 5, 3, 6};
      const uint32_t depth = (group - 1) / 2;
      return 2 + 8 * depth + (group % 2 == 1 ? light[k] : bsdf[k]);
    }

   private:
    friend class PathSampler;
    Group(uint32_t pixel, uint32_t sample, uint32_t group, uint64_t seed)
        : independent_(true), pixel_(pixel), sample_(sample), group_(group), seed_(seed) {}
    explicit Group(ScrambledSobol4 s) : independent_(false), sobol_(s) {}
    bool independent_;
    uint32_t pixel_ = 0, sample_ = 0, group_ = 0;
    uint64_t seed_ = 0;
    ScrambledSobol4 sobol_;
  };

  [[gnu::always_inline]] Group get(uint32_t group) const {
    if (block_ == 0) return Group(pixel_, sample_, group, seed_);
    return Group(ScrambledSobol4(index_in_block(), bits_, scramble(group)));
  }

  // The Sobol sampler's parts of get(), for the integrator that evaluates eight paths' groups
  // at once (lane_integrator.h): the sample's index in its block and the scramble seed of a
  // group.
  uint32_t index_in_block() const { return sample_ & (block_ - 1); }
  [[gnu::always_inline]] uint32_t scramble(uint32_t group) const {
    return uint32_t(mix64(key_ + uint64_t(group) * 0xbf58476d1ce4e5b9ull) >> 32);
  }

 private:
  uint32_t pixel_ = 0, sample_ = 0;
  uint64_t seed_ = 0;
  uint32_t block_ = 0;
  int bits_ = 0;
  uint64_t key_ = 0;
};

// Group layout: the pixel jitter, then two groups per bounce.
struct SampleDimensions {
  static constexpr uint32_t kPixel = 0;
  static constexpr uint32_t light(int depth) { return 1 + 2 * uint32_t(depth); }  // point.xy, pick, alias
  static constexpr uint32_t bsdf(int depth) { return 2 + 2 * uint32_t(depth); }   // direction.xy, lobe, roulette
};

// --- warps -----------------------------------------------------------------------------------

// Sine and cosine of an angle in [-pi/4, pi/4], by the minimax polynomials of Cephes' sinf and
// cosf for that interval (Moshier 1989, "Methods and Programs for Mathematical Functions",
// cephes/single/sinf.c), within an ulp of the true values there. The concentric map needs no
// other angles, so it can skip the general functions' range reduction and call.
// A template so that lane_integrator.h computes eight at once with the same operations.
template <class T>
struct SinCosOf {
  T sin, cos;
};
using SinCos = SinCosOf<float>;
template <class T>
inline SinCosOf<T> sincos_quarter(T a) {
  const T z = a * a;
  return {((-1.9515295891e-4f * z + 8.3321608736e-3f) * z - 1.6666654611e-1f) * z * a + a,
          ((2.443315711809948e-5f * z - 1.388731625493765e-3f) * z + 4.166664568298827e-2f) * z * z - 0.5f * z + 1.0f};
}

// Cosine-weighted hemisphere about +z via Malley's method on the concentric disk
// (Shirley & Chiu 1997, "A Low Distortion Map Between Disk and Square"). pdf = cos(theta) / pi.
// In the wedges around the y axis the angle is pi/2 - a, whose cosine and sine are a's sine
// and cosine. Written with selects rather than branches: which wedge a point falls in is a
// coin toss that a branch predictor would lose half the time.
inline glm::vec2 square_to_concentric_disk(glm::vec2 u) {
  const glm::vec2 o = 2.0f * u - 1.0f;
  const bool x_wedge = std::abs(o.x) > std::abs(o.y);
  const float r = x_wedge ? o.x : o.y, q = x_wedge ? o.y : o.x;
  const SinCos a = sincos_quarter(r != 0.0f ? (kPi / 4.0f) * (q / r) : 0.0f);  // r = 0: the centre
  return r * (x_wedge ? glm::vec2(a.cos, a.sin) : glm::vec2(a.sin, a.cos));
}
inline glm::vec3 square_to_cosine_hemisphere(glm::vec2 u) {
  const glm::vec2 d = square_to_concentric_disk(u);
  return {d.x, d.y, std::sqrt(std::max(0.0f, 1.0f - d.x * d.x - d.y * d.y))};
}
inline float cosine_hemisphere_pdf(float cos_theta) { return cos_theta > 0.0f ? cos_theta * kInvPi : 0.0f; }

// Uniform direction on the unit sphere (pbrt-v4, "Sampling the unit sphere"). pdf = 1 / (4 pi).
inline glm::vec3 square_to_uniform_sphere(glm::vec2 u) {
  const float z = 1.0f - 2.0f * u.x;
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  const float phi = 2.0f * kPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}
inline constexpr float kUniformSpherePdf = 1.0f / (4.0f * kPi);

// Uniform point on a triangle as barycentrics (b1, b2) of vertices 1 and 2
// (Osada et al. 2002, "Shape Distributions", eq. 1). pdf = 1 / area.
inline glm::vec2 square_to_triangle_barycentrics(glm::vec2 u) {
  const float s = std::sqrt(u.x);
  return {s * (1.0f - u.y), s * u.y};
}

// Veach's power heuristic with beta = 2 (Veach 1997, thesis, eq. 9.13), in the ratio form
// 1 / (1 + (b/a)^2) so that huge or infinite pdfs, whose squares overflow, and zero pdfs
// give the limit weights instead of NaN.
inline float power_heuristic(float pdf_a, float pdf_b) {
  if (!(pdf_a > 0.0f)) return 0.0f;
  if (!(pdf_b > 0.0f)) return 1.0f;
  if (std::isinf(pdf_a)) return std::isinf(pdf_b) ? 0.5f : 1.0f;
  const float r = pdf_b / pdf_a;
  return 1.0f / (1.0f + r * r);
}

// Orthonormal basis around a unit normal without branches on the normal's direction
// (Duff et al. 2017, "Building an Orthonormal Basis, Revisited", JCGT 6(1), listing 3).
struct Frame {
  glm::vec3 t, b, n;
  static Frame from_normal(glm::vec3 n) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float bb = n.x * n.y * a;
    return {{1.0f + sign * n.x * n.x * a, sign * bb, -sign * n.x}, {bb, sign + n.y * n.y * a, -n.y}, n};
  }
  glm::vec3 to_local(glm::vec3 v) const { return {glm::dot(v, t), glm::dot(v, b), glm::dot(v, n)}; }
  glm::vec3 to_world(glm::vec3 v) const { return t * v.x + b * v.y + n * v.z; }
};

}  // namespace giq::reference
