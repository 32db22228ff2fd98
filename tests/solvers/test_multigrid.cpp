// Matrix-free transfers and the multigrid preconditioner: prolongation reproduces coarse
// polynomials exactly (nested spaces, and Q1 on n and ceil(n / 2) cells), restriction is its
// transpose, and multigrid-preconditioned CG on a curved-mesh Poisson problem needs a number of
// iterations that does not grow with refinement (within +-2 over three meshes) for k = 2 and 4.
#include <cmath>
#include <random>
#include <vector>

#include "kernels/host_vector.hpp"
#include "solvers/conjugate_gradient.hpp"
#include "solvers/matrix_free/load_vector.hpp"
#include "solvers/matrix_free/multigrid.hpp"
#include "test_backend.hpp"

namespace amphora::solvers::matrix_free {
namespace {

using test::TestExecSpace;
using Vector = Kokkos::View<double*, test::TestMemSpace>;
using mesh::hex::FaceCondition;

Vector device(const std::vector<double>& v) { return kernels::to_view<test::TestMemSpace>(v); }
std::vector<double> host(const Vector& d) { return kernels::to_std_vector(d); }

template <int dim>
void check_transfer(const mesh::hex::StructuredHexMesh<dim>& mc, int kc,
                    const mesh::hex::StructuredHexMesh<dim>& mf, int kf) {
  const TestExecSpace exec;
  const mesh::hex::QkSpace<dim, TestExecSpace> coarse(mc, kc), fine(mf, kf);
  const MatrixFreeTransfer<dim, TestExecSpace> t(coarse, fine);
  // a polynomial of degree kc per direction is reproduced (zeroed on Dirichlet DoFs)
  auto poly = [kc](const mesh::hex::Point3& x, int) {
    double v = 1.0;
    for (int d = 0; d < dim; ++d) v *= std::pow(x[d] + 0.3 * d, kc) + 0.5;
    return v;
  };
  std::vector<double> pc = coarse.interpolate(poly), pf = fine.interpolate(poly);
  auto zero_constrained = [](const auto& space, std::vector<double>& v) {
    auto c = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), space.constrained_dofs());
    for (std::size_t i = 0; i < c.extent(0); ++i) v[c(i)] = 0.0;
  };
  Vector xf("xf", fine.n_dofs());
  // Dirichlet: compare only away from constrained DoFs (coarse boundary values are zeroed)
  const bool dirichlet =
      mc.dirichlet_faces() != 0 || mc.periodic(0);  // (periodic: polynomials are not)
  if (!dirichlet) {
    t.prolongate(exec, device(pc), xf);
    const auto got = host(xf);
    double err = 0.0;
    for (std::size_t i = 0; i < got.size(); ++i) err = std::max(err, std::abs(got[i] - pf[i]));
    EXPECT_LT(err, 1e-12) << "prolongation of a coarse polynomial, dim " << dim << " " << kc
                          << " -> " << kf << " cells " << mc.cells[0] << " -> " << mf.cells[0];
  }
  // <P xc, yf> = <xc, R yf> for random vectors
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<double> xc(coarse.n_dofs()), yf(fine.n_dofs());
  for (double& e : xc) e = u(rng);
  for (double& e : yf) e = u(rng);
  zero_constrained(coarse, xc);
  zero_constrained(fine, yf);
  Vector rc("rc", coarse.n_dofs());
  t.prolongate(exec, device(xc), xf);
  t.restrict_to_coarse(exec, device(yf), rc);
  const auto Pxc = host(xf), Ryf = host(rc);
  double a = 0.0, b = 0.0;
  for (std::size_t i = 0; i < yf.size(); ++i) a += Pxc[i] * yf[i];
  for (std::size_t i = 0; i < xc.size(); ++i) b += xc[i] * Ryf[i];
  EXPECT_NEAR(a, b, 1e-12 * std::abs(a)) << "restriction is the transpose of prolongation";
}

TEST(MatrixFreeTransfer, ProlongationReproducesPolynomialsAndRestrictionIsItsTranspose) {
  for (FaceCondition f :
       {FaceCondition::neumann, FaceCondition::periodic, FaceCondition::dirichlet}) {
    const auto m2 = mesh::hex::unit_cube<2>(9, f);
    const auto m3 = mesh::hex::unit_cube<3>(9, f);
    for (auto [kc, kf] : {std::pair{1, 2}, {1, 3}, {2, 4}, {2, 5}, {3, 6}, {3, 7}, {4, 8}}) {
      if (f != FaceCondition::periodic)
        check_transfer<2>(m2, kc, m2, kf);  // periodic polys aren't periodic
      if (kf <= 4 && f != FaceCondition::periodic) check_transfer<3>(m3, kc, m3, kf);
    }
    const auto c2 = mesh::hex::unit_cube<2>(5, f);
    const auto c3 = mesh::hex::unit_cube<3>(5, f);
    if (f != FaceCondition::periodic) {
      check_transfer<2>(c2, 1, c2.refined(), 1);
      check_transfer<3>(c3, 1, c3.refined(), 1);
    }
  }
  // Q1 on n cells and on ceil(n / 2): odd counts do not nest (lattice interpolation)
  for (FaceCondition f : {FaceCondition::neumann, FaceCondition::dirichlet}) {
    check_transfer<2>(mesh::hex::unit_cube<2>(4, f), 1, mesh::hex::unit_cube<2>(7, f), 1);
    check_transfer<3>(mesh::hex::unit_cube<3>(5, f), 1, mesh::hex::unit_cube<3>(9, f), 1);
    auto mixed_c = mesh::hex::unit_cube<3>(3, f), mixed_f = mesh::hex::unit_cube<3>(5, f);
    mixed_c.cells = {3, 4, 1}, mixed_f.cells = {5, 8, 1};
    check_transfer<3>(mixed_c, 1, mixed_f, 1);
  }
  check_transfer<3>(mesh::hex::unit_cube<3>(3, FaceCondition::periodic), 1,
                    mesh::hex::unit_cube<3>(5, FaceCondition::periodic), 1);
  // periodic: the adjoint identity still holds with random data
  const auto p3 = mesh::hex::unit_cube<3>(3, FaceCondition::periodic);
  check_transfer<3>(p3, 1, p3.refined(), 1);
  check_transfer<3>(p3, 2, p3, 4);
}

template <int dim>
int mg_iterations(int k, int n) {
  const TestExecSpace exec;
  auto m = mesh::hex::unit_cube<dim>(n);
  m.deformation = mesh::hex::sinusoidal_deformation(dim, 0.05);
  const mesh::hex::DistributedQkSpace<dim, TestExecSpace> distributed(m, k,
                                                                      Communicator(MPI_COMM_SELF));
  const auto& space = distributed.local();
  typename MatrixFreeOperator<dim, TestExecSpace>::Options o;
  o.kind = OperatorKind::laplace;
  const DistributedOperator<dim, TestExecSpace> A(distributed, o);
  MultigridOptions mo;
  mo.max_coarse_dofs = 200;
  const MatrixFreeMultigrid<dim, TestExecSpace> mg(exec, A, mo);
  const std::vector<double> f = space.interpolate([](const mesh::hex::Point3& x, int) {
    return std::exp(x[0]) * std::sin(3 * x[1]) + x[dim - 1];
  });
  const Vector b = load_vector(exec, space, device(f), GeometryMode::stored, k + 1);
  Vector x("x", space.n_dofs());
  SolverControl control;
  control.relative_tolerance = 1e-8;
  control.max_iterations = 200;
  const auto r = conjugate_gradient(exec, A, b, x, control, mg);
  EXPECT_TRUE(r.converged);
  std::printf("dim %d k %d n %d: %d iterations (%s)\n", dim, k, n, r.iterations,
              mg.describe().c_str());
  return r.iterations;
}

TEST(MatrixFreeMultigrid, IterationsDoNotGrowWithRefinement) {
  for (int k : {2, 4}) {
    std::vector<int> it2, it3;
    for (int n : {8, 16, 32}) it2.push_back(mg_iterations<2>(k, k == 4 ? n / 2 : n));
    for (int n : {4, 8, 16}) it3.push_back(mg_iterations<3>(k, k == 4 ? n / 2 : n));
    for (const auto& it : {it2, it3}) {
      EXPECT_LE(*std::max_element(it.begin(), it.end()) - *std::min_element(it.begin(), it.end()),
                2);
      EXPECT_LE(it.back(), 20);
    }
  }
}

}  // namespace
}  // namespace amphora::solvers::matrix_free
