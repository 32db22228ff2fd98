// The beam over an inviscid channel, partitioned: AMP converges at second order for heavy and
// very light beams; the traditional scheme (TP) is stable for a heavy beam and blows up for a
// light one, which is detected and reported (not a crash), while AMP on the same case stays
// bounded.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "coupling/fsi/beam_channel_fsi.hpp"
#include "coupling/fsi/beam_channel_wave.hpp"

namespace {

using namespace amphora::coupling::fsi;

BeamChannelSetup setup(double rho_h, int n, BeamScheme scheme) {
  return beam_channel_wave_case(rho_h, n, scheme);
}

void expect_second_order(double rho_h) {
  double pe = 0, ee = 0;
  for (int n : {20, 40, 80, 160}) {
    const BeamChannelResult r = run_beam_channel(setup(rho_h, n, BeamScheme::amp));
    ASSERT_TRUE(r.stable) << r.message;
    if (n > 20) {
      const double oe = std::log2(ee / r.eta_error), op = std::log2(pe / r.pressure_error);
      std::printf("rho_h/rho %g  n %3d  eta error %.3e (order %.2f)  p error %.3e (order %.2f)\n",
                  rho_h, n, r.eta_error, oe, r.pressure_error, op);
      if (n >= 80) {
        EXPECT_NEAR(oe, 2.0, 0.2) << "eta, n = " << n;
        EXPECT_NEAR(op, 2.0, 0.2) << "pressure, n = " << n;
      }
    }
    ee = r.eta_error;
    pe = r.pressure_error;
  }
}

TEST(BeamChannelFsi, AmpConvergesAtSecondOrderForAHeavyBeam) { expect_second_order(100.0); }

TEST(BeamChannelFsi, AmpConvergesAtSecondOrderForAVeryLightBeam) { expect_second_order(0.01); }

TEST(BeamChannelFsi, TraditionalSchemeFailsForALightBeamWhereAmpDoesNot) {
  const BeamChannelResult heavy = run_beam_channel(setup(100.0, 80, BeamScheme::traditional));
  EXPECT_TRUE(heavy.stable) << heavy.message;
  EXPECT_LT(heavy.eta_error, 0.05);
  const BeamChannelResult tp = run_beam_channel(setup(0.01, 80, BeamScheme::traditional));
  EXPECT_FALSE(tp.stable);
  EXPECT_NE(tp.message.find("unstable"), std::string::npos) << tp.message;
  std::printf("%s\n", tp.message.c_str());
  const BeamChannelResult amp = run_beam_channel(setup(0.01, 80, BeamScheme::amp));
  EXPECT_TRUE(amp.stable) << amp.message;
  EXPECT_LT(amp.max_eta, 1.1);
}

TEST(BeamChannelFsi, AitkenSubiterationsStabiliseTraditionalAtACost) {
  // Converged sub-iterations solve the same coupled step as AMP (both are the monolithic
  // Newmark step), so the results agree to the sub-iteration tolerance; the price is several
  // fluid solves per step, more as the beam gets lighter.
  const BeamChannelResult amp = run_beam_channel(setup(0.01, 80, BeamScheme::amp));
  const BeamChannelResult light = run_beam_channel(setup(0.01, 80, BeamScheme::traditional_aitken));
  ASSERT_TRUE(light.stable) << light.message;
  EXPECT_NEAR(light.eta_error, amp.eta_error, 1e-6);
  const BeamChannelResult heavy = run_beam_channel(setup(1.0, 80, BeamScheme::traditional_aitken));
  ASSERT_TRUE(heavy.stable) << heavy.message;
  std::printf("tp_aitken mean sub-iterations: rho_h/rho 1: %.2f, 0.01: %.2f\n",
              heavy.mean_subiterations, light.mean_subiterations);
  EXPECT_GT(light.mean_subiterations, 2.0);
  EXPECT_GT(light.mean_subiterations, heavy.mean_subiterations);
}

TEST(BeamChannelFsi, UnknownSchemeIsRefusedNamingTheChoices) {
  try {
    parse_beam_scheme("aitken");
    FAIL() << "accepted an unknown scheme";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("tp, tp_aitken, amp"), std::string::npos) << e.what();
  }
}

}  // namespace
