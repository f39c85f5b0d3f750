#include "techniques/gi1/gi1_projection.h"

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "techniques/gi1/gi1_shared.h"

namespace giq::realtime {
namespace {

// Real spherical harmonics of bands 0 to 2 (Sloan 2008, "Stupid Spherical Harmonics Tricks",
// appendix 2), in gi1_sh_basis's order.
void sh_basis(double x, double y, double z, double out[GIQ_GI1_SH]) {
  out[0] = 0.28209479177387814;
  out[1] = 0.4886025119029199 * y;
  out[2] = 0.4886025119029199 * z;
  out[3] = 0.4886025119029199 * x;
  out[4] = 1.0925484305920792 * x * y;
  out[5] = 1.0925484305920792 * y * z;
  out[6] = 0.31539156525252005 * (3.0 * z * z - 1.0);
  out[7] = 1.0925484305920792 * x * z;
  out[8] = 0.5462742152960396 * (x * x - y * y);
}

}  // namespace

// On the map's square e in [-1, 1]^2 the point p = ((e.x + e.y) / 2, (e.x - e.y) / 2) of the
// octahedron's face |x| + |y| + z = 1 subtends the solid angle dA_e / (2 |v|^3),
// v = (p.x, p.y, 1 - |p.x| - |p.y|): the face's area element sqrt(3) dA_p seen from the centre
// at distance |v| under the cosine 1 / (sqrt(3) |v|), and dA_p = dA_e / 2 for the turned
// square. Integrated by the midpoint rule on 256 x 256 points per cell, in double: the
// integrands are smooth but for the kinks of |p.x| and |p.y| along the square's diagonals,
// where the rule is first-order, and every basis function's integral over the hemisphere
// comes out right to 1e-6 of its magnitude (tests/realtime/gi1_test.cpp). Computed once.
std::vector<float> gi1_projection_table() {
  static const std::vector<float> table = [] {
    constexpr int kSub = 256;
    const uint32_t n = GIQ_GI1_PROBE;
    const double h = 2.0 / (n * kSub);
    std::vector<float> table(size_t(GIQ_GI1_SH) * GIQ_GI1_CELLS);
    for (uint32_t c = 0; c < GIQ_GI1_CELLS; ++c) {
      double sum[GIQ_GI1_SH] = {};
      for (int j = 0; j < kSub; ++j)
        for (int i = 0; i < kSub; ++i) {
          const double ex = -1.0 + (c % n) * 2.0 / n + (i + 0.5) * h;
          const double ey = -1.0 + (c / n) * 2.0 / n + (j + 0.5) * h;
          const double px = 0.5 * (ex + ey), py = 0.5 * (ex - ey);
          const double vz = 1.0 - std::abs(px) - std::abs(py);
          const double len = std::sqrt(px * px + py * py + vz * vz);
          const double solid_angle = h * h / (2.0 * len * len * len);
          double y[GIQ_GI1_SH];
          sh_basis(px / len, py / len, vz / len, y);
          for (uint32_t k = 0; k < GIQ_GI1_SH; ++k) sum[k] += y[k] * solid_angle;
        }
      for (uint32_t k = 0; k < GIQ_GI1_SH; ++k) table[k * GIQ_GI1_CELLS + c] = float(sum[k]);
    }
    return table;
  }();
  return table;
}

}  // namespace giq::realtime
