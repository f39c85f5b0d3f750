// Cone marching through the voxel mips, shared by the screen-space cone tracing
// (cone_trace.comp) and the voxels' own bounce (voxel_light.comp). The includer declares the
// samplers `chain_px` .. `chain_nz` (the six anisotropic chains) and, unless
// GIQ_VCT_CHAINS_ONLY is defined, `base`; and defines VCT_GRID (a VctGrid), VCT_MAX_DISTANCE,
// VCT_STEP_FACTOR, VCT_AO_FALLOFF, VCT_START (the apex's distance from the surface) and
// VCT_GUARD (the footprint guard).
#ifndef GIQ_VCT_CONE_GLSL
#define GIQ_VCT_CONE_GLSL

// GetAnisotropicSample of the thesis, with a fractional level between the chain's mips (the
// thesis truncates it to an integer). lod is in base voxels: chain level 0 is lod 1.
vec4 sample_voxels(vec3 uvw, vec3 dir, float lod) {
  vec3 w = dir * dir;
  float l = max(lod - 1.0, 0.0);
  vec4 s = w.x * (dir.x > 0.0 ? textureLod(chain_px, uvw, l) : textureLod(chain_nx, uvw, l)) +
           w.y * (dir.y > 0.0 ? textureLod(chain_py, uvw, l) : textureLod(chain_ny, uvw, l)) +
           w.z * (dir.z > 0.0 ? textureLod(chain_pz, uvw, l) : textureLod(chain_nz, uvw, l));
#ifndef GIQ_VCT_CHAINS_ONLY
  if (lod < 1.0) s = mix(textureLod(base, uvw, 0.0), s, clamp(lod, 0.0, 1.0));
#endif
  return s;
}

// TraceCone of the thesis: front-to-back compositing, the sample spacing a fraction
// (step factor) of the cone's diameter. Each sample stands for a segment of length
// step = step factor x diameter while a voxel of that diameter holds the opacity of a
// segment one diameter long, so opacity is corrected to 1 - (1 - a)^(step factor)
// (Crassin et al. 2011). Returns premultiplied radiance (stored units) and alpha; occlusion
// follows the thesis's AO with falloff 1 / (1 + falloff x diameter in voxels).
vec4 trace_cone(vec3 p, vec3 dir, float aperture, out float occlusion) {
  float voxel = VCT_GRID.origin.w;
  float inv_extent = 1.0 / (voxel * float(VCT_GRID.resolution));
  float max_lod = float(VCT_GRID.levels);
  float dist = voxel;
  vec4 acc = vec4(0.0);
  occlusion = 0.0;
  while (dist < VCT_MAX_DISTANCE && acc.a < 0.99) {
    float diameter = max(2.0 * aperture * dist, voxel);
    // The footprint guard: a cell of the level sampled, with the trilinear filter's reach of
    // about 1.5 cells, must not extend behind the surface the cone leaves, or a thick wall's
    // far (possibly sunlit) face is composited first by the directional mips and leaks in.
    // The cell size is capped at (distance from the surface) / guard; guard 0 = Afanasev 2021's
    // level log2(diameter / voxel).
    float cell = VCT_GUARD > 0.0 ? min(diameter, max((dist + VCT_START) / VCT_GUARD, voxel)) : diameter;
    float lod = min(log2(cell / voxel), max_lod);
    vec3 uvw = (p + dist * dir - VCT_GRID.origin.xyz) * inv_extent;
    if (any(lessThan(uvw, vec3(0.0))) || any(greaterThan(uvw, vec3(1.0)))) break;
    vec4 s = sample_voxels(uvw, dir, lod);
    if (s.a > 0.0) {
      float a = 1.0 - pow(max(1.0 - s.a, 0.0), VCT_STEP_FACTOR);
      s = vec4(s.rgb * (a / s.a), a);
      acc += (1.0 - acc.a) * s;
      occlusion += (1.0 - occlusion) * s.a / (1.0 + VCT_AO_FALLOFF * diameter / voxel);
    }
    dist += diameter * VCT_STEP_FACTOR;
  }
  return acc;
}


// Diffuse cone i of `cones` around the unit normal n, and its weight (the cones' weights sum
// to 1). Cone 0 is along the normal (weight 0.25); the others lie on a ring at 60 deg from it,
// sharing 0.75. For 6 cones the azimuths 90 - 72 i deg reproduce the thesis's table
// ((0, .5, .866), (.824, .5, .268), (.509, .5, -.701), ...) in its frame: right = the fixed up
// axis made orthogonal to n, up = right x n, with the table's y along n.
void diffuse_cone(uint i, uint cones, vec3 n, out vec3 dir, out float weight) {
  if (i == 0u) {
    dir = n;
    weight = cones == 1u ? 1.0 : 0.25;
    return;
  }
  vec3 ref = abs(n.y) > 0.999 ? vec3(0.0, 0.0, 1.0) : vec3(0.0, 1.0, 0.0);
  vec3 right = normalize(ref - dot(n, ref) * n);
  vec3 up = cross(right, n);
  float phi = radians(90.0 - 360.0 / float(cones - 1u) * float(i - 1u));
  vec3 t = vec3(0.866025 * cos(phi), 0.5, 0.866025 * sin(phi));
  dir = normalize(t.x * right + t.y * n + t.z * up);
  weight = 0.75 / float(cones - 1u);
}

#endif
