#pragma once
// Chebyshev smoother/preconditioner around point Jacobi (Adams, Brezina, Hu & Tuminaro 2003;
// deal.II's PreconditionChebyshev): damps the eigencomponents of D^-1 A in
// [lambda_max / smoothing_range, 1.2 lambda_max] with a degree-d polynomial. lambda_max comes
// from a few CG steps on D^-1 A (Lanczos), or the caller gives an upper bound (then the
// interval ends there). Parallel and deterministic, unlike Gauss–Seidel.
#include <cmath>
#include <vector>

#include <Kokkos_Core.hpp>

#include "kernels/blas1.hpp"
#include "solvers/conjugate_gradient.hpp"
#include "solvers/lanczos.hpp"

namespace amphora::solvers {

struct ChebyshevOptions {
  int degree = 4;
  double smoothing_range = 15.0;
  int eigenvalue_iterations = 12;
  /// If positive: a known upper bound of lambda_max(D^-1 A) (jacobi_gershgorin_bound), used as
  /// the interval's upper end instead of 1.2 times an estimate, which is then not made.
  double lambda_max_bound = 0.0;
  /// Estimate the largest |lambda| of D^-1 A by power iteration instead of Lanczos: for
  /// non-symmetric A (the stabilised Oseen operator), as deal.II's
  /// EigenvalueAlgorithm::power_iteration.
  bool power_iteration = false;
};

/// The eigenvalue estimate's start entry for DoF number g, in [-0.5, 0.5): deterministic and
/// rich in every eigencomponent (Knuth's multiplicative hash). A distributed operator numbers
/// its DoFs globally, so that every rank count starts from the same vector.
KOKKOS_INLINE_FUNCTION double eigenvalue_start_entry(unsigned g) {
  return static_cast<double>((g * 2654435761u) % 1000003u) / 1000003.0 - 0.5;
}

/// `Inner` is the inner product of the eigenvalue estimate (conjugate_gradient's); `start`,
/// if given, its start vector (a distributed operator passes one that depends on global DoF
/// numbers only, so every rank count estimates the same lambda_max).
template <class ExecSpace, class Operator, class Vector, class Inner = LocalInnerProduct>
class ChebyshevSmoother {
 public:
  ChebyshevSmoother(const ExecSpace& exec, const Operator& A, const Vector& inverse_diagonal,
                    const ChebyshevOptions& options = {}, const Inner& inner = Inner(),
                    const Vector& start = Vector())
      : A_(&A),
        inv_diag_(inverse_diagonal),
        options_(options),
        r_("amphora::chebyshev::r", inverse_diagonal.extent(0)),
        d_("amphora::chebyshev::d", inverse_diagonal.extent(0)) {
    set_interval(exec, inner, start);
  }

  /// As a new smoother of A with `options` over the inverse diagonal it has (whose values may
  /// have changed), in the vectors it has: a power-iteration estimate allocates nothing.
  void refresh(const ExecSpace& exec, const Operator& A, const ChebyshevOptions& options,
               const Inner& inner = Inner(), const Vector& start = Vector()) {
    A_ = &A;
    options_ = options;
    set_interval(exec, inner, start);
  }

  /// Smooths A from now on over the interval that options.lambda_max_bound = lambda_max_bound
  /// gives, in the vectors it has: as a new smoother with that bound, allocating nothing (an
  /// operator rebuilt with new coefficients; A must outlive this).
  void reuse(const Operator& A, double lambda_max_bound) {
    A_ = &A;
    lambda_max_ = upper_ = lambda_max_bound;
  }

  double lambda_max() const { return lambda_max_; }
  /// The damped interval's upper end (1.2 lambda_max, or the bound given).
  double upper() const { return upper_; }

  /// `degree` Chebyshev steps on A x = b from x (from zero if zero_initial).
  void smooth(const ExecSpace& exec, const Vector& b, const Vector& x, bool zero_initial) const {
    const double hi = upper_, lo = lambda_max_ / options_.smoothing_range;
    const double theta = 0.5 * (hi + lo), delta = 0.5 * (hi - lo), sigma = theta / delta;
    const Vector r = r_, d = d_, D = inv_diag_;
    const int n = static_cast<int>(x.extent(0));
    double rho_old = 1.0 / sigma;
    for (int step = 0; step < options_.degree; ++step) {
      const bool first = step == 0;
      if (!(first && zero_initial)) A_->apply(exec, x, r);  // r = A x
      const bool skip_ax = first && zero_initial;
      const double rho = first ? rho_old : 1.0 / (2.0 * sigma - rho_old);
      const double c_old = first ? 0.0 : rho * rho_old,
                   c_new = first ? 1.0 / theta : 2.0 * rho / delta;
      Kokkos::parallel_for(
          "amphora::ChebyshevSmoother::step", kernels::RangePolicy<ExecSpace>(exec, 0, n),
          KOKKOS_LAMBDA(int i) {
            const double res = skip_ax ? b(i) : b(i) - r(i);
            const double di = (c_old != 0.0 ? c_old * d(i) : 0.0) + c_new * D(i) * res;
            d(i) = di;
            x(i) = (skip_ax ? 0.0 : x(i)) + di;
          });
      rho_old = rho;
    }
  }

  /// As a preconditioner: z = p(D^-1 A) D^-1 r (smoothing from zero).
  void apply(const ExecSpace& exec, const Vector& r, const Vector& z) const {
    smooth(exec, r, z, true);
  }

 public:  // (CUDA: extended lambdas may not live in private member functions)
  /// The damped interval: the options' bound, else 1.2 x the estimated lambda_max.
  void set_interval(const ExecSpace& exec, const Inner& inner, const Vector& start) {
    if (options_.lambda_max_bound > 0.0) {
      lambda_max_ = upper_ = options_.lambda_max_bound;
    } else {
      lambda_max_ = options_.power_iteration ? estimate_lambda_max_power(exec, inner, start)
                                             : estimate_lambda_max(exec, inner, start);
      upper_ = 1.2 * lambda_max_;  // the estimate approaches lambda_max from below
    }
  }

  /// |lambda|_max of D^-1 A: x <- D^-1 A x / |x|, |D^-1 A x| / |x| after the last step (x and
  /// A x in the smoother's own vectors).
  double estimate_lambda_max_power(const ExecSpace& exec, const Inner& dot,
                                   const Vector& start) const {
    const int n = static_cast<int>(inv_diag_.extent(0));
    const Vector x = r_, y = d_;
    const Vector D = inv_diag_;
    const bool given = start.extent(0) > 0;
    Kokkos::parallel_for(
        "amphora::ChebyshevSmoother::start", kernels::RangePolicy<ExecSpace>(exec, 0, n),
        KOKKOS_LAMBDA(int i) {
          const double h = given ? start(i) : eigenvalue_start_entry(static_cast<unsigned>(i));
          x(i) = h * (D(i) != 0.0 ? 1.0 : 0.0);
        });
    double norm = std::sqrt(dot(exec, x, x)), lambda = 1.0;
    for (int it = 0; it < options_.eigenvalue_iterations && norm > 0.0; ++it) {
      kernels::blas1::scale(exec, 1.0 / norm, x);
      A_->apply(exec, x, y);
      Kokkos::parallel_for(
          "amphora::ChebyshevSmoother::power", kernels::RangePolicy<ExecSpace>(exec, 0, n),
          KOKKOS_LAMBDA(int i) { x(i) = D(i) * y(i); });
      norm = std::sqrt(dot(exec, x, x));
      lambda = norm;
    }
    return lambda;
  }

  double estimate_lambda_max(const ExecSpace& exec, const Inner& dot, const Vector& start) const {
    // Jacobi-preconditioned CG from a smooth-free start vector; alphas, betas -> Lanczos.
    const int n = static_cast<int>(inv_diag_.extent(0));
    Vector x("x", n), r("r", n), z("z", n), p("p", n), q("q", n);
    const Vector D = inv_diag_;
    const bool given = start.extent(0) > 0;
    Kokkos::parallel_for(
        "amphora::ChebyshevSmoother::start", kernels::RangePolicy<ExecSpace>(exec, 0, n),
        KOKKOS_LAMBDA(int i) {
          const double h = given ? start(i) : eigenvalue_start_entry(static_cast<unsigned>(i));
          r(i) = h * (D(i) != 0.0 ? 1.0 : 0.0);
        });
    std::vector<double> alphas, betas;
    Kokkos::parallel_for(
        "amphora::ChebyshevSmoother::z", kernels::RangePolicy<ExecSpace>(exec, 0, n),
        KOKKOS_LAMBDA(int i) { z(i) = D(i) * r(i); });
    kernels::blas1::copy(exec, z, p);
    double rz = dot(exec, r, z);
    for (int it = 0; it < options_.eigenvalue_iterations && rz > 0.0; ++it) {
      A_->apply(exec, p, q);
      const double pq = dot(exec, p, q);
      if (!(pq > 0.0)) break;
      const double alpha = rz / pq;
      alphas.push_back(alpha);
      kernels::blas1::axpy(exec, -alpha, q, r);
      Kokkos::parallel_for(
          "amphora::ChebyshevSmoother::z", kernels::RangePolicy<ExecSpace>(exec, 0, n),
          KOKKOS_LAMBDA(int i) { z(i) = D(i) * r(i); });
      const double rz_new = dot(exec, r, z);
      const double beta = rz_new / rz;
      betas.push_back(beta);
      kernels::blas1::axpby(exec, 1.0, z, beta, p);
      rz = rz_new;
    }
    return alphas.empty() ? 1.0 : lanczos_extreme_eigenvalues(alphas, betas).second;
  }

 private:
  const Operator* A_;
  Vector inv_diag_;
  ChebyshevOptions options_;
  Vector r_, d_;
  double lambda_max_ = 1.0;  ///< estimated or bound
  double upper_ = 1.2;       ///< the damped interval's upper end
};

}  // namespace amphora::solvers
