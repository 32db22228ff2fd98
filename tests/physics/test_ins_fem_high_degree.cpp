// Degrees 5 and 6, the top of the flow solver's compiled range, against exact solutions (slow:
// about a minute, most of it Kovasznay, whose viscous cells leave the multigrid for Jacobi).
#include "ins_cases.hpp"

namespace amphora::physics::ins_fem {
namespace test_ins_fem_cases {

/// Degrees 5 and 6 (the top of the compiled range): the same orders. Smaller steps than above
/// (BDF2's error, 5e-7 at dt = 0.02, would hide the spatial one), Kovasznay between 6 and 8
/// cells (coarser meshes are not yet asymptotic: 4 -> 6 cells gave 2.5 at k = 5).
TEST(InsFem, HighDegreesConvergeAtOrderKPlusOne) {
  check_space_orders("Taylor-Green", 5, 8, 16,
                     [](int k, int n) { return taylor_green(k, n, 0.01, 0.2, 40, false); });
  check_space_orders("Taylor-Green", 6, 6, 12,
                     [](int k, int n) { return taylor_green(k, n, 0.01, 0.2, 80, false); });
  const FlowErrors k5 = check_space_orders("Kovasznay", 5, 6, 8, kovasznay);
  const FlowErrors k6 = check_space_orders("Kovasznay", 6, 6, 8, kovasznay);
  // one degree more on the same 8 cells: at least 8 times smaller (measured 18)
  EXPECT_LT(k6.u, k5.u / 8.0);
  EXPECT_LT(k6.p, k5.p / 8.0);
}

}  // namespace test_ins_fem_cases
}  // namespace amphora::physics::ins_fem
