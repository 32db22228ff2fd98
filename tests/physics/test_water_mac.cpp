// The MAC water module: still water over uneven terrain stays at rest with exactly hydrostatic
// pressure, with and without tall cells, for each pressure back end.
#include <cmath>

#include "physics/water_mac/stoker_dam_break.hpp"
#include "physics/water_mac/water_mac.hpp"
#include "test_backend.hpp"

namespace amphora::physics::water_mac {
namespace {

struct StillWater {
  double max_speed = 0, pressure_error = 0;
};

StillWater run_still(int optical_depth, const char* solver) {
  Parameters p(parameter_table());
  p.set("scene", std::string("still"));
  p.set("cells_x", std::int64_t(32));
  p.set("cells_y", std::int64_t(32));
  p.set("cells_z", std::int64_t(16));
  p.set("length_x", 1.0);
  p.set("pool_depth", 0.63);
  p.set("terrain_base", 0.2);
  p.set("terrain_amplitude", 0.1);
  p.set("optical_depth", std::int64_t(optical_depth));
  p.set("solver", std::string(solver));
  p.set("tolerance", 1e-11);
  auto m = create(p, Communicator());
  double t = 0;
  for (int s = 0; s < 4; ++s, t += 0.01) m->advance(t, 0.01);

  StillWater r;
  for (const auto& [k, v] : m->diagnostics(t))
    if (k == "max_speed") r.max_speed = v;
  const OutputBlock b = m->output(t)[0];
  const std::vector<double>*phi = nullptr, *pressure = nullptr;
  for (const auto& [name, f] : b.fields) {
    if (name == "phi") phi = &f;
    if (name == "pressure") pressure = &f;
  }
  const double rho_g = 1000.0 * 9.81;
  std::size_t c = 0;
  for (double z : b.z)
    for (double y : b.y)
      for (double x : b.x) {
        (void)x, (void)z;
        if ((*phi)[c] < 0 && (*pressure)[c] != 0.0)  // fluid (solid cells carry no pressure)
          r.pressure_error = std::max(
              r.pressure_error, std::abs((*pressure)[c] - rho_g * (0.63 - y)) / (rho_g * 0.63));
        ++c;
      }
  return r;
}

TEST(WaterMac, StillWaterOverTerrainStaysAtRestWithHydrostaticPressure) {
  for (int depth : {0, 4})
    for (const char* solver : {"multigrid", "hypre", "mic0"}) {
      const StillWater r = run_still(depth, solver);
      // g dt = 0.1 m/s would appear at once if the pressure did not balance gravity
      EXPECT_LT(r.max_speed, 1e-7) << solver << ", optical depth " << depth;
      EXPECT_LT(r.pressure_error, 1e-8) << solver << ", optical depth " << depth;
    }
}

TEST(WaterMac, MartinMoyceTableIsInterpolated) {
  EXPECT_DOUBLE_EQ(martin_moyce_front(0.832), 1.217);
  EXPECT_DOUBLE_EQ(martin_moyce_front(9.237), 13.970);
  EXPECT_NEAR(martin_moyce_front(0.5 * (1.997 + 2.547)), 0.5 * (2.292 + 2.995), 1e-12);
}

// Stoker's wet-bed dam break: the state it returns satisfies the bore's mass and momentum
// balances and the rarefaction's Riemann invariant, and it tends to Ritter's dry-bed front
// (S -> 2 sqrt(g h0)) as h1 -> 0 and to a linear wave (S -> sqrt(g h0)) as h1 -> h0.
TEST(StokerDamBreak, SatisfiesTheJumpConditionsAndTheLimits) {
  const double g = 9.81, h0 = 0.1, c0 = std::sqrt(g * h0);
  for (const double ratio : {0.05, 0.1, 0.3, 0.6}) {
    const double h1 = ratio * h0;
    const StokerDamBreak s = stoker_dam_break(g, h0, h1);
    EXPECT_GT(s.hm, h1);
    EXPECT_LT(s.hm, h0);
    // in the bore's frame the still water enters at -S and leaves at um - S
    const double w1 = -s.bore_speed, wm = s.um - s.bore_speed;
    EXPECT_NEAR(h1 * w1, s.hm * wm, 1e-12) << ratio;  // mass
    EXPECT_NEAR(h1 * w1 * w1 + 0.5 * g * h1 * h1, s.hm * wm * wm + 0.5 * g * s.hm * s.hm, 1e-12)
        << ratio;                                                             // momentum
    EXPECT_NEAR(s.um + 2.0 * std::sqrt(g * s.hm), 2.0 * c0, 1e-12) << ratio;  // Riemann invariant
  }
  EXPECT_NEAR(stoker_dam_break(g, h0, 1e-9 * h0).bore_speed / (2.0 * c0), 1.0, 0.02);
  EXPECT_NEAR(stoker_dam_break(g, h0, (1 - 1e-6) * h0).bore_speed / c0, 1.0, 1e-5);
  EXPECT_THROW(stoker_dam_break(g, h0, h0), std::invalid_argument);
}

}  // namespace
}  // namespace amphora::physics::water_mac
