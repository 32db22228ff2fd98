// Volumetric locking of incompressible linear tetrahedra on the cantilever of
// locking_cantilever.hpp: the per-element constraint locks on the Kuhn split, the per-node
// one does not; on the centred 24-tetrahedra split neither does. (The full study, finer
// meshes and the 5 % criterion: test_solid_locking_study.)
#include <cmath>
#include <cstdio>

#include "locking_cantilever.hpp"

namespace amphora::test::locking {

TEST(SolidLocking, Q2ReferenceAgreesWithTimoshenkoBeam) {
  const double coarse = q2_tip_deflection(2, kLambda), fine = q2_reference();
  const double beam = timoshenko_tip_deflection();
  std::printf("Q2 tip deflection %.6g (m = 2), %.6g (m = 4); Timoshenko %.6g\n", coarse, fine,
              beam);
  EXPECT_LT(std::abs(fine - coarse), 0.01 * fine) << "Q2 converged to 1 %";
  EXPECT_LT(std::abs(fine - beam), 0.05 * beam) << "within 5 % of beam theory";
  EXPECT_LT(std::abs(q2_tip_deflection(2, 10.0 * kLambda) - coarse), 1e-3 * coarse)
      << "reduced integration: no locking as lambda grows";
}

TEST(SolidLocking, KuhnSplitLocksPerElementNotPerNode) {
  const double reference = q2_reference();
  double last_error = 1.0;
  for (const int k : {2, 4, 6}) {
    const TetCantilever beam(k, Split::kuhn6);
    const double elem = beam.tip_deflection(Constraint::element, kLambda);
    const double node = beam.tip_deflection(Constraint::node, kLambda);
    const double error = std::abs(node - reference) / reference;
    std::printf("Kuhn k %d: per element %.4g, per node %.4g of Q2 %.6g\n", k, elem / reference,
                node / reference, reference);
    EXPECT_LT(elem, 0.05 * reference) << "per element locks, k " << k;
    EXPECT_LT(error, 0.75 * last_error) << "per node converges, k " << k;
    last_error = error;
  }
  EXPECT_LT(last_error, 0.15) << "per node at k = 6";
}

TEST(SolidLocking, PerNodeDeflectionHasALimitAsLambdaGrows) {
  const TetCantilever beam(4, Split::kuhn6);
  const double n6 = beam.tip_deflection(Constraint::node, kLambda);
  const double n7 = beam.tip_deflection(Constraint::node, 10.0 * kLambda);
  std::printf("lambda 1e6, 1e7 mu: per node %.6g, %.6g\n", n6, n7);
  EXPECT_LT(std::abs(n7 - n6), 0.005 * n6) << "per node: the constraint's limit";
}

TEST(SolidLocking, CentredSplitLocksNeither) {
  const double reference = q2_reference();
  const TetCantilever beam(3, Split::centred24);
  const double elem = beam.tip_deflection(Constraint::element, kLambda);
  const double node = beam.tip_deflection(Constraint::node, kLambda);
  std::printf("centred k 3: per element %.4g, per node %.4g of Q2\n", elem / reference,
              node / reference);
  EXPECT_GT(elem, 0.85 * reference);
  EXPECT_GT(node, elem) << "per node: more freedom than per element";
  EXPECT_LT(node, reference);
}

}  // namespace amphora::test::locking
