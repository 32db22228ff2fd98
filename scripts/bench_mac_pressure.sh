#!/usr/bin/env bash
# MAC pressure-solve benchmarks (perf/mac_pressure.cpp): uniform 64^3/128^3/192^3 and tall-cell
# grids of the same footprint, every back end, at 1 and 2 threads; multigrid and hypre PFMG also
# on 2 ranks (z slabs), and the tall-cell multigrid and BoomerAMG on the tall-cell grids.
# JSON in output/bench/, then output/bench/mac_pressure.png and mac_pressure_summary.txt (the
# ratios against PFMG-CG on 2 ranks and MIC(0)-CG, measured in this run).
#   scripts/bench_mac_pressure.sh [quick]   (quick: 64^3 and 128^3 only)
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bash "$here/scripts/build.sh" release
cd "$here"
out=output/bench
mkdir -p "$out"
export OMP_PROC_BIND=spread OMP_PLACES=threads
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
bench=build/release/perf/bench_mac_pressure
sizes='(64|128|192)'
[ "${1:-}" = quick ] && sizes='(64|128)'
run() {  # name threads ranks filter [extra args]
  local name=$1 threads=$2 ranks=$3 filter=$4; shift 4
  echo "== $name, $threads thread(s), $ranks rank(s)"
  # one rank: no mpiexec (it would bind the rank, and so both threads, to one core)
  local launch=()
  [ "$ranks" -gt 1 ] && launch=(mpiexec -n "$ranks" --bind-to core)
  OMP_NUM_THREADS=$threads "${launch[@]}" "$bench" --benchmark_filter="$filter" \
    --benchmark_out="$out/mac_pressure_${name}_${threads}t${ranks}r.json" --benchmark_out_format=json "$@" \
    | sed 's/\x1b\[[0-9;]*m//g' | grep -E "^(Uniform|TallCells|Kernels)" | grep -v "_mean\|_stddev\|_cv" || true
}
for t in 1 2; do
  run uniform $t 1 "^Uniform/[0-2]/$sizes/" --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
  run tall $t 1 "^TallCells/[0-2]/$sizes/"
  run kernels $t 1 "^Kernels/"
done
run pfmg 1 2 "^Uniform/1/$sizes/" --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
run mg 1 2 "^Uniform/0/$sizes/" --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
run tall 1 2 "^TallCells/[01]/$sizes/"
/usr/bin/python3 scripts/plot_mac_pressure.py "$out"
