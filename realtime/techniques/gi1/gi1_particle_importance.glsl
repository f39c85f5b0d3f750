// `gi1`'s light grid (gi1_light_grid.comp): the importance of a stage of glowing particles at
// a point, through the stage's subtree of the particles' light tree (LinearBvh::LightTree,
// depth first: a node of n particles spans the 2n - 1 nodes from it). Each particle counts as
// its octahedron's mean projected area (a quarter of its surface: sqrt(3) r^2 for
// circumradius r) times its radiance, from both sides where the emitter is two-sided, over its
// squared distance no less than near^2: what its eight faces' sum gives, averaged over
// directions (the faces' sum lies within 0.82 and 1.15 times it, the octahedron's projected
// area lying between sqrt(2) r^2 and 2 r^2). A cluster whose box is smaller than `cut` times
// its centroid's distance (clamped to near as well) counts as all its particles at their
// centroid: the first-order terms cancel, and a cluster's relative error is at most
// c^2 + c^2 (2 + c)^2 / (1 - c)^2 (GridImportanceOfParticlesByCluster). The faces' sum visited
// every particle's every face at every corner of every cell: 48 ms a frame for 45k particles
// on an H100 (bench/results/particle-tree-h100.md).
// The includer binds particle_tree[] (GpuBvhNode), particle_clusters[] (vec4: xyz the
// centroid, w the count) and stage_roots[] (uint); needs shaders/scene.glsl, sampling.glsl
// and passes/direct_light_shared.h.
#ifndef GIQ_GI1_PARTICLE_IMPORTANCE_GLSL
#define GIQ_GI1_PARTICLE_IMPORTANCE_GLSL

// The grid's cut: importance only orders a cell's lights and culls those that deposit nothing;
// clusters a quarter of their distance across err by at most 0.63 by the bound above, and by
// 0.4 % on the fountain (GridImportanceOfParticlesByCluster).
const float kGi1ParticleImportanceCut = 0.25;

// The importance at c of the stage in light-tree slot `slot`, whose area light is a.
float gi1_particle_importance(GpuAreaLight a, uint slot, vec3 c, float near, float cut) {
  uint node = stage_roots[slot];
  if (node == 0xffffffffu) return 0.0;
  uint end = node + 2u * uint(particle_clusters[node].w) - 1u;
  float sum = 0.0, cut2 = cut * cut;
  while (node < end) {
    GpuBvhNode b = particle_tree[node];
    vec4 k = particle_clusters[node];
    vec3 size = b.hi - b.lo, to = k.xyz - c;
    float d2 = max(dot(to, to), near * near);
    if (b.count > 0u || dot(size, size) < cut2 * d2) {
      sum += k.w / d2;
      node += 2u * uint(k.w) - 1u;
    } else {
      ++node;  // opened
    }
  }
  float r = a.particle.w;
  return luminance(a.particle.rgb) * sqrt(3.0) * r * r * (a.extent.y != 0.0 ? 2.0 : 1.0) * sum;
}

#endif
