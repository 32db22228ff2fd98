#pragma once
// A one-dimensional overlapping (composite) grid of two component grids, as in the Overture
// talk (Henshaw; ../shared/seeds/000): grid 1 covers [0, x_b] and ends in an interpolation
// point, grid 2 covers [x_a, 1] and starts with one; each interpolation point takes a
// three-point quadratic Lagrange interpolant from the other grid.
#include <array>

namespace amphora::mesh {

/// A uniform 1D grid stored as one array: x(s) = x0 + s dx for storage index s.
struct ComponentGrid1D {
  double x0 = 0.0;
  double dx = 0.0;
  int size = 0;   ///< storage points, ghosts and interpolation points included
  int first = 0;  ///< discretisation-equation points are [first, last)
  int last = 0;
  double x(int s) const { return x0 + s * dx; }
};

/// u(target) = sum_k w[k] * u_donor(donor_first + k).
struct QuadraticInterpolation {
  int target = 0;
  int donor_first = 0;
  std::array<double, 3> w{};
};

/// Weights of the quadratic through three equally spaced points at offsets 0, 1, 2 evaluated at
/// offset s (s in [0, 2] interpolates): the talk's (1-s)(1-s/2), s(2-s), s(s-1)/2.
std::array<double, 3> quadratic_weights(double s);

class OverlappingGrid1D {
 public:
  /// `cells`: grid-1 cells per unit length (h1 = 1/cells); `interface`: right end x_b of grid 1;
  /// `overlap`: x_b - x_a in units of h1; `spacing_ratio`: target h2/h1.
  /// Throws std::invalid_argument if the interpolation stencils would extrapolate.
  OverlappingGrid1D(int cells, double interface, double overlap, double spacing_ratio);

  /// Grid 1: storage 0 = Dirichlet point x = 0, 1..N1 interior, N1+1 interpolation point.
  /// Grid 2: storage 0 = interpolation point, 1..N2+1 interior with the Neumann boundary point
  /// x = 1 last, N2+2 the ghost point beyond it.
  const ComponentGrid1D& grid(int g) const { return grids_[g]; }
  /// Interpolation of grid g's interpolation point from the other grid.
  const QuadraticInterpolation& interpolation(int g) const { return interp_[g]; }
  double alpha() const { return alpha_; }
  double beta() const { return beta_; }

 private:
  std::array<ComponentGrid1D, 2> grids_;
  std::array<QuadraticInterpolation, 2> interp_;
  double alpha_ = 0.0, beta_ = 0.0;
};

}  // namespace amphora::mesh
