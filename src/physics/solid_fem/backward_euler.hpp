#pragma once
// Implicit backward Euler for the lumped-mass tetrahedral solid. x_{n+1} minimises the
// incremental potential E(x) = c/2 |x - x_n|_M^2 - (x - x_n) . M (v_n/dt + g) + Psi(x),
// c = (1 + alpha dt)/dt^2 with mass damping alpha, by Newton's method on the definite part of
// the Hessian c M + K (kernels/solid/tet_stiffness; Teran et al., SCA 2005): each Newton step
// solved by Jacobi-preconditioned conjugate gradients to a relative tolerance (inexact Newton)
// and backtracked until E decreases enough (Armijo). Pinned nodes stay; v_{n+1} = (x_{n+1} -
// x_n)/dt. Only scalars (dot products, energies) come back to the host.
#include <algorithm>
#include <cmath>

#include "kernels/blas1.hpp"
#include "kernels/solid/tet_stiffness.hpp"

namespace amphora::physics::solid_fem {

struct NewtonOptions {
  double tolerance = 1e-6;     ///< |gradient| relative to its value at x_n
  double absolute = 0.0;       ///< |gradient| small enough in any case [N] (round-off's level)
  int max_iterations = 50;     ///< Newton steps
  double cg_tolerance = 1e-3;  ///< CG's residual relative to the Newton gradient
  int max_cg = 2000;
};

struct NewtonReport {
  int iterations = 0, cg_iterations = 0;
  double initial_residual = 0.0, residual = 0.0;
  bool converged = false;
};

// A named namespace, not an anonymous one (CUDA extended lambdas; Kokkos issue #1547).
namespace backward_euler_detail {

template <class ExecSpace, class Nodes>
double dot(const ExecSpace& exec, const Nodes& a, const Nodes& b) {
  double s = 0.0;
  Kokkos::parallel_reduce(
      "amphora::solid::be::dot", kernels::RangePolicy<ExecSpace>(exec, 0, int(a.extent(0))),
      KOKKOS_LAMBDA(const int i, double& acc) {
        acc += a(i, 0) * b(i, 0) + a(i, 1) * b(i, 1) + a(i, 2) * b(i, 2);
      },
      s);
  return s;
}

/// y = a x + b y (node vectors).
template <class ExecSpace, class Nodes>
void axpby(const ExecSpace& exec, double a, const Nodes& x, double b, const Nodes& y) {
  Kokkos::parallel_for(
      "amphora::solid::be::axpby", kernels::RangePolicy<ExecSpace>(exec, 0, int(x.extent(0))),
      KOKKOS_LAMBDA(const int i) {
        for (int d = 0; d < 3; ++d) y(i, d) = a * x(i, d) + b * y(i, d);
      });
}

}  // namespace backward_euler_detail

/// The solid's data the step reads (views shared with TetSolid).
template <class Mem>
struct ImplicitSystem {
  kernels::solid::Material material;
  kernels::solid::TetRestShapes<Mem> rest;
  Kokkos::View<int* [4], Mem> tets;
  Kokkos::View<double*, Mem> mass;
  Kokkos::View<char*, Mem> pinned;
  Kokkos::View<double* [3], Mem> external;  ///< nodal loads [N]; empty: none
  double gravity[3] = {0.0, 0.0, 0.0};
  double damping = 0.0;
};

template <class ExecSpace>
class BackwardEuler {
 public:
  using Mem = typename ExecSpace::memory_space;
  using Nodes = Kokkos::View<double* [3], Mem>;

  BackwardEuler(int n_nodes, int n_tets, const NewtonOptions& o, const ExecSpace& exec)
      : o_(o), exec_(exec), k_(kernels::solid::allocate_stiffness<Mem>(n_tets)) {
    for (Nodes* v : {&x0_, &g_, &dx_, &r_, &z_, &p_, &q_, &diag_, &trial_, &f_})
      *v = Nodes("amphora::solid::be::work", n_nodes);
    J_ = Kokkos::View<double*, Mem>("amphora::solid::be::J", n_tets);
  }

  /// x: x_n in, x_{n+1} out; v: v_n in, v_{n+1} out.
  NewtonReport step(const ImplicitSystem<Mem>& s, double dt, const Nodes& x, const Nodes& v) {
    using namespace backward_euler_detail;
    const double c = (1.0 + s.damping * dt) / (dt * dt);
    Kokkos::deep_copy(exec_, x0_, x);
    if (unit_strain_energy_ == 0.0)
      unit_strain_energy_ =
          kernels::blas1::sum(exec_, s.rest.volume) * (s.material.lambda + 2.0 * s.material.mu);
    NewtonReport rep;
    gradient(s, c, dt, x, v);
    rep.initial_residual = rep.residual = std::sqrt(dot(exec_, g_, g_));
    double energy = incremental_energy(s, c, dt, x, v);
    const double goal = std::max(o_.tolerance * rep.initial_residual, o_.absolute);
    while (rep.residual > goal && rep.iterations < o_.max_iterations) {
      rep.cg_iterations += solve_newton_step(s, c, x, rep.residual);
      energy = line_search(s, c, dt, x, v, energy);
      gradient(s, c, dt, x, v);
      rep.residual = std::sqrt(dot(exec_, g_, g_));
      ++rep.iterations;
    }
    rep.converged = rep.residual <= goal;
    axpby(exec_, 1.0 / dt, x, 0.0, v);
    axpby(exec_, -1.0 / dt, x0_, 1.0, v);
    return rep;
  }
  /// x_n of the last step.
  const Nodes& start() const { return x0_; }

  // The pieces of a step (public: CUDA forbids extended lambdas in private members).

  /// g = c M (x - x_n) - M (v_n/dt + gravity) - f(x) - f_ext, zero at pinned nodes.
  void gradient(const ImplicitSystem<Mem>& s, double c, double dt, const Nodes& x, const Nodes& v) {
    if (s.external.extent(0) > 0)
      Kokkos::deep_copy(exec_, f_, s.external);
    else
      Kokkos::deep_copy(exec_, f_, 0.0);
    kernels::solid::tet_forces(exec_, s.material, s.rest, s.tets, x, f_, J_);
    const auto g = g_, f = f_, x0 = x0_;
    const auto m = s.mass;
    const auto pinned = s.pinned;
    const double gx = s.gravity[0], gy = s.gravity[1], gz = s.gravity[2];
    Kokkos::parallel_for(
        "amphora::solid::be::gradient", kernels::RangePolicy<ExecSpace>(exec_, 0, n()),
        KOKKOS_LAMBDA(const int i) {
          const double grav[3] = {gx, gy, gz};
          for (int d = 0; d < 3; ++d)
            g(i, d) = pinned(i)
                          ? 0.0
                          : m(i) * (c * (x(i, d) - x0(i, d)) - v(i, d) / dt - grav[d]) - f(i, d);
        });
  }

  /// E(x) up to a constant.
  double incremental_energy(const ImplicitSystem<Mem>& s, double c, double dt, const Nodes& x,
                            const Nodes& v) {
    const auto x0 = x0_;
    const auto m = s.mass;
    const auto fe = s.external;
    const bool loaded = fe.extent(0) > 0;
    const double gx = s.gravity[0], gy = s.gravity[1], gz = s.gravity[2];
    double e = 0.0;
    Kokkos::parallel_reduce(
        "amphora::solid::be::inertia", kernels::RangePolicy<ExecSpace>(exec_, 0, n()),
        KOKKOS_LAMBDA(const int i, double& acc) {
          const double grav[3] = {gx, gy, gz};
          for (int d = 0; d < 3; ++d) {
            const double u = x(i, d) - x0(i, d);
            acc += m(i) * (0.5 * c * u * u - u * (v(i, d) / dt + grav[d])) -
                   (loaded ? u * fe(i, d) : 0.0);
          }
        },
        e);
    return e + kernels::solid::tet_elastic_energy(exec_, s.material, s.rest, s.tets, x);
  }

  /// dx ~ -(c M + K)^-1 g by Jacobi-preconditioned CG; returns its iterations.
  int solve_newton_step(const ImplicitSystem<Mem>& s, double c, const Nodes& x, double gnorm) {
    using namespace backward_euler_detail;
    Kokkos::deep_copy(exec_, diag_, 0.0);
    kernels::solid::tet_stiffness(exec_, s.material, s.rest, s.tets, x, true, k_, diag_);
    const auto diag = diag_, r = r_, z = z_, g = g_, dx = dx_;
    const auto m = s.mass;
    Kokkos::parallel_for(
        "amphora::solid::be::cg_start", kernels::RangePolicy<ExecSpace>(exec_, 0, n()),
        KOKKOS_LAMBDA(const int i) {
          for (int d = 0; d < 3; ++d) {
            diag(i, d) += c * m(i);
            r(i, d) = -g(i, d);
            z(i, d) = r(i, d) / diag(i, d);
            dx(i, d) = 0.0;
          }
        });
    Kokkos::deep_copy(exec_, p_, z_);
    double rz = dot(exec_, r_, z_);
    int it = 0;
    while (it < o_.max_cg && std::sqrt(dot(exec_, r_, r_)) > o_.cg_tolerance * gnorm) {
      apply_hessian(s, c, p_, q_);
      const double alpha = rz / dot(exec_, p_, q_);
      axpby(exec_, alpha, p_, 1.0, dx_);
      axpby(exec_, -alpha, q_, 1.0, r_);
      precondition(z_, r_);
      const double rz_new = dot(exec_, r_, z_);
      axpby(exec_, 1.0, z_, rz_new / rz, p_);
      rz = rz_new;
      ++it;
    }
    return it;
  }

  /// out = (c M + K) in, zero at pinned nodes.
  void apply_hessian(const ImplicitSystem<Mem>& s, double c, const Nodes& in, const Nodes& out) {
    Kokkos::deep_copy(exec_, out, 0.0);
    kernels::solid::tet_stiffness_apply(exec_, s.rest, s.tets, k_, in, out);
    const auto m = s.mass;
    const auto pinned = s.pinned;
    Kokkos::parallel_for(
        "amphora::solid::be::mass", kernels::RangePolicy<ExecSpace>(exec_, 0, n()),
        KOKKOS_LAMBDA(const int i) {
          for (int d = 0; d < 3; ++d) out(i, d) = pinned(i) ? 0.0 : out(i, d) + c * m(i) * in(i, d);
        });
  }

  void precondition(const Nodes& z, const Nodes& r) {
    const auto diag = diag_;
    Kokkos::parallel_for(
        "amphora::solid::be::jacobi", kernels::RangePolicy<ExecSpace>(exec_, 0, n()),
        KOKKOS_LAMBDA(const int i) {
          for (int d = 0; d < 3; ++d) z(i, d) = r(i, d) / diag(i, d);
        });
  }

  /// x += a dx with a = 1, 1/2, ... until E falls by at least 1e-4 a |g . dx| (Armijo); the
  /// last halving is taken if none does. A full step whose predicted decrease |g . dx| is
  /// below E's round-off is taken as it is (E cannot tell it from no step): the elastic
  /// energy cancels terms of the size of a unit strain's, so its round-off is about 1e-16
  /// V (lambda + 2 mu), and 1e-15 of that is the threshold. Returns E at the new x.
  double line_search(const ImplicitSystem<Mem>& s, double c, double dt, const Nodes& x,
                     const Nodes& v, double energy) {
    using namespace backward_euler_detail;
    const double slope = dot(exec_, g_, dx_);
    const bool below_round_off = std::abs(slope) < 1e-15 * unit_strain_energy_;
    double a = 1.0, e = energy;
    for (int k = 0; k < 12; ++k, a *= 0.5) {
      Kokkos::deep_copy(exec_, trial_, x);
      axpby(exec_, a, dx_, 1.0, trial_);
      e = incremental_energy(s, c, dt, trial_, v);
      if (below_round_off || e <= energy + 1e-4 * a * slope) break;
    }
    Kokkos::deep_copy(exec_, x, trial_);
    return e;
  }

  int n() const { return static_cast<int>(x0_.extent(0)); }

 private:
  NewtonOptions o_;
  ExecSpace exec_;
  kernels::solid::TetStiffness<Mem> k_;
  Nodes x0_, g_, dx_, r_, z_, p_, q_, diag_, trial_, f_;
  Kokkos::View<double*, Mem> J_;
  double unit_strain_energy_ = 0.0;  ///< V (lambda + 2 mu): the scale of E's round-off
};

}  // namespace amphora::physics::solid_fem
