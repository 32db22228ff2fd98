// The stabilised Q_k-Q_k Navier-Stokes solver against exact solutions: Kovasznay flow (steady,
// walls all round, Picard) and the 2D Taylor-Green vortex (periodic, BDF2): velocity errors
// converge at order k + 1 and pressure errors at order k or better (within 0.2), the divergence
// at order k; BDF2 converges at order 2 in time on a forced Taylor-Green flow. The coupled
// multigrid keeps GMRES's iterations bounded under refinement and gives Jacobi's solution.
#include "ins_cases.hpp"

namespace amphora::physics::ins_fem {
namespace test_ins_fem_cases {

TEST(InsFem, KovasznayConvergesAtOrderKPlusOne) {
  check_space_orders("Kovasznay", 1, 16, 32, kovasznay);
  check_space_orders("Kovasznay", 2, 8, 16, kovasznay);
  check_space_orders("Kovasznay", 3, 6, 12, kovasznay);
  check_space_orders("Kovasznay", 4, 6, 12, kovasznay);
}

TEST(InsFem, TaylorGreen2DConvergesAtOrderKPlusOne) {
  auto run = [](int k, int n) { return taylor_green(k, n, 0.01, 0.2, 10, false); };
  check_space_orders("Taylor-Green", 1, 16, 32, run);
  check_space_orders("Taylor-Green", 2, 16, 32, run);
  check_space_orders("Taylor-Green", 3, 8, 16, run);
  check_space_orders("Taylor-Green", 4, 8, 16, run);
}

/// Inflow, walls and a do-nothing outflow: Q_k (k >= 2) holds plane Poiseuille flow exactly on
/// straight cells (errors at the solver's tolerance); on curved cells the velocity converges at
/// order k + 1 and the pressure, the divergence at order k or better.
TEST(InsFem, ChannelWithOutflowIsExactAndConvergesOnCurvedCells) {
  for (int k = 2; k <= 3; ++k) {
    const FlowErrors e = channel(k, 4, 0.0);
    std::printf("channel k %d, straight cells: u %.2e, p %.2e, div %.2e\n", k, e.u, e.p, e.div);
    EXPECT_LT(e.u, 1e-8) << "k " << k;
    EXPECT_LT(e.p, 1e-8) << "k " << k;
    check_space_orders(
        "channel, curved", k, 4, 8, [](int kk, int n) { return channel(kk, n, 0.05); }, true);
  }
}

/// Curved cells (the sinusoidal deformation, faces in place, periodic faces matching): the
/// Taylor-Green vortex converges at the same orders or faster (k = 3, 16 -> 32 cells: 4.51;
/// 8 cells are too coarse for these cells, error 0.4).
TEST(InsFem, TaylorGreen2DConvergesOnCurvedCells) {
  auto run = [](int k, int n) {
    return taylor_green(k, n, 0.01, 0.2, 10, false, InsPreconditioner::multigrid, nullptr, 0.05);
  };
  check_space_orders("Taylor-Green, curved", 2, 16, 32, run, true);
  check_space_orders("Taylor-Green, curved", 3, 16, 32, run, true);
}

/// GMRES iterations per step with the multigrid stay bounded as the mesh is refined (the last
/// step's count grows by at most 3 per halving of h and stays under 30), are at least 5 times
/// fewer than with point Jacobi on the finest mesh, and the solutions agree to the solver
/// tolerance.
TEST(InsFem, MultigridIterationsStayBoundedUnderRefinement) {
  const int cells[3][2] = {{32, 64}, {16, 32}, {16, 32}};
  for (int k = 1; k <= 3; ++k) {
    int last = 0;
    for (int n : cells[k - 1]) {
      std::vector<int> mg, jacobi;
      const FlowErrors a =
          taylor_green(k, n, 0.01, 0.2, 4, false, InsPreconditioner::multigrid, &mg);
      const FlowErrors b =
          taylor_green(k, n, 0.01, 0.2, 4, false, InsPreconditioner::jacobi, &jacobi);
      std::printf("k %d, %d cells: GMRES iterations of the last step: multigrid %d, Jacobi %d\n", k,
                  n, mg.back(), jacobi.back());
      for (int its : mg) EXPECT_GT(its, 0) << "k " << k << ", " << n << " cells: fell back";
      EXPECT_LT(mg.back(), 30) << "k " << k << ", " << n << " cells";
      if (last > 0) {
        EXPECT_LE(mg.back(), last + 3) << "k " << k << ", " << n << " cells";
      }
      EXPECT_LT(5 * mg.back(), jacobi.back()) << "k " << k << ", " << n << " cells";
      EXPECT_NEAR(a.u, b.u, 1e-6 * b.u);
      EXPECT_NEAR(a.p, b.p, 1e-6 * b.p);
      last = mg.back();
    }
  }
}

/// Odd cell counts coarsen as well (65 -> 33 -> 17 -> 9, the non-nested lattice transfer):
/// GMRES needs at most 3 iterations more than on the even count next to it (where the coarse
/// levels nest), never falls back, and reaches the same accuracy.
TEST(InsFem, MultigridCoarsensOddCellCounts) {
  const int cases[2][3] = {{1, 64, 65}, {2, 32, 33}};  // degree, even cells, odd cells
  for (const auto& c : cases) {
    std::vector<int> even, odd;
    const FlowErrors a =
        taylor_green(c[0], c[1], 0.01, 0.2, 4, false, InsPreconditioner::multigrid, &even);
    const FlowErrors b =
        taylor_green(c[0], c[2], 0.01, 0.2, 4, false, InsPreconditioner::multigrid, &odd);
    std::printf("k %d: GMRES iterations of the last step: %d cells %d, %d cells %d\n", c[0], c[1],
                even.back(), c[2], odd.back());
    for (int its : odd) EXPECT_GT(its, 0) << "k " << c[0] << ", " << c[2] << " cells: fell back";
    EXPECT_LE(odd.back(), even.back() + 3) << "k " << c[0] << ", " << c[2] << " cells";
    EXPECT_LT(b.u, 1.2 * a.u) << "k " << c[0];  // h is 1.5 % smaller: the error is no larger
  }
}

/// The multigrid's operators without -nu lap u in the stabilisation (GMRES keeps the full
/// operator): the same solution to the solver tolerance, no fallback, and on the last (BDF2)
/// step at most 2 GMRES iterations more, on viscous cells (nu = 0.05, h = 2 pi / 16, cell
/// Reynolds number 8); Cartesian and curved cells, k = 2, 3. (The BDF1 first step, with a
/// smaller mass term beside the viscous one, may take up to twice as many.)
TEST(InsFem, MultigridWithoutViscousResidualSolvesTheSameSystem) {
  for (double deformation : {0.0, 0.05})
    for (int k = 2; k <= 3; ++k) {
      std::vector<int> full, reduced;
      const FlowErrors a = taylor_green(k, 16, 0.05, 0.2, 4, false, InsPreconditioner::multigrid,
                                        &full, deformation, true);
      const FlowErrors b = taylor_green(k, 16, 0.05, 0.2, 4, false, InsPreconditioner::multigrid,
                                        &reduced, deformation, false);
      std::printf("k %d, deformation %g: GMRES iterations per step, full / reduced:", k,
                  deformation);
      for (std::size_t i = 0; i < full.size(); ++i) std::printf(" %d/%d", full[i], reduced[i]);
      std::printf("\n");
      for (std::size_t i = 0; i < full.size(); ++i)
        EXPECT_GT(reduced[i], 0) << "k " << k << ", step " << i << ": fell back";
      EXPECT_LE(reduced.back(), full.back() + 2) << "k " << k;
      EXPECT_NEAR(a.u, b.u, 1e-6 * a.u);
      EXPECT_NEAR(a.p, b.p, 1e-6 * a.p);
    }
}

}  // namespace test_ins_fem_cases
}  // namespace amphora::physics::ins_fem

namespace amphora::physics::ins_fem::test_ins_fem_cases {
TEST(InsFem, Bdf2ConvergesAtOrderTwoInTime) {
  const FlowErrors a = taylor_green(4, 12, 0.1, 1.0, 20, true);
  const FlowErrors b = taylor_green(4, 12, 0.1, 1.0, 40, true);
  const double ou = order(a.u, b.u, 20, 40), op = order(a.p, b.p, 20, 40);
  std::printf("BDF2, dt 0.05 -> 0.025: u %.3e -> %.3e (order %.2f), p %.3e -> %.3e (%.2f)\n", a.u,
              b.u, ou, a.p, b.p, op);
  EXPECT_NEAR(ou, 2.0, 0.2);
  EXPECT_NEAR(op, 2.0, 0.2);
}
}  // namespace amphora::physics::ins_fem::test_ins_fem_cases
