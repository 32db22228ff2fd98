#include "mesh/overlapping_grid_1d.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace amphora::mesh {

std::array<double, 3> quadratic_weights(double s) {
  return {(1.0 - s) * (1.0 - 0.5 * s), s * (2.0 - s), 0.5 * s * (s - 1.0)};
}

OverlappingGrid1D::OverlappingGrid1D(int cells, double interface, double overlap,
                                     double spacing_ratio) {
  const double h1 = 1.0 / cells;
  const int n1p1 = static_cast<int>(std::lround(interface * cells));  // N1 + 1
  const double xb = n1p1 * h1;
  const double xa = xb - overlap * h1;
  const int n2p1 = static_cast<int>(std::ceil((1.0 - xa) / (spacing_ratio * h1) - 1e-12));
  const double h2 = (1.0 - xa) / n2p1;
  if (n1p1 < 3 || n2p1 < 3) {
    throw std::invalid_argument(
        "overlapping grid: each component grid needs at least 3 cells; "
        "increase cells or move the interface");
  }
  grids_[0] = ComponentGrid1D{0.0, h1, n1p1 + 1, 1, n1p1};
  grids_[1] = ComponentGrid1D{xa, h2, n2p1 + 2, 1, n2p1 + 1};

  // U_{N1+1} at x_b from V_{-1}, V_0, V_1 (grid-2 storage 0, 1, 2).
  alpha_ = (xb - xa) / h2;
  // V_{-1} at x_a from U_{N1-1}, U_N1, U_{N1+1} (grid-1 storage N1-1 .. N1+1).
  beta_ = (xa - (xb - 2.0 * h1)) / h1;
  if (!(alpha_ >= 0.0 && alpha_ <= 2.0 && beta_ >= 0.0 && beta_ <= 2.0)) {
    std::ostringstream m;
    m << "overlapping grid: interpolation would extrapolate (alpha = " << alpha_
      << ", beta = " << beta_ << ", both must lie in [0, 2]); choose overlap and spacing_ratio "
      << "so that overlap <= 2 and overlap / spacing_ratio <= 2";
    throw std::invalid_argument(m.str());
  }
  interp_[0] = QuadraticInterpolation{n1p1, 0, quadratic_weights(alpha_)};
  interp_[1] = QuadraticInterpolation{0, n1p1 - 2, quadratic_weights(beta_)};
}

}  // namespace amphora::mesh
