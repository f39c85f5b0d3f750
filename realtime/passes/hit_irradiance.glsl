// The irradiance the light sources send onto a surface point that a probe's or a cache's ray
// found (off screen, so the frame's shadow maps do not cover it): punctual lights exactly,
// emissive meshes by the exact polygon irradiance of each triangle (shaders/
// polygon_irradiance.glsl) or, for glowing particles, particle by particle, each light
// shadowed by one BVH ray (towards an area light's representative point). Written once for
// `ddgi`'s probe rays and `gi1`'s cache rays.
// The includer declares the frame's area lights as `area_lights[]` and their triangles as
// `area_triangles[]` (passes/direct_light.h); needs shaders/scene.glsl, bvh.glsl, lights.glsl,
// sampling.glsl, octahedron_irradiance.glsl, passes/direct_light_shared.h and
// passes/area_light_parts.glsl.
#ifndef GIQ_HIT_IRRADIANCE_GLSL
#define GIQ_HIT_IRRADIANCE_GLSL

// Diffuse irradiance of area light l at p (normal n): each triangle exactly, or each particle
// of a stage of them (shaders/octahedron_irradiance.glsl), unshadowed.
vec3 area_irradiance(GpuAreaLight l, vec3 p, vec3 n) {
  vec3 e = vec3(0.0);
  for (uint k = 0u; k < lit_particles(l); ++k) {
    GpuParticleLight q = stage_particle(l, k);
    e += q.radiance.rgb * octahedron_irradiance(q.centre.xyz - p, q.centre.w, n);
  }
  uint triangles = lit_triangles(l);
  for (uint k = 0u; k < triangles; ++k) {
    GpuAreaTriangle t = area_triangle(l, k);
    vec3 a = t.a.xyz - p, b = t.b.xyz - p, c = t.c.xyz - p;
    // A one-sided emitter lights only the half-space in front of it.
    if (t.a.w == 0.0 && dot(cross(b - a, c - a), -a) <= 0.0) continue;
    e += t.radiance.rgb * polygon_irradiance(a, b, c, n);
  }
  return e;
}

// Irradiance from the light sources at p (geometric normal ng, shading normal ns), shadowed;
// light_count punctual lights, area_light_count emissive meshes.
vec3 hit_irradiance(vec3 p, vec3 ng, vec3 ns, uint light_count, uint area_light_count) {
  vec3 origin = offset_ray(p, ng);
  vec3 e = vec3(0.0);
  for (uint i = 0u; i < light_count; ++i) {
    vec3 wi;
    float dist;
    vec3 li = punctual_incident(scene_lights[i], p, wi, dist);
    float cos_i = dot(ns, wi);
    if (cos_i <= 0.0 || dot(ng, wi) <= 0.0 || all(equal(li, vec3(0.0)))) continue;
    if (occluded(origin, wi, dist < 1e30 ? dist * (1.0 - 1e-4) : 1e30)) continue;
    e += li * cos_i;
  }
  for (uint i = 0u; i < area_light_count; ++i) {
    GpuAreaLight l = area_lights[i];
    vec3 el = area_irradiance(l, p, ns);
    if (all(equal(el, vec3(0.0)))) continue;
    vec3 to = l.position.xyz - p;
    float dist = length(to);
    // Stop short of the emitter so that its own triangles do not shadow it (of a closed
    // emitter, whose representative point is inside it, at the sphere that holds it).
    float reach = (dist - l.extent.x) * 0.999;
    if (reach > 0.0 && occluded(origin, to / dist, reach)) continue;
    e += el;
  }
  return e;
}

#endif
