#include <sstream>
#include <stdexcept>
#include <string>

#include "kernels/kernel_profile.hpp"
#include "test_backend.hpp"

namespace amphora {
namespace test_kernel_profile_cases {

using test::TestExecSpace;
using test::TestMemSpace;
using View = Kokkos::View<double*, TestMemSpace>;

const kernels::KernelTime* find(const std::vector<kernels::KernelTime>& rows,
                                const std::string& label, const std::string& region = "") {
  for (const auto& row : rows)
    if (row.label == label && row.region == region) return &row;
  return nullptr;
}

/// n passes of a loop that only the compiler's arithmetic bounds (so its time grows with n).
void spin(const View& v, int passes) {
  Kokkos::parallel_for(
      "test::spin", Kokkos::RangePolicy<TestExecSpace>(0, int(v.extent(0))), KOKKOS_LAMBDA(int i) {
        double s = v(i);
        for (int p = 0; p < passes; ++p) s = s * 0.999 + 1e-3;
        v(i) = s;
      });
}

// (kernels in free functions: nvcc takes no device lambda in a test body, a private member)
void fill(const View& v) {
  Kokkos::parallel_for(
      "test::fill", Kokkos::RangePolicy<TestExecSpace>(0, int(v.extent(0))),
      KOKKOS_LAMBDA(int i) { v(i) = i; });
}

double sum(const View& v) {
  double s = 0.0;
  Kokkos::parallel_reduce(
      "test::sum", Kokkos::RangePolicy<TestExecSpace>(0, int(v.extent(0))),
      KOKKOS_LAMBDA(int i, double& acc) { acc += v(i); }, s);
  return s;
}

void count(const View& v) {
  Kokkos::parallel_scan(
      "test::scan", Kokkos::RangePolicy<TestExecSpace>(0, int(v.extent(0))),
      KOKKOS_LAMBDA(int i, double& acc, bool final) {
        acc += 1.0;
        if (final) v(i) = acc;
      });
}

TEST(KernelProfile, CountsEveryKernelByLabelAndTimesIt) {
  View v("v", 4096);
  kernels::KernelProfile profile;
  for (int r = 0; r < 3; ++r) fill(v);
  double total = 0.0;
  for (int r = 0; r < 2; ++r) total = sum(v);
  count(v);
  spin(v, 1), spin(v, 50000);
  const auto rows = profile.kernels();
  const auto *filled = find(rows, "test::fill"), *reduce = find(rows, "test::sum"),
             *scan = find(rows, "test::scan"), *spun = find(rows, "test::spin");
  ASSERT_TRUE(filled && reduce && scan && spun);
  EXPECT_EQ(filled->calls, 3);
  EXPECT_EQ(reduce->calls, 2);
  EXPECT_EQ(scan->calls, 1);
  EXPECT_EQ(spun->calls, 2);
  EXPECT_DOUBLE_EQ(total, 4095.0 * 4096.0 / 2.0);
  // 50000 dependent multiply-adds per entry take far longer than one: the long call's time is
  // in the total, so the total is well above twice the shortest call.
  EXPECT_GT(spun->seconds, 4.0 * spun->min_seconds);
  EXPECT_GE(filled->min_seconds, 0.0);
  EXPECT_LE(filled->min_seconds * 3, filled->seconds * (1 + 1e-12));
  EXPECT_EQ(rows.front().label, "test::spin");  // the longest total first
  double covered = 0.0;
  for (const auto& row : rows) covered += row.seconds;
  EXPECT_LE(covered, profile.seconds());
  std::ostringstream csv;
  kernels::write_kernel_profile_csv(csv, profile);
  EXPECT_EQ(
      csv.str().rfind("region,label,calls,seconds,mean_us,min_us,share\n\"\",\"test::spin\",2,", 0),
      0u)
      << csv.str();
  EXPECT_NE(csv.str().find("\"(outside kernels)\""), std::string::npos);
}

TEST(KernelProfile, CountsAKernelApartInEachRegion) {
  View v("v", 16);
  kernels::KernelProfile profile;
  spin(v, 1);
  Kokkos::Profiling::pushRegion("outer");
  spin(v, 1);
  Kokkos::Profiling::pushRegion("inner");
  spin(v, 1), spin(v, 1);
  Kokkos::Profiling::popRegion();
  spin(v, 1), spin(v, 1), spin(v, 1);
  Kokkos::Profiling::popRegion();
  const auto rows = profile.kernels();
  ASSERT_EQ(rows.size(), 3u);
  const auto *none = find(rows, "test::spin"), *outer = find(rows, "test::spin", "outer"),
             *inner = find(rows, "test::spin", "inner");
  ASSERT_TRUE(none && outer && inner);
  EXPECT_EQ(none->calls, 1);
  EXPECT_EQ(outer->calls, 4);
  EXPECT_EQ(inner->calls, 2);
}

TEST(KernelProfile, ResetsStopsAndAllowsOneAtATime) {
  View v("v", 16);
  {
    kernels::KernelProfile profile;
    EXPECT_THROW(kernels::KernelProfile second, std::logic_error);
    spin(v, 1);
    profile.reset();
    EXPECT_TRUE(profile.kernels().empty());
    spin(v, 1);
    ASSERT_EQ(profile.kernels().size(), 1u);
    EXPECT_EQ(profile.kernels()[0].calls, 1);
  }
  spin(v, 1);  // no profile: nothing is recorded, nothing breaks
  kernels::KernelProfile again;
  EXPECT_TRUE(again.kernels().empty());
  spin(v, 1);
  EXPECT_EQ(again.kernels().at(0).calls, 1);
}

}  // namespace test_kernel_profile_cases
}  // namespace amphora
