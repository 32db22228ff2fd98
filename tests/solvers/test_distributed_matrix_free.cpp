// Matrix-free operators on a Q_k space split over MPI ranks (slabs along the last direction)
// equal the operator of the whole box to 1e-12 relative on every owned DoF, at 1 and 2 ranks:
// Laplace and mass, k = 1..6, and the stabilised Oseen operator, k = 1..4, 2D and 3D,
// curved/affine/Cartesian cells, Dirichlet, Neumann and periodic faces (periodic along the split
// direction too), the collocated and 3-component variants, the diagonal; Jacobi-CG,
// multigrid-CG, Jacobi-GMRES and multigrid-GMRES (Oseen) on the slabs reach the undistributed
// solution in the same number of iterations.
#include <cmath>
#include <string>
#include <type_traits>
#include <vector>

#include "deformed_box.hpp"
#include "kernels/host_vector.hpp"
#include "mesh/box_decomposition.hpp"
#include "solvers/conjugate_gradient.hpp"
#include "solvers/gmres.hpp"
#include "solvers/matrix_free/load_vector.hpp"
#include "solvers/matrix_free/multigrid.hpp"
#include "solvers/matrix_free/oseen_multigrid.hpp"
#include "solvers/matrix_free/transfer.hpp"
#include "test_backend.hpp"

namespace amphora::solvers::matrix_free {
namespace {

using test::TestExecSpace;
using Vector = Kokkos::View<double*, test::TestMemSpace>;
using mesh::hex::FaceCondition;

template <int dim>
mesh::hex::StructuredHexMesh<dim> box(int n, const std::string& shape, bool periodic_split) {
  mesh::hex::StructuredHexMesh<dim> m;
  m.cells = {n + 1, n, n + 2};
  m.faces = {FaceCondition::dirichlet, FaceCondition::neumann,   FaceCondition::periodic,
             FaceCondition::periodic,  FaceCondition::dirichlet, FaceCondition::dirichlet};
  if (dim == 2) m.faces[2] = m.faces[3] = FaceCondition::dirichlet;
  if (periodic_split) m.faces[2 * (dim - 1)] = m.faces[2 * (dim - 1) + 1] = FaceCondition::periodic;
  test::deform(m, shape);
  return m;
}

double sample(long i) { return std::sin(0.37 * i) + 0.5 * std::cos(1.3 * double(i * i % 97)); }

struct Case {
  OperatorKind kind = OperatorKind::laplace;
  GeometryMode geometry = GeometryMode::stored;
  std::string shape = "curved";
  int degree = 2;
  bool periodic_split = false;
  bool gauss_lobatto = false;
  int components = 1;
};

template <int dim>
typename MatrixFreeOperator<dim, TestExecSpace>::Options options(const Case& c) {
  typename MatrixFreeOperator<dim, TestExecSpace>::Options o;
  o.kind = c.kind;
  o.geometry = c.geometry;
  o.components = c.kind == OperatorKind::oseen ? dim + 1 : c.components;
  if (c.gauss_lobatto) {
    o.quadrature = kernels::sumfac::QuadratureKind::gauss_lobatto;
    o.n_q = c.degree + 1;
  }
  if (c.kind == OperatorKind::oseen) {  // a BDF2 step of a convective flow (cell Re ~ 10)
    o.nu = 0.02, o.alpha = 30.0, o.grad_div = 0.1, o.dt_inverse = 20.0;
  }
  return o;
}

/// The Oseen operator's advecting velocity, a smooth field of the nodes' coordinates, on the
/// whole box (dim blocks of n_dofs).
template <int dim>
std::vector<double> advecting_field(const mesh::hex::QkSpace<dim, TestExecSpace>& whole) {
  return whole.interpolate(
      [](const mesh::hex::Point3& x, int d) {
        return std::sin(2.0 * x[(d + 1) % dim] + d) + 0.3 * std::cos(3.0 * x[d]);
      },
      dim);
}

/// A rank's local vector of `components` blocks: the owned entries from the whole box's vector
/// `global`, the ghost layer junk (what an operator or transfer must overwrite first).
template <int dim>
std::vector<double> owned_part(const mesh::hex::DistributedQkSpace<dim, TestExecSpace>& space,
                               const std::vector<double>& global, int components,
                               double ghost = 1e3) {
  const long nl = space.n_local(), ng = space.n_global();
  std::vector<double> local(static_cast<std::size_t>(nl) * components, ghost);
  for (int a = 0; a < components; ++a)
    for (long i = 0; i < space.n_owned(); ++i)
      local[a * nl + i] = global[a * ng + space.global_index(i)];
  return local;
}

/// max over the owned entries of every rank of |local - global| (collective).
template <int dim>
double owned_difference(const mesh::hex::DistributedQkSpace<dim, TestExecSpace>& space,
                        const std::vector<double>& local, const std::vector<double>& global,
                        int components) {
  const long nl = space.n_local(), ng = space.n_global();
  double err = 0.0;
  for (int a = 0; a < components; ++a)
    for (long i = 0; i < space.n_owned(); ++i)
      err = std::max(err, std::abs(local[a * nl + i] - global[a * ng + space.global_index(i)]));
  return space.communicator().max(err);
}

/// The advecting field on a rank's slab, its ghost layer from the owners (the operator reads
/// the field at the ghost layer too).
template <int dim>
Vector local_field(const mesh::hex::DistributedQkSpace<dim, TestExecSpace>& space,
                   const mesh::hex::QkSpace<dim, TestExecSpace>& whole) {
  const Vector u =
      kernels::to_view<test::TestMemSpace>(owned_part(space, advecting_field(whole), dim));
  space.update_ghosts(TestExecSpace(), u, dim);
  return u;
}

double max_abs(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

template <int dim>
void check(const Case& c, int n) {
  Communicator comm;
  auto o = options<dim>(c);
  SCOPED_TRACE("dim " + std::to_string(dim) + " k " + std::to_string(c.degree) + " kind " +
               std::to_string(static_cast<int>(c.kind)) + " " + c.shape +
               (c.periodic_split ? " periodic split" : "") + (c.gauss_lobatto ? " GL" : "") +
               " components " + std::to_string(o.components) + " ranks " +
               std::to_string(comm.size()));
  const TestExecSpace exec;
  const auto m = box<dim>(n, c.shape, c.periodic_split);

  // The whole box on every rank: the reference.
  const mesh::hex::QkSpace<dim, TestExecSpace> whole(m, c.degree);
  const long ng = whole.n_dofs();
  if (c.kind == OperatorKind::oseen)
    o.field = kernels::to_view<test::TestMemSpace>(advecting_field(whole));
  const MatrixFreeOperator<dim, TestExecSpace> reference(whole, o);
  std::vector<double> xg(static_cast<size_t>(ng) * o.components);
  for (size_t i = 0; i < xg.size(); ++i) xg[i] = sample(static_cast<long>(i));
  Vector yg("yg", xg.size()), dg("dg", xg.size());
  reference.apply(exec, kernels::to_view<test::TestMemSpace>(xg), yg);
  reference.compute_diagonal(exec, dg);
  const std::vector<double> y_ref = kernels::to_std_vector(yg), d_ref = kernels::to_std_vector(dg);

  const mesh::hex::DistributedQkSpace<dim, TestExecSpace> space(m, c.degree, comm);
  ASSERT_EQ(space.n_global(), ng);
  if (c.kind == OperatorKind::oseen) o.field = local_field(space, whole);
  const DistributedOperator<dim, TestExecSpace> op(space, o);
  const std::vector<double> xl = owned_part(space, xg, o.components);
  Vector y("y", xl.size()), d("d", xl.size());
  op.apply(exec, kernels::to_view<test::TestMemSpace>(xl), y);
  op.compute_diagonal(exec, d);
  EXPECT_LE(owned_difference(space, kernels::to_std_vector(y), y_ref, o.components),
            1e-12 * max_abs(y_ref));
  EXPECT_LE(owned_difference(space, kernels::to_std_vector(d), d_ref, o.components),
            1e-12 * max_abs(d_ref));
}

TEST(DistributedMatrixFree, LaplaceAndMassOnSlabsEqualTheWholeBoxOperator) {
  for (int k = 1; k <= 6; ++k) {
    for (const bool periodic : {false, true}) {
      Case c;
      c.degree = k;
      c.periodic_split = periodic;
      check<2>(c, 3);
      check<3>(c, 2);
      c.kind = OperatorKind::mass;
      check<3>(c, 2);
    }
  }
}

TEST(DistributedMatrixFree, EveryGeometryCollocationAndVectorVariantAgrees) {
  for (const std::string shape : {"cartesian", "affine", "curved"}) {
    Case c;
    c.shape = shape;
    c.degree = 3;
    check<3>(c, 3);
  }
  Case c;
  c.geometry = GeometryMode::on_the_fly;
  c.degree = 4;
  check<3>(c, 2);
  c.geometry = GeometryMode::stored;
  c.gauss_lobatto = true;
  check<3>(c, 2);
  c.gauss_lobatto = false;
  c.components = 3;
  c.periodic_split = true;
  check<3>(c, 2);
}

// The stabilised Oseen operator (velocity and pressure blocked, the advecting velocity read at
// the ghost layer too): the pressure is free where the velocity is constrained, so the slabs'
// partial sums on a Dirichlet face's nodes of the shared layer are added for it alone.
TEST(DistributedMatrixFree, OseenOnSlabsEqualsTheWholeBoxOperator) {
  for (int k = 1; k <= 4; ++k)
    for (const bool periodic : {false, true})
      for (const std::string shape : {"cartesian", "curved"}) {
        Case c;
        c.kind = OperatorKind::oseen;
        c.degree = k;
        c.periodic_split = periodic;
        c.shape = shape;
        check<2>(c, 3);
        check<3>(c, 2);
      }
}

// Jacobi-CG to 1e-13 on the slabs and on the whole box: the same solution (to the solver's
// accuracy times the condition number's effect on round-off, 1e-10 relative) and the same
// number of iterations within one.
TEST(DistributedMatrixFree, ConjugateGradientOnSlabsReachesTheUndistributedSolution) {
  Communicator comm;
  const TestExecSpace exec;
  constexpr int dim = 3;
  const auto m = box<dim>(3, "curved", false);
  typename MatrixFreeOperator<dim, TestExecSpace>::Options o;
  const int k = 3;
  const mesh::hex::QkSpace<dim, TestExecSpace> whole(m, k);
  const MatrixFreeOperator<dim, TestExecSpace> reference(whole, o);
  const long ng = whole.n_dofs();
  std::vector<double> bg(ng);
  for (long i = 0; i < ng; ++i) bg[i] = sample(i);
  SolverControl control;
  control.relative_tolerance = 1e-13;
  control.max_iterations = 2000;

  Vector dgv("dg", ng), xg("xg", ng);
  reference.compute_diagonal(exec, dgv);
  auto inv = kernels::to_std_vector(dgv);
  for (auto& v : inv) v = 1.0 / v;
  const JacobiPreconditioner<Vector> mg{kernels::to_view<test::TestMemSpace>(inv)};
  const SolverResult rg = conjugate_gradient(
      exec, reference, kernels::to_view<test::TestMemSpace>(bg), xg, control, mg);
  ASSERT_TRUE(rg.converged);

  const mesh::hex::DistributedQkSpace<dim, TestExecSpace> space(m, k, comm);
  const DistributedOperator<dim, TestExecSpace> op(space, o);
  const long nl = space.n_local();
  const std::vector<double> bl = owned_part(space, bg, 1, 0.0);
  Vector dl("dl", nl), xl("xl", nl);
  op.compute_diagonal(exec, dl);
  auto invl = kernels::to_std_vector(dl);
  for (auto& v : invl) v = 1.0 / v;  // ghost layer: partial sums, never used
  const JacobiPreconditioner<Vector> ml{kernels::to_view<test::TestMemSpace>(invl)};
  const SolverResult rl = conjugate_gradient(exec, op, kernels::to_view<test::TestMemSpace>(bl), xl,
                                             control, ml, space.inner_product());
  ASSERT_TRUE(rl.converged);
  EXPECT_NEAR(rl.iterations, rg.iterations, 1);

  const auto xgh = kernels::to_std_vector(xg);
  EXPECT_LE(owned_difference(space, kernels::to_std_vector(xl), xgh, 1), 1e-10 * max_abs(xgh))
      << "iterations " << rl.iterations << " / " << rg.iterations;
}

// Jacobi-GMRES on the Oseen system (3D, curved cells, Dirichlet faces beside the shared
// layers) to 1e-12 on the slabs and on the whole box: the same solution to 1e-10 relative (the
// solver's accuracy times the system's conditioning) and the same iteration count within two.
TEST(DistributedMatrixFree, OseenGmresOnSlabsReachesTheUndistributedSolution) {
  Communicator comm;
  const TestExecSpace exec;
  constexpr int dim = 3;
  Case c;
  c.kind = OperatorKind::oseen;
  c.degree = 2;
  const auto m = box<dim>(3, "curved", false);
  auto o = options<dim>(c);
  const int nc = dim + 1;
  SolverControl control;
  control.relative_tolerance = 1e-12;
  control.max_iterations = 3000;

  const mesh::hex::QkSpace<dim, TestExecSpace> whole(m, c.degree);
  o.field = kernels::to_view<test::TestMemSpace>(advecting_field(whole));
  const MatrixFreeOperator<dim, TestExecSpace> reference(whole, o);
  const long ng = whole.n_dofs();
  std::vector<double> bg(nc * ng);
  for (std::size_t i = 0; i < bg.size(); ++i) bg[i] = sample(static_cast<long>(i));
  auto jacobi = [&](const auto& A, long n) {
    Vector d("d", nc * n);
    A.compute_diagonal(exec, d);
    auto inv = kernels::to_std_vector(d);
    for (auto& v : inv) v = 1.0 / v;  // slabs' ghost layers: partial sums, never used
    return JacobiPreconditioner<Vector>{kernels::to_view<test::TestMemSpace>(inv)};
  };
  Vector xg("xg", nc * ng);
  const SolverResult rg = gmres(exec, reference, kernels::to_view<test::TestMemSpace>(bg), xg,
                                control, 60, jacobi(reference, ng));
  ASSERT_TRUE(rg.converged);

  const mesh::hex::DistributedQkSpace<dim, TestExecSpace> space(m, c.degree, comm);
  o.field = local_field(space, whole);
  const DistributedOperator<dim, TestExecSpace> op(space, o);
  const std::vector<double> bl = owned_part(space, bg, nc, 0.0);
  Vector xl("xl", bl.size());
  const SolverResult rl = gmres(exec, op, kernels::to_view<test::TestMemSpace>(bl), xl, control, 60,
                                jacobi(op, space.n_local()), space.inner_product(nc));
  ASSERT_TRUE(rl.converged);
  EXPECT_NEAR(rl.iterations, rg.iterations, 2);

  const auto xgh = kernels::to_std_vector(xg);
  const double scale = max_abs(xgh);
  const double err = owned_difference(space, kernels::to_std_vector(xl), xgh, nc);
  EXPECT_LE(err, 1e-10 * scale) << "iterations " << rl.iterations << " / " << rg.iterations;
  if (comm.is_root())
    std::printf(
        "Oseen Jacobi-GMRES: %d iterations on the whole box, %d on %d ranks; max "
        "difference %.2e of max |x| %.3f\n",
        rg.iterations, rl.iterations, comm.size(), err, scale);
}

// The multigrid's transfers on the Oseen layout (dim + 1 blocks, the velocity constrained, the
// pressure free) on slabs, with the ghost update before and the compression after, equal the
// whole box's: restriction and prolongation, p (k to k - 1) and h (Q1, cells halved), 2D and
// 3D, Dirichlet faces beside the shared layer, periodic split or not.
template <int dim>
void check_transfer(int fine_degree, bool h, bool periodic) {
  Communicator comm;
  SCOPED_TRACE("dim " + std::to_string(dim) + (h ? " h" : " p") + " from Q" +
               std::to_string(fine_degree) + (periodic ? " periodic split" : "") + " ranks " +
               std::to_string(comm.size()));
  const TestExecSpace exec;
  const int nc = dim + 1;
  auto m = box<dim>(3, "curved", periodic);
  if (h) m.cells = {4, 4, 4};
  const mesh::hex::QkSpace<dim, TestExecSpace> whole_f(m, fine_degree);
  const mesh::hex::QkSpace<dim, TestExecSpace> whole_c(h ? m.coarsened() : m,
                                                       h ? 1 : fine_degree - 1);
  const MatrixFreeTransfer<dim, TestExecSpace> whole(whole_c, whole_f, nc, dim);
  const mesh::hex::DistributedQkSpace<dim, TestExecSpace> fine(m, fine_degree, comm);
  const auto coarse = h ? fine.coarsened(1) : fine.with_degree(fine_degree - 1);
  const MatrixFreeTransfer<dim, TestExecSpace> slabs(coarse->local(), fine.local(), nc, dim);

  std::vector<double> xf(nc * whole_f.n_dofs()), xc(nc * whole_c.n_dofs());
  for (std::size_t i = 0; i < xf.size(); ++i) xf[i] = sample(static_cast<long>(i));
  for (std::size_t i = 0; i < xc.size(); ++i) xc[i] = sample(static_cast<long>(3 * i + 1));
  Vector rc("rc", xc.size()), pf("pf", xf.size());
  whole.restrict_to_coarse(exec, kernels::to_view<test::TestMemSpace>(xf), rc);
  whole.prolongate(exec, kernels::to_view<test::TestMemSpace>(xc), pf);
  const auto rc_ref = kernels::to_std_vector(rc), pf_ref = kernels::to_std_vector(pf);

  const Vector lf = kernels::to_view<test::TestMemSpace>(owned_part(fine, xf, nc));
  const Vector lc = kernels::to_view<test::TestMemSpace>(owned_part(*coarse, xc, nc));
  Vector lrc("lrc", lc.extent(0)), lpf("lpf", lf.extent(0));
  fine.update_ghosts(exec, lf, nc);
  slabs.restrict_to_coarse(exec, lf, lrc);
  coarse->compress_add(exec, lrc, nc, dim);
  coarse->update_ghosts(exec, lc, nc);
  slabs.prolongate(exec, lc, lpf);
  fine.compress_add(exec, lpf, nc, dim);
  EXPECT_LE(owned_difference(*coarse, kernels::to_std_vector(lrc), rc_ref, nc),
            1e-13 * max_abs(rc_ref));
  EXPECT_LE(owned_difference(fine, kernels::to_std_vector(lpf), pf_ref, nc),
            1e-13 * max_abs(pf_ref));
}

TEST(DistributedMatrixFree, OseenTransfersOnSlabsEqualTheWholeBox) {
  for (const bool periodic : {false, true}) {
    for (const int k : {2, 3, 4}) {
      check_transfer<2>(k, false, periodic);
      check_transfer<3>(k, false, periodic);
    }
    check_transfer<2>(1, true, periodic);
    check_transfer<3>(1, true, periodic);
  }
}

// Multigrid-CG (p-levels, h-levels while the slabs allow, BoomerAMG on the gathered coarsest
// level) on the slabs against the same solver on one rank: the same iteration count, the same
// solution to 1e-12 relative (the two differ only by round-off in the sums at the shared
// layers; 1e-16 measured).
TEST(DistributedMatrixFree, MultigridOnSlabsMatchesOneRank) {
  Communicator comm;
  const TestExecSpace exec;
  constexpr int dim = 3;
  for (const int k : {2, 4}) {
    auto m = mesh::hex::unit_cube<dim>(8);
    m.deformation = mesh::hex::sinusoidal_deformation(dim, 0.05);
    typename MatrixFreeOperator<dim, TestExecSpace>::Options o;
    MultigridOptions mo;
    mo.max_coarse_dofs = 200;
    SolverControl control;
    control.relative_tolerance = 1e-10;
    control.max_iterations = 100;
    auto solve = [&](const mesh::hex::DistributedQkSpace<dim, TestExecSpace>& space,
                     std::vector<double>& x_global, std::string& levels) {
      const DistributedOperator<dim, TestExecSpace> A(space, o);
      const MatrixFreeMultigrid<dim, TestExecSpace> mg(exec, A, mo);
      levels = mg.describe();
      const auto f = space.local().interpolate([](const mesh::hex::Point3& x, int) {
        return std::exp(x[0]) * std::sin(3 * x[1]) + x[2];
      });
      const Vector b = load_vector(exec, space.local(), kernels::to_view<test::TestMemSpace>(f),
                                   GeometryMode::stored, k + 1);
      space.compress_add(exec, b);
      Vector x("x", space.n_local());
      const SolverResult r = conjugate_gradient(exec, A, b, x, control, mg, space.inner_product());
      EXPECT_TRUE(r.converged);
      const auto xh = kernels::to_std_vector(x);
      x_global = space.communicator().allgatherv(
          std::vector<double>(xh.begin(), xh.begin() + space.n_owned()));
      return r.iterations;
    };
    std::vector<double> x1, xp;
    std::string levels1, levelsp;
    const int it1 =
        solve(mesh::hex::DistributedQkSpace<dim, TestExecSpace>(m, k, Communicator(MPI_COMM_SELF)),
              x1, levels1);
    const int itp =
        solve(mesh::hex::DistributedQkSpace<dim, TestExecSpace>(m, k, comm), xp, levelsp);
    SCOPED_TRACE("k " + std::to_string(k) + ": 1 rank " + levels1 + "; " +
                 std::to_string(comm.size()) + " ranks " + levelsp);
    EXPECT_LE(it1, 12);
    EXPECT_NEAR(itp, it1, 1);
    ASSERT_EQ(x1.size(), xp.size());
    double scale = 0, err = 0;
    for (std::size_t i = 0; i < x1.size(); ++i) {
      scale = std::max(scale, std::abs(x1[i]));
      err = std::max(err, std::abs(x1[i] - xp[i]));
    }
    EXPECT_LE(err, 1e-12 * scale);
    if (comm.is_root())
      std::printf("k %d: %d iterations on 1 rank, %d on %d; max difference %.2e of max |x| %.3f\n",
                  k, it1, itp, comm.size(), err, scale);
  }
}

/// Multigrid-GMRES on the Oseen system of `m` (degree k) on the slabs of `space`: iterations,
/// the solution and the multigrid's state in global order, its levels.
template <int dim>
struct OseenMultigridRun {
  int iterations = 0;
  std::vector<double> x, state;
  std::string levels;
};

template <int dim>
OseenMultigridRun<dim> solve_oseen_multigrid(
    const mesh::hex::DistributedQkSpace<dim, TestExecSpace>& space, const Case& c,
    const OseenMultigridOptions& mo) {
  const TestExecSpace exec;
  const int nc = dim + 1;
  const mesh::hex::QkSpace<dim, TestExecSpace> whole(space.global_mesh(), c.degree);
  auto o = options<dim>(c);
  o.field = local_field(space, whole);
  const DistributedOperator<dim, TestExecSpace> A(space, o);
  OseenMultigrid<dim, TestExecSpace> mg(space, mo);
  mg.update(exec, A);
  std::vector<double> bg(nc * whole.n_dofs());
  for (std::size_t i = 0; i < bg.size(); ++i) bg[i] = sample(static_cast<long>(i));
  const auto b = kernels::to_view<test::TestMemSpace>(owned_part(space, bg, nc, 0.0));
  Vector x("x", b.extent(0));
  SolverControl control;
  control.relative_tolerance = 1e-10;
  control.max_iterations = 200;
  const SolverResult r = gmres(exec, A, b, x, control, 60, mg, space.inner_product(nc));
  EXPECT_TRUE(r.converged);
  return {r.iterations, space.gather(x, nc), mg.state(), mg.describe()};
}

// The Oseen multigrid (p-levels, h-levels while the slabs allow, the gathered dense coarse
// solve) as GMRES's preconditioner on the slabs against the same solver on one rank: the same
// levels and iteration count (within one), the same solution to 1e-9 relative (GMRES's 1e-10
// times the system's conditioning) and the same smoother data (inverse diagonals to 1e-12,
// lambda_max bounds to 1e-8: power iterations' round-off). 3D curved Q3 with Dirichlet,
// Neumann and periodic faces; 2D Q2 periodic along the split.
TEST(DistributedMatrixFree, OseenMultigridOnSlabsMatchesOneRank) {
  Communicator comm;
  for (const int dim : {3, 2}) {
    Case c;
    c.kind = OperatorKind::oseen;
    c.degree = dim == 3 ? 3 : 2;
    OseenMultigridOptions mo;
    mo.max_coarse_dofs = dim == 3 ? 1000 : 300;
    auto run = [&](auto dimension) {
      constexpr int d = decltype(dimension)::value;
      auto m = box<d>(0, "curved", d == 2);
      m.cells = {d == 3 ? 8 : 12, d == 3 ? 6 : 16, 8};
      using DSpace = mesh::hex::DistributedQkSpace<d, TestExecSpace>;
      const auto one =
          solve_oseen_multigrid<d>(DSpace(m, c.degree, Communicator(MPI_COMM_SELF)), c, mo);
      const auto many = solve_oseen_multigrid<d>(DSpace(m, c.degree, comm), c, mo);
      SCOPED_TRACE(std::to_string(d) + "D on " + std::to_string(comm.size()) +
                   " ranks: " + many.levels);
      EXPECT_EQ(many.levels, one.levels);
      EXPECT_NE(one.levels.find("-> Q1 " + std::to_string(m.cells[0] / 2)), std::string::npos);
      EXPECT_LE(one.iterations, 40);
      EXPECT_NEAR(many.iterations, one.iterations, 1);
      ASSERT_EQ(many.x.size(), one.x.size());
      double err = 0.0;
      for (std::size_t i = 0; i < one.x.size(); ++i)
        err = std::max(err, std::abs(many.x[i] - one.x[i]));
      EXPECT_LE(err, 1e-9 * max_abs(one.x));
      ASSERT_EQ(many.state.size(), one.state.size());
      double state_err = 0.0;
      for (std::size_t i = 2; i < one.state.size(); ++i)
        state_err = std::max(state_err, std::abs(many.state[i] - one.state[i]) /
                                            std::max(1e-300, std::abs(one.state[i])));
      EXPECT_LE(state_err, 1e-8);
      if (comm.is_root())
        std::printf(
            "Oseen MG-GMRES %dD (%s): %d iterations on 1 rank, %d on %d; max difference %.2e of "
            "max |x| %.3f; smoother data %.1e relative\n",
            d, one.levels.c_str(), one.iterations, many.iterations, comm.size(), err,
            max_abs(one.x), state_err);
    };
    if (dim == 3)
      run(std::integral_constant<int, 3>());
    else
      run(std::integral_constant<int, 2>());
  }
}

TEST(DistributedMatrixFree, TooFewCellsForTheRanksAreRefused) {
  Communicator comm;
  auto m = mesh::hex::unit_cube<3>(2);
  m.cells[2] = 1;
  if (comm.size() == 1) {
    EXPECT_NO_THROW((mesh::hex::DistributedQkSpace<3, TestExecSpace>(m, 2, comm)));
  } else {
    try {
      mesh::hex::DistributedQkSpace<3, TestExecSpace> s(m, 2, comm);
      FAIL() << "1 cell over 2 ranks accepted";
    } catch (const mesh::DecompositionError& e) {
      EXPECT_NE(std::string(e.what()).find("more ranks (2) than blocks"), std::string::npos)
          << e.what();
    }
  }
  // Slabs given by hand that do not tile the box are refused on every rank (no rank is left
  // waiting in a collective): here every rank claims the first cell of two.
  m.cells[2] = 2;
  try {
    mesh::hex::DistributedQkSpace<3, TestExecSpace> s(m, 2, comm, 0, 1);
    FAIL() << "slabs [0, 1) on every rank accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("do not tile the 2 cells"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace amphora::solvers::matrix_free
