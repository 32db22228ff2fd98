// The backflow stabilisation of open faces (physics/ins_fem/backflow_stabilisation.hpp): its
// coefficients integrate the inflow beta int_Gamma max(-(a . n), 0) through the open faces
// exactly for a bilinear flux (the face's Gauss-Lobatto rule), leave out the faces where the
// flow leaves and the constrained nodes; on a channel whose outflow never reverses the solver
// gives the plain do-nothing solution to round-off.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "ins_cases.hpp"
#include "physics/ins_fem/backflow_stabilisation.hpp"

namespace amphora::physics::ins_fem {
namespace test_ins_fem_cases {

using Space3 = mesh::hex::QkSpace<3, TestExecSpace>;
using Backflow3 = BackflowStabilisation<3, TestExecSpace>;
using Vector = Kokkos::View<double*, TestExecSpace::memory_space>;

/// The box [0, 1] x [0, 2] x [0, 1] with `faces` conditions (all six given).
mesh::hex::StructuredHexMesh<3> box(int k, mesh::hex::FaceCondition all) {
  mesh::hex::StructuredHexMesh<3> m;
  m.cells = {3, 2, k == 1 ? 4 : 2};
  m.upper = {1.0, 2.0, 1.0};
  for (auto& f : m.faces) f = all;
  return m;
}

/// beta sum_i c_i for the advecting velocity a(x) (3 components at each node).
template <class A>
double inflow(const mesh::hex::StructuredHexMesh<3>& m, int k, double beta, A a) {
  const Space3 space(m, k);
  Backflow3 b(space, beta);
  const std::vector<double> av =
      space.interpolate([&](const mesh::hex::Point3& x, int c) { return a(x, c); }, 3);
  const Vector adv = kernels::to_view<TestExecSpace::memory_space>(av);
  b.update(TestExecSpace(), adv, Vector());
  return b.coefficient_sum();
}

/// a = (0, 0, -(1 + x)(2 + y)) enters through the top (z = 1) only: int (1 + x)(2 + y) dx dy =
/// 9; a uniform a = (-1, 2, -3) enters through x = 1 (area 2), y = 0 (area 1, speed 2) and z = 1
/// (area 2, speed 3): 10. Times beta.
TEST(BackflowStabilisation, IntegratesTheInflowThroughOpenFaces) {
  const double beta = 0.5;
  for (int k = 1; k <= 3; ++k) {
    const auto m = box(k, mesh::hex::FaceCondition::neumann);
    const double top = inflow(m, k, beta, [](const mesh::hex::Point3& x, int c) {
      return c == 2 ? -(1.0 + x[0]) * (2.0 + x[1]) : 0.0;
    });
    const double uniform = inflow(m, k, beta, [](const mesh::hex::Point3&, int c) {
      return c == 0 ? -1.0 : (c == 1 ? 2.0 : -3.0);
    });
    std::printf("k %d: top %.15f (exact %.1f), uniform %.15f (exact %.1f)\n", k, top, 9 * beta,
                uniform, 10 * beta);
    EXPECT_NEAR(top, 9.0 * beta, 1e-13) << "k " << k;
    EXPECT_NEAR(uniform, 10.0 * beta, 1e-13) << "k " << k;
  }
}

/// Only Neumann faces carry the term: with the top open, the rest walls, the top's rim nodes
/// are the walls' (constrained), so a uniform inflow through the top integrates over the open
/// nodes only: (1 - h_x w_0)(2 - h_y w_0) for the Gauss-Lobatto end weight w_0 per cell width.
TEST(BackflowStabilisation, OnlyOpenFacesAndFreeNodes) {
  for (int k = 1; k <= 3; ++k) {
    auto m = box(k, mesh::hex::FaceCondition::dirichlet);
    m.faces[5] = mesh::hex::FaceCondition::neumann;
    const double w0 = kernels::sumfac::gauss_lobatto(k + 1).weights[0];
    const double hx = 1.0 / m.cells[0], hy = 2.0 / m.cells[1];
    const double expected = (1.0 - 2.0 * hx * w0) * (2.0 - 2.0 * hy * w0);
    const double got = inflow(m, k, 1.0, [](const mesh::hex::Point3&, int c) {
      return c == 2 ? -1.0 : 1.0;  // the sides' tangential flow and the bottom's outflow: none
    });
    EXPECT_NEAR(got, expected, 1e-13) << "k " << k;
    const double leaving =
        inflow(m, k, 1.0, [](const mesh::hex::Point3&, int c) { return c == 2 ? 1.0 : 0.0; });
    EXPECT_EQ(leaving, 0.0) << "k " << k;
  }
}

/// Plane Poiseuille flow leaves through its do-nothing face everywhere: the term is zero and the
/// solution is the unstabilised one to round-off (and exact at k = 2).
TEST(BackflowStabilisation, OutflowChannelIsUnchanged) {
  mesh::hex::StructuredHexMesh<2> m;
  m.cells = {8, 4, 1};
  m.upper = {2.0, 1.0, 0.0};
  m.faces[1] = mesh::hex::FaceCondition::neumann;
  std::vector<std::vector<double>> states;
  for (double beta : {0.0, 1.0}) {
    InsOptions o;
    o.nu = 0.01;
    o.tolerance = 1e-11;
    o.backflow = beta;
    Solver s(m, 2, o);
    EXPECT_EQ(s.backflow() != nullptr, beta > 0.0);
    const Poiseuille exact{0, o.nu, 2.0};
    start_from_boundary_values(s, exact);
    s.solve_steady(1e-10, 20);
    if (s.backflow()) {
      EXPECT_EQ(s.backflow()->coefficient_sum(), 0.0);
    }
    EXPECT_LT(errors(s, exact).u, 1e-8) << "beta " << beta;
    auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), s.state());
    states.emplace_back(h.data(), h.data() + h.extent(0));
  }
  double diff = 0.0;
  for (std::size_t i = 0; i < states[0].size(); ++i)
    diff = std::max(diff, std::abs(states[0][i] - states[1][i]));
  EXPECT_LT(diff, 1e-12);
}

}  // namespace test_ins_fem_cases
}  // namespace amphora::physics::ins_fem
