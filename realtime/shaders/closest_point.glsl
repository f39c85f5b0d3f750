// The point of triangle (a, b, c) closest to q (Ericson 2004, "Real-Time Collision Detection",
// §5.1.5): area lights' representative points (passes/direct_light.comp) and the surface
// point a voxel stands for (techniques/vct/voxel_light.comp).
#ifndef GIQ_CLOSEST_POINT_GLSL
#define GIQ_CLOSEST_POINT_GLSL

vec3 closest_on_triangle(vec3 q, vec3 a, vec3 b, vec3 c) {
  vec3 ab = b - a, ac = c - a, ap = q - a;
  float d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) return a;
  vec3 bp = q - b;
  float d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return b;
  float vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + ab * (d1 / (d1 - d3));
  vec3 cp = q - c;
  float d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return c;
  float vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + ac * (d2 / (d2 - d6));
  float va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  float denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

#endif
