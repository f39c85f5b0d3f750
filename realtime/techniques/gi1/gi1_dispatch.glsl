// Indirect dispatches of `gi1`: n work groups as (x, y, 1) within the 65535 per axis every
// device allows; a group finds its index with gi1_group() and skips it when it is >= n.
#ifndef GIQ_GI1_DISPATCH_GLSL
#define GIQ_GI1_DISPATCH_GLSL

uvec4 gi1_groups(uint n) { return uvec4(min(n, 65535u), max(1u, (n + 65534u) / 65535u), 1u, n); }

uint gi1_group() { return gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x; }

#endif
