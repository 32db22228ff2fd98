#pragma once
// Pressure of linearised inviscid incompressible flow in a channel periodic in x, -H < y < 0:
//   lap p = 0,  p_y = 0 at the wall y = -H,  alpha p + B p_y = g(x) at the top y = 0,
// where the top is the fluid-structure interface and B is a periodic 5-point operator along x
// (B = identity: Neumann data; B = beta I: the Robin condition; the beam coupling's AMP
// condition adds the beam's implicit stiffness to B). The fluid's momentum equation
// rho v_t = -grad p then fixes the flow; at the interface it says rho eta_tt = -p_y, which is
// all the beam coupling needs (coupling/fsi/beam_channel_fsi.hpp). A Neumann top (alpha = 0)
// leaves p up to a constant: the caller's condition on the mean picks it.
// Discretisation: nodes (x_i, y_j) = (i L/nx, -H + j H/ny), j = 0..ny, 5-point Laplacian,
// both boundary conditions by centred differences through a ghost line (second order): the
// bottom ghost is eliminated, the top ghost row (j = ny + 1) is kept as unknowns because B
// couples it along x. The matrix is factored once (Eigen SparseLU): every step only changes g.
#include <array>
#include <memory>
#include <vector>

namespace amphora::physics::channel_flow {

struct ChannelGrid {
  int nx = 32, ny = 16;
  double length = 1.0, depth = 1.0;
  double hx() const { return length / nx; }
  double hy() const { return depth / ny; }
};

class ChannelPressure {
 public:
  /// top_operator: B's coefficients at x offsets -2..2. Throws std::invalid_argument for
  /// alpha < 0, a zero B, or a grid below 3 x 2 cells.
  ChannelPressure(const ChannelGrid& g, double alpha, const std::array<double, 5>& top_operator);
  ~ChannelPressure();
  ChannelPressure(ChannelPressure&&) noexcept;

  /// p (row-major, (ny+2) x nx: rows 0..ny are the nodes, row ny at the interface, row ny+1
  /// the ghost line) for the top data g (nx values). With alpha = 0 the constant is chosen so
  /// that the interface mean of p is `mean_top`.
  std::vector<double> solve(const std::vector<double>& g, double mean_top = 0.0) const;

  /// p_y at the interface (centred through the ghost line) of a solution of solve().
  std::vector<double> top_normal_derivative(const std::vector<double>& p) const;
  const ChannelGrid& grid() const { return g_; }

 private:
  struct Factor;
  ChannelGrid g_;
  double alpha_;
  std::unique_ptr<Factor> factor_;
};

}  // namespace amphora::physics::channel_flow
