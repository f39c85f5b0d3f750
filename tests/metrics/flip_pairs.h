#pragma once
// Deterministic image pairs for FLIP's agreement tests and benchmark: smooth gradients, noise,
// edges, very bright and near-black HDR values, constants and tiny sizes, and a procedural
// rendering-like HDR scene at any size. Every value is a pure function of (pattern, x, y), so
// the pairs are identical on every machine and in every run.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace giq::flip_pairs {

struct Rgb {
  int width = 0, height = 0;
  std::vector<float> r, g, b;
  Rgb() = default;
  Rgb(int w, int h) : width(w), height(h), r(size_t(w) * size_t(h)), g(r.size()), b(r.size()) {}
  void set(int x, int y, float vr, float vg, float vb) {
    const size_t i = size_t(y) * size_t(width) + size_t(x);
    r[i] = vr, g[i] = vg, b[i] = vb;
  }
};

struct Pair {
  std::string name;
  bool hdr = false;
  Rgb reference, test;
};

// Uniform in [0, 1) from integer coordinates (a 32-bit integer hash, lowbias32 by C. Wellons).
inline float hash01(uint32_t x, uint32_t y, uint32_t seed) {
  uint32_t h = x * 0x9E3779B1u ^ (y + 0x7F4A7C15u) * 0x85EBCA77u ^ seed * 0xC2B2AE3Du;
  h ^= h >> 16, h *= 0x7FEB352Du, h ^= h >> 15, h *= 0x846CA68Bu, h ^= h >> 16;
  return float(h >> 8) * (1.0f / 16777216.0f);
}

inline Rgb fill(int w, int h, const std::function<void(int, int, float*)>& f) {
  Rgb img(w, h);
  float c[3];
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      f(x, y, c);
      img.set(x, y, c[0], c[1], c[2]);
    }
  return img;
}

// A rendering-like HDR scene: a lit wall gradient, a bright window (area light), a textured
// floor, discs of different materials, soft shadows, dark corners. The test copy imitates a
// real-time technique's failures: Monte Carlo noise, a blurred (lagging) region, light leaking
// into a dark corner, a shifted edge and a few fireflies.
inline void procedural_scene(int x, int y, int w, int h, float* c) {
  const float u = (float(x) + 0.5f) / float(w), v = (float(y) + 0.5f) / float(h);
  const float floor_line = 0.62f;
  float r, g, b;
  if (v < floor_line) {
    const float wall = 0.15f + 0.6f * std::exp(-8.0f * ((u - 0.3f) * (u - 0.3f) + (v - 0.3f) * (v - 0.3f)));
    r = wall * 0.9f, g = wall * 0.85f, b = wall * 0.8f;
  } else {
    const bool check = (int(u * 16.0f) + int((v - floor_line) * 24.0f)) % 2 == 0;
    const float f = (check ? 0.5f : 0.08f) * (0.4f + 0.6f * (1.0f - v));
    r = f * 0.8f, g = f * 0.7f, b = f * 0.55f;
  }
  // Window: an emitter of radiance ~ 400.
  if (u > 0.62f && u < 0.82f && v > 0.12f && v < 0.38f) r = 380.0f, g = 400.0f, b = 450.0f;
  // Discs: a glossy red sphere-like shading and a blue one.
  const float d1 = std::hypot(u - 0.35f, (v - 0.55f) * float(h) / float(w));
  if (d1 < 0.09f) {
    const float s = std::sqrt(std::max(0.0f, 1.0f - d1 * d1 / 0.0081f));
    r = 0.7f * s + 6.0f * std::pow(s, 40.0f), g = 0.08f * s + 6.0f * std::pow(s, 40.0f), b = 0.05f * s;
  }
  const float d2 = std::hypot(u - 0.7f, (v - 0.7f) * float(h) / float(w));
  if (d2 < 0.07f) r = 0.05f, g = 0.2f, b = 0.9f;
  // Soft shadow under the red disc, dark corner at the left.
  const float shadow = std::exp(-60.0f * ((u - 0.38f) * (u - 0.38f) + 4.0f * (v - 0.68f) * (v - 0.68f)));
  const float corner = std::min(1.0f, 0.02f + 4.0f * u);
  const float k = (1.0f - 0.8f * shadow) * corner;
  c[0] = r * k, c[1] = g * k, c[2] = b * k;
}

inline void procedural_scene_test(int x, int y, int w, int h, uint32_t seed, float* c) {
  const float u = (float(x) + 0.5f) / float(w), v = (float(y) + 0.5f) / float(h);
  // Shifted edge: the scene sampled 2 pixels to the left in the lower half.
  const int sx = v > 0.5f ? std::max(0, x - 2) : x;
  procedural_scene(sx, y, w, h, c);
  // Blurred region (temporal lag): a 5x5 box average.
  if (u > 0.1f && u < 0.3f && v > 0.65f && v < 0.9f) {
    float acc[3] = {0, 0, 0}, t[3];
    for (int dy = -2; dy <= 2; ++dy)
      for (int dx = -2; dx <= 2; ++dx) {
        procedural_scene(std::clamp(x + dx, 0, w - 1), std::clamp(y + dy, 0, h - 1), w, h, t);
        for (int i = 0; i < 3; ++i) acc[i] += t[i] / 25.0f;
      }
    for (int i = 0; i < 3; ++i) c[i] = acc[i];
  }
  // Leak: light added in the dark corner.
  if (u < 0.06f && v < 0.6f) c[0] += 0.05f, c[1] += 0.05f, c[2] += 0.04f;
  // Monte Carlo-like multiplicative noise, and rare fireflies of radiance ~ 1e3.
  const float n = hash01(uint32_t(x), uint32_t(y), seed);
  const float m = 0.75f + 0.5f * n;
  for (int i = 0; i < 3; ++i) c[i] *= m;
  if (hash01(uint32_t(x), uint32_t(y), seed + 1) > 0.9995f) c[0] += 1500.0f, c[1] += 1200.0f, c[2] += 900.0f;
}

inline Pair procedural_hdr_pair(int w, int h, uint32_t seed) {
  Pair p;
  p.name = "procedural_" + std::to_string(w) + "x" + std::to_string(h);
  p.hdr = true;
  p.reference = fill(w, h, [&](int x, int y, float* c) { procedural_scene(x, y, w, h, c); });
  p.test = fill(w, h, [&](int x, int y, float* c) { procedural_scene_test(x, y, w, h, seed, c); });
  return p;
}

// The pairs stored under tests/data/flip/ with NVIDIA's values for them.
inline std::vector<Pair> stored_pairs() {
  std::vector<Pair> pairs;
  auto add = [&](std::string name, bool hdr, int w, int h, std::function<void(int, int, float*)> ref,
                 std::function<void(int, int, float*)> test) {
    pairs.push_back({std::move(name), hdr, fill(w, h, ref), fill(w, h, test)});
  };
  auto gradient = [](int w, int h, float scale) {
    return [=](int x, int y, float* c) {
      const float u = float(x) / float(std::max(1, w - 1)), v = float(y) / float(std::max(1, h - 1));
      c[0] = scale * u, c[1] = scale * v, c[2] = scale * 0.5f * (1.0f - u);
    };
  };
  auto noise = [](uint32_t seed, float scale) {
    return [=](int x, int y, float* c) {
      for (int i = 0; i < 3; ++i) c[i] = scale * hash01(uint32_t(x), uint32_t(y), seed + uint32_t(i));
    };
  };
  auto edges = [](float lo, float hi, int shift) {
    return [=](int x, int y, float* c) {
      const bool on = ((x + shift) / 8 + y / 8) % 2 == 0 || (x + shift > 20 && x + shift < 23);
      c[0] = on ? hi : lo, c[1] = on ? hi * 0.9f : lo, c[2] = on ? hi * 0.7f : lo * 2.0f;
    };
  };
  auto constant = [](float r, float g, float b) {
    return [=](int, int, float* c) { c[0] = r, c[1] = g, c[2] = b; };
  };
  auto plus = [](std::function<void(int, int, float*)> base, std::function<void(int, int, float*)> add_on) {
    return [=](int x, int y, float* c) {
      float t[3];
      base(x, y, c);
      add_on(x, y, t);
      for (int i = 0; i < 3; ++i) c[i] += t[i];
    };
  };
  auto times = [](std::function<void(int, int, float*)> base, uint32_t seed, float amount) {
    return [=](int x, int y, float* c) {
      base(x, y, c);
      for (int i = 0; i < 3; ++i) c[i] *= 1.0f + amount * (2.0f * hash01(uint32_t(x), uint32_t(y), seed + uint32_t(i)) - 1.0f);
    };
  };

  // LDR-FLIP: linear values, mostly in [0, 1].
  add("ldr_gradient", false, 48, 32, gradient(48, 32, 1.0f),
      [g = gradient(48, 32, 1.0f)](int x, int y, float* c) { g(x, y, c), c[0] *= 0.9f, c[2] = std::min(1.0f, c[2] + 0.05f); });
  add("ldr_noise", false, 40, 40, noise(1, 1.0f), plus(noise(1, 0.9f), noise(7, 0.1f)));
  add("ldr_edges", false, 40, 40, edges(0.05f, 0.9f, 0), edges(0.05f, 0.9f, 1));
  add("ldr_constant", false, 12, 12, constant(0.5f, 0.5f, 0.5f), constant(0.6f, 0.5f, 0.4f));
  add("ldr_near_black", false, 32, 32, times(gradient(32, 32, 0.01f), 3, 0.3f), times(gradient(32, 32, 0.01f), 4, 0.3f));
  add("ldr_out_of_range", false, 24, 24, gradient(24, 24, 1.6f), times(gradient(24, 24, 1.6f), 5, 0.2f));
  add("ldr_1x1", false, 1, 1, constant(0.2f, 0.4f, 0.6f), constant(0.6f, 0.4f, 0.2f));
  add("ldr_3x5", false, 3, 5, noise(11, 1.0f), noise(12, 1.0f));
  add("ldr_identical", false, 24, 16, noise(13, 1.0f), noise(13, 1.0f));
  // HDR-FLIP: linear radiance.
  add("hdr_gradient", true, 48, 32, gradient(48, 32, 20.0f), times(gradient(48, 32, 20.0f), 21, 0.1f));
  add("hdr_noise", true, 40, 40, times(constant(1.0f, 0.8f, 0.6f), 22, 0.5f), times(constant(1.0f, 0.8f, 0.6f), 23, 0.5f));
  add("hdr_edges", true, 40, 40, edges(0.02f, 50.0f, 0), edges(0.02f, 50.0f, 1));
  add("hdr_bright", true, 32, 32, times(gradient(32, 32, 3000.0f), 24, 0.2f),
      plus(times(gradient(32, 32, 3000.0f), 25, 0.2f), constant(100.0f, 0.0f, 0.0f)));
  add("hdr_near_black", true, 32, 32, times(gradient(32, 32, 1e-3f), 26, 0.3f), times(gradient(32, 32, 1e-3f), 27, 0.3f));
  add("hdr_constant", true, 12, 12, constant(2.0f, 2.0f, 2.0f), constant(2.5f, 2.0f, 1.5f));
  add("hdr_1x1", true, 1, 1, constant(5.0f, 1.0f, 0.2f), constant(1.0f, 1.0f, 1.0f));
  add("hdr_3x5", true, 3, 5, noise(31, 10.0f), noise(32, 10.0f));
  add("hdr_identical", true, 24, 16, noise(33, 100.0f), noise(33, 100.0f));
  pairs.push_back(procedural_hdr_pair(96, 64, 41));
  pairs.back().name = "hdr_scene";
  {
    Pair ldr_scene = procedural_hdr_pair(96, 64, 42);
    ldr_scene.name = "ldr_scene";
    ldr_scene.hdr = false;
    pairs.push_back(std::move(ldr_scene));
  }
  return pairs;
}

}  // namespace giq::flip_pairs
