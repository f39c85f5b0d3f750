// Appending to and taking from the particle system's lists with one atomic per subgroup
// rather than one per particle: a million particles adding to one counter serialise on it
// (bench/results/particles-h200.md). Each invocation's place is the subgroup's base plus the
// number of taking invocations before it (Vulkan subgroup ballot). Every invocation of the
// subgroup must call these, taking or not.
#ifndef GIQ_PARTICLE_LISTS_GLSL
#define GIQ_PARTICLE_LISTS_GLSL

#extension GL_KHR_shader_subgroup_ballot : require

// The counter's value before this subgroup's `take`s were added to it (by `step`: 1 or
// 0xffffffff to subtract), plus this invocation's rank among them; unused when !take.
uint subgroup_atomic_add(uint counter, bool take, uint step) {
  uvec4 ballot = subgroupBallot(take);
  uint n = subgroupBallotBitCount(ballot), base = 0u;
  if (subgroupElect() && n > 0u) base = atomicAdd(counters[counter], step * n);
  base = subgroupBroadcastFirst(base);
  return base + step * subgroupBallotExclusiveBitCount(ballot);
}

#endif
