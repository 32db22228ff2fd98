#include <cmath>
#include <random>
#include <vector>

#include "kernels/solid/plastic_flow.hpp"
#include "test_backend.hpp"

namespace amphora {
// A named namespace, not an anonymous one: CUDA does not support extended lambdas in
// anonymous namespaces (Kokkos issue #1547); the kernels run in free functions, not TEST bodies.
namespace test_solid_plastic_flow_cases {

using kernels::solid::Mat3;
using kernels::solid::PlasticFlow;
using kernels::solid::Vec3;
using test::TestExecSpace;

Mat3 rotation(double angle, int axis) {
  Mat3 R = Mat3::identity();
  const int a = (axis + 1) % 3, b = (axis + 2) % 3;
  R(a, a) = R(b, b) = std::cos(angle);
  R(a, b) = -std::sin(angle), R(b, a) = std::sin(angle);
  return R;
}

/// plastic_update(p, Fe[i], Fp[i]) for each i, on the test backend.
std::vector<Mat3> update_on_backend(const PlasticFlow& p, const std::vector<Mat3>& Fe,
                                    const std::vector<Mat3>& Fp) {
  const int n = static_cast<int>(Fe.size());
  Kokkos::View<Mat3*, test::TestMemSpace> e("Fe", n), q("Fp", n), out("out", n);
  auto he = Kokkos::create_mirror_view(e);
  auto hq = Kokkos::create_mirror_view(q);
  for (int i = 0; i < n; ++i) he(i) = Fe[i], hq(i) = Fp[i];
  Kokkos::deep_copy(e, he);
  Kokkos::deep_copy(q, hq);
  Kokkos::parallel_for(
      "test::plastic_update", kernels::RangePolicy<TestExecSpace>(0, n),
      KOKKOS_LAMBDA(const int i) { out(i) = kernels::solid::plastic_update(p, e(i), q(i)); });
  auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), out);
  return std::vector<Mat3>(h.data(), h.data() + n);
}

/// The deviatoric Hencky strain's norm of F (positive determinant).
double hencky_deviator_norm(const Mat3& F) {
  const kernels::solid::Svd3 d = kernels::solid::svd3(F);
  double e[3], mean = 0.0;
  for (int i = 0; i < 3; ++i) e[i] = std::log(d.s[i]), mean += e[i] / 3.0;
  double n = 0.0;
  for (double v : e) n += (v - mean) * (v - mean);
  return std::sqrt(n);
}

double max_abs_difference(const Mat3& a, const Mat3& b) {
  double m = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m = std::max(m, std::abs(a(i, j) - b(i, j)));
  return m;
}

/// Stretches (s, 1/sqrt(s), 1/sqrt(s)) in a rotated frame, rotated again: F = R1 S R2^T.
Mat3 stretch(double s, double a1, double a2) {
  const Vec3 d{{s, 1.0 / std::sqrt(s), 1.0 / std::sqrt(s)}};
  return rotation(a1, 2) * rotation(0.3, 0) * Mat3::diagonal(d) *
         kernels::solid::transpose(rotation(a2, 1));
}

TEST(SolidPlasticFlow, WithinYieldOrInvertedNothingFlows) {
  PlasticFlow p;
  p.yield = 0.2;
  const Mat3 Fp = stretch(1.1, 0.4, -0.2);
  Mat3 inverted = stretch(1.5, 0.1, 0.2);
  for (int j = 0; j < 3; ++j) inverted(2, j) = -inverted(2, j);  // det < 0
  const std::vector<Mat3> Fe = {stretch(1.15, 0.7, 1.1), inverted};
  ASSERT_LT(hencky_deviator_norm(Fe[0]), p.yield);
  const auto out = update_on_backend(p, Fe, {Fp, Fp});
  for (const Mat3& q : out) EXPECT_EQ(max_abs_difference(q, Fp), 0.0);
}

TEST(SolidPlasticFlow, ReturnsToTheYieldSurfaceKeepingVolumeAndFrame) {
  PlasticFlow p;
  p.yield = 0.05;
  p.clamp = 100.0;
  const Mat3 Fp0 = stretch(1.2, -0.5, 0.8);
  std::vector<Mat3> Fe, Fp;
  for (double s : {1.3, 1.8, 0.6})
    for (double a : {0.0, 0.9, 2.1}) Fe.push_back(stretch(s, a, 0.5 * a + 0.1)), Fp.push_back(Fp0);
  // the same elastic stretch rotated in space: the same F_p
  const std::vector<Mat3> out = update_on_backend(p, Fe, Fp);
  for (std::size_t i = 0; i < Fe.size(); ++i) {
    const Mat3 F = Fe[i] * Fp0;  // the total deformation, unchanged by the flow
    const Mat3 Fe_new = F * kernels::solid::inverse(out[i]);
    EXPECT_NEAR(hencky_deviator_norm(Fe_new), p.yield, 1e-12) << "on the yield surface, " << i;
    EXPECT_NEAR(kernels::solid::determinant(out[i]), 1.0, 1e-12) << "volume kept, " << i;
    EXPECT_NEAR(kernels::solid::determinant(Fe_new), kernels::solid::determinant(Fe[i]), 1e-12);
  }
  // a rotation R applied in space (R Fe) flows the same
  std::vector<Mat3> rotated;
  for (const Mat3& F : Fe) rotated.push_back(rotation(1.3, 0) * rotation(-0.4, 2) * F);
  const std::vector<Mat3> out_r = update_on_backend(p, rotated, Fp);
  for (std::size_t i = 0; i < Fe.size(); ++i)
    EXPECT_LT(max_abs_difference(out_r[i], out[i]), 1e-12) << "frame indifferent, " << i;
}

TEST(SolidPlasticFlow, ClampBoundsThePlasticStretch) {
  PlasticFlow p;
  p.yield = 0.01;
  p.clamp = 1.5;
  const std::vector<Mat3> out =
      update_on_backend(p, {stretch(4.0, 0.3, 0.2), stretch(0.2, 1.0, -0.7)},
                        {Mat3::identity(), stretch(1.4, 0.0, 0.5)});
  for (const Mat3& q : out) {
    const kernels::solid::Svd3 d = kernels::solid::svd3(q);
    double n = 0.0;
    for (int i = 0; i < 3; ++i) {
      EXPECT_LE(d.s[i], p.clamp * (1.0 + 1e-12));
      EXPECT_GE(d.s[i], (1.0 - 1e-12) / p.clamp);
      n += std::log(d.s[i]) * std::log(d.s[i]);
    }
    EXPECT_NEAR(std::sqrt(n), std::log(p.clamp), 1e-12) << "clamped to the bound";
    EXPECT_NEAR(kernels::solid::determinant(q), 1.0, 1e-12);
  }
}

}  // namespace test_solid_plastic_flow_cases
}  // namespace amphora
