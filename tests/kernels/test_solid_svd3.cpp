#include <cmath>
#include <random>
#include <vector>

#include "kernels/solid/svd3.hpp"
#include "test_backend.hpp"

namespace amphora {
// A named namespace, not an anonymous one: CUDA does not support extended lambdas in
// anonymous namespaces (Kokkos issue #1547); the kernels run in free functions, not TEST bodies.
namespace test_solid_svd3_cases {

using kernels::solid::Mat3;
using kernels::solid::Svd3;
using test::TestExecSpace;

/// A random rotation from a random unit quaternion.
Mat3 random_rotation(std::mt19937& g) {
  std::normal_distribution<double> n;
  double q[4], s = 0.0;
  for (double& v : q) v = n(g), s += v * v;
  for (double& v : q) v /= std::sqrt(s);
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  Mat3 R;
  R(0, 0) = 1 - 2 * (y * y + z * z), R(0, 1) = 2 * (x * y - w * z), R(0, 2) = 2 * (x * z + w * y);
  R(1, 0) = 2 * (x * y + w * z), R(1, 1) = 1 - 2 * (x * x + z * z), R(1, 2) = 2 * (y * z - w * x);
  R(2, 0) = 2 * (x * z - w * y), R(2, 1) = 2 * (y * z + w * x), R(2, 2) = 1 - 2 * (x * x + y * y);
  return R;
}

/// Random, near-singular, singular, inverted, repeated-value and zero matrices.
std::vector<Mat3> test_matrices() {
  std::mt19937 g(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Mat3> fs;
  for (int i = 0; i < 200; ++i) {  // dense random (about half with det < 0)
    Mat3 F;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) F(r, c) = u(g);
    fs.push_back(F);
  }
  const double diagonals[][3] = {{2.0, 1.0, 1e-10}, {1.0, 1e-9, 1e-12}, {3.0, 2.0, 0.0},
                                 {1.0, 0.0, 0.0},   {1.0, 1.0, -1.0},   {1.0, 1.0, 1.0},
                                 {2.0, 2.0, 1e-14}, {1.0, 1.0, -1e-8},  {0.5, -0.2, 0.1}};
  for (const auto& d : diagonals)
    for (int i = 0; i < 20; ++i) {
      kernels::solid::Vec3 s{{d[0], d[1], d[2]}};
      fs.push_back(random_rotation(g) * Mat3::diagonal(s) *
                   kernels::solid::transpose(random_rotation(g)));
    }
  fs.push_back(Mat3());
  return fs;
}

/// svd3 of each matrix, computed on the test backend.
std::vector<Svd3> svd_on_backend(const std::vector<Mat3>& fs) {
  const int n = static_cast<int>(fs.size());
  Kokkos::View<Mat3*, test::TestMemSpace> F("F", n);
  Kokkos::View<Svd3*, test::TestMemSpace> out("svd", n);
  auto h = Kokkos::create_mirror_view(F);
  for (int i = 0; i < n; ++i) h(i) = fs[i];
  Kokkos::deep_copy(F, h);
  Kokkos::parallel_for(
      "test::svd3", kernels::RangePolicy<TestExecSpace>(0, n),
      KOKKOS_LAMBDA(const int i) { out(i) = kernels::solid::svd3(F(i)); });
  auto r = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), out);
  return std::vector<Svd3>(r.data(), r.data() + n);
}

TEST(SolidSvd3, ReproducesFWithRotationsAndTheInversionSignConvention) {
  const std::vector<Mat3> fs = test_matrices();
  const int n = static_cast<int>(fs.size());
  const std::vector<Svd3> r = svd_on_backend(fs);
  using kernels::solid::determinant;
  using kernels::solid::frobenius;
  using kernels::solid::transpose;
  for (int i = 0; i < n; ++i) {
    const Svd3& d = r[i];
    const Mat3 back = d.U * Mat3::diagonal(d.s) * transpose(d.V);
    Mat3 diff;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) diff(a, b) = back(a, b) - fs[i](a, b);
    const double size = frobenius(fs[i]);
    EXPECT_LE(frobenius(diff), 1e-12 * size) << "matrix " << i;
    for (const Mat3& Q : {d.U, d.V}) {
      EXPECT_NEAR(determinant(Q), 1.0, 1e-12) << "matrix " << i;
      const Mat3 QtQ = transpose(Q) * Q;
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) EXPECT_NEAR(QtQ(a, b), a == b ? 1.0 : 0.0, 1e-12);
    }
    EXPECT_GE(d.s[0], d.s[1] - 1e-14 * size) << "matrix " << i;  // sorted up to round-off
    EXPECT_GE(d.s[1], std::abs(d.s[2]) - 1e-14 * size) << "matrix " << i;
    EXPECT_GE(d.s[1], 0.0) << "matrix " << i;
    const double det = determinant(fs[i]);
    if (std::abs(det) > 1e-10 * size * size * size) {
      EXPECT_EQ(d.s[2] < 0.0, det < 0.0) << "matrix " << i << ": only s_2 carries det F's sign";
    }
  }
}

}  // namespace test_solid_svd3_cases
}  // namespace amphora
