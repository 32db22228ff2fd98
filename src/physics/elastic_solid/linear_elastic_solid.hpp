#pragma once
// The 2D linear elastic bulk solid of the FSI model problems (Banks, Henshaw & Schwendeman,
// MP-VE: the solid 0 < y < Hbar, periodic in x), in displacement form on a uniform node grid,
// second order in space and time (kernels/elastic/elastic_wave_step.hpp). Runs alone with
// Dirichlet rows; the couplings will set the interface row from their own conditions.
// Time levels rotate in place: after step(), displacement() is u at time(), previous() at
// time() - dt. Fields hold grid row j at storage row j + 1 (row 0: the ghost line below the
// bottom boundary, used by the traction condition).
#include <sstream>
#include <vector>
#include <stdexcept>
#include <utility>

#include "kernels/elastic/elastic_wave_step.hpp"

namespace amphora::physics::elastic_solid {

// The grid, material and update of the kernel layer, as this module's vocabulary.
using kernels::elastic::elastic_wave_dt_limit;
using kernels::elastic::elastic_wave_step;
using kernels::elastic::ElasticGrid;
using kernels::elastic::ElasticMaterial;
using kernels::elastic::NodeField;

template <class ExecSpace>
class LinearElasticSolid {
 public:
  using Mem = typename ExecSpace::memory_space;
  using Field = NodeField<Mem>;

  /// Throws std::invalid_argument for rho, mu <= 0, lambda + mu <= 0 (not elliptic), grids
  /// below 3 x 2 cells, or dt above the stability limit (the message names it).
  LinearElasticSolid(const ElasticGrid& g, const ElasticMaterial& m, double dt,
                     const ExecSpace& exec = ExecSpace())
      : g_(g), m_(m), dt_(dt), exec_(exec) {
    auto fail = [](const std::string& what) {
      throw std::invalid_argument("elastic solid: " + what);
    };
    if (!(m.rho > 0)) fail("density must be > 0");
    if (!(m.mu > 0)) fail("mu must be > 0");
    if (!(m.lambda + m.mu > 0)) fail("lambda + mu must be > 0");
    if (g.nx < 3 || g.ny < 2 || !(g.hx > 0) || !(g.hy > 0))
      fail("grid needs nx >= 3, ny >= 2, h > 0");
    const double limit = elastic_wave_dt_limit(g, m);
    if (!(dt > 0) || dt > limit) {
      std::ostringstream s;
      s << "dt = " << dt << " outside (0, " << limit << "], the leapfrog stability limit";
      fail(s.str());
    }
    u_old_ = Field("amphora::elastic::u_old", g.ny + 2, g.nx);
    u_ = Field("amphora::elastic::u", g.ny + 2, g.nx);
    u_new_ = Field("amphora::elastic::u_new", g.ny + 2, g.nx);
    f_ = Field("amphora::elastic::f", g.ny + 2, g.nx);
  }

  const ElasticGrid& grid() const { return g_; }
  const ElasticMaterial& material() const { return m_; }
  double dt() const { return dt_; }
  double time() const { return t_; }
  Field displacement() const { return u_; }
  Field previous() const { return u_old_; }
  /// The body force at time(): filled by the caller before step().
  Field forcing() const { return f_; }

  /// Sets u at t and at t - dt from a device functor value(x, y, t, c).
  template <class Value>
  void set_state(double t, const Value& value) {
    t_ = t;
    fill(u_, value, t);
    fill(u_old_, value, t - dt_);
  }

  /// Restores u at t and t - dt from host copies of displacement() and previous().
  void restore(double t, const std::vector<double>& u, const std::vector<double>& u_old) {
    if (u.size() != u_.size() || u_old.size() != u_old_.size())
      throw std::invalid_argument("elastic solid: restored fields have the wrong size");
    auto hu = Kokkos::create_mirror_view(u_);
    auto ho = Kokkos::create_mirror_view(u_old_);
    for (size_t k = 0; k < u.size(); ++k) {
      hu.data()[k] = u[k];
      ho.data()[k] = u_old[k];
    }
    Kokkos::deep_copy(u_, hu);
    Kokkos::deep_copy(u_old_, ho);
    t_ = t;
  }

  /// Fills f from a device functor force(x, y, t, c) at time().
  template <class Force>
  void set_forcing(const Force& force) {
    fill(f_, force, t_);
  }

  /// One leapfrog step; the boundary rows 0 and ny of the new level from boundary(x, y, t, c).
  template <class Boundary>
  void step(const Boundary& boundary) {
    elastic_wave_step(exec_, g_, m_, dt_, u_old_, u_, f_, u_new_, 1);
    set_rows(boundary, true);
    rotate();
  }

  /// One leapfrog step with the traction (sigma_xy, sigma_yy) = traction(x, t, c) given on the
  /// bottom boundary y = 0 (the fluid side in the FSI problems) and the top row from
  /// boundary(x, y, t, c). The traction enters through the ghost line (centred differences:
  /// mu (u_y + v_x) = sigma_xy, (lambda + 2 mu) v_y + lambda u_x = sigma_yy), second order.
  template <class Traction, class Boundary>
  void step_with_bottom_traction(const Traction& traction, const Boundary& boundary) {
    const ElasticGrid g = g_;
    const ElasticMaterial m = m_;
    const double t = t_;
    const Field u = u_;
    const kernels::AnySpaceCall<Traction> traction_at{traction};
    Kokkos::parallel_for(
        "amphora::elastic::traction_ghosts", kernels::RangePolicy<ExecSpace>(exec_, 0, g.nx),
        KOKKOS_LAMBDA(int i) {
          const int e = i + 1 < g.nx ? i + 1 : 0, w = i > 0 ? i - 1 : g.nx - 1;
          const double ux = (u(1, e, 0) - u(1, w, 0)) / (2 * g.hx);
          const double vx = (u(1, e, 1) - u(1, w, 1)) / (2 * g.hx);
          const double x = i * g.hx;
          u(0, i, 0) = u(2, i, 0) - 2 * g.hy * (traction_at(x, t, 0) / m.mu - vx);
          u(0, i, 1) = u(2, i, 1) -
                       2 * g.hy * (traction_at(x, t, 1) - m.lambda * ux) / (m.lambda + 2 * m.mu);
        });
    elastic_wave_step(exec_, g_, m_, dt_, u_old_, u_, f_, u_new_, 0);
    set_rows(boundary, false);
    rotate();
  }

 public:  // (CUDA: extended lambdas may not live in private member functions)
  /// Rows ny (and 0 if `bottom`) of the new level from boundary(x, y, t + dt, c).
  template <class Boundary>
  void set_rows(const Boundary& boundary, bool bottom) {
    const ElasticGrid g = g_;
    const double t = t_ + dt_;
    const Field un = u_new_;
    const kernels::AnySpaceCall<Boundary> boundary_at{boundary};
    Kokkos::parallel_for(
        "amphora::elastic::boundary_rows",
        Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<2>>(exec_, {bottom ? 0 : 1, 0}, {2, g.nx}),
        KOKKOS_LAMBDA(int side, int i) {
          const int j = side == 0 ? 0 : g.ny;
          for (int c = 0; c < 2; ++c) un(j + 1, i, c) = boundary_at(i * g.hx, j * g.hy, t, c);
        });
  }

  void rotate() {
    std::swap(u_old_, u_);  // u_old <- u
    std::swap(u_, u_new_);  // u <- u_new (the old u_old becomes scratch)
    t_ += dt_;
  }

  template <class Value>
  void fill(const Field& field, const Value& value, double t) const {
    const ElasticGrid g = g_;
    const kernels::AnySpaceCall<Value> value_at{value};
    Kokkos::parallel_for(
        "amphora::elastic::fill",
        Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<2>>(exec_, {0, 0}, {g.ny + 1, g.nx}),
        KOKKOS_LAMBDA(int j, int i) {
          for (int c = 0; c < 2; ++c) field(j + 1, i, c) = value_at(i * g.hx, j * g.hy, t, c);
        });
  }

 private:
  ElasticGrid g_;
  ElasticMaterial m_;
  double dt_, t_ = 0;
  ExecSpace exec_;
  Field u_old_, u_, u_new_, f_;
};

}  // namespace amphora::physics::elastic_solid
