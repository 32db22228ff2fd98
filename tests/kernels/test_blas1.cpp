#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "kernels/blas1.hpp"
#include "test_backend.hpp"

namespace amphora {
namespace {

using test::TestExecSpace;
using View = Kokkos::View<double*, test::TestMemSpace>;

View from_host(const std::vector<double>& v) {
  View d("v", v.size());
  auto h = Kokkos::create_mirror_view(d);
  for (size_t i = 0; i < v.size(); ++i) h(i) = v[i];
  Kokkos::deep_copy(d, h);
  return d;
}

std::vector<double> to_host(const View& d) {
  auto h = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), d);
  return std::vector<double>(h.data(), h.data() + h.size());
}

TEST(Blas1, RunsOnTheRequestedThreadCount) {
  const int want = test::requested_threads();
  if (want > 0 && std::string(TestExecSpace::name()) == "OpenMP") {
    EXPECT_EQ(TestExecSpace().concurrency(), want);
  }
}

TEST(Blas1, FillCopyScale) {
  const TestExecSpace exec;
  View x("x", 1000), y("y", 1000);
  kernels::blas1::fill(exec, x, 2.5);
  kernels::blas1::copy(exec, x, y);
  kernels::blas1::scale(exec, -2.0, y);
  for (double v : to_host(x)) EXPECT_EQ(v, 2.5);
  for (double v : to_host(y)) EXPECT_EQ(v, -5.0);
}

TEST(Blas1, AxpyAndAxpby) {
  const TestExecSpace exec;
  std::vector<double> xs(777), ys(777);
  for (size_t i = 0; i < xs.size(); ++i) {
    xs[i] = 0.5 * double(i);
    ys[i] = 3.0 - double(i);
  }
  View x = from_host(xs), y = from_host(ys);
  kernels::blas1::axpy(exec, 2.0, x, y);  // y = 3 - i + i = 3
  for (double v : to_host(y)) EXPECT_EQ(v, 3.0);
  kernels::blas1::axpby(exec, 4.0, x, -1.0, y);  // y = 2 i - 3
  const auto r = to_host(y);
  for (size_t i = 0; i < r.size(); ++i) EXPECT_EQ(r[i], 2.0 * double(i) - 3.0);
}

TEST(Blas1, ReductionsOnIntegerDataAreExact) {
  // Integer-valued data far below 2^53: every partial sum is exact in any order, so the result
  // must be exact on every backend and thread count.
  const TestExecSpace exec;
  const int n = 100001;
  std::vector<double> xs(n);
  for (int i = 0; i < n; ++i) xs[i] = (i % 2 ? -1.0 : 1.0) * double(i % 1000);
  View x = from_host(xs);
  double sum = 0, dot = 0, n1 = 0, ninf = 0;
  for (double v : xs) {
    sum += v;
    dot += v * v;
    n1 += std::abs(v);
    ninf = std::max(ninf, std::abs(v));
  }
  EXPECT_EQ(kernels::blas1::sum(exec, x), sum);
  EXPECT_EQ(kernels::blas1::dot(exec, x, x), dot);
  EXPECT_EQ(kernels::blas1::norm1(exec, x), n1);
  EXPECT_EQ(kernels::blas1::norm_inf(exec, x), ninf);
  EXPECT_DOUBLE_EQ(kernels::blas1::norm2(exec, x), std::sqrt(dot));
}

TEST(Blas1, DotOfRandomDataAgreesWithLongDoubleToRoundOff) {
  const TestExecSpace exec;
  const int n = 1 << 18;
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> xs(n), ys(n);
  long double ref = 0, mag = 0;
  for (int i = 0; i < n; ++i) {
    xs[i] = u(rng);
    ys[i] = u(rng);
    ref += (long double)xs[i] * ys[i];
    mag += std::abs((long double)xs[i] * ys[i]);
  }
  // Summation error bound: n * eps * sum |x_i y_i| (Higham, Accuracy and Stability, 3.1).
  const double bound = double(n) * std::numeric_limits<double>::epsilon() * double(mag);
  EXPECT_NEAR(kernels::blas1::dot(exec, from_host(xs), from_host(ys)), double(ref), bound);
}

TEST(Blas1, EmptyViews) {
  const TestExecSpace exec;
  View x("x", 0);
  EXPECT_EQ(kernels::blas1::sum(exec, x), 0.0);
  EXPECT_EQ(kernels::blas1::norm_inf(exec, x), 0.0);
  EXPECT_EQ(kernels::blas1::norm2(exec, x), 0.0);
}

}  // namespace
}  // namespace amphora
