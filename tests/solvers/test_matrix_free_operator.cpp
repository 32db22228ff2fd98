// Every matrix-free operator equals the textbook assembled matrix (Eigen) to 1e-12 relative:
// k = 1..6, 2D and 3D, Cartesian, affine and curved cells, every geometry mode, periodic,
// Dirichlet and Neumann faces, full and partial cell batches. Plus the diagonal, the mass of
// the unit cube and the Laplacian of a constant.
#include <Eigen/Sparse>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "deformed_box.hpp"
#include "kernels/blas1.hpp"
#include "kernels/host_vector.hpp"
#include "reference_assembly.hpp"
#include "kernels/sumfac/cell_operator_kernel.hpp"
#include "kernels/sumfac/generic_cell_kernel.hpp"
#include "solvers/conjugate_gradient.hpp"
#include "solvers/matrix_free/assembly.hpp"
#include "solvers/matrix_free/matrix_free_operator.hpp"
#include "test_backend.hpp"

namespace amphora::solvers::matrix_free {
namespace {

using test::TestExecSpace;
using Vector = Kokkos::View<double*, test::TestMemSpace>;
using mesh::hex::FaceCondition;

template <int dim>
mesh::hex::StructuredHexMesh<dim> mixed_mesh(int nx, int ny, int nz, const std::string& shape) {
  mesh::hex::StructuredHexMesh<dim> m;
  m.cells = {nx, ny, nz};
  m.faces = {FaceCondition::periodic, FaceCondition::periodic, FaceCondition::dirichlet,
             FaceCondition::neumann,  FaceCondition::neumann,  FaceCondition::dirichlet};
  test::deform(m, shape);
  return m;
}

Vector to_device(const std::vector<double>& v) { return kernels::to_view<test::TestMemSpace>(v); }
std::vector<double> to_host(const Vector& d) { return kernels::to_std_vector(d); }

struct Case {
  OperatorKind kind;
  GeometryMode geometry;
  std::string shape;  // cartesian, affine, curved
  int degree;
  int n_q_extra = 0;  // n_q = degree + 1 + extra
  bool gauss_lobatto = false;
  bool with_field = false;
  int components = 1;
  bool generic = false;  // force the run-time-size kernel
  int team_size = -1;    // >= 0: the team schedule with this many threads (0: its choice)
};

template <int dim>
void check(const Case& c, int nx, int ny, int nz) {
  SCOPED_TRACE("dim " + std::to_string(dim) + " k " + std::to_string(c.degree) + " kind " +
               std::to_string(static_cast<int>(c.kind)) + " geometry " +
               std::to_string(static_cast<int>(c.geometry)) + " " + c.shape + " nq+" +
               std::to_string(c.n_q_extra) + (c.gauss_lobatto ? " GL" : "") +
               (c.with_field ? " field" : "") +
               (c.team_size >= 0 ? " team " + std::to_string(c.team_size) : ""));
  const TestExecSpace exec;
  const auto m = mixed_mesh<dim>(nx, ny, nz, c.shape);
  const mesh::hex::QkSpace<dim, TestExecSpace> space(m, c.degree);
  const long n = space.n_dofs();
  std::vector<double> field;
  if (c.kind == OperatorKind::convection) {
    field = space.interpolate(
        [](const mesh::hex::Point3& x, int a) {
          return a == 0 ? std::sin(3 * x[1]) : a == 1 ? std::cos(2 * x[0]) : 0.5;
        },
        dim);
  } else if (c.with_field) {
    field = space.interpolate([](const mesh::hex::Point3& x, int) {
      return 1.0 + 0.5 * std::sin(3 * x[0]) * std::cos(2 * x[1]);
    });
  }
  typename MatrixFreeOperator<dim, TestExecSpace>::Options o;
  o.kind = c.kind;
  o.geometry = c.geometry;
  o.n_q = c.degree + 1 + c.n_q_extra;
  o.quadrature = c.gauss_lobatto ? kernels::sumfac::QuadratureKind::gauss_lobatto
                                 : kernels::sumfac::QuadratureKind::gauss;
  o.components = c.components;
  o.generic_kernel = c.generic;
  o.team_kernel = c.team_size >= 0;
  o.team_size = c.team_size;
  if (!field.empty()) o.field = to_device(field);
  const MatrixFreeOperator<dim, TestExecSpace> op(space, o);
  const auto A = test::assemble_reference<dim>(space, c.kind, o.n_q, c.gauss_lobatto, field);

  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> x(n * c.components);
  for (double& e : x) e = u(rng);
  Vector xd = to_device(x), yd("y", n * c.components);
  op.apply(exec, xd, yd);
  const std::vector<double> y = to_host(yd);
  double scale = 0.0, err = 0.0;
  for (int comp = 0; comp < c.components; ++comp) {
    const Eigen::VectorXd ref = A * Eigen::Map<const Eigen::VectorXd>(x.data() + comp * n, n);
    for (long i = 0; i < n; ++i) {
      scale = std::max(scale, std::abs(ref[i]));
      err = std::max(err, std::abs(ref[i] - y[comp * n + i]));
    }
  }
  EXPECT_LT(err, 1e-12 * scale) << "max |A x - A_ref x| = " << err << " of " << scale;

  if (c.kind != OperatorKind::convection) {
    Vector dd("d", n * c.components);
    op.compute_diagonal(exec, dd);
    const std::vector<double> d = to_host(dd);
    double derr = 0.0, dscale = 0.0;
    for (long i = 0; i < n; ++i) {
      dscale = std::max(dscale, std::abs(A.coeff(i, i)));
      for (int comp = 0; comp < c.components; ++comp)
        derr = std::max(derr, std::abs(A.coeff(i, i) - d[comp * n + i]));
    }
    EXPECT_LT(derr, 1e-12 * dscale) << "diagonal";
  }
}

using K = OperatorKind;
using G = GeometryMode;

TEST(MatrixFreeOperator, LaplaceAndMassMatchAssembledMatricesForDegrees1To6In2D) {
  for (int k = 1; k <= 6; ++k) {
    check<2>({K::laplace, G::stored, "curved", k}, 9, 3, 1);
    check<2>({K::laplace, G::on_the_fly, "curved", k, 1}, 9, 3, 1);
    check<2>({K::mass, G::stored, "curved", k, 1}, 9, 3, 1);
    check<2>({K::laplace, G::affine, "affine", k}, 9, 3, 1);
    check<2>({K::mass, G::cartesian, "cartesian", k}, 9, 3, 1);
    check<2>({K::mass, G::affine, "affine", k, 1}, 9, 3, 1);
    check<2>({K::laplace, G::cartesian, "cartesian", k, 0, true}, 9, 3, 1);  // collocated
  }
}

TEST(MatrixFreeOperator, LaplaceAndMassMatchAssembledMatricesForDegrees1To6In3D) {
  for (int k = 1; k <= 6; ++k) {
    const int nx = k <= 3 ? 9 : 9, ny = k <= 3 ? 3 : 3, nz = k <= 4 ? 2 : 1;
    check<3>({K::laplace, G::stored, "curved", k}, nx, ny, nz);
    check<3>({K::mass, G::on_the_fly, "curved", k, 1}, nx, ny, nz);
    // The operators of the 1D matrices: Kronecker sums (Laplace) and products (mass), Gauss
    // and collocated Gauss–Lobatto points.
    check<3>({K::laplace, G::cartesian, "cartesian", k}, nx, ny, nz);
    check<3>({K::laplace, G::cartesian, "cartesian", k, 0, true}, nx, ny, nz);
    check<3>({K::mass, G::cartesian, "cartesian", k, 1}, nx, ny, nz);
    check<3>({K::mass, G::affine, "affine", k}, nx, ny, nz);
    if (k <= 4) {
      check<3>({K::laplace, G::on_the_fly, "curved", k, 1}, nx, ny, nz);
      check<3>({K::laplace, G::affine, "affine", k}, nx, ny, nz);
    }
  }
}

// The run-time-size fallback: pairs the compiled table lacks (degree + 3 and degree points per
// direction) and, forced, pairs it has; 2D and 3D, curved, mass and Laplace, 3 components.
// 16 slabs or more run in blocks of consecutive slabs (QkLattice::slabs_per_block): block
// counts even and odd, the last block short, along a periodic direction (the last block of an
// odd count then runs in a third colour) and a Dirichlet one.
TEST(MatrixFreeOperator, SlabBlocksOfEveryCountMatchAssembledMatrices) {
  for (int n : {16, 17, 18, 33}) {  // 8, 9 (last short), 9, 9 (last short) blocks
    check<2>({K::laplace, G::cartesian, "cartesian", 2}, 9, n, 1);  // y periodic
    check<2>({K::mass, G::stored, "curved", 3}, 9, n, 1);
  }
  check<3>({K::laplace, G::affine, "affine", 2}, 9, 2, 18);  // z Dirichlet
}

TEST(MatrixFreeOperator, GenericKernelMatchesAssembledMatrices) {
  for (int k : {1, 2, 4}) {
    check<2>({K::laplace, G::on_the_fly, "curved", k, 2}, 5, 3, 1);
    check<2>({K::mass, G::stored, "curved", k, 2}, 5, 3, 1);
    check<3>({K::laplace, G::stored, "curved", k, 2}, 3, 2, 2);
    check<3>({K::mass, G::on_the_fly, "curved", k, -1}, 3, 2, 2);
  }
  Case forced{K::laplace, G::stored, "curved", 3};
  forced.generic = true;
  check<3>(forced, 3, 2, 2);
  forced.components = 3;
  forced.kind = K::mass;
  check<3>(forced, 3, 2, 2);
}

// The generic kernel's element matrices (one team per cell, team scratch) equal the compiled
// kernel's for the same operator, cell by cell.
TEST(MatrixFreeOperator, GenericKernelElementMatricesEqualTheCompiledKernels) {
  const TestExecSpace exec;
  for (const auto kind : {OperatorKind::laplace, OperatorKind::mass}) {
    const auto m = mixed_mesh<3>(3, 2, 2, "curved");
    const mesh::hex::QkSpace<3, TestExecSpace> space(m, 2);
    typename MatrixFreeOperator<3, TestExecSpace>::Options o;
    o.kind = kind;
    o.geometry = GeometryMode::on_the_fly;
    const std::vector<double> compiled =
        MatrixFreeOperator<3, TestExecSpace>(space, o).element_matrices(exec);
    o.generic_kernel = true;
    const std::vector<double> generic =
        MatrixFreeOperator<3, TestExecSpace>(space, o).element_matrices(exec);
    ASSERT_EQ(generic.size(), compiled.size());
    ASSERT_EQ(generic.size(), static_cast<std::size_t>(12 * 27 * 27));
    double scale = 0.0, err = 0.0;
    for (std::size_t e = 0; e < compiled.size(); ++e) {
      scale = std::max(scale, std::abs(compiled[e]));
      err = std::max(err, std::abs(generic[e] - compiled[e]));
    }
    EXPECT_LT(err, 1e-13 * scale) << "kind " << static_cast<int>(kind);
  }
}

// y += A x by the generic kernel's batches (a functor: no device lambda in a test body).
template <int dim, class Point>
struct GenericBatches {
  kernels::sumfac::GenericCellKernel<dim, TestExecSpace, Point> k;
  Vector x;
  double* y;
  long n;
  KOKKOS_INLINE_FUNCTION void operator()(
      const typename kernels::sumfac::GenericCellKernel<dim, TestExecSpace, Point>::Team& team,
      int b0, int b1) const {
    k.template add_batches<true>(team, b0, b1, x, y, n, 1, 0);
  }
};

// The devices' schedule of the generic kernel (one team per batch, all at once, atomic adds)
// with teams of two threads where the backend has them, so the team shares every sweep, point
// loop and scatter: the product equals the operator's on every unconstrained row.
template <class Point>
void check_generic_in_teams(OperatorKind kind) {
  const TestExecSpace exec;
  const int team_size = TestExecSpace().concurrency() >= 2 ? 2 : 1;
  {
    const auto m = mixed_mesh<3>(5, 3, 2, "curved");
    const mesh::hex::QkSpace<3, TestExecSpace> space(m, 3);
    const long n = space.n_dofs();
    typename MatrixFreeOperator<3, TestExecSpace>::Options o;
    o.kind = kind;
    o.n_q = 6;  // degree + 3: no compiled kernel
    const MatrixFreeOperator<3, TestExecSpace> op(space, o);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<double> xh(n);
    for (double& e : xh) e = u(rng);
    const Vector x = to_device(xh), y_op("y_op", n), y_teams("y_teams", n);
    op.apply(exec, x, y_op);
    const auto k = kernels::sumfac::make_generic_cell_kernel<3, TestExecSpace>(
        space.lattice(), space.coordinates(), Point{}, 3, 6,
        kernels::sumfac::QuadratureKind::gauss);
    kernels::sumfac::for_each_batch_team_at_once(exec, k.lattice, "test::generic_in_teams",
                                                 k.scratch_bytes(), team_size,
                                                 GenericBatches<3, Point>{k, x, y_teams.data(), n});
    exec.fence();
    const std::vector<double> a = to_host(y_op), b = to_host(y_teams);
    std::vector<char> constrained(n, 0);
    const auto cons =
        Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), space.constrained_dofs());
    for (std::size_t i = 0; i < cons.extent(0); ++i) constrained[cons(i)] = 1;
    double scale = 0.0, err = 0.0;
    long rows = 0;
    for (long i = 0; i < n; ++i) {
      if (constrained[i]) continue;
      ++rows;
      scale = std::max(scale, std::abs(a[i]));
      err = std::max(err, std::abs(a[i] - b[i]));
    }
    EXPECT_GT(rows, n / 2);
    EXPECT_LT(err, 1e-13 * scale) << "kind " << static_cast<int>(kind) << ", teams of "
                                  << team_size;
  }
}

TEST(MatrixFreeOperator, GenericKernelInTeamsOfTwoMatchesTheOperator) {
  check_generic_in_teams<kernels::sumfac::LaplacePoint<3>>(OperatorKind::laplace);
  check_generic_in_teams<kernels::sumfac::MassPoint<3>>(OperatorKind::mass);
}

TEST(MatrixFreeOperator, CollocatedVectorVariableCoefficientAndConvectionOperatorsMatch) {
  for (int k : {2, 3}) {
    check<2>({K::laplace, G::stored, "curved", k, 0, true}, 9, 3, 1);  // collocation (BP5)
    check<3>({K::laplace, G::cartesian, "cartesian", k, 0, true, false, 3}, 9, 3, 2);  // BP6
    check<3>({K::mass, G::cartesian, "cartesian", k, 1, false, false, 3}, 9, 3, 2);    // BP2
    check<2>({K::laplace, G::stored, "curved", k, 1, false, true}, 9, 3, 1);
    check<3>({K::laplace, G::on_the_fly, "curved", k, 0, false, true}, 9, 3, 2);
    check<2>({K::convection, G::stored, "curved", k, 1}, 9, 3, 1);
    check<3>({K::convection, G::on_the_fly, "affine", k}, 9, 3, 2);
  }
  // 3D collocation through the points: from n_q = 6 the point sweeps run in place and the
  // integration goes straight into the nodal values
  for (int k : {2, 5, 7}) check<3>({K::laplace, G::stored, "curved", k, 0, true}, 3, 2, 2);
}

// The team schedule (kernels/sumfac/team_cell_kernel.hpp), which devices may take for the
// stored-geometry mass and Laplace: the same assembled matrices, on curved cells with periodic,
// Dirichlet and Neumann faces and partial batches, Gauss (n_q = k + 1, k + 2) and collocated
// Gauss-Lobatto points, a coefficient field, 3 components; teams of one thread, of the
// kernel's choice and of two where the backend has them (then the team shares every sweep).
TEST(MatrixFreeOperator, TeamKernelMatchesAssembledMatrices) {
  std::vector<int> sizes{1};  // (0, the kernel's choice, is 1 on host spaces)
  if (TestExecSpace().concurrency() >= 2) sizes.push_back(2);
  if (!kernels::runs_on_host_v<TestExecSpace>) sizes.push_back(0);
  for (int t : sizes)
    for (int k = 1; k <= 4; ++k) {
      Case c{K::laplace, G::stored, "curved", k};
      c.team_size = t;
      check<2>(c, 5, 3, 1);
      check<3>(c, 5, 3, 2);
      c.gauss_lobatto = true;  // collocated
      check<3>(c, 5, 3, 2);
      c.gauss_lobatto = false, c.n_q_extra = 1, c.with_field = true;
      check<3>(c, 5, 3, 2);
      Case m{K::mass, G::stored, "curved", k, 1};
      m.team_size = t;
      check<2>(m, 5, 3, 1);
      m.components = 3;
      check<3>(m, 5, 3, 2);
    }
  Case high{K::laplace, G::stored, "curved", 7, 1};  // 9 points: one cell per team
  high.team_size = 0;
  check<3>(high, 2, 2, 1);
}

// The team schedule's apply_unconstrained (the lifting of Dirichlet values) and CG direction
// equal the cell-per-thread schedule's to round-off.
TEST(MatrixFreeOperator, TeamKernelUnconstrainedAndDirectionMatchTheCellKernel) {
  const TestExecSpace exec;
  const auto m = mixed_mesh<3>(5, 3, 2, "curved");
  const mesh::hex::QkSpace<3, TestExecSpace> space(m, 3);
  const long n = space.n_dofs();
  typename MatrixFreeOperator<3, TestExecSpace>::Options o;
  const MatrixFreeOperator<3, TestExecSpace> cell(space, o);
  o.team_kernel = true;
  const MatrixFreeOperator<3, TestExecSpace> team(space, o);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> xh(n), zh(n);
  for (double& e : xh) e = u(rng);
  for (double& e : zh) e = u(rng);
  const Vector x = to_device(xh), y_cell("y_cell", n), y_team("y_team", n);
  cell.apply_unconstrained(exec, x, y_cell);
  team.apply_unconstrained(exec, x, y_team);
  const auto max_diff = [&](const Vector& a, const Vector& b, double& scale) {
    const std::vector<double> ah = to_host(a), bh = to_host(b);
    double err = 0.0;
    scale = 0.0;
    for (long i = 0; i < n; ++i) {
      scale = std::max(scale, std::abs(ah[i]));
      err = std::max(err, std::abs(ah[i] - bh[i]));
    }
    return err;
  };
  double scale = 0.0, err = max_diff(y_cell, y_team, scale);
  EXPECT_LT(err, 1e-13 * scale) << "apply_unconstrained";
  const Vector z = to_device(zh), p_cell = to_device(xh), p_team = to_device(xh);
  const double pq_cell = cell.apply_direction(exec, z, 0.5, p_cell, y_cell);
  const double pq_team = team.apply_direction(exec, z, 0.5, p_team, y_team);
  err = max_diff(y_cell, y_team, scale);
  EXPECT_LT(err, 1e-13 * scale) << "apply_direction: q";
  EXPECT_NEAR(pq_team, pq_cell, 1e-13 * std::abs(pq_cell)) << "apply_direction: p.q";
}

TEST(MatrixFreeOperator, TeamKernelRefusesOperatorsItDoesNotTake) {
  const auto m = mixed_mesh<3>(3, 2, 2, "curved");
  const mesh::hex::QkSpace<3, TestExecSpace> space(m, 2);
  typename MatrixFreeOperator<3, TestExecSpace>::Options o;
  o.team_kernel = true;
  o.geometry = G::on_the_fly;
  EXPECT_THROW((MatrixFreeOperator<3, TestExecSpace>(space, o)), std::invalid_argument);
  o.geometry = G::stored;
  o.n_q = 5;  // degree + 3: only the generic kernel has it
  EXPECT_THROW((MatrixFreeOperator<3, TestExecSpace>(space, o)), std::invalid_argument);
  o.n_q = 0;
  o.kind = K::elasticity;
  o.components = 3;
  EXPECT_THROW((MatrixFreeOperator<3, TestExecSpace>(space, o)), std::invalid_argument);
  o.kind = K::laplace;
  o.components = 1;
  EXPECT_NO_THROW((MatrixFreeOperator<3, TestExecSpace>(space, o)));
}

// Linear elasticity, dim coupled components through one point functor, equals the textbook
// assembled block matrix (operator and diagonal) on curved cells.
/// A x and the diagonal of the operator equal the assembled matrix's to 1e-12 (relative to
/// their largest entries).
template <class Op>
void expect_matches_assembled(const Op& op, const Eigen::SparseMatrix<double>& A,
                              const std::vector<double>& x) {
  const long n = static_cast<long>(x.size());
  Vector yd("y", n), dd("d", n);
  op.apply(TestExecSpace(), to_device(x), yd);
  op.compute_diagonal(TestExecSpace(), dd);
  const std::vector<double> y = to_host(yd), d = to_host(dd);
  const Eigen::VectorXd ref = A * Eigen::Map<const Eigen::VectorXd>(x.data(), n);
  double scale = 0.0, err = 0.0, dscale = 0.0, derr = 0.0;
  for (long i = 0; i < n; ++i) {
    scale = std::max(scale, std::abs(ref[i]));
    err = std::max(err, std::abs(ref[i] - y[i]));
    dscale = std::max(dscale, std::abs(A.coeff(i, i)));
    derr = std::max(derr, std::abs(A.coeff(i, i) - d[i]));
  }
  EXPECT_LT(err, 1e-12 * scale) << "max |A x - A_ref x| = " << err << " of " << scale;
  EXPECT_LT(derr, 1e-12 * dscale) << "diagonal";
}

template <int dim>
void check_elasticity(GeometryMode geometry, int degree, int nx, int ny, int nz) {
  SCOPED_TRACE("elasticity dim " + std::to_string(dim) + " k " + std::to_string(degree));
  const auto m = mixed_mesh<dim>(nx, ny, nz, "curved");
  const mesh::hex::QkSpace<dim, TestExecSpace> space(m, degree);
  const long n = dim * space.n_dofs();
  typename MatrixFreeOperator<dim, TestExecSpace>::Options o;
  o.kind = OperatorKind::elasticity;
  o.geometry = geometry;
  o.components = dim;
  o.lambda = 2.5;
  o.mu = 0.7;
  const MatrixFreeOperator<dim, TestExecSpace> op(space, o);
  const auto A = test::assemble_elasticity_reference<dim>(space, degree + 1, o.lambda, o.mu);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> x(n);
  for (double& e : x) e = u(rng);
  expect_matches_assembled(op, A, x);
}

TEST(MatrixFreeOperator, ElasticityMatchesAssembledBlockMatrix) {
  for (int k = 1; k <= 4; ++k) {
    check_elasticity<2>(GeometryMode::stored, k, 9, 3, 1);
    check_elasticity<3>(GeometryMode::on_the_fly, k, 5, 3, 2);
  }
  check_elasticity<3>(GeometryMode::stored, 2, 9, 3, 2);
}

/// n values drawn uniformly from [-scale, scale).
std::vector<double> uniform_values(std::mt19937& rng, long n, double scale) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> v(n);
  for (double& e : v) e = scale * u(rng);
  return v;
}

// The stabilised Oseen operator (velocity and pressure coupled, SUPG/PSPG, grad-div) and its
// history form against term-by-term assembly, on curved cells with a random advecting field.
// The viscous term of the strong residual (-nu lap u) is checked on Cartesian cells, where the
// reference's Laplacians are exact; on curved cells the operator interpolates J^-1.
template <int dim>
void check_oseen(GeometryMode geometry, int degree, int nx, int ny, int nz, bool history,
                 const char* shape = "curved") {
  SCOPED_TRACE("Oseen dim " + std::to_string(dim) + " k " + std::to_string(degree) +
               (history ? " history " : " ") + shape);
  const mesh::hex::QkSpace<dim, TestExecSpace> space(mixed_mesh<dim>(nx, ny, nz, shape), degree);
  const long n = (dim + 1) * space.n_dofs();
  std::mt19937 rng(5);
  const std::vector<double> b = uniform_values(rng, dim * space.n_dofs(), 2.0);
  const std::vector<double> x = uniform_values(rng, n, 1.0);
  typename MatrixFreeOperator<dim, TestExecSpace>::Options o;
  o.kind = OperatorKind::oseen;
  o.geometry = geometry;
  o.components = dim + 1;
  o.field = to_device(b);
  o.nu = 0.03, o.alpha = 3.0, o.grad_div = 0.4, o.dt_inverse = 2.0, o.history = history;
  o.viscous_residual = std::string(shape) != "curved";
  const MatrixFreeOperator<dim, TestExecSpace> op(space, o);
  const auto A = test::assemble_oseen_reference<dim>(space, degree + 1, b, o);
  expect_matches_assembled(op, A, x);
  // and the CSR matrix assembled from the operator's own element matrices (the comparisons'
  // sparse-matrix form) applies the same
  const CsrMatrix C = assemble(TestExecSpace(), op);
  ASSERT_EQ(C.n, n);
  Vector yd("y", n);
  op.apply(TestExecSpace(), to_device(x), yd);
  const std::vector<double> y = to_host(yd);
  double err = 0.0, scale = 0.0;
  for (long i = 0; i < n; ++i) {
    double s = 0.0;
    for (long e = C.row_ptr[i]; e < C.row_ptr[i + 1]; ++e) s += C.values[e] * x[C.cols[e]];
    err = std::max(err, std::abs(s - y[i]));
    scale = std::max(scale, std::abs(y[i]));
  }
  EXPECT_LT(err, 1e-12 * scale) << "assembled CSR";
}

TEST(MatrixFreeOperator, OseenMatchesAssembledStabilisedForm) {
  for (int k = 1; k <= 3; ++k) {
    check_oseen<2>(GeometryMode::stored, k, 7, 3, 1, false);
    check_oseen<2>(GeometryMode::on_the_fly, k, 7, 3, 1, true);
  }
  check_oseen<3>(GeometryMode::stored, 2, 4, 3, 2, false);
  check_oseen<3>(GeometryMode::on_the_fly, 1, 4, 3, 2, true);
  for (int k = 1; k <= 3; ++k) check_oseen<2>(GeometryMode::stored, k, 7, 3, 1, false, "affine");
  check_oseen<3>(GeometryMode::on_the_fly, 2, 4, 3, 2, false, "cartesian");
}

// without_viscous_residual() shares the stored coefficients and applies (and has the diagonal
// of) the operator built without -nu lap u; at k = 2 that differs from the full operator.
TEST(MatrixFreeOperator, OseenWithoutViscousResidualIsTheOperatorBuiltWithout) {
  const mesh::hex::QkSpace<2, TestExecSpace> space(mixed_mesh<2>(5, 4, 1, "affine"), 2);
  const long n = 3 * space.n_dofs();
  std::mt19937 rng(7);
  const std::vector<double> b = uniform_values(rng, 2 * space.n_dofs(), 1.0);
  const std::vector<double> x = uniform_values(rng, n, 1.0);
  typename MatrixFreeOperator<2, TestExecSpace>::Options o;
  o.kind = OperatorKind::oseen;
  o.components = 3;
  o.field = to_device(b);
  o.nu = 0.05, o.alpha = 3.0, o.grad_div = 0.4, o.dt_inverse = 2.0;
  const MatrixFreeOperator<2, TestExecSpace> full(space, o);
  const auto variant = full.without_viscous_residual();
  o.viscous_residual = false;
  const MatrixFreeOperator<2, TestExecSpace> built(space, o);
  EXPECT_FALSE(variant.options().viscous_residual);
  const TestExecSpace exec;
  const auto apply = [&](const MatrixFreeOperator<2, TestExecSpace>& op, bool diagonal) {
    Vector y("y", n);
    if (diagonal)
      op.compute_diagonal(exec, y);
    else
      op.apply(exec, to_device(x), y);
    return to_host(y);
  };
  for (bool diagonal : {false, true}) {
    const std::vector<double> yf = apply(full, diagonal), yv = apply(variant, diagonal),
                              yb = apply(built, diagonal);
    double same = 0.0, apart = 0.0, scale = 0.0;
    for (long i = 0; i < n; ++i) {
      same = std::max(same, std::abs(yv[i] - yb[i]));
      apart = std::max(apart, std::abs(yv[i] - yf[i]));
      scale = std::max(scale, std::abs(yb[i]));
    }
    EXPECT_LE(same, 1e-14 * scale) << (diagonal ? "diagonal" : "apply");
    EXPECT_GT(apart, 1e-6 * scale) << (diagonal ? "diagonal" : "apply");
  }
}

TEST(MatrixFreeOperator, OseenRefusesBadOptions) {
  const mesh::hex::QkSpace<2, TestExecSpace> space(mixed_mesh<2>(3, 2, 1, "curved"), 2);
  typename MatrixFreeOperator<2, TestExecSpace>::Options o;
  o.kind = OperatorKind::oseen;
  o.components = 3;
  EXPECT_THROW((MatrixFreeOperator<2, TestExecSpace>(space, o)), std::invalid_argument);  // field
  o.field = Vector("b", 2 * space.n_dofs());
  o.nu = 0.0;
  EXPECT_THROW((MatrixFreeOperator<2, TestExecSpace>(space, o)), std::invalid_argument);  // nu
  o.nu = 1.0;
  o.components = 2;
  EXPECT_THROW((MatrixFreeOperator<2, TestExecSpace>(space, o)), std::invalid_argument);
  o.components = 3;
  EXPECT_NO_THROW((MatrixFreeOperator<2, TestExecSpace>(space, o)));
}

TEST(MatrixFreeOperator, ElasticityRefusesPerCellGeometryAndScalarVectors) {
  const mesh::hex::QkSpace<3, TestExecSpace> space(mixed_mesh<3>(3, 2, 2, "cartesian"), 2);
  typename MatrixFreeOperator<3, TestExecSpace>::Options o;
  o.kind = OperatorKind::elasticity;
  o.components = 1;
  EXPECT_THROW((MatrixFreeOperator<3, TestExecSpace>(space, o)), std::invalid_argument);
  o.components = 3;
  o.geometry = GeometryMode::cartesian;
  EXPECT_THROW((MatrixFreeOperator<3, TestExecSpace>(space, o)), std::invalid_argument);
}

TEST(MatrixFreeOperator, MassOfUnitCubeIsOneAndLaplacianOfConstantVanishes) {
  const TestExecSpace exec;
  for (int k : {1, 2, 4, 7, 8}) {
    auto m = mesh::hex::unit_cube<3>(k <= 2 ? 8 : 3, FaceCondition::neumann);
    m.deformation = mesh::hex::sinusoidal_deformation(3, 0.05);  // boundary fixed: volume stays 1
    const mesh::hex::QkSpace<3, TestExecSpace> space(m, k);
    const long n = space.n_dofs();
    Vector one("one", n), y("y", n);
    Kokkos::deep_copy(one, 1.0);
    typename MatrixFreeOperator<3, TestExecSpace>::Options o;
    o.kind = OperatorKind::mass;
    o.n_q = k + 2;
    MatrixFreeOperator<3, TestExecSpace> mass(space, o);
    mass.apply(exec, one, y);
    // 1^T M 1 = volume; the deformation keeps the faces, so the volume is exactly 1 (quadrature
    // integrates det J of the curved map only approximately: tolerance from k+2 points).
    EXPECT_NEAR(kernels::blas1::sum(exec, y), 1.0, k <= 2 ? 1e-4 : 1e-9) << "k " << k;
    o.kind = OperatorKind::laplace;
    MatrixFreeOperator<3, TestExecSpace> lap(space, o);
    lap.apply(exec, one, y);
    EXPECT_LT(kernels::blas1::norm_inf(exec, y), 1e-12) << "k " << k;
  }
  // undeformed: exact to round-off
  const mesh::hex::QkSpace<2, TestExecSpace> space(
      mesh::hex::unit_cube<2>(5, FaceCondition::neumann), 3);
  Vector one("one", space.n_dofs()), y("y", space.n_dofs());
  Kokkos::deep_copy(one, 1.0);
  typename MatrixFreeOperator<2, TestExecSpace>::Options o;
  o.kind = OperatorKind::mass;
  o.geometry = GeometryMode::cartesian;
  MatrixFreeOperator<2, TestExecSpace> mass(space, o);
  mass.apply(exec, one, y);
  EXPECT_NEAR(kernels::blas1::sum(exec, y), 1.0, 1e-14);
}

// Equal cells (a uniform box, uniformly sheared) keep one set of per-cell coefficients, whatever
// the mesh size; stored geometry grows with the cells. (The operators' values on such meshes are
// checked against assembled matrices above.)
TEST(MatrixFreeOperator, EqualCellsShareOneSetOfCoefficients) {
  using Op = MatrixFreeOperator<3, TestExecSpace>;
  const std::size_t simd =
      sizeof(kernels::sumfac::Simd<kernels::sumfac::simd_width_v<TestExecSpace>>);
  for (const int n : {3, 8}) {
    typename Op::Options o;
    o.geometry = GeometryMode::cartesian;
    const mesh::hex::QkSpace<3, TestExecSpace> box(mixed_mesh<3>(n, n, n, "cartesian"), 2);
    EXPECT_EQ(Op(box, o).geometry_bytes(), 3 * simd)
        << "cartesian Laplace, n " << n;  // G_00, G_11, G_22
    o.geometry = GeometryMode::affine;
    const mesh::hex::QkSpace<3, TestExecSpace> sheared(mixed_mesh<3>(n, n, n, "affine"), 2);
    EXPECT_EQ(Op(sheared, o).geometry_bytes(), 6 * simd)
        << "affine Laplace, n " << n;  // packed symmetric G
    o.geometry = GeometryMode::stored;
    EXPECT_GT(Op(sheared, o).geometry_bytes(), std::size_t(n * n) * 6 * simd) << "stored, n " << n;
  }
}

TEST(MatrixFreeOperator, BadOptionsAreRefusedWithAReason) {
  const mesh::hex::QkSpace<2, TestExecSpace> curved(mixed_mesh<2>(4, 4, 1, "curved"), 2);
  typename MatrixFreeOperator<2, TestExecSpace>::Options o;
  o.geometry = GeometryMode::cartesian;
  EXPECT_THROW((MatrixFreeOperator<2, TestExecSpace>(curved, o)), std::invalid_argument);
  o.geometry = GeometryMode::stored;
  o.n_q = 7;  // not compiled: the generic kernel takes it
  EXPECT_NO_THROW((MatrixFreeOperator<2, TestExecSpace>(curved, o)));
  o.n_q = 13;  // beyond the generic kernel too
  EXPECT_THROW((MatrixFreeOperator<2, TestExecSpace>(curved, o)), std::invalid_argument);
  o.n_q = 0;
  o.kind = OperatorKind::convection;
  EXPECT_THROW((MatrixFreeOperator<2, TestExecSpace>(curved, o)), std::invalid_argument);
  o.n_q = 7;  // convection has no generic kernel
  o.field = Vector("velocity", 2 * curved.n_dofs());
  EXPECT_THROW((MatrixFreeOperator<2, TestExecSpace>(curved, o)), std::invalid_argument);
  EXPECT_THROW((mesh::hex::QkSpace<2, TestExecSpace>(mixed_mesh<2>(4, 4, 1, ""), 9)),
               std::invalid_argument);
}

}  // namespace
}  // namespace amphora::solvers::matrix_free

namespace amphora::solvers::matrix_free {
namespace {

// CG's direction step in one sweep (apply_direction: p = z + beta p, q = A p, p.q) equals its
// three passes: Dirichlet and Neumann boxes and the mixed mesh, periodic along x (the sweep), a
// periodic cube (the passes); one and three components, 2D and 3D, k = 1..4, beta = 0 (p not
// read: NaN before) and beta != 0, slab counts of one and several blocks.
template <int dim>
void check_direction(const mesh::hex::StructuredHexMesh<dim>& m, int k, int components,
                     bool gauss_lobatto) {
  SCOPED_TRACE(std::to_string(dim) + "D k " + std::to_string(k) + " components " +
               std::to_string(components) + (gauss_lobatto ? " GL" : ""));
  const TestExecSpace exec;
  const mesh::hex::QkSpace<dim, TestExecSpace> space(m, k);
  typename MatrixFreeOperator<dim, TestExecSpace>::Options o;
  o.geometry = G::cartesian;
  o.components = components;
  o.quadrature = gauss_lobatto ? kernels::sumfac::QuadratureKind::gauss_lobatto
                               : kernels::sumfac::QuadratureKind::gauss;
  const MatrixFreeOperator<dim, TestExecSpace> op(space, o);
  const long n = op.size();
  std::vector<double> z(n), p0(n);
  for (long i = 0; i < n; ++i) z[i] = std::sin(0.37 * i) + 0.1, p0[i] = std::cos(0.21 * i);
  for (const double beta : {0.0, 0.7}) {
    Vector zd = to_device(z), p = to_device(p0), q("q", n);
    if (beta == 0.0) kernels::blas1::fill(exec, p, std::nan(""));
    const double pq = op.apply_direction(exec, zd, beta, p, q);
    // the passes, on the host's p = z + beta p
    std::vector<double> p_ref(n);
    for (long i = 0; i < n; ++i) p_ref[i] = z[i] + beta * p0[i];
    Vector pr = to_device(p_ref), qr("qr", n);
    op.apply(exec, pr, qr);
    const double pq_ref = kernels::blas1::dot(exec, pr, qr);
    const auto ph = to_host(p), qh = to_host(q), qrh = to_host(qr);
    double perr = 0.0, qerr = 0.0, qscale = 0.0;
    for (long i = 0; i < n; ++i) {
      perr = std::max(perr, std::abs(ph[i] - p_ref[i]));
      qerr = std::max(qerr, std::abs(qh[i] - qrh[i]));
      qscale = std::max(qscale, std::abs(qrh[i]));
    }
    EXPECT_LT(perr, 1e-15 * 2.0) << "beta " << beta << ": p";
    EXPECT_LT(qerr, 1e-13 * qscale) << "beta " << beta << ": q";
    EXPECT_NEAR(pq, pq_ref, 1e-12 * std::abs(pq_ref)) << "beta " << beta << ": p.q";
  }
}

TEST(MatrixFreeOperator, DirectionStepInOneSweepEqualsItsPasses) {
  for (int k = 1; k <= 4; ++k)
    for (int nz : {3, 18}) {  // slab blocks: 3 of one slab; 9 of two
      check_direction<3>(mesh::hex::unit_cube<3>(nz + 1, FaceCondition::dirichlet), k, 1, true);
      check_direction<3>(mixed_mesh<3>(11, 4, nz, "cartesian"), k, 1, false);
      check_direction<2>(mixed_mesh<2>(11, nz, 1, "cartesian"), k, 3, false);
      auto box = mesh::hex::unit_cube<2>(nz, FaceCondition::dirichlet);
      check_direction<2>(box, k, 1, false);
    }
  check_direction<3>(mesh::hex::unit_cube<3>(9, FaceCondition::neumann), 3, 3, false);
  check_direction<3>(mesh::hex::unit_cube<3>(6, FaceCondition::periodic), 2, 1,
                     false);  // the passes
}

// CG takes the sweep wherever the operator offers it; its iterates equal those of the passes
// (the operator seen through apply() only) to round-off, with and without a preconditioner.
template <class Op>
struct ApplyOnly {
  const Op* op;
  void apply(const TestExecSpace& exec, const Vector& x, const Vector& y) const {
    op->apply(exec, x, y);
  }
};

TEST(MatrixFreeOperator, ConjugateGradientTakesTheSweepAndMatchesThePasses) {
  using Op = MatrixFreeOperator<3, TestExecSpace>;
  static_assert(has_fused_direction<Op, TestExecSpace, Vector, LocalInnerProduct>::value);
  static_assert(
      !has_fused_direction<ApplyOnly<Op>, TestExecSpace, Vector, LocalInnerProduct>::value);
  const TestExecSpace exec;
  const mesh::hex::QkSpace<3, TestExecSpace> space(
      mesh::hex::unit_cube<3>(10, FaceCondition::dirichlet), 2);
  Op::Options o;
  o.geometry = G::cartesian;
  const Op op(space, o);
  const long n = op.size();
  std::vector<double> b(n);
  for (long i = 0; i < n; ++i) b[i] = std::sin(0.37 * i) + 0.1;
  Vector bd = to_device(b), d("d", n);
  op.compute_diagonal(exec, d);
  kernels::blas1::reciprocal(exec, d);
  SolverControl control;
  control.max_iterations = 10;
  control.relative_tolerance = 0.0;
  for (const bool jacobi : {false, true}) {
    Vector x_sweep("x_sweep", n), x_passes("x_passes", n);
    SolverResult sweep, passes;
    if (jacobi) {
      const JacobiPreconditioner<Vector> M{d};
      sweep = conjugate_gradient(exec, op, bd, x_sweep, control, M);
      passes = conjugate_gradient(exec, ApplyOnly<Op>{&op}, bd, x_passes, control, M);
    } else {
      sweep = conjugate_gradient(exec, op, bd, x_sweep, control);
      passes = conjugate_gradient(exec, ApplyOnly<Op>{&op}, bd, x_passes, control);
    }
    EXPECT_EQ(sweep.iterations, 10);
    EXPECT_EQ(passes.iterations, 10);
    EXPECT_NEAR(sweep.final_residual, passes.final_residual, 1e-9 * passes.final_residual)
        << "jacobi " << jacobi;
    const auto xs = to_host(x_sweep), xp = to_host(x_passes);
    double err = 0.0, scale = 0.0;
    for (long i = 0; i < n; ++i)
      err = std::max(err, std::abs(xs[i] - xp[i])), scale = std::max(scale, std::abs(xp[i]));
    // CG amplifies the round-off of a different summation order: the passes alone differ by
    // ~1e-10 of |x| between Serial and OpenMP after 10 iterations here; a wrong p.q by O(1)
    EXPECT_LT(err, 1e-8 * scale) << "jacobi " << jacobi;
  }
}

// The coloured cell loop forms every sum in the same order whatever the thread count: on a host
// backend the result equals Kokkos::Serial's bit for bit (curved 3D Laplace, Q3 and Q5). A GPU
// adds the cells' contributions atomically, in no fixed order, and contracts other products into
// FMAs: there the result may differ by round-off, a few ulps of the entries it sums.
TEST(MatrixFreeOperator, ResultDoesNotDependOnTheBackendOrThreadCount) {
#if defined(KOKKOS_ENABLE_SERIAL)
  for (int k : {3, 5}) {
    auto m = mixed_mesh<3>(17, 6, 18, "curved");  // 9 slab blocks of 2
    const mesh::hex::QkSpace<3, TestExecSpace> space(m, k);
    const mesh::hex::QkSpace<3, Kokkos::Serial> serial_space(m, k);
    typename MatrixFreeOperator<3, TestExecSpace>::Options o;
    typename MatrixFreeOperator<3, Kokkos::Serial>::Options os;
    const MatrixFreeOperator<3, TestExecSpace> op(space, o);
    const MatrixFreeOperator<3, Kokkos::Serial> ops(serial_space, os);
    std::vector<double> x(space.n_dofs());
    for (std::size_t i = 0; i < x.size(); ++i) x[i] = std::sin(0.37 * i) + 0.1;
    Vector xd = to_device(x), yd("y", x.size());
    op.apply(TestExecSpace(), xd, yd);
    Kokkos::View<double*, Kokkos::HostSpace> xs("xs", x.size()), ys("ys", x.size());
    for (std::size_t i = 0; i < x.size(); ++i) xs(i) = x[i];
    ops.apply(Kokkos::Serial(), xs, ys);
    const auto y = to_host(yd);
    long differ = 0;
    double worst = 0.0, scale = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      differ += y[i] != ys(i);
      worst = std::max(worst, std::abs(y[i] - ys(i)));
      scale = std::max(scale, std::abs(ys(i)));
    }
    if (kernels::runs_on_host_v<TestExecSpace>) {
      EXPECT_EQ(differ, 0) << "k " << k << ": entries differing from Serial";
    } else {  // 1e-12: ~4500 ulps of the largest entry; a wrong term is off by O(1) of it
      EXPECT_LT(worst, 1e-12 * scale) << "k " << k << ": " << differ << " entries differ";
    }
  }
#endif
}

}  // namespace
}  // namespace amphora::solvers::matrix_free
