#version 460
// `pt`: progressive path tracer with the reference's light transport: next-event estimation
// towards emissive triangles (chosen by power, sampled uniformly by area, solid-angle pdf)
// combined with BRDF sampling by the power heuristic (Veach 1997, section 9.2.4), every
// punctual light sampled at every vertex, the environment (constant or a map) found by BRDF sampling,
// Russian roulette after the third bounce. Samples accumulate across frames; the outputs are
// the running means: direct (emission seen directly plus light reaching the first surface
// after one reflection), indirect (the rest), their sum, and the variance of the mean.
#extension GL_GOOGLE_include_directive : require

#include "shaders/bvh.glsl"
#include "shaders/brdf.glsl"
#include "shaders/surface.glsl"
#include "shaders/camera.glsl"
#include "shaders/lights.glsl"
#include "shaders/environment.glsl"
#include "pt_shared.h"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = GIQ_SCENE_BINDING_COUNT + 0, rgba32f) uniform image2D accum_direct;
layout(binding = GIQ_SCENE_BINDING_COUNT + 1, rgba32f) uniform image2D accum_indirect;
layout(binding = GIQ_SCENE_BINDING_COUNT + 2, rgba32f) uniform image2D accum_square;
layout(binding = GIQ_SCENE_BINDING_COUNT + 3, rgba32f) uniform writeonly image2D out_beauty;
layout(binding = GIQ_SCENE_BINDING_COUNT + 4, rgba32f) uniform writeonly image2D out_direct;
layout(binding = GIQ_SCENE_BINDING_COUNT + 5, rgba32f) uniform writeonly image2D out_indirect;
layout(binding = GIQ_SCENE_BINDING_COUNT + 6, rgba32f) uniform writeonly image2D out_variance;

layout(push_constant) uniform Push { PtPush pc; };

float power_heuristic(float a, float b) {
  float a2 = a * a, b2 = b * b;
  return a2 + b2 > 0.0 ? a2 / (a2 + b2) : 0.0;
}

// Emitted radiance of a triangle at barycentrics (b1, b2) seen from direction -w (w travels
// towards the surface); with its emissive texture where the scene has textures.
vec3 emitted(uint tri, float b1, float b2, vec3 w) {
  GpuTriangle t = scene_triangles[tri];
  GpuMaterial m = scene_materials[t.v.w];
  if (m.emissive.w == 0.0) return vec3(0.0);
  vec3 a, b, c;
  triangle_vertices(tri, a, b, c);
  vec3 ng = cross(b - a, c - a);
  if (dot(ng, w) >= 0.0 && m.params.w == 0.0) return vec3(0.0);  // one-sided: front only
  return emission_at(m, tri, b1, b2);
}

// Solid-angle pdf with which NEE would pick direction w from p to hit `tri` at distance t.
float light_pdf(uint tri, vec3 w, float t) {
  uint e = scene_triangles[tri].extra.x;
  if (e == 0u) return 0.0;
  GpuEmissive em = scene_emissive[e - 1u];
  vec3 a, b, c;
  triangle_vertices(tri, a, b, c);
  vec3 ng = normalize(cross(b - a, c - a));
  float cos_l = abs(dot(ng, w));
  if (cos_l <= 0.0) return 0.0;
  return em.sampling.y * t * t / (cos_l * em.radiance.w);
}

uint pick_emissive(float u) {
  // First entry whose CDF exceeds u (binary search).
  uint lo = 0u, hi = pc.emissive_count - 1u;
  while (lo < hi) {
    uint mid = (lo + hi) / 2u;
    if (scene_emissive[mid].sampling.x > u) hi = mid; else lo = mid + 1u;
  }
  return lo;
}

struct PathResult { vec3 direct; vec3 indirect; };

PathResult trace_path(vec3 org, vec3 dir, inout Rng rng) {
  PathResult res;
  res.direct = vec3(0.0);
  res.indirect = vec3(0.0);
  vec3 throughput = vec3(1.0);
  float prev_pdf = 0.0;     // solid-angle pdf of the BRDF sample that produced `dir`
  for (uint depth = 0u; depth <= pc.max_bounces; ++depth) {
    // `depth` surfaces were hit before this ray; light found now belongs to `direct` when it
    // reaches the camera directly (depth 0) or after one reflection (depth 1).
    RayHit hit = trace_ray(org, dir, 1e30, false, depth == 0u);
    if (hit.triangle == 0xffffffffu) {
#ifdef GIQ_ENVIRONMENT
      vec3 env = throughput * environment_radiance(pc.environment, dir);
      if (depth <= 1u) res.direct += env; else res.indirect += env;
#endif
      break;
    }
    vec3 a, b, c;
    triangle_vertices(hit.triangle, a, b, c);
    vec3 p = a + hit.u * (b - a) + hit.v * (c - a);

    // Emission, weighted against NEE when a BRDF sample found it.
    vec3 le = emitted(hit.triangle, hit.u, hit.v, dir);
    if (any(greaterThan(le, vec3(0.0)))) {
      float w = 1.0;
      if (depth > 0u && pc.emissive_count > 0u) w = power_heuristic(prev_pdf, light_pdf(hit.triangle, dir, hit.t));
      vec3 contrib = throughput * le * w;
      if (depth <= 1u) res.direct += contrib; else res.indirect += contrib;
    }
    if (depth == pc.max_bounces) break;
    // Normals and material as the reference's make_surface: the back of a one-sided
    // material is black (it absorbs), shading normals are interpolated, normal-mapped and
    // kept above the viewer's horizon; textures scale the material's factors.
    HitNormals hn = hit_normals(hit.triangle, hit.u, hit.v, dir);
    if (hn.black) break;
    vec3 ng = hn.ng, ns = hn.ns;
    Surface s = hit_material(hit.triangle, hit.u, hit.v, ns);
    vec3 wo = -dir;
    vec3 p_off = offset_ray(p, ng);
    // Light arriving at this vertex (depth + 1 surfaces before the camera sees it).
    vec3 nee = vec3(0.0);

#if defined(GIQ_POINT_LIGHTS) || defined(GIQ_SPOT_LIGHTS) || defined(GIQ_DIRECTIONAL_LIGHTS)
    for (uint i = 0u; i < pc.light_count; ++i) {
      vec3 wi;
      float dist;
      vec3 e = punctual_incident(scene_lights[i], p, wi, dist);
      // Light below the geometric horizon would leak through the surface.
      if (dot(wi, ng) <= 0.0 || all(equal(e, vec3(0.0)))) continue;
      vec3 f = brdf_eval(s, wo, wi);
      if (all(equal(f, vec3(0.0)))) continue;
      if (occluded(p_off, wi, dist < 1e30 ? dist * (1.0 - 1e-4) : 1e30)) continue;
      nee += f * e * dot(ns, wi);
    }
#endif
#ifdef GIQ_EMISSIVE_MESHES
    if (pc.emissive_count > 0u) {
      GpuEmissive em = scene_emissive[pick_emissive(rng_next(rng))];
      vec3 la, lb, lc;
      triangle_vertices(em.triangle.x, la, lb, lc);
      vec2 bc = sample_triangle(vec2(rng_next(rng), rng_next(rng)));
      vec3 q = la + bc.x * (lb - la) + bc.y * (lc - la);
      vec3 d = q - p;
      float dist2 = dot(d, d);
      float dist = sqrt(dist2);
      vec3 wi = d / dist;
      vec3 lng = normalize(cross(lb - la, lc - la));
      float cos_l = abs(dot(lng, wi));
      vec3 le2 = emitted(em.triangle.x, bc.x, bc.y, wi);
#ifdef GIQ_ALPHA_MASK
      // A ray that found this point would have met it with probability equal to its
      // coverage (the reference's LightSampler::sample).
      le2 *= alpha_coverage(em.triangle.x, bc.x, bc.y);
#endif
      if (dot(wi, ng) > 0.0 && cos_l > 0.0 && any(greaterThan(le2, vec3(0.0)))) {
        vec3 f = brdf_eval(s, wo, wi);
        if (any(greaterThan(f, vec3(0.0))) && !occluded(p_off, wi, dist * (1.0 - 1e-4))) {
          float pdf_light = em.sampling.y * dist2 / (cos_l * em.radiance.w);
          float w = power_heuristic(pdf_light, brdf_pdf(s, wo, wi));
          nee += f * le2 * dot(ns, wi) * w / pdf_light;
        }
      }
    }
#endif
    if (depth == 0u) res.direct += throughput * nee; else res.indirect += throughput * nee;

    // Continue by BRDF sampling.
    vec3 wi;
    if (!brdf_sample(s, wo, vec3(rng_next(rng), rng_next(rng), rng_next(rng)), wi)) break;
    if (dot(wi, ng) <= 0.0) break;  // below the geometric surface: would leak
    float pdf = brdf_pdf(s, wo, wi);
    if (!(pdf > 0.0)) break;
    throughput *= brdf_eval(s, wo, wi) * dot(ns, wi) / pdf;
    prev_pdf = pdf;
    // Russian roulette after the third bounce, unbiased: survivors are divided by the
    // survival probability, twice the throughput's largest component as in the reference
    // (reference/src/path_integrator.h, kRouletteScale, explains the factor).
    if (depth >= 3u) {
      float q = clamp(2.0 * max(throughput.r, max(throughput.g, throughput.b)), 0.05, 1.0);
      if (rng_next(rng) >= q) break;
      throughput /= q;
    }
    if (!all(lessThan(abs(throughput), vec3(1e30)))) break;
    org = p_off;
    dir = wi;
  }
  return res;
}

void main() {
  uvec2 px = gl_GlobalInvocationID.xy;
  if (px.x >= pc.width || px.y >= pc.height) return;
  ivec2 ip = ivec2(px);
  vec4 sum_d = pc.first_sample == 0u ? vec4(0.0) : imageLoad(accum_direct, ip);
  vec4 sum_i = pc.first_sample == 0u ? vec4(0.0) : imageLoad(accum_indirect, ip);
  vec4 sum_sq = pc.first_sample == 0u ? vec4(0.0) : imageLoad(accum_square, ip);
  vec2 size = vec2(pc.width, pc.height);
  for (uint k = 0u; k < pc.samples_per_frame; ++k) {
    uint sample_index = pc.first_sample + k;
    Rng rng = rng_init(px, sample_index, pc.seed);
    // A uniformly jittered position in the pixel: the box filter of the reference.
    vec2 pixel = vec2(px) + vec2(rng_next(rng), rng_next(rng));
    vec3 dir = camera_ray_direction(pc.camera, pixel, size);
    PathResult r = trace_path(camera_ray_origin(pc.camera, pixel, size), dir, rng);
    // A non-finite sample would poison the running mean forever; it can only come from a
    // degenerate configuration, and is dropped (counted as black).
    if (!all(lessThan(abs(r.direct + r.indirect), vec3(3.0e38)))) { r.direct = vec3(0.0); r.indirect = vec3(0.0); }
    sum_d.rgb += r.direct;
    sum_i.rgb += r.indirect;
    vec3 beauty = r.direct + r.indirect;
    sum_sq.rgb += beauty * beauty;
  }
  imageStore(accum_direct, ip, sum_d);
  imageStore(accum_indirect, ip, sum_i);
  imageStore(accum_square, ip, sum_sq);
  float n = float(pc.first_sample + pc.samples_per_frame);
  vec3 mean_d = sum_d.rgb / n, mean_i = sum_i.rgb / n, mean = mean_d + mean_i;
  // Variance of the mean: the unbiased sample variance over n.
  vec3 var = n > 1.0 ? max(sum_sq.rgb / n - mean * mean, vec3(0.0)) * n / (n - 1.0) / n : vec3(0.0);
  imageStore(out_beauty, ip, vec4(mean, 1.0));
  imageStore(out_direct, ip, vec4(mean_d, 1.0));
  imageStore(out_indirect, ip, vec4(mean_i, 1.0));
  imageStore(out_variance, ip, vec4(var, 1.0));
}
