#pragma once
// MPRGP, modified proportioning with reduced gradient projections (Dostál & Schöberl, Comput.
// Optim. Appl. 30 (2005) 23; Dostál, Optimal Quadratic Programming Algorithms, Springer 2009,
// sec. 5.8), for a box-constrained SPD problem
//   min 1/2 x^T A x - b^T x  subject to  lower <= x_i <= upper:
// CG on the free nodes while their gradient outweighs the chopped one (the part that would
// lift nodes off their bounds), a step to the box's face and a projected gradient step where
// CG would leave the box, and proportioning steps along the chopped gradient. It converges for
// any SPD A; a primal-dual active set (deal.II's step-41) can cycle when A is not an M-matrix,
// as a consistent mass matrix is not. A is only applied (`apply(exec, x, y)`, which on several
// ranks updates x's ghosts itself): the solver works on the owned prefix of each vector and
// reduces through `ranks` (sum and min over the ranks, `owned` entries here).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>

#include <Kokkos_Core.hpp>

#include "kernels/blas1.hpp"
#include "kernels/spaces.hpp"

namespace amphora::solvers {

struct BoxControl {
  double lower = 0.0, upper = 1.0;
  /// Stop when the projected gradient's norm is at most this times |b|.
  double relative_tolerance = 1e-12;
  int max_iterations = 1000;
  /// The fixed step of the gradient projections, in (0, 2 / lambda_max(A)].
  double step = 1.0;
  /// Gamma: proportional while |chopped gradient| <= Gamma |reduced free gradient| (Dostál's 1).
  double gamma = 1.0;
};

struct BoxResult {
  bool converged = false;
  int iterations = 0;               ///< CG, expansion and proportioning steps
  double projected_gradient = 0.0;  ///< its norm at the end, over |b|
  long at_lower = 0, at_upper = 0;  ///< nodes on each bound at the end, over all ranks
};

/// One rank: the owned entries are the whole vector.
struct OneRank {
  long owned = 0;
  double sum(double v) const { return v; }
  double min(double v) const { return v; }
};

/// The vectors a repeated solve keeps (reallocated only when the length changes).
template <class View>
struct BoxWorkspace {
  View g, p, q, f;
  void reserve(std::size_t n) {
    if (g.extent(0) == n) return;
    g = View(std::string("amphora::mprgp::g"), n);
    p = View(std::string("amphora::mprgp::p"), n);
    q = View(std::string("amphora::mprgp::q"), n);
    f = View(std::string("amphora::mprgp::f"), n);
  }
};

namespace mprgp_detail {

/// The free gradient g_i where lower < x_i < upper, else 0.
KOKKOS_INLINE_FUNCTION double free_part(double x, double g, double lo, double hi) {
  return x > lo && x < hi ? g : 0.0;
}
/// The chopped gradient: the part of g at a bound that points into the box.
KOKKOS_INLINE_FUNCTION double chopped_part(double x, double g, double lo, double hi) {
  return x <= lo ? (g < 0.0 ? g : 0.0) : (x >= hi ? (g > 0.0 ? g : 0.0) : 0.0);
}
/// The reduced free gradient: the free gradient cut to what a step `a` can take in the box.
KOKKOS_INLINE_FUNCTION double reduced_part(double x, double g, double lo, double hi, double a) {
  const double f = free_part(x, g, lo, hi);
  if (f > 0.0) return (x - lo) / a < f ? (x - lo) / a : f;
  return (x - hi) / a > f ? (x - hi) / a : f;
}

}  // namespace mprgp_detail

/// sum over the ranks' owned entries of x y.
template <class ExecSpace, class View, class Ranks>
double owned_dot(const ExecSpace& exec, const View& x, const View& y, const Ranks& ranks) {
  const Kokkos::pair<long, long> owned(0, ranks.owned);
  return ranks.sum(kernels::blas1::dot(exec, Kokkos::subview(x, owned), Kokkos::subview(y, owned)));
}

/// |projected gradient|^2, |chopped|^2 and (reduced free gradient).(free gradient), summed
/// over the ranks.
template <class ExecSpace, class View, class Ranks>
void gradient_norms(const ExecSpace& exec, const View& x, const View& g, const BoxControl& c,
                    const Ranks& ranks, double& projected, double& chopped, double& reduced) {
  using namespace mprgp_detail;
  const double lo = c.lower, hi = c.upper, a = c.step;
  const auto policy = kernels::RangePolicy<ExecSpace>(exec, 0, static_cast<int>(ranks.owned));
  double s[3] = {0.0, 0.0, 0.0};
  Kokkos::parallel_reduce(
      "amphora::mprgp::projected", policy,
      KOKKOS_LAMBDA(int i, double& v) {
        const double p = free_part(x(i), g(i), lo, hi) + chopped_part(x(i), g(i), lo, hi);
        v += p * p;
      },
      s[0]);
  Kokkos::parallel_reduce(
      "amphora::mprgp::chopped", policy,
      KOKKOS_LAMBDA(int i, double& v) {
        const double p = chopped_part(x(i), g(i), lo, hi);
        v += p * p;
      },
      s[1]);
  Kokkos::parallel_reduce(
      "amphora::mprgp::reduced", policy,
      KOKKOS_LAMBDA(int i, double& v) {
        v += reduced_part(x(i), g(i), lo, hi, a) * free_part(x(i), g(i), lo, hi);
      },
      s[2]);
  projected = ranks.sum(s[0]), chopped = ranks.sum(s[1]), reduced = ranks.sum(s[2]);
}

/// The largest step a with lower <= x - a p <= upper, over the ranks.
template <class ExecSpace, class View, class Ranks>
double feasible_step(const ExecSpace& exec, const View& x, const View& p, const BoxControl& c,
                     const Ranks& ranks) {
  const double lo = c.lower, hi = c.upper;
  double m = HUGE_VAL;
  Kokkos::parallel_reduce(
      "amphora::mprgp::feasible_step",
      kernels::RangePolicy<ExecSpace>(exec, 0, static_cast<int>(ranks.owned)),
      KOKKOS_LAMBDA(int i, double& a) {
        const double s =
            p(i) > 0.0 ? (x(i) - lo) / p(i) : (p(i) < 0.0 ? (x(i) - hi) / p(i) : HUGE_VAL);
        if (s < a) a = s;
      },
      Kokkos::Min<double>(m));
  return ranks.min(m);
}

/// p = free gradient of (x, g) (+ beta p with beta != 0), or the chopped gradient.
template <class ExecSpace, class View>
void set_direction(const ExecSpace& exec, const View& x, const View& g, const BoxControl& c,
                   long owned, bool chopped, double beta, const View& p) {
  using namespace mprgp_detail;
  const double lo = c.lower, hi = c.upper;
  Kokkos::parallel_for(
      "amphora::mprgp::direction",
      kernels::RangePolicy<ExecSpace>(exec, 0, static_cast<int>(owned)), KOKKOS_LAMBDA(int i) {
        const double d = chopped ? chopped_part(x(i), g(i), lo, hi) : free_part(x(i), g(i), lo, hi);
        p(i) = beta != 0.0 ? d + beta * p(i) : d;
      });
}

/// x = P(x - a d) onto the box, with d the free gradient (expansion) or p (proportioning).
template <class ExecSpace, class View>
void projected_step(const ExecSpace& exec, const View& x, const View& d, double a,
                    const BoxControl& c, long owned, bool free_gradient) {
  using namespace mprgp_detail;
  const double lo = c.lower, hi = c.upper;
  Kokkos::parallel_for(
      "amphora::mprgp::project", kernels::RangePolicy<ExecSpace>(exec, 0, static_cast<int>(owned)),
      KOKKOS_LAMBDA(int i) {
        const double di = free_gradient ? free_part(x(i), d(i), lo, hi) : d(i);
        const double y = x(i) - a * di;
        x(i) = y < lo ? lo : (y > hi ? hi : y);
      });
}

/// Whether every owned entry of x lies within the bounds, on every rank.
template <class ExecSpace, class View, class Ranks>
bool inside_box(const ExecSpace& exec, const View& x, const BoxControl& c, const Ranks& ranks) {
  const double lo = c.lower, hi = c.upper;
  double outside = 0.0;
  Kokkos::parallel_reduce(
      "amphora::mprgp::outside",
      kernels::RangePolicy<ExecSpace>(exec, 0, static_cast<int>(ranks.owned)),
      KOKKOS_LAMBDA(int i, double& a) { a += x(i) < lo || x(i) > hi ? 1.0 : 0.0; }, outside);
  return ranks.sum(outside) == 0.0;
}

/// The nodes on each bound, over the ranks.
template <class ExecSpace, class View, class Ranks>
void count_bounds(const ExecSpace& exec, const View& x, const BoxControl& c, const Ranks& ranks,
                  BoxResult& r) {
  const double lo = c.lower, hi = c.upper;
  const auto policy = kernels::RangePolicy<ExecSpace>(exec, 0, static_cast<int>(ranks.owned));
  double n_lo = 0.0, n_hi = 0.0;
  Kokkos::parallel_reduce(
      "amphora::mprgp::at_lower", policy,
      KOKKOS_LAMBDA(int i, double& a) { a += x(i) <= lo ? 1.0 : 0.0; }, n_lo);
  Kokkos::parallel_reduce(
      "amphora::mprgp::at_upper", policy,
      KOKKOS_LAMBDA(int i, double& a) { a += x(i) >= hi ? 1.0 : 0.0; }, n_hi);
  r.at_lower = std::lround(ranks.sum(n_lo));
  r.at_upper = std::lround(ranks.sum(n_hi));
}

/// Solves the box-constrained problem from the guess in x (projected onto the box first; the
/// unconstrained solution is a good guess). Dostál's algorithm 5.8 with CG's steps along the
/// free gradient, without preconditioning.
template <class ExecSpace, class Operator, class View, class Ranks>
BoxResult mprgp(const ExecSpace& exec, const Operator& A, const View& b, const View& x,
                const BoxControl& c, const Ranks& ranks, BoxWorkspace<View>& work) {
  work.reserve(x.extent(0));
  const View g = work.g, p = work.p, q = work.q, f = work.f;
  const long n = ranks.owned;
  const auto gradient = [&]() {  // g = A x - b
    A.apply(exec, x, g);
    kernels::blas1::axpy(exec, -1.0, b, g);
  };
  projected_step(exec, x, x, 0.0, c, n, false);  // x = P(x)
  gradient();
  set_direction(exec, x, g, c, n, false, 0.0, p);
  const double target = c.relative_tolerance * std::sqrt(owned_dot(exec, b, b, ranks));
  BoxResult r;
  for (r.iterations = 0; r.iterations <= c.max_iterations; ++r.iterations) {
    double projected, chopped, reduced;
    gradient_norms(exec, x, g, c, ranks, projected, chopped, reduced);
    r.projected_gradient = std::sqrt(projected);
    if (r.projected_gradient <= target) {
      r.converged = true;
      break;
    }
    if (r.iterations == c.max_iterations) break;
    if (chopped <= c.gamma * c.gamma * reduced) {  // proportional: a CG step, if it fits
      A.apply(exec, p, q);
      const double pq = owned_dot(exec, p, q, ranks);
      const double a_cg = owned_dot(exec, g, p, ranks) / pq;
      const double a_f = feasible_step(exec, x, p, c, ranks);
      if (a_cg <= a_f) {
        kernels::blas1::axpy(exec, -a_cg, p, x);
        kernels::blas1::axpy(exec, -a_cg, q, g);
        set_direction(exec, x, g, c, n, false, 0.0, f);
        const double beta = owned_dot(exec, f, q, ranks) / pq;  // keeps p A-conjugate
        kernels::blas1::xpby(exec, f, -beta, p);
      } else {  // expansion: to the face, then a projected free-gradient step
        kernels::blas1::axpy(exec, -a_f, p, x);
        kernels::blas1::axpy(exec, -a_f, q, g);
        projected_step(exec, x, g, c.step, c, n, true);
        gradient();
        set_direction(exec, x, g, c, n, false, 0.0, p);
      }
    } else {  // proportioning: along the chopped gradient
      set_direction(exec, x, g, c, n, true, 0.0, p);
      A.apply(exec, p, q);
      const double a = owned_dot(exec, g, p, ranks) / owned_dot(exec, p, q, ranks);
      projected_step(exec, x, p, a, c, n, false);
      gradient();
      set_direction(exec, x, g, c, n, false, 0.0, p);
    }
  }
  count_bounds(exec, x, c, ranks, r);
  return r;
}

}  // namespace amphora::solvers
