#pragma once
// Preconditioned conjugate gradients (Hestenes & Stiefel 1952; Saad, Iterative Methods, alg.
// 9.1) on any operator with `apply(exec, x, y)` (y = A x) and any preconditioner with
// `apply(exec, r, z)` (z = M^-1 r). The inner product is a parameter so a distributed vector
// sums over ranks; vectors are rank-local 1D Views.
#include <cmath>
#include <cstddef>
#include <type_traits>
#include <utility>

#include "kernels/blas1.hpp"

namespace amphora::solvers {

/// An inner product with fused_update(exec, a, p, q, x, r) (x += a p, r -= a q, returning r.r
/// summed over ranks) lets CG do the three in one pass.
/// (It says so with a member `static constexpr bool fuses_cg_update = true`.)
template <class Inner, class = void>
struct has_fused_update : std::false_type {};
template <class Inner>
struct has_fused_update<Inner, std::void_t<decltype(Inner::fuses_cg_update)>>
    : std::bool_constant<Inner::fuses_cg_update> {};

/// An operator with apply_direction(exec, z, beta, p, q, dot) (p = z + beta p, p = z if beta is
/// 0; q = A p; returns p.q under `dot`) lets CG do the three in one sweep over its cells (see
/// MatrixFreeOperator::apply_direction).
template <class Operator, class ExecSpace, class View, class Inner, class = void>
struct has_fused_direction : std::false_type {};
template <class Operator, class ExecSpace, class View, class Inner>
struct has_fused_direction<
    Operator, ExecSpace, View, Inner,
    std::void_t<decltype(std::declval<const Operator&>().apply_direction(
        std::declval<const ExecSpace&>(), std::declval<const View&>(), 0.0,
        std::declval<const View&>(), std::declval<const View&>(), std::declval<const Inner&>()))>>
    : std::true_type {};

/// CG's direction step in three passes: p = z + beta p (p = z if beta is 0), q = A p; returns
/// p.q under `dot`. What an operator without apply_direction gets, and what one with it falls
/// back to where it cannot sweep.
template <class ExecSpace, class Operator, class View, class Inner>
double direction_in_passes(const ExecSpace& exec, const Operator& A, const View& z, double beta,
                           const View& p, const View& q, const Inner& dot) {
  kernels::blas1::xpby(exec, z, beta, p);
  A.apply(exec, p, q);
  return dot(exec, p, q);
}

struct SolverControl {
  int max_iterations = 1000;
  double relative_tolerance = 1e-8;  ///< stop when |r| <= rel * |b| ...
  double absolute_tolerance = 0.0;   ///< ... or |r| <= abs
};

struct SolverResult {
  bool converged = false;
  int iterations = 0;
  double initial_residual = 0.0;  ///< |b - A x0|
  double final_residual = 0.0;
  double rhs_norm = 0.0;
};

/// Rank-local Euclidean inner product.
struct LocalInnerProduct {
  static constexpr bool fuses_cg_update = true;
  template <class ExecSpace, class X, class Y>
  double operator()(const ExecSpace& exec, const X& x, const Y& y) const {
    return kernels::blas1::dot(exec, x, y);
  }
  template <class ExecSpace, class View>
  double fused_update(const ExecSpace& exec, double alpha, const View& p, const View& q,
                      const View& x, const View& r) const {
    return kernels::blas1::cg_update(exec, alpha, p, q, x, r);
  }
};

struct IdentityPreconditioner {
  template <class ExecSpace, class R, class Z>
  void apply(const ExecSpace& exec, const R& r, const Z& z) const {
    kernels::blas1::copy(exec, r, z);
  }
};

/// z = r / diag(A).
template <class View>
struct JacobiPreconditioner {
  View inverse_diagonal;
  template <class ExecSpace, class R, class Z>
  void apply(const ExecSpace& exec, const R& r, const Z& z) const {
    const View d = inverse_diagonal;
    Kokkos::parallel_for(
        "amphora::solvers::JacobiPreconditioner::apply",
        kernels::RangePolicy<ExecSpace>(exec, 0, static_cast<int>(z.extent(0))),
        KOKKOS_LAMBDA(int i) { z(i) = d(i) * r(i); });
  }
};

/// CG's four work vectors, kept by a caller that solves every time step so that no solve
/// allocates (on a GPU each allocation is a device malloc and free inside the step).
template <class View>
struct CgWorkspace {
  View r, z, p, q;
  /// Views of n entries, reallocated only when n changes; z is r when unpreconditioned.
  void reserve(std::size_t n, bool preconditioned) {
    if (r.extent(0) != n) {
      r = View(Kokkos::view_alloc(Kokkos::WithoutInitializing, "amphora::cg::r"), n);
      p = View(Kokkos::view_alloc(Kokkos::WithoutInitializing, "amphora::cg::p"), n);
      q = View(Kokkos::view_alloc(Kokkos::WithoutInitializing, "amphora::cg::q"), n);
    }
    if (!preconditioned) {
      z = r;
    } else if (z.extent(0) != n || z.data() == r.data()) {
      z = View(Kokkos::view_alloc(Kokkos::WithoutInitializing, "amphora::cg::z"), n);
    }
  }
};

/// Solves A x = b from the initial guess in x, with the work vectors in w (reserved here). A
/// and M must be symmetric positive definite.
template <class ExecSpace, class Operator, class View, class Preconditioner, class Inner>
SolverResult conjugate_gradient(const ExecSpace& exec, const Operator& A, const View& b,
                                const View& x, const SolverControl& control,
                                const Preconditioner& M, const Inner& dot, CgWorkspace<View>& w) {
  // Unpreconditioned: z is r, so neither the copy z = r nor the product r.z (it is r.r) is
  // formed: 32 of 136 bytes per unknown and iteration (the CEED BPs' CG).
  constexpr bool unpreconditioned = std::is_same_v<Preconditioner, IdentityPreconditioner>;
  w.reserve(x.extent(0), !unpreconditioned);
  const View r = w.r, z = w.z, p = w.p, q = w.q;

  SolverResult result;
  result.rhs_norm = std::sqrt(dot(exec, b, b));
  A.apply(exec, x, q);
  kernels::blas1::copy(exec, b, r);
  kernels::blas1::axpy(exec, -1.0, q, r);  // r = b - A x
  double rr = dot(exec, r, r);
  result.initial_residual = result.final_residual = std::sqrt(rr);
  const double target =
      std::max(control.relative_tolerance * result.rhs_norm, control.absolute_tolerance);
  if (result.final_residual <= target) {
    result.converged = true;
    return result;
  }
  if (!unpreconditioned) M.apply(exec, r, z);
  double rz = unpreconditioned ? rr : dot(exec, r, z);
  double beta = 0.0;  // p = z + beta p: p = z on the first iteration
  for (int it = 1; it <= control.max_iterations; ++it) {
    double pq;
    if constexpr (has_fused_direction<Operator, ExecSpace, View, Inner>::value) {
      pq = A.apply_direction(exec, z, beta, p, q, dot);
    } else {
      pq = direction_in_passes(exec, A, z, beta, p, q, dot);
    }
    if (!(pq > 0.0)) break;  // not SPD (or breakdown): stop, not converged
    const double alpha = rz / pq;
    if constexpr (has_fused_update<Inner>::value) {
      rr = dot.fused_update(exec, alpha, p, q, x, r);
    } else {
      kernels::blas1::axpy(exec, alpha, p, x);
      kernels::blas1::axpy(exec, -alpha, q, r);
      rr = dot(exec, r, r);
    }
    result.iterations = it;
    result.final_residual = std::sqrt(rr);
    if (result.final_residual <= target) {
      result.converged = true;
      break;
    }
    if (!unpreconditioned) M.apply(exec, r, z);
    const double rz_new = unpreconditioned ? rr : dot(exec, r, z);
    beta = rz_new / rz;
    rz = rz_new;
  }
  return result;
}

/// Solves A x = b from the initial guess in x (work vectors allocated for this solve).
template <class ExecSpace, class Operator, class View,
          class Preconditioner = IdentityPreconditioner, class Inner = LocalInnerProduct>
SolverResult conjugate_gradient(const ExecSpace& exec, const Operator& A, const View& b,
                                const View& x, const SolverControl& control,
                                const Preconditioner& M = Preconditioner(),
                                const Inner& dot = Inner()) {
  CgWorkspace<View> w;
  return conjugate_gradient(exec, A, b, x, control, M, dot, w);
}

}  // namespace amphora::solvers
