#pragma once
// Eight float or integer lanes as one value, for the integrator that advances eight paths with
// every instruction (lane_integrator.h). A value is two SSE vectors (GCC's vector
// extensions, the baseline x86-64 instruction set), and every operation works on both halves
// back to back, so their dependency chains overlap. (GCC's own 32-byte vectors would do
// comparisons one lane at a time on this target.)
//
// Every function computes, lane by lane, exactly the IEEE operations of its scalar
// counterpart in the same order, so a path gives the same bits in a lane as alone.

#include <glm/glm.hpp>

#include <cstdint>
#include <cstring>
#include <xmmintrin.h>

namespace giq::reference::lanes {

inline constexpr int kWidth = 8;

using F4 = float __attribute__((vector_size(16)));
using I4 = int32_t __attribute__((vector_size(16)));
using U4 = uint32_t __attribute__((vector_size(16)));

template <class V, class E>
struct Wide;
using F = Wide<F4, float>;
using I = Wide<I4, int32_t>;  // masks: -1 true, 0 false
using U = Wide<U4, uint32_t>;

template <class V, class E>
struct Wide {
  union {
    V h[2];
    E e[kWidth];
  };
  Wide() : h{V{}, V{}} {}
  Wide(E s) : h{V{} + s, V{} + s} {}  // every lane s
  Wide(V a, V b) : h{a, b} {}
  E& operator[](int l) { return e[l]; }
  const E& operator[](int l) const { return e[l]; }

#define GIQ_LANES_BINARY(op)                                                                                          \
  [[gnu::always_inline]] friend Wide operator op(Wide a, Wide b) { return {a.h[0] op b.h[0], a.h[1] op b.h[1]}; }   \
  [[gnu::always_inline]] Wide& operator op##=(Wide b) { return *this = *this op b; }
  GIQ_LANES_BINARY(+)
  GIQ_LANES_BINARY(-)
  GIQ_LANES_BINARY(*)
  GIQ_LANES_BINARY(/)
  GIQ_LANES_BINARY(&)
  GIQ_LANES_BINARY(|)
  GIQ_LANES_BINARY(^)
#undef GIQ_LANES_BINARY
#define GIQ_LANES_COMPARE(op) \
  [[gnu::always_inline]] friend I operator op(Wide a, Wide b) { return {a.h[0] op b.h[0], a.h[1] op b.h[1]}; }
  GIQ_LANES_COMPARE(<)
  GIQ_LANES_COMPARE(<=)
  GIQ_LANES_COMPARE(>)
  GIQ_LANES_COMPARE(>=)
  GIQ_LANES_COMPARE(==)
  GIQ_LANES_COMPARE(!=)
#undef GIQ_LANES_COMPARE
  [[gnu::always_inline]] friend Wide operator-(Wide a) { return {-a.h[0], -a.h[1]}; }
  [[gnu::always_inline]] friend Wide operator~(Wide a) { return {~a.h[0], ~a.h[1]}; }
  [[gnu::always_inline]] friend Wide operator>>(Wide a, int n) { return {a.h[0] >> n, a.h[1] >> n}; }
  [[gnu::always_inline]] friend Wide operator<<(Wide a, int n) { return {a.h[0] << n, a.h[1] << n}; }
};

[[gnu::always_inline]] inline F load(const float* p) {
  F v;
  std::memcpy(v.e, p, sizeof v.e);
  return v;
}

[[gnu::always_inline]] inline F select(I m, F a, F b) { return {m.h[0] ? a.h[0] : b.h[0], m.h[1] ? a.h[1] : b.h[1]}; }
[[gnu::always_inline]] inline I select(I m, I a, I b) { return {m.h[0] ? a.h[0] : b.h[0], m.h[1] ? a.h[1] : b.h[1]}; }
[[gnu::always_inline]] inline bool any(I m) {
  const I4 o = m.h[0] | m.h[1];
  return (o[0] | o[1] | o[2] | o[3]) != 0;
}

// Bits as the other type, and value conversions (C's casts: float to int truncates).
[[gnu::always_inline]] inline I bits(F v) { return {I4(v.h[0]), I4(v.h[1])}; }
[[gnu::always_inline]] inline I bits(U v) { return {I4(v.h[0]), I4(v.h[1])}; }
[[gnu::always_inline]] inline F float_bits(I v) { return {F4(v.h[0]), F4(v.h[1])}; }
[[gnu::always_inline]] inline F to_float(I v) { return {__builtin_convertvector(v.h[0], F4), __builtin_convertvector(v.h[1], F4)}; }
[[gnu::always_inline]] inline I to_int(F v) { return {__builtin_convertvector(v.h[0], I4), __builtin_convertvector(v.h[1], I4)}; }

[[gnu::always_inline]] inline F sqrt(F v) { return {F4(_mm_sqrt_ps(__m128(v.h[0]))), F4(_mm_sqrt_ps(__m128(v.h[1])))}; }
[[gnu::always_inline]] inline F abs(F v) { return float_bits(bits(v) & 0x7fffffff); }
// std::max(a, b) and std::min(a, b): (a < b) ? b : a and (b < a) ? b : a, NaN handling included.
[[gnu::always_inline]] inline F max(F a, F b) { return select(a < b, b, a); }
[[gnu::always_inline]] inline F min(F a, F b) { return select(b < a, b, a); }
[[gnu::always_inline]] inline I is_inf(F v) { return abs(v) == F(__builtin_inff()); }
[[gnu::always_inline]] inline I is_finite(F v) { return abs(v) < F(__builtin_inff()); }
// std::copysign(1.0f, v).
[[gnu::always_inline]] inline F copysign_one(F v) { return float_bits((bits(v) & int32_t(0x80000000u)) | bits(F(1.0f))); }

// glm::vec3 across the lanes.
struct V3 {
  F x, y, z;
};
[[gnu::always_inline]] inline V3 splat(glm::vec3 v) { return {v.x, v.y, v.z}; }
[[gnu::always_inline]] inline V3 splat(F s) { return {s, s, s}; }  // glm::vec3(s)
[[gnu::always_inline]] inline V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
[[gnu::always_inline]] inline V3 operator-(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
[[gnu::always_inline]] inline V3 operator-(V3 a) { return {-a.x, -a.y, -a.z}; }
[[gnu::always_inline]] inline V3 operator*(V3 a, V3 b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
[[gnu::always_inline]] inline V3 operator*(V3 a, F s) { return {a.x * s, a.y * s, a.z * s}; }
[[gnu::always_inline]] inline V3 operator*(F s, V3 a) { return {s * a.x, s * a.y, s * a.z}; }
[[gnu::always_inline]] inline V3 operator/(V3 a, F s) { return {a.x / s, a.y / s, a.z / s}; }
[[gnu::always_inline]] inline F dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
[[gnu::always_inline]] inline V3 select(I m, V3 a, V3 b) { return {select(m, a.x, b.x), select(m, a.y, b.y), select(m, a.z, b.z)}; }
// glm's vec3 != vec3(0): some component is not zero (NaN included).
[[gnu::always_inline]] inline I nonzero(V3 a) { return (a.x != 0.0f) | (a.y != 0.0f) | (a.z != 0.0f); }
// bsdf.h's max_component: std::max(x, std::max(y, z)).
[[gnu::always_inline]] inline F max_component(V3 a) { return max(a.x, max(a.y, a.z)); }

[[gnu::always_inline]] inline void set(V3& v, int l, glm::vec3 s) { v.x[l] = s.x, v.y[l] = s.y, v.z[l] = s.z; }
[[gnu::always_inline]] inline glm::vec3 get(const V3& v, int l) { return {v.x[l], v.y[l], v.z[l]}; }

}  // namespace giq::reference::lanes
