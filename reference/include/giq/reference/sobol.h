#pragma once
// Owen-scrambled Sobol points in up to four dimensions, padded to any number of dimensions by
// independent scrambles and index shuffles per group of four (Burley 2020, "Practical
// Hash-based Owen Scrambling", JCGT 9(4), sections 3 and 4), with the scrambling hash of
// Vegdahl 2021 ("Building a Better LK Hash", psychopath.io), which improves on Laine and
// Karras 2011 ("Stratified Sampling for Stochastic Transparency").
//
// Why: a randomised net stratifies every group's first two dimensions, so the low-dimensional
// parts of a path (the pixel, the light sample, the first bounce's direction) converge faster
// than with independent numbers, while every point stays uniformly distributed and a render
// stays unbiased. All pure functions of their arguments: nothing depends on a generator's
// state or on which thread asks.

#include <array>
#include <bit>
#include <cstdint>
#include <type_traits>

namespace giq::reference {

// 32-bit direction numbers of Sobol's first four dimensions: van der Corput, then the
// primitive polynomials x+1, x^2+x+1, x^3+x+1 with initial numbers m = (1), (1,3), (1,3,1)
// (Joe & Kuo 2008, "Constructing Sobol sequences with better two-dimensional projections",
// SIAM J. Sci. Comput. 30(5), the first lines of their table new-joe-kuo-6.21201).
struct SobolMatrices {
  std::array<std::array<uint32_t, 32>, 4> v{};

  constexpr SobolMatrices() {
    for (int i = 0; i < 32; ++i) v[0][size_t(i)] = 1u << (31 - i);
    struct Poly {
      int degree;
      uint32_t a;  // the polynomial's inner coefficients, highest first
      uint32_t m[3];
    };
    constexpr Poly polys[3] = {{1, 0, {1, 0, 0}}, {2, 1, {1, 3, 0}}, {3, 1, {1, 3, 1}}};
    for (int d = 1; d < 4; ++d) {
      const Poly& p = polys[d - 1];
      std::array<uint32_t, 32>& w = v[size_t(d)];
      for (int i = 0; i < p.degree; ++i) w[size_t(i)] = p.m[i] << (31 - i);
      // Bratley & Fox 1988, "Algorithm 659", eq. 2: v_i = a_1 v_{i-1} ^ ... ^ v_{i-s} ^ (v_{i-s} >> s).
      for (int i = p.degree; i < 32; ++i) {
        uint32_t x = w[size_t(i - p.degree)] ^ (w[size_t(i - p.degree)] >> p.degree);
        for (int k = 1; k < p.degree; ++k)
          if ((p.a >> (p.degree - 1 - k)) & 1u) x ^= w[size_t(i - k)];
        w[size_t(i)] = x;
      }
    }
  }
};
inline constexpr SobolMatrices kSobol{};

// The hashes and the bit reversal below are templates so that lane_integrator.h runs them on
// eight lanes at once (T = lanes::U) with the same operations.
template <class T>
constexpr T reverse_bits(T x) {
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
  if constexpr (std::is_same_v<T, uint32_t>) {
    return __builtin_bswap32(x);
  } else {
    x = ((x >> 8) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8);
    return (x >> 16) | (x << 16);
  }
}

// A hash in which each output bit depends only on the input bits below it, so applied to
// bit-reversed values it flips each bit according to the bits above it: a nested uniform
// (Owen) scramble, approximated by one seeded hash (Vegdahl 2021).
template <class T>
constexpr T lk_hash(T x, T seed) {
  x ^= x * 0x3d20adeau;
  x += seed;
  x *= (seed >> 16) | 1u;
  x ^= x * 0x05526c56u;
  x ^= x * 0x53a22864u;
  return x;
}

template <class T>
constexpr T owen_scramble(T x, T seed) { return reverse_bits(lk_hash(reverse_bits(x), seed)); }

// Seeds of the scrambles of one group, derived by a full-avalanche hash (Wellons 2018,
// "Prospecting for Hash Functions", lowbias32): seeds that differ by a constant would flip
// the leading bits of different dimensions together and correlate them.
template <class T>
constexpr T hash32(T x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

// The largest block of points the tables below hold.
inline constexpr int kSobolMaxBits = 8;

// The first 2^kSobolMaxBits points of the four dimensions, bit-reversed, so that the scramble
// (which works on reversed bits) needs no reversal going in.
struct SobolTable {
  std::array<std::array<uint32_t, 4>, (1u << kSobolMaxBits)> rev{};
  constexpr SobolTable() {
    for (uint32_t i = 0; i < rev.size(); ++i)
      for (int d = 0; d < 4; ++d) {
        uint32_t x = 0;
        for (int bit = 0; bit < kSobolMaxBits; ++bit)
          if ((i >> bit) & 1u) x ^= kSobol.v[size_t(d)][size_t(bit)];
        rev[i][size_t(d)] = reverse_bits(x);
      }
  }
};
inline constexpr SobolTable kSobolTable{};

// Point `index` (< 2^bits, bits <= kSobolMaxBits) of a block of 2^bits scrambled Sobol points
// in dimensions 0 to 3, one dimension at a time, as 32-bit fractions of 1. The index is
// Owen-scrambled first, within the block (Burley's shuffle): every prefix of 2^m points is
// still an aligned block of Sobol points, a (0,m,2)-net in dimensions 0 and 1, but groups
// with different seeds visit the block in unrelated orders, so padded groups do not repeat
// each other's points. Each output bit of the shuffle depends only on the index bits above
// it, which are zero above the block, so the masked shuffle is a permutation of the block.
// Only the first aligned block is used: any other differs from it by a constant XOR, which
// the scramble that follows absorbs.
class ScrambledSobol4 {
 public:
  ScrambledSobol4() = default;
  ScrambledSobol4(uint32_t index, int bits, uint32_t seed)
      : index_(owen_scramble(index, seed) & ((1u << bits) - 1u)), seed_(seed) {}
  [[gnu::always_inline]] uint32_t operator[](int d) const {
    return reverse_bits(lk_hash(kSobolTable.rev[index_][size_t(d)], hash32(seed_ + 0x9e3779b9u * uint32_t(d + 1))));
  }

 private:
  uint32_t index_ = 0, seed_ = 0;
};

inline std::array<uint32_t, 4> scrambled_sobol4(uint32_t index, int bits, uint32_t seed) {
  const ScrambledSobol4 p(index, bits, seed);
  return {p[0], p[1], p[2], p[3]};
}

}  // namespace giq::reference
