#pragma once
// Viscous incompressible flow (linearised: unsteady Stokes) in a channel periodic in x,
// -H < y < 0, with the velocity given on both walls:
//   rho v_t + grad p = mu lap v + f,  div v = 0.
// Staggered (MAC) grid: p at cell centres, u on x-faces, v on y-faces (the wall faces carry the
// data), so the discrete divergence of the projected velocity vanishes to round-off.
// Fractional step, second order (Brown, Cortez & Minion, J. Comput. Phys. 168, 2001, the
// rotational incremental pressure-correction scheme): Crank–Nicolson velocity predictor with
// the old pressure gradient, pressure increment phi from lap phi = rho/dt div v*, projection,
// p^{n+1/2} = p^{n-1/2} + phi - (mu/2) div v*. The pressure lives at half steps. The implicit
// matrices are fixed, so they are factored once (Eigen SparseLU).
#include <functional>
#include <memory>
#include <vector>

#include "physics/channel_flow/channel_pressure.hpp"

namespace amphora::channel {

/// The problem data: body force and wall velocities as functions of position and time.
struct StokesData {
  std::function<double(double x, double y, double t)> fx, fy;
  std::function<double(double x, double t)> u_bottom, v_bottom, u_top, v_top;
};

class ChannelStokes {
 public:
  /// Throws std::invalid_argument for rho, mu, dt <= 0 or a grid below 3 x 2 cells.
  ChannelStokes(const ChannelGrid& g, double rho, double mu, double dt);
  ~ChannelStokes();
  ChannelStokes(ChannelStokes&&) noexcept;

  // Coordinates of the unknowns (cell (i, j): x in [i hx, (i+1) hx], y in -H + [j hy, (j+1) hy]).
  double u_x(int i) const { return i * g_.hx(); }
  double u_y(int j) const { return -g_.depth + (j + 0.5) * g_.hy(); }
  double v_x(int i) const { return (i + 0.5) * g_.hx(); }
  double v_y(int j) const { return -g_.depth + j * g_.hy(); }  ///< j = 0 .. ny (walls at 0, ny)

  /// u: ny x nx, v: (ny+1) x nx, p at t - dt/2: ny x nx, all row-major (row = j).
  void set_state(double t, std::vector<double> u, std::vector<double> v, std::vector<double> p);
  void step(const StokesData& data);

  const std::vector<double>& u() const { return u_; }
  const std::vector<double>& v() const { return v_; }
  /// The pressure at time() - dt/2.
  const std::vector<double>& p() const { return p_; }
  /// max over cells of |div v| (the projection's leftover: round-off).
  double max_divergence() const;
  double time() const { return t_; }
  double dt() const { return dt_; }
  const ChannelGrid& grid() const { return g_; }

 private:
  struct Factors;
  ChannelGrid g_;
  double rho_, mu_, dt_, t_ = 0;
  std::vector<double> u_, v_, p_;
  std::unique_ptr<Factors> f_;
};

}  // namespace amphora::channel
