#!/usr/bin/env bash
# Matrix-free FEM benchmarks (perf/matrix_free.cpp), each suite at 1 and 2 threads (and the
# deal.II configuration also at 2 MPI ranks of 1 thread, the anchor's own setting), JSON in
# output/bench/, then the charts:
#   matrix_free_bp.png        CEED BP1-6 throughput against degree and problem size (2 threads)
#   matrix_free_geometry.png  Laplace throughput against geometry bytes per DoF (the modes)
# and a table of the deal.II comparison, the large-size bandwidth fractions (LaplaceLarge and
# the bare BP operators, BPOperator, and both with geometry stored at the points,
# StoredGeometryLarge) and the multigrid-vs-BoomerAMG solve in
# output/bench/matrix_free_summary.txt.
#   scripts/bench_matrix_free.sh [quick]   (quick: BP sizes up to 1e6, no Poisson solves)
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bash "$here/scripts/build.sh" release
cd "$here"
out=output/bench
mkdir -p "$out"
export OMP_PROC_BIND=spread OMP_PLACES=threads
bench=build/release/perf/bench_matrix_free
run() {  # name threads filter [extra args]; RANKS=n for an MPI run (one core per rank)
  local name=$1 threads=$2 filter=$3 ranks=${RANKS:-1} launch=() tag; shift 3
  tag=${threads}threads
  if [ "$ranks" -gt 1 ]; then
    launch=(mpiexec --bind-to core -n "$ranks")
    tag=${ranks}ranks
    export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
  fi
  echo "== $name, $threads thread(s), $ranks rank(s)"
  OMP_NUM_THREADS=$threads "${launch[@]}" "$bench" --benchmark_filter="$filter" \
    --benchmark_out="$out/matrix_free_${name}_${tag}.json" --benchmark_out_format=json "$@" \
    | grep -E "^(LaplaceDealii|LaplaceLarge|BP|BPOperator|StoredGeometryLarge|GeometryModes|PoissonSolve)" | grep -v "_mean\|_stddev\|_cv" || true
}
bp_filter='^BP/'
[ "${1:-}" = quick ] && bp_filter='^BP/[1-6]/[1-8]/[4-6]/'
for t in 1 2; do
  run dealii $t '^LaplaceDealii' --benchmark_repetitions=5 --benchmark_min_time=2 --benchmark_report_aggregates_only=true
  run large $t '^LaplaceLarge' --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
  run geometry $t '^GeometryModes' --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
  [ "${1:-}" = quick ] || run poisson $t '^PoissonSolve'
done
RANKS=2 run dealii 1 '^LaplaceDealii' --benchmark_repetitions=5 --benchmark_min_time=2 --benchmark_report_aggregates_only=true
run bp 2 "$bp_filter"
run bpop 2 '^BPOperator/' --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
run stored 2 '^StoredGeometryLarge/[0-9]+/[0-9]+/0/' --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
/usr/bin/python3 scripts/plot_matrix_free.py "$out"
