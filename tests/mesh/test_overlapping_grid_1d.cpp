#include <cmath>
#include <stdexcept>

#include "mesh/overlapping_grid_1d.hpp"
#include "test_backend.hpp"

namespace amphora {
namespace {

TEST(OverlappingGrid1D, QuadraticWeightsReproduceQuadratics) {
  for (double s : {0.0, 0.3, 1.0, 1.5, 2.0}) {
    const auto w = mesh::quadratic_weights(s);
    EXPECT_NEAR(w[0] + w[1] + w[2], 1.0, 1e-15);
    for (int p = 0; p <= 2; ++p) {  // f(t) = t^p at t = 0, 1, 2
      const double interp = w[0] * std::pow(0.0, p) + w[1] * 1.0 + w[2] * std::pow(2.0, p);
      EXPECT_NEAR(interp, std::pow(s, p), 1e-14) << "s = " << s << ", p = " << p;
    }
  }
}

TEST(OverlappingGrid1D, GeometryAndInterpolationPoints) {
  const mesh::OverlappingGrid1D g(80, 0.5, 1.5, 1.3);
  const mesh::ComponentGrid1D& g1 = g.grid(0);
  const mesh::ComponentGrid1D& g2 = g.grid(1);
  EXPECT_DOUBLE_EQ(g1.x(0), 0.0);
  EXPECT_DOUBLE_EQ(g1.x(g1.size - 1), 0.5);     // interpolation point x_b
  EXPECT_NEAR(g2.x(g2.last - 1), 1.0, 1e-14);   // Neumann boundary point
  EXPECT_NEAR(g2.x(0), 0.5 - 1.5 / 80, 1e-15);  // interpolation point x_a
  // Each interpolation point lies inside its donor stencil, at offset alpha or beta.
  const auto& ia = g.interpolation(0);
  const auto& ib = g.interpolation(1);
  EXPECT_NEAR(g2.x(ia.donor_first) + g.alpha() * g2.dx, g1.x(ia.target), 1e-14);
  EXPECT_NEAR(g1.x(ib.donor_first) + g.beta() * g1.dx, g2.x(ib.target), 1e-14);
  EXPECT_GE(g.alpha(), 0.0);
  EXPECT_LE(g.alpha(), 2.0);
  EXPECT_NEAR(g.beta(), 0.5, 1e-12);
}

TEST(OverlappingGrid1D, ExtrapolatingStencilIsRejected) {
  // overlap / spacing_ratio = 1.9 / 0.5 > 2: grid 1's interpolation point lies outside the
  // three grid-2 donors.
  EXPECT_THROW(mesh::OverlappingGrid1D(40, 0.5, 1.9, 0.5), std::invalid_argument);
}

}  // namespace
}  // namespace amphora
