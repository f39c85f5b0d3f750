// Random numbers and sampling. A sample is a function of (pixel, sample index, dimension,
// seed) only: any pixel re-renders alone to the same value, whatever the dispatch order.
#ifndef GIQ_SAMPLING_GLSL
#define GIQ_SAMPLING_GLSL

const float PI = 3.14159265358979323846;

// PCG hash (Jarzynski and Olano 2020, "Hash Functions for GPU Rendering", JCGT 9(3)).
uint pcg_hash(uint v) {
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

struct Rng { uint state; };

Rng rng_init(uvec2 pixel, uint sample_index, uint seed) {
  Rng r;
  r.state = pcg_hash(pixel.x ^ pcg_hash(pixel.y ^ pcg_hash(sample_index ^ pcg_hash(seed))));
  return r;
}

// Uniform in [0, 1): the top 24 bits, so 1.0 is never returned.
float rng_next(inout Rng r) {
  r.state = r.state * 747796405u + 2891336453u;
  uint word = ((r.state >> ((r.state >> 28u) + 4u)) ^ r.state) * 277803737u;
  word = (word >> 22u) ^ word;
  return float(word >> 8u) * (1.0 / 16777216.0);
}

// Orthonormal basis around a unit n (Duff et al. 2017, "Building an Orthonormal Basis,
// Revisited", JCGT 6(1)).
void make_basis(vec3 n, out vec3 t, out vec3 b) {
  float s = n.z >= 0.0 ? 1.0 : -1.0;
  float a = -1.0 / (s + n.z);
  float c = n.x * n.y * a;
  t = vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
  b = vec3(c, s + n.y * n.y * a, -n.y);
}

vec3 to_world(vec3 v, vec3 n) {
  vec3 t, b;
  make_basis(n, t, b);
  return v.x * t + v.y * b + v.z * n;
}

vec3 to_local(vec3 v, vec3 n) {
  vec3 t, b;
  make_basis(n, t, b);
  return vec3(dot(v, t), dot(v, b), dot(v, n));
}

// Cosine-weighted hemisphere around +z (Malley's method); pdf = cos / pi.
vec3 sample_cosine(vec2 u) {
  float r = sqrt(u.x), phi = 2.0 * PI * u.y;
  return vec3(r * cos(phi), r * sin(phi), sqrt(max(0.0, 1.0 - u.x)));
}

// Uniform point on a triangle: barycentrics (b1, b2) of the second and third vertex
// (pbrt-v4, SampleUniformTriangle's square-root mapping).
vec2 sample_triangle(vec2 u) {
  float su = sqrt(u.x);
  return vec2(su * (1.0 - u.y), su * u.y);
}

// Offsets a ray origin off a surface along the geometric normal by a few ulps of the
// position (Waechter and Binder 2019, "A Fast and Robust Method for Avoiding
// Self-Intersection", Ray Tracing Gems ch. 6): scale-independent, so it holds from
// millimetre scenes to scenes far from the origin.
vec3 offset_ray(vec3 p, vec3 n) {
  const float origin = 1.0 / 32.0, float_scale = 1.0 / 65536.0, int_scale = 256.0;
  ivec3 of_i = ivec3(int_scale * n);
  vec3 p_i = vec3(intBitsToFloat(floatBitsToInt(p.x) + (p.x < 0.0 ? -of_i.x : of_i.x)),
                  intBitsToFloat(floatBitsToInt(p.y) + (p.y < 0.0 ? -of_i.y : of_i.y)),
                  intBitsToFloat(floatBitsToInt(p.z) + (p.z < 0.0 ? -of_i.z : of_i.z)));
  return vec3(abs(p.x) < origin ? p.x + float_scale * n.x : p_i.x,
              abs(p.y) < origin ? p.y + float_scale * n.y : p_i.y,
              abs(p.z) < origin ? p.z + float_scale * n.z : p_i.z);
}

float luminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

#endif
