#pragma once
// The execution space a test body runs on; CMake compiles each test once per backend.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "kernels/spaces.hpp"

#ifndef AMPHORA_TEST_BACKEND
#error "AMPHORA_TEST_BACKEND must name a Kokkos execution space"
#endif

namespace amphora::test {
using TestExecSpace = AMPHORA_TEST_BACKEND;
using TestMemSpace = TestExecSpace::memory_space;

/// Threads the test harness asked for (AMPHORA_TEST_THREADS), or 0 if unset.
inline int requested_threads() {
  const char* s = std::getenv("AMPHORA_TEST_THREADS");
  return s ? std::atoi(s) : 0;
}
}  // namespace amphora::test
