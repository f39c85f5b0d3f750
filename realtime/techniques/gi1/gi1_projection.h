#pragma once
// How `gi1` projects a screen probe onto spherical harmonics (Boissé et al. 2022, section
// 2.4.2): the integral of each basis function over each cell of the probe's map.

#include <vector>

namespace giq::realtime {

// [basis][cell]: the integral of real spherical harmonic k (bands 0 to 2, in the order
// gi1_sh_basis in gi1_probe.glsl has them) over cell c of a probe's 8x8 hemispherical
// octahedral map (hemi_oct_decode), in the probe's frame (its normal +z). A probe whose cells
// hold radiance L_c has coefficients sum_c L_c table[k][c]: exact for radiance constant over
// each cell.
std::vector<float> gi1_projection_table();

}  // namespace giq::realtime
