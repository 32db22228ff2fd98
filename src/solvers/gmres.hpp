#pragma once
// Restarted GMRES with right preconditioning (Saad & Schultz 1986; Saad, Iterative Methods,
// alg. 6.9 and 9.5) on any operator with `apply(exec, x, y)` and preconditioner with
// `apply(exec, r, z)`, for the non-symmetric systems CG does not take (the stabilised Oseen
// operator). Modified Gram-Schmidt on device vectors; the small Hessenberg least-squares
// problem is solved on the host by Givens rotations, so each iteration reads back j + 2 scalars
// (the inner products). Right preconditioning keeps the residual it monitors the true one.
#include <cmath>
#include <vector>

#include "kernels/blas1.hpp"
#include "solvers/conjugate_gradient.hpp"

namespace amphora::solvers {

/// GMRES's device vectors (the Krylov basis, w and z), kept by a caller that solves every
/// time step so that no solve allocates (on a GPU, restart + 3 device mallocs and frees).
template <class View>
struct GmresWorkspace {
  std::vector<View> v;
  View w, z;
  /// restart + 1 basis vectors and w, z of n entries, reallocated only when either changes.
  void reserve(long n, int restart) {
    const bool fits =
        static_cast<int>(v.size()) == restart + 1 && static_cast<long>(w.extent(0)) == n;
    if (fits) return;
    v.assign(restart + 1, View());
    for (auto& e : v)
      e = View(Kokkos::view_alloc(Kokkos::WithoutInitializing, "amphora::gmres::v"), n);
    w = View(Kokkos::view_alloc(Kokkos::WithoutInitializing, "amphora::gmres::w"), n);
    z = View(Kokkos::view_alloc(Kokkos::WithoutInitializing, "amphora::gmres::z"), n);
  }
};

namespace gmres_detail {

/// The Krylov basis (the workspace's) and the host side of one cycle: Hessenberg columns,
/// rotations, g.
template <class View>
struct Cycle {
  const std::vector<View>& v;
  std::vector<double> h, cs, sn, g;
  int m;
  Cycle(const std::vector<View>& basis, int restart)
      : v(basis), h((restart + 1) * restart), m(restart) {
    cs.resize(restart), sn.resize(restart), g.resize(restart + 1);
  }
  double& H(int i, int j) { return h[j * (m + 1) + i]; }

  /// Applies the earlier rotations to column j, makes the one that zeroes H(j+1, j); returns
  /// the new residual norm |g[j+1]|.
  double rotate(int j) {
    for (int i = 0; i < j; ++i) {
      const double a = H(i, j), b = H(i + 1, j);
      H(i, j) = cs[i] * a + sn[i] * b;
      H(i + 1, j) = -sn[i] * a + cs[i] * b;
    }
    const double a = H(j, j), b = H(j + 1, j), r = std::hypot(a, b);
    cs[j] = r > 0.0 ? a / r : 1.0;
    sn[j] = r > 0.0 ? b / r : 0.0;
    H(j, j) = r;
    H(j + 1, j) = 0.0;
    g[j + 1] = -sn[j] * g[j];
    g[j] = cs[j] * g[j];
    return std::abs(g[j + 1]);
  }

  /// y of the upper triangular system H(0:k, 0:k) y = g(0:k).
  std::vector<double> solve(int k) {
    std::vector<double> y(k);
    for (int i = k - 1; i >= 0; --i) {
      double s = g[i];
      for (int j = i + 1; j < k; ++j) s -= H(i, j) * y[j];
      y[i] = s / H(i, i);
    }
    return y;
  }
};

}  // namespace gmres_detail

/// Solves A x = b from the initial guess in x, with the device vectors in ws (reserved here);
/// stops when |b - A x| <= max(rel |b|, abs) or after control.max_iterations inner iterations
/// in all, restarting every `restart`.
template <class ExecSpace, class Operator, class View, class Preconditioner, class Inner>
SolverResult gmres(const ExecSpace& exec, const Operator& A, const View& b, const View& x,
                   const SolverControl& control, int restart, const Preconditioner& M,
                   const Inner& dot, GmresWorkspace<View>& ws) {
  ws.reserve(static_cast<long>(x.extent(0)), restart);
  gmres_detail::Cycle<View> c(ws.v, restart);
  const View w = ws.w, z = ws.z;
  SolverResult result;
  result.rhs_norm = std::sqrt(dot(exec, b, b));
  const double target =
      std::max(control.relative_tolerance * result.rhs_norm, control.absolute_tolerance);
  for (bool first = true;; first = false) {
    A.apply(exec, x, w);  // v_0 = (b - A x) / beta
    kernels::blas1::copy(exec, b, c.v[0]);
    kernels::blas1::axpy(exec, -1.0, w, c.v[0]);
    const double beta = std::sqrt(dot(exec, c.v[0], c.v[0]));
    if (first) result.initial_residual = beta;
    result.final_residual = beta;
    if (beta <= target) {
      result.converged = true;
      return result;
    }
    if (result.iterations >= control.max_iterations || !std::isfinite(beta)) return result;
    kernels::blas1::scale(exec, 1.0 / beta, c.v[0]);
    std::fill(c.g.begin(), c.g.end(), 0.0);
    c.g[0] = beta;
    int k = 0;
    while (k < restart && result.iterations < control.max_iterations) {
      M.apply(exec, c.v[k], z);
      A.apply(exec, z, w);
      for (int i = 0; i <= k; ++i) {  // modified Gram-Schmidt
        c.H(i, k) = dot(exec, w, c.v[i]);
        kernels::blas1::axpy(exec, -c.H(i, k), c.v[i], w);
      }
      c.H(k + 1, k) = std::sqrt(dot(exec, w, w));
      const bool breakdown = !(c.H(k + 1, k) > 0.0);
      if (!breakdown) {
        kernels::blas1::copy(exec, w, c.v[k + 1]);
        kernels::blas1::scale(exec, 1.0 / c.H(k + 1, k), c.v[k + 1]);
      }
      const double estimate = c.rotate(k);
      ++k, ++result.iterations;
      if (breakdown || estimate <= target) break;
    }
    const std::vector<double> y = c.solve(k);  // x += M^-1 (V y)
    kernels::blas1::fill(exec, w, 0.0);
    for (int i = 0; i < k; ++i) kernels::blas1::axpy(exec, y[i], c.v[i], w);
    M.apply(exec, w, z);
    kernels::blas1::axpy(exec, 1.0, z, x);
  }
}

/// Solves A x = b from the initial guess in x (work vectors allocated for this solve).
template <class ExecSpace, class Operator, class View,
          class Preconditioner = IdentityPreconditioner, class Inner = LocalInnerProduct>
SolverResult gmres(const ExecSpace& exec, const Operator& A, const View& b, const View& x,
                   const SolverControl& control, int restart = 30,
                   const Preconditioner& M = Preconditioner(), const Inner& dot = Inner()) {
  GmresWorkspace<View> ws;
  return gmres(exec, A, b, x, control, restart, M, dot, ws);
}

}  // namespace amphora::solvers
