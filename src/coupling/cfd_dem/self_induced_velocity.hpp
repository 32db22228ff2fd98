#pragma once
// The velocity a particle's own force induces in the fluid at the particle (unresolved
// coupling on cells not much larger than the particle), so that the drag closure can be given
// the undisturbed velocity instead. The steady Stokes response is the flow discretisation's
// own (in the manner of Horwitz & Mani, J. Comput. Phys. 318 (2016) 85): a unit load at one node
// of a wall-bounded box of the flow's cells gives the discrete Green's function g(o) between
// nodes o cells apart, and a force F spread with the Q1 basis phi_i of the particle's cell and
// read back there induces u_self = sum_ij phi_i phi_j g(x_i - x_j) F / rho. Inertia screens it:
// the Oseen factor of a Gaussian kernel of the same Stokes response (Balachandar, Liu & Lakhote,
// J. Comput. Phys. 376 (2019) 160), at the slip's Reynolds number over that width.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <Kokkos_Core.hpp>

#include "kernels/blas1.hpp"
#include "kernels/sumfac/qk_point_basis.hpp"
#include "mesh/hex/structured_hex_mesh.hpp"
#include "physics/ins_fem/ins_solver.hpp"

namespace amphora::coupling::cfd_dem {

/// The Oseen factor S(Re) of a Gaussian kernel of width sigma, Re = |U| sigma / nu: the
/// translating Stokeslet's velocity at the kernel's centre over the Stokes one,
/// int e^(-s^2/2) I(Re / s) ds / ((4/3) sqrt(pi / 2)) with I(a) = int_-1^1 (1 - m^2) /
/// (1 + a^2 m^2) dm (Fourier transform of the Oseen tensor along U).
inline double oseen_screening(double re) {
  const auto angular = [](double a) {
    if (a < 1e-3) return 4.0 / 3.0 - 4.0 * a * a / 15.0;
    return (1.0 + 1.0 / (a * a)) * 2.0 * std::atan(a) / a - 2.0 / (a * a);
  };
  // Simpson in t = ln s over s in [1e-6 min(1, Re), 12]: the integrand turns over at s ~ Re.
  const double t0 = std::log(1e-6 * std::min(1.0, re)), t1 = std::log(12.0);
  const int n = 4000;
  const double dt = (t1 - t0) / n;
  double sum = 0.0;
  for (int k = 0; k <= n; ++k) {
    const double s = std::exp(t0 + k * dt);
    const double w = (k == 0 || k == n) ? 1.0 : (k % 2 ? 4.0 : 2.0);
    sum += w * s * std::exp(-0.5 * s * s) * angular(re / s);
  }
  return sum * dt / 3.0 / (4.0 / 3.0 * std::sqrt(M_PI / 2.0));
}

/// The table a kernel reads: the discrete Green's function between the nodes of one cell and
/// the Oseen factor. Plain data, copied into kernels by value.
struct SelfInducedVelocity {
  static constexpr int n_screen = 81;  ///< log10 Re from -3 to 5 in steps of 0.1
  kernels::sumfac::QkPointBasis<3> basis;
  double g[27][3][3] = {};  ///< g[o][a][b]: u_a at x + o h from a unit load (per mass) b at x
  double nu = 1.0;
  /// The Q1 response to a moving force is screened as if its kernel were this much wider than
  /// its Stokes response says: a force towed at Re_h = U h / nu = 50 (CFL 0.1) gives it
  /// (test_cfd_dem_self_induced.cpp, TowedForceScreening).
  double oseen_width = 1.51;
  double screen[n_screen] = {};

  /// W (3 x 3, row-major): u_self = W F / rho for a force F at x, unscreened.
  KOKKOS_INLINE_FUNCTION void response(const double* x, double* W) const {
    int cell[3];
    double xi[3];
    basis.locate(x, cell, xi);
    double phi[3][2];  // the Q1 values per direction at xi
    for (int d = 0; d < 3; ++d) basis.values_1d(xi[d], phi[d]);
    for (int k = 0; k < 9; ++k) W[k] = 0.0;
    for (int i = 0; i < 8; ++i)
      for (int j = 0; j < 8; ++j) {
        double w = 1.0;
        int o = 0;
        for (int d = 2; d >= 0; --d) {
          const int a = (i >> d) & 1, b = (j >> d) & 1;
          w *= phi[d][a] * phi[d][b];
          o = 3 * o + (a - b + 1);
        }
        for (int k = 0; k < 9; ++k) W[k] += w * g[o][k / 3][k % 3];
      }
  }
  /// The Oseen factor for slip speed u at a response W: a Gaussian's of the width whose Stokes
  /// response is tr W / 3, times oseen_width.
  KOKKOS_INLINE_FUNCTION double screening(const double* W, double u) const {
    const double w = (W[0] + W[4] + W[8]) / 3.0;
    const double sigma = oseen_width * 0.7978845608028654 / (6.0 * M_PI * nu * w);  // sqrt(2/pi)
    const double re = u * sigma / nu;
    if (!(re > 1e-3)) return 1.0;
    const double t = (kernels::math::log(re) / 2.302585092994046 + 3.0) * 10.0;
    if (t >= n_screen - 1) return screen[n_screen - 1] * 1e5 / re;  // S ~ 1 / Re
    const int k = static_cast<int>(t);
    return screen[k] + (t - k) * (screen[k + 1] - screen[k]);
  }
};

/// g (as SelfInducedVelocity::g) of a box of `cells`^3 cells of widths h with no-slip walls:
/// the steady Stokes velocity at the centre node's 27 neighbours from a unit load at it, one
/// solve per direction.
template <class ExecSpace>
void walled_box_response(const double* h, double nu, int cells, double (&g)[27][3][3]) {
  mesh::hex::StructuredHexMesh<3> m;
  m.cells = {cells, cells, cells};
  for (int d = 0; d < 3; ++d) m.upper[d] = cells * h[d];
  physics::ins_fem::InsOptions o;
  o.model = physics::ins_fem::FlowModel::vans_a;  // eps = 1: the particles' load enters
  o.nu = nu;
  o.tolerance = 1e-12;
  physics::ins_fem::InsSolver<3, ExecSpace> probe(m, 1, o);
  using Vector = typename physics::ins_fem::InsSolver<3, ExecSpace>::Vector;
  const long n = probe.n_dofs();
  const std::vector<double> x =
      probe.space().interpolate([](const mesh::hex::Point3& p, int c) { return p[c]; }, 3);
  long near[27];
  for (int k = 0; k < 27; ++k) {
    const int off[3] = {k % 3 - 1, (k / 3) % 3 - 1, k / 9 - 1};  // k = 9 (oz+1) + 3 (oy+1) + ox+1
    near[k] = -1;
    for (long i = 0; i < n; ++i) {
      bool at = true;
      for (int d = 0; d < 3; ++d)
        at = at && std::abs(x[d * n + i] - (cells / 2 + off[d]) * h[d]) < 1e-9 * h[d];
      if (at) near[k] = i;
    }
    if (near[k] < 0) throw std::logic_error("cfd_dem: the probe's centre nodes are missing");
  }
  const ExecSpace exec;
  Vector ones("amphora::cfd_dem::probe_eps", n), zeros("amphora::cfd_dem::probe_drag", n);
  kernels::blas1::fill(exec, ones, 1.0);
  probe.set_void_fraction(ones);
  probe.set_drag(zeros);
  const double f0 = nu * h[0] * 1e-6;  // small: the response's own advection is nil
  for (int b = 0; b < 3; ++b) {
    Vector load("amphora::cfd_dem::probe_load", 3 * n);
    Kokkos::deep_copy(Kokkos::subview(load, b * n + near[13]), f0);
    probe.set_particle_load(load);
    probe.set_state(std::vector<double>(4 * n, 0.0));
    if (!probe.solve_steady(1e-6, 5).converged)
      throw std::runtime_error(
          "cfd_dem: the self-induced velocity's Stokes probe did not converge");
    const auto u = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), probe.velocity());
    for (int k = 0; k < 27; ++k)
      for (int a = 0; a < 3; ++a) g[k][a][b] = u(a * n + near[k]) / f0;
  }
}

/// The table for Q1 cells of `basis` (kinematic viscosity nu). The walls of a box of M cells
/// lower the response near its centre by c / M (the Stokeslet's 1/r tail cut off; c the same for
/// all 27 offsets): boxes of M and 2 M give the unbounded response as 2 g_2M - g_M. Throws
/// std::invalid_argument unless the cells are Q1.
template <class ExecSpace>
SelfInducedVelocity self_induced_velocity(const kernels::sumfac::QkPointBasis<3>& basis, double nu,
                                          int box_cells = 8) {
  if (basis.lattice.degree != 1)
    throw std::invalid_argument(
        "cfd_dem: self_induced_correction needs Q1 cells (degree = 1), got degree " +
        std::to_string(basis.lattice.degree));
  SelfInducedVelocity t;
  t.basis = basis;
  t.nu = nu;
  for (int k = 0; k < SelfInducedVelocity::n_screen; ++k)
    t.screen[k] = oseen_screening(std::pow(10.0, -3.0 + 0.1 * k));
  double coarse[27][3][3], fine[27][3][3];
  walled_box_response<ExecSpace>(basis.h, nu, box_cells, coarse);
  walled_box_response<ExecSpace>(basis.h, nu, 2 * box_cells, fine);
  for (int k = 0; k < 27; ++k)
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) t.g[k][a][b] = 2.0 * fine[k][a][b] - coarse[k][a][b];
  return t;
}

}  // namespace amphora::coupling::cfd_dem
