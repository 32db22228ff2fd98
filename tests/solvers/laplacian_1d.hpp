#pragma once
// The 1D Dirichlet Laplacian tridiag(-1, 2 + shift, -1) (h^2-scaled, plus a shift), matrix-free
// on the test backend: the operator the CG and Chebyshev tests know the eigenpairs of.
#include "kernels/spaces.hpp"
#include "test_backend.hpp"

namespace amphora::test {

struct Laplacian1D {
  using View = Kokkos::View<double*, TestMemSpace>;
  double shift = 0.0;
  void apply(const TestExecSpace& exec, const View& x, const View& y) const {
    const int n = static_cast<int>(x.extent(0));
    const double s = shift;
    Kokkos::parallel_for(
        "test::Laplacian1D", kernels::RangePolicy<TestExecSpace>(exec, 0, n), KOKKOS_LAMBDA(int i) {
          const double left = i > 0 ? x(i - 1) : 0.0, right = i < n - 1 ? x(i + 1) : 0.0;
          y(i) = (2.0 + s) * x(i) - left - right;
        });
  }
};

}  // namespace amphora::test
