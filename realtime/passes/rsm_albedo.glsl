// The diffuse reflectance of a surface for one-bounce diffuse GI (passes/rsm.frag for the VPLs,
// the gathers and lookups of `rsm` and `lpv` for the receivers): the diffuse lobe of
// shaders/brdf.glsl with the dielectric Fresnel term at normal incidence (brdf_parts weights
// Lambert by 1 - max(F_d) at the half vector; for light arriving from the whole hemisphere the
// normal-incidence value is its first-order stand-in). Metals reflect no diffuse light.
// Needs brdf.glsl.
#ifndef GIQ_RSM_ALBEDO_GLSL
#define GIQ_RSM_ALBEDO_GLSL

vec3 diffuse_albedo(Surface s) {
#ifdef GIQ_SPECULAR
  vec3 f0 = dielectric_f0(s);
  return (1.0 - s.metallic) * (1.0 - max(f0.r, max(f0.g, f0.b))) * s.base_color;
#else
  return (1.0 - s.metallic) * s.base_color;
#endif
}

#endif
