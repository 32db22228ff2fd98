#!/usr/bin/env bash
# Runs every benchmark suite at 1 and 2 threads (medians of 5) and keeps the JSON results in
# output/bench/. Builds first (release).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bash "$here/scripts/build.sh" release
cd "$here"
mkdir -p output/bench
export OMP_PROC_BIND=spread OMP_PLACES=threads
for suite in build/release/perf/bench_*; do
  name=$(basename "$suite")
  for threads in 1 2; do
    echo "== $name, $threads thread(s)"
    OMP_NUM_THREADS=$threads "$suite" --benchmark_repetitions=5 \
      --benchmark_report_aggregates_only=true --benchmark_display_aggregates_only=true \
      --benchmark_out="output/bench/${name}_${threads}threads.json" --benchmark_out_format=json \
      "$@" | grep -E "median|^-|Benchmark"
  done
done
