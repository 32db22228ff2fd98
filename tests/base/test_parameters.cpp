// Parameter rows declared once: a row's range reads back as the statement it makes, a value on
// an open bound is refused and one on a closed bound accepted, and a table gives defaults.
#include <gtest/gtest.h>

#include "base/parameters.hpp"

namespace amphora {
namespace {

TEST(Parameters, RangesReadBackAndBoundsHold) {
  const ParamSpec open = real_param("fill", 0.3, "1", above(0.0) & below(0.6), "bed fill");
  EXPECT_EQ(open.allowed(), "a real number in (0, 0.6)");
  EXPECT_EQ(open.check(0.0), "out of range");
  EXPECT_EQ(open.check(0.6), "out of range");
  EXPECT_EQ(open.check(0.59), "");

  const ParamSpec closed = int_param("degree", 4, at_least(1) & at_most(8), "degree");
  EXPECT_EQ(closed.allowed(), "an integer in [1, 8]");
  EXPECT_EQ(closed.check(std::int64_t{1}), "");
  EXPECT_EQ(closed.check(std::int64_t{8}), "");
  EXPECT_EQ(closed.check(std::int64_t{9}), "out of range");
  EXPECT_EQ(closed.check(2.5), "wrong type");

  EXPECT_EQ(real_param("nu", 0.05, "m^2/s", above(0.0), "").allowed(), "a real number > 0");
  EXPECT_EQ(real_param("g", 9.81, "m/s^2", at_least(0.0), "").allowed(), "a real number >= 0");
  EXPECT_EQ(real_param("a", 1.0, "m/s", "speed").allowed(), "a real number");
  // the right operand's bound wins where both give one side
  EXPECT_EQ(int_param("n", 2, at_least(1) & at_least(2), "").allowed(), "an integer >= 2");
}

TEST(Parameters, TableGivesDefaultsAndFindsRows) {
  const ParamTable t{"demo",
                     "a table",
                     {real_param("x", 1.5, "m", above(0.0), "length"),
                      int_param("n", std::nullopt, at_least(1), "count, no default"),
                      string_param("mode", std::string("a"), "mode", {"a", "b"})}};
  const Parameters p(t);
  EXPECT_EQ(p.real("x"), 1.5);
  EXPECT_FALSE(p.has("n"));
  EXPECT_EQ(p.string("mode"), "a");
  ASSERT_NE(t.find("mode"), nullptr);
  EXPECT_EQ(t.find("mode")->allowed(), "one of: a, b");
  EXPECT_EQ(t.find("missing"), nullptr);
}

}  // namespace
}  // namespace amphora
