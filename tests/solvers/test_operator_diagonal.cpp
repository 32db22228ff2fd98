// The diagonal of the coupled flow operators (Oseen, VANS), which the kernel takes by probing
// the point functor with unit inputs and integrating against 1D products, against the diagonal
// of the operator's own element matrices (unit vectors through the cell loop): equal to
// round-off. On curved cells, where the SUPG viscous residual's Laplacian differentiates J^-1,
// the kernel takes unit vectors instead; without that term the probe is exact there as well.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "deformed_box.hpp"
#include "kernels/host_vector.hpp"
#include "mesh/hex/qk_space.hpp"
#include "solvers/matrix_free/assembly.hpp"
#include "solvers/matrix_free/matrix_free_operator.hpp"
#include "test_backend.hpp"

namespace test_operator_diagonal {

using namespace amphora;
using solvers::matrix_free::GeometryMode;
using solvers::matrix_free::OperatorKind;
using test::TestExecSpace;
template <int dim>
using Operator = solvers::matrix_free::MatrixFreeOperator<dim, TestExecSpace>;
using Vector = Operator<2>::Vector;

struct Case {
  OperatorKind kind;
  GeometryMode geometry;
  std::string shape;
  int degree;
  int cells;
  bool viscous_residual = true;
};

/// max |d - diag(A)| / max |diag(A)| over the rows of the velocity (which = 0) or of the
/// pressure (which = 1), d from compute_diagonal and A assembled from the element matrices.
template <int dim>
std::vector<double> diagonal_gaps(const Case& c) {
  mesh::hex::StructuredHexMesh<dim> m;
  m.cells = {c.cells, c.cells, dim == 3 ? c.cells : 1};
  m.faces[2] = m.faces[3] = mesh::hex::FaceCondition::dirichlet;
  test::deform(m, c.shape);
  const mesh::hex::QkSpace<dim, TestExecSpace> space(m, c.degree);
  const long n = space.n_dofs();
  std::mt19937 gen(3);
  std::uniform_real_distribution<double> r(-1.0, 1.0);
  const int n_fields = c.kind == OperatorKind::vans ? dim + 2 : dim;
  std::vector<double> f(n_fields * n);
  for (long i = 0; i < dim * n; ++i) f[i] = 2.0 * r(gen);
  for (long i = dim * n; i < n_fields * n; ++i)  // VANS: eps in [0.4, 1], beta in [0, 50]
    f[i] = i < (dim + 1) * n ? 0.7 + 0.3 * r(gen) : 25.0 + 25.0 * r(gen);
  typename Operator<dim>::Options o;
  o.kind = c.kind;
  o.geometry = c.geometry;
  o.components = dim + 1;
  o.field = kernels::to_view<test::TestMemSpace>(f);
  o.nu = 0.03, o.alpha = 3.0, o.grad_div = 0.4, o.dt_inverse = 2.0;
  o.viscous_residual = c.viscous_residual;
  const Operator<dim> op(space, o);
  Vector d("d", (dim + 1) * n);
  op.compute_diagonal(TestExecSpace(), d);
  const std::vector<double> dh = kernels::to_std_vector(d);
  const solvers::CsrMatrix A = solvers::matrix_free::assemble(TestExecSpace(), op);
  std::vector<double> gap(2, 0.0), scale(2, 0.0);
  for (long i = 0; i < A.n; ++i) {
    double a = 0.0;
    for (long e = A.row_ptr[i]; e < A.row_ptr[i + 1]; ++e)
      if (A.cols[e] == i) a += A.values[e];
    const int which = i < dim * n ? 0 : 1;
    scale[which] = std::max(scale[which], std::abs(a));
    gap[which] = std::max(gap[which], std::abs(a - dh[i]));
  }
  return {gap[0] / scale[0], gap[1] / scale[1]};
}

template <int dim>
void expect_exact(const Case& c) {
  SCOPED_TRACE(std::string(c.kind == OperatorKind::vans ? "VANS" : "Oseen") + " dim " +
               std::to_string(dim) + " k " + std::to_string(c.degree) + " " + c.shape);
  const std::vector<double> g = diagonal_gaps<dim>(c);
  EXPECT_LT(g[0], 1e-12) << "velocity rows";
  EXPECT_LT(g[1], 1e-12) << "pressure rows";
}

TEST(OperatorDiagonal, OseenAndVansEqualTheirElementMatricesWhereJInverseIsConstant) {
  for (const auto kind : {OperatorKind::oseen, OperatorKind::vans}) {
    for (int k = 1; k <= 3; ++k) {  // VANS is compiled to k = 3
      expect_exact<2>({kind, GeometryMode::stored, "cartesian", k, 4});
      expect_exact<2>({kind, GeometryMode::on_the_fly, "affine", k, 3});
    }
    expect_exact<3>({kind, GeometryMode::stored, "affine", 2, 3});
    expect_exact<3>({kind, GeometryMode::on_the_fly, "cartesian", 3, 2});
  }
}

TEST(OperatorDiagonal, CurvedCellsWithoutTheViscousResidualAreExact) {
  for (const auto kind : {OperatorKind::oseen, OperatorKind::vans})
    for (int k = 1; k <= 3; ++k) {
      expect_exact<2>({kind, GeometryMode::stored, "curved", k, 4, false});
      expect_exact<3>({kind, GeometryMode::on_the_fly, "curved", k, 2, false});
    }
}

// With the viscous residual on curved cells the kernel takes unit vectors: exact too.
TEST(OperatorDiagonal, CurvedCellsWithTheViscousResidualAreExact) {
  for (const auto kind : {OperatorKind::oseen, OperatorKind::vans})
    for (int k = 2; k <= 3; ++k) expect_exact<2>({kind, GeometryMode::stored, "curved", k, 4});
}

}  // namespace test_operator_diagonal
