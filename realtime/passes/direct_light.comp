#version 460
// The shared direct-lighting pass: for each G-buffer texel, emission seen directly plus light
// arriving straight from the light sources, each attenuated by its shadow map; no indirect
// light. Every technique's `direct` layer comes from here.
// Punctual lights are evaluated exactly (glTF units and falloff). Emissive meshes are area
// lights: the diffuse part integrates each emissive triangle exactly
// (shaders/polygon_irradiance.glsl), the specular part uses a representative point with
// energy normalisation (Karis 2013, "Real Shading in Unreal Engine 4"; Turánszki 2017, "Area
// Lights"): of the declared shape (sphere, disc, rectangle, tube) when the mesh declares one,
// else of each triangle, the point closest to the reflection ray. A glowing particle is one
// light (shaders/octahedron_irradiance.glsl), a small sphere for the specular part. An area
// light is shadowed by its cube shadow map from the representative point (hard shadows) or,
// with area_shadow_rays, by rays to points on it (soft shadows: area_visibility).
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_vote : require

#include "shaders/scene.glsl"
#include "shaders/bvh.glsl"
#include "shaders/brdf.glsl"
#include "shaders/surface.glsl"
#include "shaders/camera.glsl"
#include "shaders/lights.glsl"
#include "shaders/closest_point.glsl"
#include "shaders/polygon_irradiance.glsl"
#include "shaders/octahedron_irradiance.glsl"
#include "shaders/environment.glsl"
#include "passes/direct_light_shared.h"
#include "passes/shadow_maps_shared.h"

layout(local_size_x = 8, local_size_y = 8) in;

#include "passes/receiver.glsl"
layout(binding = GIQ_RECEIVER_BINDING_COUNT + 0) uniform sampler2DArrayShadow shadow_map;
layout(std430, binding = GIQ_RECEIVER_BINDING_COUNT + 1) readonly buffer ShadowLayers { GpuShadowLayer shadow_layers[]; };
layout(std430, binding = GIQ_RECEIVER_BINDING_COUNT + 2) readonly buffer AreaLights { GpuAreaLight area_lights[]; };
layout(std430, binding = GIQ_RECEIVER_BINDING_COUNT + 3) readonly buffer AreaTriangles { GpuAreaTriangle area_triangles[]; };
layout(std430, binding = GIQ_RECEIVER_BINDING_COUNT + 4) readonly buffer LightShadow { uint light_shadow_layer[]; };
layout(binding = GIQ_RECEIVER_BINDING_COUNT + 5, rgba32f) uniform writeonly image2D out_direct;
// The particles' light tree (LinearBvh::LightTree): nodes, each node's particles' centroid and
// count, each stage's subtree.
layout(std430, binding = GIQ_RECEIVER_BINDING_COUNT + 6) readonly buffer ParticleTree { GpuBvhNode particle_tree[]; };
layout(std430, binding = GIQ_RECEIVER_BINDING_COUNT + 7) readonly buffer ParticleClusters { vec4 particle_clusters[]; };
layout(std430, binding = GIQ_RECEIVER_BINDING_COUNT + 8) readonly buffer StageRoots { uint stage_roots[]; };

#include "passes/area_light_parts.glsl"

layout(push_constant) uniform Push { DirectPush pc; };

#include "passes/shadow.glsl"

#ifdef GIQ_SPECULAR
// The point of the sphere of `radius` about c (relative to the shading point) closest to the
// reflection ray r (Karis 2013, "Sphere Lights").
vec3 sphere_point(vec3 c, vec3 r, float radius) {
  vec3 to_ray = dot(c, r) * r - c;
  float d = length(to_ray);
  return d > 0.0 ? c + to_ray * min(1.0, radius / d) : c;
}

// The point of the declared shape (GpuAreaLight::shape*, relative to the shading point) closest
// to the reflection ray r from the shading point (Turánszki 2017, "Area Lights": sphere, disc,
// rectangle, tube), and its source radius for the energy normalisation. Disc and rectangle
// take the ray's intersection with their plane (the point on the ray nearest the centre when
// the ray leaves the plane) and clamp it into the shape; the tube takes the segment point
// nearest the ray (Karis 2013, "Tube Lights"), then the sphere around it.
vec3 shape_point(GpuAreaLight l, vec3 c, vec3 r, int shape, out float source_radius) {
  float radius = l.shape_u.w;
  source_radius = radius;
  if (shape == GIQ_AREA_TUBE) {
    vec3 a = c - l.shape_u.xyz, ab = 2.0 * l.shape_u.xyz;
    float rab = dot(r, ab), denom = dot(ab, ab) - rab * rab;
    float t = denom > 0.0 ? clamp((dot(r, a) * rab - dot(a, ab)) / denom, 0.0, 1.0) : 0.5;
    c = a + t * ab;
  }
  if (shape == GIQ_AREA_SPHERE || shape == GIQ_AREA_TUBE) return sphere_point(c, r, radius);
  // Disc and rectangle: the plane's normal (a disc keeps it in v, a rectangle's is u x v).
  vec3 n = shape == GIQ_AREA_DISC ? l.shape_v.xyz : normalize(cross(l.shape_u.xyz, l.shape_v.xyz));
  float rn = dot(r, n);
  float t = abs(rn) > 1e-6 ? dot(c, n) / rn : -1.0;
  vec3 x = t > 0.0 ? r * t : max(dot(c, r), 0.0) * r;
  vec3 d = x - c;
  d -= n * dot(d, n);
  if (shape == GIQ_AREA_DISC) {
    float len = length(d);
    return c + (len > radius ? d * (radius / len) : d);
  }
  vec3 u = l.shape_u.xyz, v = l.shape_v.xyz;
  source_radius = l.shape_v.w;
  return c + u * clamp(dot(d, u) / dot(u, u), -1.0, 1.0) + v * clamp(dot(d, v) / dot(v, v), -1.0, 1.0);
}
#endif

// Karis 2013's energy normalisation: a light of angular radius source_radius / d widens the
// lobe from alpha to alpha' = alpha + source_radius / (2 d); scaling the peak by
// (alpha / alpha')^2 keeps a wide light's energy from concentrating at the representative point.
float widening(float alpha, float source_radius, float d) {
  float a2 = clamp(alpha + source_radius / (2.0 * d), 0.0, 1.0);
  return a2 > 0.0 ? (alpha * alpha) / (a2 * a2) : 1.0;
}

// Particle k as one light: the diffuse part from its octahedron's irradiance, the specular
// part from the representative point of the sphere of its mean projected area (a convex
// body's is a quarter of its surface, sqrt(3) r^2 for the octahedron: radius
// r (sqrt(3) / pi)^(1/2)), energy-normalised like a declared sphere.
vec3 particle_light(GpuParticleLight particle, Surface s, vec3 p, vec3 wo) {
  vec3 c = particle.centre.xyz - p;
  float r = particle.centre.w;
  float e = octahedron_irradiance(c, r, s.n);
  if (e <= 0.0) return vec3(0.0);
  float d = length(c);
  vec3 diffuse, specular;
  brdf_parts(s, wo, c / d, diffuse, specular);
  vec3 f = diffuse;
#ifdef GIQ_SPECULAR
  float radius = r * sqrt(sqrt(3.0) / PI);
  vec3 q = sphere_point(c, reflect(-wo, s.n), radius);
  float dq = length(q);
  if (dq > 0.0) {
    brdf_parts(s, wo, q / dq, diffuse, specular);
    f += specular * widening(s.alpha, radius, dq);
  }
#endif
  return f * particle.radiance.rgb * e;
}

// A stage's particles through its subtree of the light tree, a lightcut (Walter et al. 2005,
// "Lightcuts", section 3): a cluster whose box lies wholly in front of the surface and is
// smaller than pc.particle_cut times its distance lights as its count of particles at their
// centroid; a box wholly behind the surface sends nothing (no particle in it reaches above the
// plane); the others are opened, down to single particles, lit as in the loop. The centroid
// makes the error second order: the first-order terms of the particles' offsets from it sum
// to zero, so a cluster's relative error is of order cut^2. The specular part takes the
// cluster as one particle at its centroid, and a leaf is its particle at its box's centre.
// The walk needs no stack: in the depth-first layout a node of n particles spans the 2n - 1
// nodes from it, so the node after them is where the walk goes on when it is not opened, and
// its first child, the next node, when it is. A subgroup walks one cut, the union of its
// pixels' (a node is opened unless each pixel takes it whole or sees none of it): each pixel
// still lights only clusters that meet its own criterion, so the bound holds per pixel, and
// the invocations load the same node together instead of scattering over the tree (on an
// H100 a third less time at 48k particles, bench/results/particle-tree-h100.md).
vec3 particle_tree_light(GpuAreaLight l, uint root, Surface s, vec3 p, vec3 wo) {
  vec3 sum = vec3(0.0);
  float cut2 = pc.particle_cut * pc.particle_cut;
  bvec3 up = greaterThanEqual(s.n, vec3(0.0));
  uint node = root, end = root + 2u * uint(particle_clusters[root].w) - 1u;
  while (node < end) {
    GpuBvhNode b = particle_tree[node];
    vec4 c = particle_clusters[node];
    uint next = node + 2u * uint(c.w) - 1u;
    // The box's highest and lowest corner over the surface's plane.
    vec3 lo = b.lo - p, hi = b.hi - p;
    bool seen = dot(s.n, mix(lo, hi, up)) > 0.0;
    float count = 0.0;  // of particles lit at c.xyz
    if (b.count > 0u) {
      if (seen) count = 1.0;
    } else {
      vec3 size = b.hi - b.lo, to = c.xyz - p;
      bool whole = seen && dot(s.n, mix(hi, lo, up)) > 0.0 && dot(size, size) < cut2 * dot(to, to);
      if (subgroupAll(whole || !seen)) {
        if (whole) count = c.w;
      } else {
        next = node + 1u;  // opened
      }
    }
    if (count > 0.0) {
      GpuParticleLight q;
      q.centre = vec4(c.xyz, l.particle.w);
      q.radiance = vec4(l.particle.rgb, 0.0);
      sum += count * particle_light(q, s, p, wo);
    }
    node = next;
  }
  return sum;
}

vec3 area_light(GpuAreaLight l, Surface s, vec3 p, vec3 wo) {
  vec3 sum = vec3(0.0);
  vec3 incident = vec3(0.0);  // sum of radiance x irradiance over the triangles (declared shapes)
  int shape = int(l.shape.w);
  uint slot = uint(l.extent.w);
  if (slot > 0u && lit_particles(l) > 0u) {
    uint root = stage_roots[slot - 1u];
    if (root != 0xffffffffu) sum += particle_tree_light(l, root, s, p, wo);
  } else {
    for (uint k = 0u; k < lit_particles(l); ++k) sum += particle_light(stage_particle(l, k), s, p, wo);
  }
  uint triangles = lit_triangles(l);
  for (uint k = 0u; k < triangles; ++k) {
    GpuAreaTriangle t = area_triangle(l, k);
    vec3 a = t.a.xyz - p, b = t.b.xyz - p, c = t.c.xyz - p;
    vec3 ng = cross(b - a, c - a);
    // A one-sided emitter lights only the half-space in front of it.
    if (t.a.w == 0.0 && dot(ng, -a) <= 0.0) continue;
    float e = polygon_irradiance(a, b, c, s.n);
    if (e <= 0.0) continue;
    vec3 tri_mid = (a + b + c) / 3.0;
    vec3 diffuse, specular;
    brdf_parts(s, wo, normalize(tri_mid), diffuse, specular);
    vec3 f = diffuse;
#ifdef GIQ_SPECULAR
    if (shape != GIQ_AREA_MESH) {
      incident += t.radiance.rgb * e;
    } else {
      // No declared shape: each triangle is its own light, its representative point the
      // point of the triangle closest to the reflection ray.
      vec3 r = reflect(-wo, s.n);
      float rn = dot(r, ng);
      vec3 q = tri_mid;
      if (abs(rn) > 0.0) {
        float tt = dot(a, ng) / rn;
        if (tt > 0.0) q = r * tt;
      }
      q = closest_on_triangle(q, a, b, c);
      float d = length(q);
      if (d > 0.0) {
        vec3 dd, spec;
        brdf_parts(s, wo, q / d, dd, spec);
        f += spec * widening(s.alpha, sqrt(0.5 * length(ng) / PI), d);
      }
    }
#endif
    sum += f * t.radiance.rgb * e;
  }
#ifdef GIQ_SPECULAR
  // A declared shape: one representative point for the whole light, lit by what all its
  // triangles send.
  if (shape != GIQ_AREA_MESH && any(greaterThan(incident, vec3(0.0)))) {
    float source_radius;
    vec3 q = shape_point(l, l.shape.xyz - p, reflect(-wo, s.n), shape, source_radius);
    float d = length(q);
    if (d > 0.0) {
      vec3 dd, spec;
      brdf_parts(s, wo, q / d, dd, spec);
      float norm = widening(s.alpha, source_radius, d);
      // A tube widens the lobe along its length too, in one dimension: alpha / alpha'.
      if (shape == GIQ_AREA_TUBE) norm *= sqrt(widening(s.alpha, length(l.shape_u.xyz), d));
      sum += spec * norm * incident;
    }
  }
#endif
  return sum;
}

// The share of area light l's light at p that no surface blocks, by pc.area_shadow_rays shadow
// rays from p_off (p lifted off its surface) to points on the light's triangles: the ratio
// estimator of Heitz et al. 2018 ("Combining Analytic Direct Illumination and Stochastic
// Shadows", section 3), which multiplies the exact unshadowed light (area_light) by
// sum(w V) / sum(w) over the same samples, w each sample's unshadowed irradiance over its
// probability: where all the light is seen the result is exact, where none is it is exactly
// zero, and in between the noise is that of the visibility alone. The weights are the diffuse
// integrand, so a glossy highlight takes the diffuse light's share. Rays are stratified over
// the triangles (chosen uniformly, so w carries each triangle's area) and drawn per pixel and
// light, not per frame: a still image does not flicker.
float area_visibility(GpuAreaLight l, uint light, vec3 p_off, vec3 n, vec3 ng, uvec2 px) {
  uint m = l.range.y;
  if (m == 0u) return 1.0;
  Rng rng = rng_init(px, light, 0x50f7u);
  float total = 0.0, seen = 0.0;
  for (uint i = 0u; i < pc.area_shadow_rays; ++i) {
    float u = (float(i) + rng_next(rng)) / float(pc.area_shadow_rays);
    GpuAreaTriangle t = area_triangle(l, min(uint(u * float(m)), m - 1u));
    vec2 bc = sample_triangle(vec2(rng_next(rng), rng_next(rng)));
    vec3 q = t.a.xyz + bc.x * (t.b.xyz - t.a.xyz) + bc.y * (t.c.xyz - t.a.xyz);
    vec3 d = q - p_off;
    float dist2 = dot(d, d);
    if (!(dist2 > 0.0)) continue;
    float dist = sqrt(dist2);
    vec3 w = d / dist;
    // Twice the triangle's area times its cosine towards p (a one-sided emitter sends nothing
    // backwards).
    float cos_area = dot(cross(t.b.xyz - t.a.xyz, t.c.xyz - t.a.xyz), -w);
    if (t.a.w != 0.0) cos_area = abs(cos_area);
    float cos_r = dot(n, w);
    if (cos_area <= 0.0 || cos_r <= 0.0 || dot(ng, w) <= 0.0) continue;
    float weight = luminance(t.radiance.rgb) * cos_r * cos_area / dist2;
    total += weight;
    // Stop short of the sampled point, as the path tracer's shadow rays do (path.glsl).
    if (!occluded(p_off, w, dist * (1.0 - 1e-4))) seen += weight;
  }
  return total > 0.0 ? seen / total : 1.0;
}

void main() {
  ivec2 px = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(px), pc.size))) return;
  Receiver r = load_receiver(px);
  vec3 radiance = vec3(0.0);
  if (!r.hit) {
    // The camera sees the environment directly, in the direction of the pixel's centre.
    radiance = environment_radiance(pc.environment, camera_ray_direction(pc.camera, vec2(px) + 0.5, vec2(pc.size)));
  } else if (r.lit) {  // the back of a one-sided material is black
    GpuMaterial mat = scene_materials[r.material];
    vec3 p = r.x;
    vec3 n = r.n;
    vec3 wo = camera_to_eye(pc.camera, p);
    // The geometric normal on the viewer's side: light from below it would leak through the
    // surface, whatever the (interpolated or mapped) shading normal says; the reference
    // drops it too.
    vec3 ng = receiver_geometric_normal(r);
    // Textured materials are looked up at the G-buffer point (deferred texturing).
    if (mat.emissive.w != 0.0) radiance += emission_at(mat, r.tri, r.bary.x, r.bary.y, r.footprint);
    Surface s = receiver_surface(r);
    float normal_offset = pc.normal_offset;
    int pcf = int(pc.pcf_radius);
    for (uint i = 0u; i < pc.light_count; ++i) {
      vec3 wi;
      float dist;
      vec3 e = punctual_incident(scene_lights[i], p, wi, dist);
      float cos_i = dot(n, wi);
      if (cos_i <= 0.0 || dot(ng, wi) <= 0.0 || all(equal(e, vec3(0.0)))) continue;
      float vis = int(scene_lights[i].position.w) == GIQ_LIGHT_DIRECTIONAL
                      ? shadow_cascades(light_shadow_layer[i], dot(p - pc.camera.position.xyz, pc.camera.forward.xyz), p, n, normal_offset, pcf)
                      : shadow_cube(light_shadow_layer[i], scene_lights[i].position.xyz, p, n, normal_offset, pcf);
      radiance += brdf_eval(s, wo, wi) * e * cos_i * vis;
    }
    for (uint i = 0u; i < pc.area_light_count; ++i) {
      GpuAreaLight l = area_lights[i];
      vec3 c = area_light(l, s, p, wo);
      if (all(equal(c, vec3(0.0)))) continue;
      radiance += c * (pc.area_shadow_rays > 0u
                           ? area_visibility(l, i, offset_ray(p, ng), n, ng, uvec2(px))
                           : shadow_cube(uint(l.position.w), l.position.xyz, p, n, normal_offset, pcf));
    }
  }
  imageStore(out_direct, px, vec4(radiance, 1.0));
}
