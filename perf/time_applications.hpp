#pragma once
// The timed loop of an operator benchmark: y = A x once to warm up, then once per iteration,
// fenced, so that each iteration times one whole application.
#include <benchmark/benchmark.h>

namespace amphora::perf {

template <class Exec, class Operator, class Vector>
void time_applications(benchmark::State& state, const Operator& op, const Vector& x,
                       const Vector& y) {
  const Exec exec;
  op.apply(exec, x, y);
  exec.fence();
  for (auto _ : state) {
    op.apply(exec, x, y);
    exec.fence();
  }
}

}  // namespace amphora::perf
