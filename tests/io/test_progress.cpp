// The progress line's ETA and throughput follow the steps since the line before, so a run
// whose steps grow dearer is promised its present rate, not its mean.
#include <gtest/gtest.h>

#include <cstdio>
#include <sstream>
#include <string>

#include "io/progress.hpp"

namespace {

using amphora::io::Progress;

struct Parsed {
  long long step = -1, last = -1;
  double eta = -1, rate = -1;
};

Parsed parse(const std::string& line) {
  Parsed p;
  double t, dt;
  char unit[64];
  const int got =
      std::sscanf(line.c_str(), "[progress] step %lld/%lld t=%lf dt=%lf ETA %lf s %lf %63s",
                  &p.step, &p.last, &t, &dt, &p.eta, &p.rate, unit);
  EXPECT_EQ(got, 7) << line;
  return p;
}

TEST(Progress, EtaAndRateFollowTheLastInterval) {
  std::ostringstream out;
  Progress progress(out, true, 0, 1000, "particle-steps", 1.0);
  // 100 steps of 1000 particles in 1 s, then 100 steps in 10 s: the steps grew ten times dearer.
  const Parsed first = parse(progress.line(100, 0.1, 1e-3, 1e5, 1.0));
  EXPECT_DOUBLE_EQ(first.eta, 900 * 0.01);
  EXPECT_NEAR(first.rate, 1e5, 1e5 * 1e-3);  // printed with four digits
  const Parsed second = parse(progress.line(200, 0.2, 1e-3, 2e5, 11.0));
  // The mean rate (200 steps in 11 s) would promise 44 s; the last interval's, 80 s.
  EXPECT_DOUBLE_EQ(second.eta, 800 * 0.1);
  EXPECT_NEAR(second.rate, 1e4, 1e4 * 1e-3);
  // A closing line with no step since the last keeps the last interval's figures.
  const Parsed closing = parse(progress.line(200, 0.2, 1e-3, 2e5, 11.5));
  EXPECT_DOUBLE_EQ(closing.eta, second.eta);
  EXPECT_NEAR(closing.rate, 1e4, 1e4 * 1e-3);
  EXPECT_EQ(closing.step, 200);
  EXPECT_EQ(closing.last, 1000);
}

TEST(Progress, InactiveProgressPrintsNothing) {
  std::ostringstream out;
  Progress progress(out, false, 0, 10, "cell-steps", 0.0);
  progress.update(5, 0.5, 0.1, 50.0, true);
  EXPECT_TRUE(out.str().empty());
}

}  // namespace
