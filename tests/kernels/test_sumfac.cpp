// Sum-factorisation building blocks: quadrature exactness, Lagrange bases, even–odd matrices
// against dense products, the tensor evaluator against direct evaluation of a polynomial, and
// the DoFs a row of cell batches touches first and last in the coloured cell loop.
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "kernels/sumfac/qk_lattice.hpp"
#include "kernels/sumfac/quadrature_1d.hpp"
#include "kernels/sumfac/row_touch.hpp"
#include "kernels/sumfac/shape_data.hpp"
#include "kernels/sumfac/simd.hpp"
#include "kernels/sumfac/tensor_product_evaluator.hpp"
#include "test_backend.hpp"

namespace amphora::kernels::sumfac {
namespace {

double integrate_monomial(const Quadrature1D& q, int p) {
  double s = 0.0;
  for (std::size_t i = 0; i < q.points.size(); ++i) s += q.weights[i] * std::pow(q.points[i], p);
  return s;
}

TEST(Quadrature1D, GaussIsExactToDegree2nMinus1) {
  for (int n = 1; n <= 12; ++n) {
    const Quadrature1D q = gauss(n);
    for (int p = 0; p <= 2 * n - 1; ++p)
      EXPECT_NEAR(integrate_monomial(q, p), 1.0 / (p + 1), 1e-14) << "n=" << n << " p=" << p;
    // and not beyond: x^(2n) is integrated with an error
    EXPECT_GT(std::abs(integrate_monomial(q, 2 * n) - 1.0 / (2 * n + 1)), 1e-15 * (n < 9));
  }
}

TEST(Quadrature1D, GaussLobattoIsExactToDegree2nMinus3AndHasEndPoints) {
  for (int n = 2; n <= 12; ++n) {
    const Quadrature1D q = gauss_lobatto(n);
    EXPECT_EQ(q.points.front(), 0.0);
    EXPECT_EQ(q.points.back(), 1.0);
    for (int p = 0; p <= 2 * n - 3; ++p)
      EXPECT_NEAR(integrate_monomial(q, p), 1.0 / (p + 1), 1e-14) << "n=" << n << " p=" << p;
  }
}

TEST(Lagrange, BasisIsNodalAndDerivativeIsExact) {
  const std::vector<double> nodes = gauss_lobatto(6).points;
  const std::vector<double> v = lagrange_values(nodes, nodes);
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) EXPECT_NEAR(v[i * 6 + j], i == j ? 1.0 : 0.0, 1e-15);
  // d/dx of x^5 interpolated on the nodes, at Gauss points
  const std::vector<double> x = gauss(7).points;
  const std::vector<double> d = lagrange_derivatives(nodes, x);
  for (std::size_t q = 0; q < x.size(); ++q) {
    double s = 0.0;
    for (int j = 0; j < 6; ++j) s += d[q * 6 + j] * std::pow(nodes[j], 5);
    EXPECT_NEAR(s, 5.0 * std::pow(x[q], 4), 1e-12);
  }
}

template <int n_rows, int n_cols>
void check_even_odd(int sign, const std::vector<double>& dense) {
  const auto m = EvenOddMatrix<n_rows, n_cols>::from_dense(dense, sign);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<double> x(n_cols * 3), y(n_rows * 3, 0.0);
  for (double& e : x) e = u(rng);
  // three lines at stride 3 (post = 1)
  apply_even_odd<n_rows, n_cols, 3, 1, false>(m, x.data(), y.data());
  for (int s = 0; s < 3; ++s)
    for (int o = 0; o < n_rows; ++o) {
      double ref = 0.0;
      for (int i = 0; i < n_cols; ++i) ref += dense[o * n_cols + i] * x[i * 3 + s];
      EXPECT_NEAR(y[o * 3 + s], ref, 1e-13);
    }
}

TEST(EvenOddMatrix, MatchesDenseProductForValuesAndDerivatives) {
  const auto nodes5 = gauss_lobatto(5).points, nodes4 = gauss_lobatto(4).points;
  const auto g6 = gauss(6).points, g5 = gauss(5).points;
  check_even_odd<6, 5>(1, lagrange_values(nodes5, g6));
  check_even_odd<6, 5>(-1, lagrange_derivatives(nodes5, g6));
  check_even_odd<5, 4>(1, lagrange_values(nodes4, g5));
  check_even_odd<5, 4>(-1, lagrange_derivatives(nodes4, g5));
  check_even_odd<5, 5>(-1, lagrange_derivatives(g5, g5));
  check_even_odd<4, 6>(1, [&] {  // a transpose
    auto v = lagrange_values(gauss_lobatto(4).points, g6);
    std::vector<double> t(v.size());
    for (int r = 0; r < 6; ++r)
      for (int c = 0; c < 4; ++c) t[c * 6 + r] = v[r * 4 + c];
    return t;
  }());
  EXPECT_THROW((EvenOddMatrix<2, 2>::from_dense({1, 2, 3, 4}, 1)), std::invalid_argument);
}

// Values and gradients of p(x,y,z) = x^k y^(k-1) z + ... interpolated in Q_k, at the points.
template <int dim, int k, int n_q>
void check_evaluator() {
  constexpr int n_p = k + 1;
  using Eval = TensorProductEvaluator<dim, n_p, n_q>;
  using T = Simd<host_simd_width>;
  const auto shape = ShapeData<n_p, n_q>::create(QuadratureKind::gauss);
  const auto nodes = gauss_lobatto(n_p).points;
  const auto pts = gauss(n_q).points;
  auto p = [](const double* x, int lane) {
    double r = std::pow(x[0], k) * std::pow(x[1], k - 1) + (1.0 + lane) * x[1];
    if (dim == 3) r = r * (1.0 + x[2]) + std::pow(x[2], k);
    return r;
  };
  auto dp = [](const double* x, int lane, int d) {
    const double z = dim == 3 ? x[2] : 0.0, zf = dim == 3 ? 1.0 + z : 1.0;
    if (d == 0) return k * std::pow(x[0], k - 1) * std::pow(x[1], k - 1) * zf;
    if (d == 1)
      return (std::pow(x[0], k) * (k - 1) * std::pow(x[1], k - 2) + (dim == 3 ? 0.0 : 1.0 + lane)) *
                 zf +
             (dim == 3 ? (1.0 + lane) * zf : 0.0);
    return std::pow(x[0], k) * std::pow(x[1], k - 1) + (1.0 + lane) * x[1] + k * std::pow(z, k - 1);
  };
  std::vector<T> u(Eval::n_dofs), v(Eval::n_points), grad(dim * Eval::n_points),
      tmp(Eval::n_scratch);
  for (int n = 0; n < Eval::n_dofs; ++n) {
    const double x[3] = {nodes[n % n_p], nodes[(n / n_p) % n_p],
                         dim == 3 ? nodes[n / (n_p * n_p)] : 0.0};
    for (int l = 0; l < host_simd_width; ++l) u[n][l] = p(x, l);
  }
  Eval::values(shape, u.data(), v.data(), tmp.data());
  Eval::gradients(shape, v.data(), grad.data());
  for (int q = 0; q < Eval::n_points; ++q) {
    const double x[3] = {pts[q % n_q], pts[(q / n_q) % n_q], dim == 3 ? pts[q / (n_q * n_q)] : 0.0};
    for (int l = 0; l < host_simd_width; ++l) {
      EXPECT_NEAR(v[q][l], p(x, l), 1e-12);
      for (int d = 0; d < dim; ++d)
        EXPECT_NEAR(grad[d * Eval::n_points + q][l], dp(x, l, d), 1e-11);
    }
  }
  // integrate_values is the transpose of values: <values(u), w> = <u, integrate(w)>
  std::vector<T> w(Eval::n_points), back(Eval::n_dofs);
  for (int q = 0; q < Eval::n_points; ++q) w[q] = T(std::sin(1.0 + q));
  Eval::values(shape, u.data(), v.data(), tmp.data());
  double lhs = 0.0, rhs = 0.0;
  for (int q = 0; q < Eval::n_points; ++q) lhs += v[q][0] * w[q][0];
  Eval::integrate_values(shape, w.data(), back.data(), tmp.data());
  for (int n = 0; n < Eval::n_dofs; ++n) rhs += u[n][0] * back[n][0];
  EXPECT_NEAR(lhs, rhs, 1e-11 * std::abs(lhs));
}

TEST(TensorProductEvaluator, ValuesAndGradientsOfPolynomialsAreExact) {
  check_evaluator<2, 1, 2>();
  check_evaluator<2, 3, 4>();
  check_evaluator<2, 4, 6>();
  check_evaluator<3, 2, 3>();
  check_evaluator<3, 3, 5>();
  check_evaluator<3, 5, 6>();
  check_evaluator<3, 8, 10>();
}

// The cell loop (kernels::sumfac::for_each_batch_coloured) runs slabs by block colour, a
// block's slabs in order and a slab's rows in order; blocks of one colour share no node. Every
// DoF must lie in the first-touch range of the first row (in that order) whose cells hold it,
// in the last-touch range of the last one, and in no other row's.
template <int dim>
void check_row_touch(int degree, const int* cells, const bool* periodic) {
  const auto lat = QkLattice<dim>::create(degree, cells, periodic, 0, 8);
  SCOPED_TRACE(std::to_string(dim) + "D k " + std::to_string(degree) + " slabs " +
               std::to_string(lat.n_slabs()));
  const int slabs = lat.n_slabs(), rows = lat.rows_per_slab(), run = lat.slabs_per_block();
  const long line = lat.dofs[0], layer = dim == 3 ? line * lat.dofs[1] : line, n = lat.n_dofs();
  // the order of each (slab, row): colour, then block, then slab, then row
  auto order = [&](int s, int r) {
    return ((static_cast<long>(lat.slab_colour(s)) * slabs + s / run) * slabs + s) * rows + r;
  };
  std::vector<long> first(n, -1), last(n, -1);
  std::vector<int> first_row(n, -1), last_row(n, -1);
  for (int s = 0; s < slabs; ++s)
    for (int r = 0; r < rows; ++r)
      for (int a = 0; a <= degree; ++a)  // the row's node layers along the last direction
        for (int b = 0; b <= (dim == 3 ? degree : 0); ++b) {  // ... and lines along direction 1
          const long l = (s * degree + a) % lat.dofs[dim - 1];
          const long m = dim == 3 ? (r * degree + b) % lat.dofs[1] : 0;
          for (long i = 0; i < line; ++i) {
            const long dof = l * layer + m * line + i, o = order(s, r);
            if (first[dof] < 0 || o < first[dof]) first[dof] = o, first_row[dof] = s * rows + r;
            if (last[dof] < 0 || o > last[dof]) last[dof] = o, last_row[dof] = s * rows + r;
          }
        }
  for (const bool at_last : {false, true}) {
    if (at_last && !lat.last_touch_ranges()) continue;
    std::vector<int> covered(n, 0);
    long wrong = 0;
    for (int s = 0; s < slabs; ++s)
      for (int r = 0; r < rows; ++r)
        row_touch(lat, s, r, at_last).for_each_range([&](long begin, long end) {
          for (long dof = begin; dof < end; ++dof) {
            ++covered[dof];
            wrong += (at_last ? last_row[dof] : first_row[dof]) != s * rows + r;
          }
        });
    long not_once = 0;
    for (long d = 0; d < n; ++d) not_once += covered[d] != 1;
    EXPECT_EQ(not_once, 0) << (at_last ? "last" : "first")
                           << " touches: DoFs not in exactly one row's range";
    EXPECT_EQ(wrong, 0) << (at_last ? "last" : "first")
                        << " touches: DoFs in the range of another row";
  }
}

TEST(RowTouch, EveryDofIsTouchedFirstAndLastByTheRowsThatRunFirstAndLast) {
  const bool open[3] = {false, false, false}, periodic_x[3] = {true, false, false};
  const bool periodic_all[3] = {true, true, true};
  for (int k : {1, 2, 4}) {
    // slabs per block 1 (3 blocks), 2 (8 blocks; 9, an odd count), 5 (8 blocks)
    for (int nz : {3, 16, 18, 40}) {
      const int c3[3] = {10, 4, nz}, c2[2] = {10, nz};
      check_row_touch<3>(k, c3, open);
      check_row_touch<3>(k, c3, periodic_x);
      check_row_touch<3>(k, c3, periodic_all);  // periodic: first touches only
      check_row_touch<2>(k, c2, open);
      check_row_touch<2>(k, c2, periodic_all);
    }
  }
}

}  // namespace
}  // namespace amphora::kernels::sumfac
