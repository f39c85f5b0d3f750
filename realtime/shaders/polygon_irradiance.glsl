// Irradiance from a polygon of unit radiance, exactly: Lambert's formula after clipping the
// polygon to the receiver's horizon (Arvo 1995, "Applications of Irradiance Tensors to the
// Simulation of Non-Lambertian Phenomena", eq. 7). The diffuse part of every area light:
// the shared direct light (passes/direct_light.comp) and the probe rays of `ddgi`.
#ifndef GIQ_POLYGON_IRRADIANCE_GLSL
#define GIQ_POLYGON_IRRADIANCE_GLSL

// The triangle (a, b, c), relative to the shading point, clipped to the half-space n.x >= 0
// (Sutherland-Hodgman against one plane: at most 4 vertices).
int clip_to_horizon(vec3 a, vec3 b, vec3 c, vec3 n, out vec3 v[4]) {
  vec3 tri[3] = vec3[3](a, b, c);
  int count = 0;
  for (int i = 0; i < 3; ++i) {
    vec3 p0 = tri[i], p1 = tri[(i + 1) % 3];
    float d0 = dot(n, p0), d1 = dot(n, p1);
    if (d0 >= 0.0) v[count++] = p0;
    if ((d0 >= 0.0) != (d1 >= 0.0)) v[count++] = p0 + (p1 - p0) * (d0 / (d0 - d1));
  }
  return count;
}

// Irradiance at the origin (normal n) from a polygon of unit radiance:
// E = 1/2 sum_i theta_i n.unit(v_i x v_i+1) (Lambert's formula; Arvo 1995).
float polygon_irradiance(vec3 a, vec3 b, vec3 c, vec3 n) {
  vec3 v[4];
  int count = clip_to_horizon(a, b, c, n, v);
  if (count < 3) return 0.0;
  // A shading point on a vertex of the light sees it edge-on: no irradiance, and no NaN.
  for (int i = 0; i < count; ++i)
    if (dot(v[i], v[i]) <= 1e-30) return 0.0;
  float sum = 0.0;
  for (int i = 0; i < count; ++i) {
    vec3 v0 = normalize(v[i]), v1 = normalize(v[(i + 1) % count]);
    vec3 cr = cross(v0, v1);
    float len = length(cr);
    // atan(|v0 x v1|, v0.v1) keeps the angle accurate for small, distant triangles.
    if (len > 0.0) sum += atan(len, dot(v0, v1)) * dot(n, cr / len);
  }
  return 0.5 * abs(sum);
}

#endif
