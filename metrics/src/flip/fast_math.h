#pragma once
// Arithmetic for FLIP's per-pixel loops, written once for a scalar float and for Float4, four
// pixels in one SSE register (GCC/Clang vector extensions), so that each perceptual step is one
// function that the error-map passes call on four pixels at a time.
//
// Cube root, log2, exp2 and pow are branch-free approximations: the C library's cbrtf and powf
// are opaque calls that keep a loop scalar, and took a third of HDR-FLIP's time. They are
// accurate far below the 1e-2 per-pixel agreement FLIP needs (checked against the C library in
// tests/metrics/flip_test.cpp): the cube root to 2e-7 relative; pow to 1e-7 absolute for results
// in [0, 1] and 6e-6 relative everywhere (float exp2(y log2 x) loses accuracy in proportion to
// |y log2 x|).

#include <bit>
#include <cmath>
#include <cstdint>
#include <type_traits>

namespace giq::metrics::flip {

using Float4 = float __attribute__((vector_size(16)));
using Int4 = int32_t __attribute__((vector_size(16)));
using UInt4 = uint32_t __attribute__((vector_size(16)));

template <class T> struct LaneTypes;
template <> struct LaneTypes<float> { using Int = int32_t; using UInt = uint32_t; };
template <> struct LaneTypes<Float4> { using Int = Int4; using UInt = UInt4; };
template <class T> using IntOf = typename LaneTypes<T>::Int;
template <class T> using UIntOf = typename LaneTypes<T>::UInt;

template <class T> inline T splat(float v) {
  if constexpr (std::is_same_v<T, float>) return v;
  else return T{} + v;
}
inline float to_float(int32_t v) { return float(v); }
inline Float4 to_float(Int4 v) { return __builtin_convertvector(v, Float4); }
inline int32_t to_int(float v) { return int32_t(v); }  // truncation
inline Int4 to_int(Float4 v) { return __builtin_convertvector(v, Int4); }

// Lane-wise min, max, |x| and select; for scalars these are the usual ternaries.
template <class T> inline T vmin(T a, T b) { return a < b ? a : b; }
template <class T> inline T vmax(T a, T b) { return a > b ? a : b; }
template <class T> inline T vabs(T a) { return a < splat<T>(0.0f) ? -a : a; }
inline float vsqrt(float v) { return std::sqrt(v); }
inline Float4 vsqrt(Float4 v) {
#if defined(__SSE__)
  return __builtin_ia32_sqrtps(v);
#else
  return Float4{std::sqrt(v[0]), std::sqrt(v[1]), std::sqrt(v[2]), std::sqrt(v[3])};
#endif
}

inline Float4 load4(const float* p) {
  Float4 v;
  __builtin_memcpy(&v, p, sizeof(v));
  return v;
}
inline void store4(float* p, Float4 v) { __builtin_memcpy(p, &v, sizeof(v)); }

// Cube root of t > 0 (normal floats). Start: dividing the exponent by 3 through the bit pattern
// (about 5% off); then two Halley steps y <- y (y^3 + 2t) / (2y^3 + t), each of which cubes the
// relative error (5e-2 -> 1e-4 -> float precision).
template <class T> inline T fast_cbrt(T t) {
  T y = std::bit_cast<T>(std::bit_cast<UIntOf<T>>(t) / 3u + 709921077u);
  T y3 = y * y * y;
  y = y * (y3 + 2.0f * t) / (2.0f * y3 + t);
  y3 = y * y * y;
  return y * (y3 + 2.0f * t) / (2.0f * y3 + t);
}

// log2 of x > 0 (normal floats): x = m 2^e with m in [sqrt(1/2), sqrt(2)), and
// log2(m) = (2 / ln 2) atanh(s), s = (m - 1) / (m + 1), |s| <= 0.172, by its odd series to s^11
// (truncation below 1e-9).
template <class T> inline T fast_log2(T x) {
  using I = IntOf<T>;
  const I bits = std::bit_cast<I>(x);
  T m = std::bit_cast<T>((bits & 0x007FFFFF) | 0x3F800000);  // [1, 2)
  T e = to_float(((bits >> 23) & 0xFF) - 127);
  const auto high = m > splat<T>(1.41421356f);
  m = high ? 0.5f * m : m;
  e = high ? e + 1.0f : e;
  const T s = (m - 1.0f) / (m + 1.0f), s2 = s * s;
  constexpr float k = 2.88539008177792681f;  // 2 / ln 2
  const T series = 1.0f + s2 * (1.0f / 3.0f + s2 * (1.0f / 5.0f + s2 * (1.0f / 7.0f + s2 * (1.0f / 9.0f + s2 * (1.0f / 11.0f)))));
  return e + k * s * series;
}

// 2^z for z in [-126, 127] (clamped): z = n + f with n an integer, f in [-0.5, 0.5]; 2^n through
// the exponent bits and 2^f = e^(f ln 2) by its Taylor series to degree 7 (truncation < 1e-8).
template <class T> inline T fast_exp2(T z) {
  z = vmin(vmax(z, splat<T>(-126.0f)), splat<T>(127.0f));
  const auto n = to_int(z + 128.5f) - 128;  // round to nearest; z + 128.5 > 0, so truncation is floor
  const T f = (z - to_float(n)) * 0.693147180559945309f;
  const T p = 1.0f + f * (1.0f + f * (1.0f / 2.0f + f * (1.0f / 6.0f + f * (1.0f / 24.0f + f * (1.0f / 120.0f + f * (1.0f / 720.0f + f * (1.0f / 5040.0f)))))));
  return p * std::bit_cast<T>((n + 127) << 23);
}

// x^y for x >= 0 and y >= 0, with 0^0 = 1 and 0^y = 0 for y > 0 (as pow). x below the smallest
// normal float counts as 0.
template <class T> inline T fast_pow(T x, T y) {
  const auto zero = x < splat<T>(1.17549435e-38f);
  const T r = fast_exp2(y * fast_log2(zero ? splat<T>(1.0f) : x));
  return zero ? (y == splat<T>(0.0f) ? splat<T>(1.0f) : splat<T>(0.0f)) : r;
}

}  // namespace giq::metrics::flip
