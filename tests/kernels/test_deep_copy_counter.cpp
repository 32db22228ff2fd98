#include <stdexcept>
#include <type_traits>

#include "kernels/deep_copy_counter.hpp"
#include "test_backend.hpp"

namespace amphora {
namespace test_deep_copy_counter_cases {

using test::TestMemSpace;
using View = Kokkos::View<double*, TestMemSpace>;

constexpr bool device_memory = !std::is_same_v<TestMemSpace, Kokkos::HostSpace>;

TEST(DeepCopyCounter, CountsCopiesFillsAndScalarReads) {
  View a("a", 1000), b("b", 1000);
  Kokkos::View<double, TestMemSpace> s("s");
  auto h = Kokkos::create_mirror_view(a);
  kernels::DeepCopyCounter counter;
  Kokkos::deep_copy(a, 1.0);  // a fill
  Kokkos::deep_copy(b, a);    // the same space
  Kokkos::deep_copy(h, a);    // to the host mirror (no copy at all on a host space, yet counted)
  double value = 0;
  Kokkos::deep_copy(value, s);  // a rank-0 read
  const kernels::DeepCopyCount c = counter.count();
  EXPECT_EQ(c.fills, 1);
  EXPECT_EQ(c.copies, 2);
  EXPECT_EQ(c.bytes, 2 * 1000 * long(sizeof(double)));
  EXPECT_EQ(c.crossing, device_memory ? 1 : 0);
  EXPECT_EQ(c.crossing_bytes, device_memory ? 1000 * long(sizeof(double)) : 0);
  EXPECT_EQ(c.onto_itself, device_memory ? 0 : 1);  // the host mirror is `a` itself
  EXPECT_EQ(c.host_device(), 1);
  EXPECT_EQ(c.host_device_bytes(), 1000 * long(sizeof(double)));
  EXPECT_EQ(c.scalar_reads, 1);
  EXPECT_EQ(h(999), 1.0);
}

TEST(DeepCopyCounter, ResetsStopsAndAllowsOneAtATime) {
  View a("a", 10), b("b", 10);
  {
    kernels::DeepCopyCounter counter;
    EXPECT_THROW(kernels::DeepCopyCounter second, std::logic_error);
    Kokkos::deep_copy(b, a);
    counter.reset();
    EXPECT_EQ(counter.count().copies, 0);
    Kokkos::deep_copy(b, a);
    EXPECT_EQ(counter.count().copies, 1);
  }
  kernels::DeepCopyCounter again;  // the first one is gone: counting starts from zero
  EXPECT_EQ(again.count().copies, 0);
}

}  // namespace test_deep_copy_counter_cases
}  // namespace amphora
