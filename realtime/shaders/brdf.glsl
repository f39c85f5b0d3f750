// The glTF 2.0 metallic-roughness BRDF with KHR_materials_specular, as the reference renders
// it (reference/include/giq/reference/bsdf.h): Lambert diffuse and GGX specular
// (Trowbridge-Reitz D, Smith height-correlated masking-shadowing, Schlick Fresnel), combined
// as glTF 2.0 Appendix B with KHR_materials_specular's albedo scaling:
//   dielectric = (1 - max(F_d)) diffuse + F_d specular,  F_d = Schlick(min(0.04 specular_color, 1) * specular, specular)
//   metal      = Schlick(base_color, 1) specular
//   brdf       = (1 - metallic) dielectric + metallic metal
// Without GIQ_SPECULAR (no material in the scene has a GGX lobe) only Lambert is compiled.
#ifndef GIQ_BRDF_GLSL
#define GIQ_BRDF_GLSL

#include "sampling.glsl"

struct Surface {
  vec3 n;         // unit shading normal, on the side the ray came from
  vec3 base_color;
  float metallic;
  float alpha;    // GGX alpha = roughness^2
  float specular; // KHR_materials_specular factor (0: no specular layer)
  vec3 specular_color;
};

Surface make_surface(GpuMaterial m, vec3 n) {
  Surface s;
  s.n = n;
  s.base_color = m.base_color.rgb;
  s.metallic = clamp(m.params.x, 0.0, 1.0);
  // alpha is bounded below so that D stays finite in float for a perfect mirror.
  s.alpha = max(m.params.y * m.params.y, 1e-3);
  s.specular = m.params.z;
  s.specular_color = m.specular_color.rgb;
  return s;
}

#ifdef GIQ_SPECULAR
vec3 schlick(vec3 f0, vec3 f90, float cos_theta) {
  float m = clamp(1.0 - cos_theta, 0.0, 1.0);
  float m2 = m * m;
  return f0 + (f90 - f0) * (m2 * m2 * m);
}

float ggx_d(float nh, float a2) {
  float d = nh * nh * (a2 - 1.0) + 1.0;
  return a2 / (PI * d * d);
}

// Smith height-correlated visibility V = G2 / (4 nl nv) (Heitz 2014, "Understanding the
// Masking-Shadowing Function in Microfacet-Based BRDFs", eq. 99).
float smith_v(float nl, float nv, float a2) {
  float gv = nl * sqrt(nv * nv * (1.0 - a2) + a2);
  float gl = nv * sqrt(nl * nl * (1.0 - a2) + a2);
  return 0.5 / (gv + gl);
}

float smith_g1(float nv, float a2) { return 2.0 * nv / (nv + sqrt(a2 + (1.0 - a2) * nv * nv)); }

vec3 dielectric_f0(Surface s) { return min(0.04 * s.specular_color, vec3(1.0)) * s.specular; }
#endif

// f(wo, wi) without the cosine, split into its diffuse and specular parts (both zero below
// the shading horizon); brdf_eval is their sum.
void brdf_parts(Surface s, vec3 wo, vec3 wi, out vec3 diffuse, out vec3 specular) {
  diffuse = vec3(0.0);
  specular = vec3(0.0);
  float nl = dot(s.n, wi), nv = dot(s.n, wo);
  if (nl <= 0.0 || nv <= 0.0) return;
  vec3 lambert = s.base_color / PI;
#ifdef GIQ_SPECULAR
  vec3 h = normalize(wo + wi);
  float vh = max(dot(wo, h), 0.0), nh = max(dot(s.n, h), 0.0);
  float a2 = s.alpha * s.alpha;
  float spec = ggx_d(nh, a2) * smith_v(nl, nv, a2);
  vec3 fd = schlick(dielectric_f0(s), vec3(s.specular), vh);
  vec3 fm = schlick(s.base_color, vec3(1.0), vh);
  // (1 - m) ((1 - max(fd)) lambert + fd spec) + m fm spec, regrouped by lobe.
  diffuse = (1.0 - s.metallic) * (1.0 - max(fd.r, max(fd.g, fd.b))) * lambert;
  specular = ((1.0 - s.metallic) * fd + s.metallic * fm) * spec;
#else
  diffuse = (1.0 - s.metallic) * lambert;
#endif
}

vec3 brdf_eval(Surface s, vec3 wo, vec3 wi) {
  vec3 d, sp;
  brdf_parts(s, wo, wi, d, sp);
  return d + sp;
}

#ifdef GIQ_SPECULAR
// Probability of sampling the GGX lobe: its share of the Fresnel-weighted albedo at normal
// incidence of the view, bounded away from 0 and 1 so both lobes stay reachable.
float specular_probability(Surface s, float nv) {
  vec3 fd = schlick(dielectric_f0(s), vec3(s.specular), nv);
  vec3 fm = schlick(s.base_color, vec3(1.0), nv);
  float spec = luminance(mix(fd, fm, s.metallic));
  float diff = luminance(s.base_color * (1.0 - s.metallic) * (1.0 - max(fd.r, max(fd.g, fd.b))));
  if (spec <= 0.0) return 0.0;
  if (diff <= 0.0) return 1.0;
  return clamp(spec / (spec + diff), 0.1, 0.9);
}
#endif

// Solid-angle pdf of brdf_sample for direction wi.
float brdf_pdf(Surface s, vec3 wo, vec3 wi) {
  float nl = dot(s.n, wi), nv = dot(s.n, wo);
  if (nl <= 0.0 || nv <= 0.0) return 0.0;
  float p_diffuse = nl / PI;
#ifdef GIQ_SPECULAR
  float ps = specular_probability(s, nv);
  vec3 h = normalize(wo + wi);
  float a2 = s.alpha * s.alpha;
  // Visible-normal pdf: G1(wo) D(h) / (4 nv) (Heitz 2018, "Sampling the GGX Distribution of
  // Visible Normals", JCGT 7(4), eq. 17 with the reflection Jacobian 1 / (4 wo.h)).
  float p_spec = smith_g1(nv, a2) * ggx_d(max(dot(s.n, h), 0.0), a2) / (4.0 * nv);
  return mix(p_diffuse, p_spec, ps);
#else
  return p_diffuse;
#endif
}

// Samples wi; returns false when the sample falls below the horizon.
bool brdf_sample(Surface s, vec3 wo, vec3 u, out vec3 wi) {
#ifdef GIQ_SPECULAR
  float nv = dot(s.n, wo);
  if (u.z < specular_probability(s, nv)) {
    // Heitz 2018, listing 1: stretch, sample the projected hemisphere, unstretch.
    vec3 v = to_local(wo, s.n);
    vec3 vh = normalize(vec3(s.alpha * v.x, s.alpha * v.y, v.z));
    float lensq = vh.x * vh.x + vh.y * vh.y;
    vec3 t1 = lensq > 0.0 ? vec3(-vh.y, vh.x, 0.0) * inversesqrt(lensq) : vec3(1.0, 0.0, 0.0);
    vec3 t2 = cross(vh, t1);
    float r = sqrt(u.x), phi = 2.0 * PI * u.y;
    float p1 = r * cos(phi), p2 = r * sin(phi);
    float sh = 0.5 * (1.0 + vh.z);
    p2 = (1.0 - sh) * sqrt(max(0.0, 1.0 - p1 * p1)) + sh * p2;
    vec3 nh = p1 * t1 + p2 * t2 + sqrt(max(0.0, 1.0 - p1 * p1 - p2 * p2)) * vh;
    vec3 m = normalize(vec3(s.alpha * nh.x, s.alpha * nh.y, max(0.0, nh.z)));
    wi = reflect(-wo, to_world(m, s.n));
    return dot(wi, s.n) > 0.0;
  }
#endif
  wi = to_world(sample_cosine(u.xy), s.n);
  return dot(wi, s.n) > 0.0;
}

#endif
