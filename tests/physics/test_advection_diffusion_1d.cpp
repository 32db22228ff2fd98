// Verification of the 1D overlapping-grid advection-diffusion solver against its manufactured
// solution: second order in the max norm, and the stability limit the explicit scheme has.
#include <cmath>
#include <vector>

#include "physics/advection_diffusion_1d/advection_diffusion_1d.hpp"
#include "test_backend.hpp"

namespace amphora::physics::advection_diffusion_1d {
namespace {

using Solver = AdvectionDiffusion1D<test::TestExecSpace>;

/// Max-norm error at t_end with dt = cfl * stable step, landed on t_end exactly.
double run_to(int cells, double t_end, double cfl, bool* diverged = nullptr) {
  Parameters p(parameter_table());
  p.set("cells", std::int64_t(cells));
  Solver s(p, Communicator());
  const long long n = static_cast<long long>(std::ceil(t_end / (cfl * s.stable_dt()) - 1e-9));
  const double dt = t_end / double(n);
  double t = 0;
  for (long long i = 0; i < n; ++i) {
    s.advance(t, dt);
    t += dt;
    if (diverged && s.find_nonfinite()) {
      *diverged = true;
      return INFINITY;
    }
  }
  if (diverged) *diverged = false;
  return s.max_error(t);
}

TEST(AdvectionDiffusion1D, InitialStateIsTheExactSolution) {
  Parameters p(parameter_table());
  Solver s(p, Communicator());
  EXPECT_LT(s.max_error(0.0), 1e-15);
}

TEST(AdvectionDiffusion1D, SecondOrderInTheMaxNormOverFourRefinements) {
  // dt ~ h^2 (diffusive limit), so the O(dt + h^2) scheme is second order in h.
  std::vector<double> errors;
  for (int cells : {20, 40, 80, 160, 320}) errors.push_back(run_to(cells, 1.0, 0.8));
  for (size_t i = 1; i < errors.size(); ++i) {
    const double order = std::log2(errors[i - 1] / errors[i]);
    EXPECT_NEAR(order, 2.0, 0.1) << "refinement " << i << ": errors " << errors[i - 1] << " -> "
                                 << errors[i];
  }
  EXPECT_LT(errors.back(), 2e-4);  // and the constant is sane
}

TEST(AdvectionDiffusion1D, StepAboveTheStabilityLimitDivergesAndBelowDoesNot) {
  // At 1.5x the limit the highest grid mode grows by |1 - 4 * 0.75| = 2 per step, from
  // round-off to overflow in about 1100 steps; t = 10 takes about 2500.
  bool diverged = false;
  run_to(80, 10.0, 1.5, &diverged);
  EXPECT_TRUE(diverged) << "FTCS at 1.5x its von Neumann limit must blow up";
  const double e = run_to(80, 10.0, 0.95, &diverged);
  EXPECT_FALSE(diverged);
  EXPECT_LT(e, 5e-3);
}

TEST(AdvectionDiffusion1D, StateRoundTripsThroughSaveAndRestore) {
  Parameters p(parameter_table());
  Solver a(p, Communicator()), b(p, Communicator());
  const double dt = 0.5 * a.stable_dt();
  for (int i = 0; i < 10; ++i) a.advance(i * dt, dt);
  b.restore(a.state());
  for (int i = 10; i < 20; ++i) {
    a.advance(i * dt, dt);
    b.advance(i * dt, dt);
  }
  const auto sa = a.state(), sb = b.state();
  ASSERT_EQ(sa.size(), sb.size());
  for (size_t k = 0; k < sa.size(); ++k) EXPECT_EQ(sa[k].arrays, sb[k].arrays);  // bitwise
}

}  // namespace
}  // namespace amphora::physics::advection_diffusion_1d
