// Paths with the reference's light transport, written once for `pt` (from the camera) and
// `hybrid` (from the G-buffer's first hit): next-event estimation towards emissive triangles
// (chosen by power, sampled uniformly by area, solid-angle pdf) combined with BRDF sampling
// by the power heuristic (Veach 1997, section 9.2.4), the environment (constant or a map)
// found by BRDF sampling, Russian roulette after the third bounce. Light is split as the
// reference splits it: `direct` is emission seen directly plus light reaching the first
// surface after one reflection, `indirect` the rest.
//
// Next-event estimation at a vertex samples every punctual light and one emissive triangle
// (`pt`, as the reference does), or, with GIQ_ONE_LIGHT, one light source chosen uniformly
// among the punctual lights and the emissive meshes taken as one source (`hybrid`: one shadow
// ray per vertex, Kim-Chan 2022, section 3.1); the choice's probability enters both the
// estimate and the MIS weights, so both estimators are unbiased.
//
// Needs shaders/bvh.glsl, brdf.glsl, surface.glsl, lights.glsl and environment.glsl.
#ifndef GIQ_PATH_GLSL
#define GIQ_PATH_GLSL

struct PathParams {
  vec4 environment;     // constant environment radiance (rgb), w its map's texture or -1
  uint max_bounces;     // surface interactions after the camera ray
  uint light_count;     // punctual lights
  uint emissive_count;  // emissive triangles
};

struct PathState {
  vec3 throughput;
  float prev_pdf;  // solid-angle pdf of the BRDF sample that produced the current ray
  vec3 direct;
  vec3 indirect;
};

PathState path_start() {
  PathState st;
  st.throughput = vec3(1.0);
  st.prev_pdf = 0.0;
  st.direct = vec3(0.0);
  st.indirect = vec3(0.0);
  return st;
}

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

// Probability that next-event estimation samples the emissive meshes at a vertex.
float emissive_choice(PathParams pp) {
#ifdef GIQ_ONE_LIGHT
  return 1.0 / float(pp.light_count + 1u);
#else
  return 1.0;
#endif
}

// Solid-angle pdf with which next-event estimation picks direction w from p to hit `tri` at
// distance t.
float light_pdf(PathParams pp, uint tri, vec3 w, float t) {
  uint e = scene_triangles[tri].extra.x;
  if (e == 0u) return 0.0;
  GpuEmissive em = scene_emissive[e - 1u];
  vec3 a, b, c;
  triangle_vertices(tri, a, b, c);
  vec3 ng = normalize(cross(b - a, c - a));
  float cos_l = abs(dot(ng, w));
  if (cos_l <= 0.0) return 0.0;
  return emissive_choice(pp) * em.sampling.y * t * t / (cos_l * em.radiance.w);
}

uint pick_emissive(PathParams pp, float u) {
  // First entry whose CDF exceeds u (binary search).
  uint lo = 0u, hi = pp.emissive_count - 1u;
  while (lo < hi) {
    uint mid = (lo + hi) / 2u;
    if (scene_emissive[mid].sampling.x > u) hi = mid; else lo = mid + 1u;
  }
  return lo;
}

// Light of punctual light i arriving at p, shadow-tested (0 below the geometric horizon).
vec3 punctual_light(uint i, vec3 p, vec3 p_off, vec3 ng, vec3 ns, Surface s, vec3 wo) {
  vec3 wi;
  float dist;
  vec3 e = punctual_incident(scene_lights[i], p, wi, dist);
  // Light below the geometric horizon would leak through the surface.
  if (dot(wi, ng) <= 0.0 || all(equal(e, vec3(0.0)))) return vec3(0.0);
  vec3 f = brdf_eval(s, wo, wi);
  if (all(equal(f, vec3(0.0)))) return vec3(0.0);
  if (occluded(p_off, wi, dist < 1e30 ? dist * (1.0 - 1e-4) : 1e30)) return vec3(0.0);
  return f * e * dot(ns, wi);
}

// One emissive triangle sampled by power and area, MIS-weighted against BRDF sampling;
// `choice` is the probability with which the emissive meshes were chosen.
vec3 emissive_light(PathParams pp, vec3 p, vec3 p_off, vec3 ng, vec3 ns, Surface s, vec3 wo, float choice,
                    inout Rng rng) {
  GpuEmissive em = scene_emissive[pick_emissive(pp, rng_next(rng))];
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
  vec3 le = emitted(em.triangle.x, bc.x, bc.y, wi);
#ifdef GIQ_ALPHA_MASK
  // A ray that found this point would have met it with probability equal to its coverage
  // (the reference's LightSampler::sample).
  le *= alpha_coverage(em.triangle.x, bc.x, bc.y);
#endif
  if (dot(wi, ng) <= 0.0 || cos_l <= 0.0 || !any(greaterThan(le, vec3(0.0)))) return vec3(0.0);
  vec3 f = brdf_eval(s, wo, wi);
  if (!any(greaterThan(f, vec3(0.0))) || occluded(p_off, wi, dist * (1.0 - 1e-4))) return vec3(0.0);
  float pdf_light = choice * em.sampling.y * dist2 / (cos_l * em.radiance.w);
  float w = power_heuristic(pdf_light, brdf_pdf(s, wo, wi));
  return f * le * dot(ns, wi) * w / pdf_light;
}

// Light arriving at surface point p straight from the light sources (next-event estimation),
// towards the viewer direction wo; p_off is p lifted off the surface for shadow rays.
vec3 next_event(PathParams pp, vec3 p, vec3 p_off, vec3 ng, vec3 ns, Surface s, vec3 wo, inout Rng rng) {
  vec3 nee = vec3(0.0);
#ifdef GIQ_ONE_LIGHT
  uint sources = pp.light_count + (pp.emissive_count > 0u ? 1u : 0u);
  if (sources == 0u) return nee;
  uint k = min(uint(rng_next(rng) * float(sources)), sources - 1u);
#if defined(GIQ_POINT_LIGHTS) || defined(GIQ_SPOT_LIGHTS) || defined(GIQ_DIRECTIONAL_LIGHTS)
  if (k < pp.light_count) return punctual_light(k, p, p_off, ng, ns, s, wo) * float(sources);
#endif
#ifdef GIQ_EMISSIVE_MESHES
  nee = emissive_light(pp, p, p_off, ng, ns, s, wo, emissive_choice(pp), rng);
#endif
#else
#if defined(GIQ_POINT_LIGHTS) || defined(GIQ_SPOT_LIGHTS) || defined(GIQ_DIRECTIONAL_LIGHTS)
  for (uint i = 0u; i < pp.light_count; ++i) nee += punctual_light(i, p, p_off, ng, ns, s, wo);
#endif
#ifdef GIQ_EMISSIVE_MESHES
  if (pp.emissive_count > 0u) nee += emissive_light(pp, p, p_off, ng, ns, s, wo, 1.0, rng);
#endif
#endif
  return nee;
}

// Light that reaches the camera after `surfaces` surfaces goes to `direct` up to one
// reflection, to `indirect` after more.
void path_add(inout PathState st, uint surfaces, vec3 c) {
  if (surfaces <= 1u) st.direct += c; else st.indirect += c;
}

// The BRDF-sampled continuation from a surface point, `depth` surfaces before it: the new
// direction in wi and the throughput updated; false when the path ends (below the horizon,
// or Russian roulette after the third bounce).
bool path_scatter(inout PathState st, uint depth, Surface s, vec3 wo, vec3 ng, vec3 ns, inout Rng rng, out vec3 wi) {
  if (!brdf_sample(s, wo, vec3(rng_next(rng), rng_next(rng), rng_next(rng)), wi)) return false;
  if (dot(wi, ng) <= 0.0) return false;  // below the geometric surface: would leak
  float pdf = brdf_pdf(s, wo, wi);
  if (!(pdf > 0.0)) return false;
  st.throughput *= brdf_eval(s, wo, wi) * dot(ns, wi) / pdf;
  st.prev_pdf = pdf;
  // Russian roulette after the third bounce, unbiased: survivors are divided by the survival
  // probability, twice the throughput's largest component as in the reference
  // (reference/src/path_integrator.h, kRouletteScale, explains the factor).
  if (depth >= 3u) {
    float q = clamp(2.0 * max(st.throughput.r, max(st.throughput.g, st.throughput.b)), 0.05, 1.0);
    if (rng_next(rng) >= q) return false;
    st.throughput /= q;
  }
  return all(lessThan(abs(st.throughput), vec3(1e30)));
}

// Follows the ray (org, dir) with `depth` surfaces behind it (0: a camera ray) to the end of
// its path, adding what it finds to st.
void path_trace(PathParams pp, inout PathState st, uint depth, vec3 org, vec3 dir, inout Rng rng) {
  for (; depth <= pp.max_bounces; ++depth) {
    RayHit hit = trace_ray(org, dir, 1e30, false, depth == 0u);
    if (hit.triangle == 0xffffffffu) {
#ifdef GIQ_ENVIRONMENT
      path_add(st, depth, st.throughput * environment_radiance(pp.environment, dir));
#endif
      break;
    }
    vec3 a, b, c;
    triangle_vertices(hit.triangle, a, b, c);
    vec3 p = a + hit.u * (b - a) + hit.v * (c - a);

    // Emission, weighted against next-event estimation when a BRDF sample found it.
    vec3 le = emitted(hit.triangle, hit.u, hit.v, dir);
    if (any(greaterThan(le, vec3(0.0)))) {
      float w = 1.0;
      if (depth > 0u && pp.emissive_count > 0u) w = power_heuristic(st.prev_pdf, light_pdf(pp, hit.triangle, dir, hit.t));
      path_add(st, depth, st.throughput * le * w);
    }
    if (depth == pp.max_bounces) break;
    // Normals and material as the reference's make_surface: the back of a one-sided material
    // is black (it absorbs), shading normals are interpolated, normal-mapped and kept above
    // the viewer's horizon; textures scale the material's factors.
    HitNormals hn = hit_normals(hit.triangle, hit.u, hit.v, dir);
    if (hn.black) break;
    Surface s = hit_material(hit.triangle, hit.u, hit.v, hn.ns);
    vec3 wo = -dir;
    vec3 p_off = offset_ray(p, hn.ng);
    path_add(st, depth + 1u, st.throughput * next_event(pp, p, p_off, hn.ng, hn.ns, s, wo, rng));
    vec3 wi;
    if (!path_scatter(st, depth, s, wo, hn.ng, hn.ns, rng, wi)) break;
    org = p_off;
    dir = wi;
  }
}

#endif
