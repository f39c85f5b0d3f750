// Two-band spherical harmonics of LPV (Afanasev 2021, appendix "LPVInjection.hlsl",
// "LPVPropagation.hlsl", whose Common.hlsl they come from; Kaplanyan and Dachsbacher 2010,
// "Cascaded Light Propagation Volumes for Real-Time Indirect Illumination"): real SH with
// Y00 = 1 / (2 sqrt(pi)), Y1m = sqrt(3) / (2 sqrt(pi)) (-y, z, -x).
#ifndef GIQ_LPV_SH_GLSL
#define GIQ_LPV_SH_GLSL

#define PI_LPV 3.14159265358979
#define LPV_SH_C0 0.282094792        // 1 / (2 sqrt(pi))
#define LPV_SH_C1 0.488602512        // sqrt(3) / (2 sqrt(pi))
#define LPV_SH_COS_C0 0.886226925    // sqrt(pi) / 2: projection of max(0, n.w), band 0
#define LPV_SH_COS_C1 1.02332671     // sqrt(pi / 3): band 1

// Evaluating a function f at d: dot(f's coefficients, dir_to_sh(d)).
vec4 dir_to_sh(vec3 d) { return vec4(LPV_SH_C0, -LPV_SH_C1 * d.y, LPV_SH_C1 * d.z, -LPV_SH_C1 * d.x); }
// The coefficients of the clamped cosine lobe max(0, n.w).
vec4 cos_lobe_sh(vec3 n) { return vec4(LPV_SH_COS_C0, -LPV_SH_COS_C1 * n.y, LPV_SH_COS_C1 * n.z, -LPV_SH_COS_C1 * n.x); }

int lpv_cell_index(ivec3 c, int res) { return c.x + res * (c.y + res * c.z); }

#endif
