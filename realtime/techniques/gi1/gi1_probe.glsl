// A screen probe of `gi1` (Boissé et al. 2022, section 2.1): an 8x8 map of the hemisphere
// around the probe's normal, the cells' directions and solid angles, the probe's spherical
// harmonics and the adaptive cell size. Needs shaders/sampling.glsl and gi1_shared.h.
#ifndef GIQ_GI1_PROBE_GLSL
#define GIQ_GI1_PROBE_GLSL

// The hemisphere z >= 0 folded onto the square [-1, 1]^2: the octahedral map's upper half
// (shaders/octahedral.glsl, Cigolle et al. 2014), the diamond |x| + |y| <= 1 turned by 45
// degrees to fill the square, so that all 64 cells of a probe see the hemisphere.
vec2 hemi_oct_encode(vec3 d) {
  vec2 p = d.xy / (abs(d.x) + abs(d.y) + max(d.z, 0.0));
  return vec2(p.x + p.y, p.x - p.y);
}

vec3 hemi_oct_decode(vec2 e) {
  vec2 p = 0.5 * vec2(e.x + e.y, e.x - e.y);
  return normalize(vec3(p, max(0.0, 1.0 - abs(p.x) - abs(p.y))));
}

// The probe-local direction through point u in [0, 1)^2 of cell c (row-major, 8 per row).
vec3 gi1_cell_direction(uint c, vec2 u) {
  vec2 e = (vec2(c % GIQ_GI1_PROBE, c / GIQ_GI1_PROBE) + u) * (2.0 / float(GIQ_GI1_PROBE)) - 1.0;
  return hemi_oct_decode(e);
}

uint gi1_direction_cell(vec3 local) {
  uvec2 t = uvec2(clamp((hemi_oct_encode(local) * 0.5 + 0.5) * float(GIQ_GI1_PROBE), vec2(0.0),
                        vec2(float(GIQ_GI1_PROBE) - 0.5)));
  return t.x + t.y * GIQ_GI1_PROBE;
}

// Real spherical harmonics of bands 0 to 2 at unit direction d (Sloan 2008, "Stupid
// Spherical Harmonics Tricks", appendix 2), in the order gi1.cpp's projection table has them.
void gi1_sh_basis(vec3 d, out float y[GIQ_GI1_SH]) {
  y[0] = 0.28209479;
  y[1] = 0.48860251 * d.y;
  y[2] = 0.48860251 * d.z;
  y[3] = 0.48860251 * d.x;
  y[4] = 1.09254843 * d.x * d.y;
  y[5] = 1.09254843 * d.y * d.z;
  y[6] = 0.31539157 * (3.0 * d.z * d.z - 1.0);
  y[7] = 1.09254843 * d.x * d.z;
  y[8] = 0.54627421 * (d.x * d.x - d.y * d.y);
}

// Irradiance at probe-local normal n from the probe's radiance coefficients: the clamped
// cosine's coefficients pi, 2 pi / 3 and pi / 4 per band (Ramamoorthi and Hanrahan 2001, "An
// Efficient Representation for Irradiance Environment Maps"). Radiance that lies in the
// probe's hemisphere only has no band-2 part along the normal, so for n = the probe's normal
// bands 0 to 2 give the exact cosine integral (docs/techniques/gi1.md).
//
// With the near field (section 3.1), the cosine lobe is cut to the cone about n (the bent
// normal) that holds the `visible` share of it: a cone of half-angle a holds sin^2 a of the
// lobe, and band l's coefficient is 2 pi times the integral of mu P_l(mu) from cos a to 1:
// pi sin^2 a, 2 pi / 3 (1 - cos^3 a), pi (1/4 + cos^2 a / 2 - 3 cos^4 a / 4). visible = 1 gives
// the whole lobe's, bit for bit.
vec3 gi1_sh_irradiance(vec4 sh[GIQ_GI1_SH], vec3 n, float visible) {
  float y[GIQ_GI1_SH];
  gi1_sh_basis(n, y);
  float c2 = 1.0 - visible, c = sqrt(c2);
  float a[3] = float[3](PI * visible, 2.0 * PI / 3.0 * (1.0 - c2 * c), PI * (0.25 + 0.5 * c2 - 0.75 * c2 * c2));
  vec3 e = a[0] * y[0] * sh[0].rgb;
  for (uint k = 1u; k < 4u; ++k) e += a[1] * y[k] * sh[k].rgb;
  for (uint k = 4u; k < GIQ_GI1_SH; ++k) e += a[2] * y[k] * sh[k].rgb;
  return max(e, vec3(0.0));
}

// The view depth of a point: its distance along the camera's forward axis.
float gi1_view_depth(GpuCamera cam, vec3 p) { return dot(p - cam.position.xyz, cam.forward.xyz); }

// The size of a pixel at distance `view_depth` along the view.
float gi1_pixel_size(GpuGi1Frame f, float view_depth) { return f.pixel.x * view_depth + f.pixel.y; }

// The screen cache's cell size at a point (Algorithm 6): the world size of the 8 pixels
// between neighbouring probes there. How far probes may be from each other's planes and
// still share radiance.
float gi1_screen_cell(GpuGi1Frame f, float view_depth) { return float(GIQ_GI1_PROBE) * gi1_pixel_size(f, view_depth); }

// The seed of random stream `stream` (each pass its own) for the technique's `seed`; the
// frame enters each stream as its sample index.
uint gi1_stream(GpuGi1Frame f, uint stream) { return pcg_hash(f.jitter.w ^ (stream * 0x9e3779b9u)); }

// Whether last frame's pixel, which showed a surface at view depth `seen` (< 0: none), showed
// the point whose depth in the previous view is `expected`: the two within `cells` screen
// cells there. The disocclusion test of the reprojection, the feedback and the denoiser.
bool gi1_seen_last_frame(GpuGi1Frame f, float seen, float expected, float cells) {
  return seen >= 0.0 && abs(seen - expected) <= cells * gi1_screen_cell(f, expected);
}

uint gi1_pack_pixel(uvec2 p) { return p.x | (p.y << 16); }
uvec2 gi1_unpack_pixel(uint v) { return uvec2(v & 0xffffu, v >> 16); }

#endif
