#version 460
// Each stage of particles as the GPU wrote it into the scene's vertex array (six vertices a
// particle on its octahedron's axes: shaders/particles_vertices.comp), reduced to what the
// scene's area light and bounds need (ParticleBounds): the centroid of the particles' centres
// (a stage's faces all have one area, so this is the area-weighted centroid the scene library
// computes for placed particles), the box of the vertices, and the largest distance of a
// vertex from the centroid (scenes::AreaLight::extent), and for each point of `points` (the
// scene's point and spot lights) a lower bound on its distance to the particles' surfaces,
// which bounds the irradiance a particle can receive from that light (the voxel radiance scale
// of techniques/vct/voxel_scale.h). In chunks of GIQ_BOUNDS_CHUNK
// particles, each summed in a fixed order (a tree in shared memory, then the chunks in turn),
// so the same vertices give the same bits.
//   phase 0, a group per chunk: its sum of centres, its box, its least distance from each point;
//   phase 1, a group per stage: the chunks' sums and boxes, in order, the centroid;
//   phase 2, a group per chunk: its largest distance from its stage's centroid.
#extension GL_GOOGLE_include_directive : require

#define GIQ_BOUNDS_GROUP 256u
#define GIQ_BOUNDS_CHUNK 4096u

layout(local_size_x = GIQ_BOUNDS_GROUP) in;

layout(std430, binding = 0) readonly buffer Vertices { vec4 vertices[]; };  // GpuVertex rows: position, normal
layout(std430, binding = 1) readonly buffer Chunks { uvec4 chunks[]; };  // x first vertex, y particles, z stage
layout(std430, binding = 2) readonly buffer Stages { uvec4 stages[]; };  // x first chunk, y chunks
layout(std430, binding = 3) buffer Partials { vec4 partials[]; };  // a chunk: sum (w count), lo, hi, extent (x)
layout(std430, binding = 4) buffer Results { vec4 results[]; };    // a stage: centroid (w count), lo, hi
layout(std430, binding = 5) readonly buffer Points { vec4 points[]; };  // xyz; w 0: none (a directional light)
layout(std430, binding = 6) buffer Nearest { float nearest[]; };  // a chunk's least distance from each point
layout(push_constant) uniform Push { uint phase, points; } pc;

shared vec4 sum_s[GIQ_BOUNDS_GROUP];
shared vec3 lo_s[GIQ_BOUNDS_GROUP], hi_s[GIQ_BOUNDS_GROUP];
shared float near_s[GIQ_BOUNDS_GROUP];

vec3 corner(uint particle_first_vertex, uint k) { return vertices[2u * (particle_first_vertex + k)].xyz; }

// A lower bound on the distance from q to the octahedron with corners c +- s along the axes
// (|x - c|_1 <= s): at least |q - c|_2 - s (its circumsphere) and (|q - c|_1 - s) / sqrt(3)
// (for x inside, |q - x|_2 >= |q - x|_1 / sqrt(3) >= (|q - c|_1 - |x - c|_1) / sqrt(3)); the
// second is the tighter off the axes. 0 inside.
float octahedron_distance(vec3 q, vec3 c, float s) {
  vec3 d = abs(q - c);
  return max(max(length(d) - s, (d.x + d.y + d.z - s) * 0.57735026), 0.0);
}

// Phase 0's least distance from point k to the chunk's particles, written to nearest[].
void reduce_nearest(uvec4 chunk, uint g, uint t, uint k) {
  vec4 q = points[k];
  float near = 3.0e38;
  if (q.w != 0.0)
    for (uint i = t; i < chunk.y; i += GIQ_BOUNDS_GROUP) {
      uint first = chunk.x + 6u * i;
      vec3 a = corner(first, 0u), b = corner(first, 1u);
      near = min(near, octahedron_distance(q.xyz, 0.5 * (a + b), 0.5 * distance(a, b)));
    }
  near_s[t] = near;
  barrier();
  for (uint stride = GIQ_BOUNDS_GROUP / 2u; stride > 0u; stride /= 2u) {
    if (t < stride) near_s[t] = min(near_s[t], near_s[t + stride]);
    barrier();
  }
  if (t == 0u) nearest[g * pc.points + k] = near_s[0];
  barrier();
}

void main() {
  uint t = gl_LocalInvocationID.x, g = gl_WorkGroupID.x;
  if (pc.phase == 1u) {
    if (t != 0u) return;
    uvec4 st = stages[g];
    vec4 sum = vec4(0.0);
    vec3 lo = vec3(3.0e38), hi = vec3(-3.0e38);
    for (uint c = st.x; c < st.x + st.y; ++c) {
      sum += partials[4u * c];
      lo = min(lo, partials[4u * c + 1u].xyz);
      hi = max(hi, partials[4u * c + 2u].xyz);
    }
    results[3u * g] = vec4(sum.w > 0.0 ? sum.xyz / sum.w : vec3(0.0), sum.w);
    results[3u * g + 1u] = vec4(lo, 0.0);
    results[3u * g + 2u] = vec4(hi, 0.0);
    return;
  }
  uvec4 chunk = chunks[g];
  if (pc.phase == 0u)
    for (uint k = 0u; k < pc.points; ++k) reduce_nearest(chunk, g, t, k);
  vec3 centre_of_stage = pc.phase == 2u ? results[3u * chunk.z].xyz : vec3(0.0);
  vec4 sum = vec4(0.0);
  vec3 lo = vec3(3.0e38), hi = vec3(-3.0e38);
  float far = 0.0;
  for (uint i = t; i < chunk.y; i += GIQ_BOUNDS_GROUP) {
    uint first = chunk.x + 6u * i;
    // The centre midway between the +x and -x corners, as scenes::particle_centres reads it.
    sum += vec4(0.5 * (corner(first, 0u) + corner(first, 1u)), 1.0);
    for (uint k = 0u; k < 6u; ++k) {
      vec3 v = corner(first, k);
      lo = min(lo, v);
      hi = max(hi, v);
      far = max(far, length(v - centre_of_stage));
    }
  }
  if (pc.phase == 2u) {
    sum_s[t] = vec4(far);
  } else {
    sum_s[t] = sum;
    lo_s[t] = lo;
    hi_s[t] = hi;
  }
  barrier();
  for (uint stride = GIQ_BOUNDS_GROUP / 2u; stride > 0u; stride /= 2u) {
    if (t < stride) {
      if (pc.phase == 2u) {
        sum_s[t] = max(sum_s[t], sum_s[t + stride]);
      } else {
        sum_s[t] += sum_s[t + stride];
        lo_s[t] = min(lo_s[t], lo_s[t + stride]);
        hi_s[t] = max(hi_s[t], hi_s[t + stride]);
      }
    }
    barrier();
  }
  if (t != 0u) return;
  if (pc.phase == 2u) {
    partials[4u * g + 3u] = vec4(sum_s[0].x, 0.0, 0.0, 0.0);
  } else {
    partials[4u * g] = sum_s[0];
    partials[4u * g + 1u] = vec4(lo_s[0], 0.0);
    partials[4u * g + 2u] = vec4(hi_s[0], 0.0);
  }
}
