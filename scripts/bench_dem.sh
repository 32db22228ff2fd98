#!/usr/bin/env bash
# DEM throughput against the LIGGGHTS 3.8 anchor, measured in one run on this machine: the
# same dense bed (perf/liggghts/dense_bed.in = perf/dem.cpp's DenseBed: 3 mm glass beads on a
# touching simple-cubic lattice under gravity, Hertz + tangential history, E = 5 MPa, e = 0.9,
# mu = 0.5, dt = 1e-5 s, skin 0.75 mm) at 1e4, 1e5 and 1e6 particles, on 1 and 2 threads and
# 1 and 2 ranks. Writes output/bench/dem.csv and the chart output/bench/dem.png.
#   scripts/bench_dem.sh [STEPS]   (LIGGGHTS steps timed after 20 untimed ones, default 200: the
#   window of perf/dem.cpp, steps 21-220)
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
steps=${1:-200}
source "$here/scripts/bench_dem_common.sh"
bench_dem_setup
csv=$out/dem.csv
echo "code,particles,threads,ranks,particle_steps_per_s" > "$csv"

liggghts_rate() {  # n ranks
  local n=$1 ranks=$2 nz nx
  nz=$(python3 -c "print(round(($n*0.64)**(1/3)))")
  nx=$(python3 -c "print(round(($n/$nz)**0.5))")
  local dir; dir=$(mktemp -d)
  (cd "$dir" && OMP_NUM_THREADS=1 mpiexec -n "$ranks" liggghts -var NX "$nx" -var NY "$nx" -var NZ "$nz" \
      -var STEPS "$steps" -in "$here/perf/liggghts/dense_bed.in" > log.txt 2>&1)
  local loop; loop=$(liggghts_loop_time "$dir/log.txt")
  python3 -c "print($nx*$nx*$nz*$steps/$loop)"
  rm -rf "$dir"
}

for n in 10000 100000 1000000; do
  for cfg in "1 1" "2 1" "1 2"; do
    set -- $cfg
    a=$(amphora_rate "^DenseBed/$n/" "$1" "$2")
    echo "amphora,$n,$1,$2,$a" | tee -a "$csv"
  done
  for ranks in 1 2; do
    [ "$n" -le 100000 ] || [ "${LIGGGHTS_LARGE:-0}" = 1 ] || continue
    l=$(liggghts_rate "$n" "$ranks")
    echo "liggghts,$n,1,$ranks,$l" | tee -a "$csv"
  done
done
/usr/bin/python3 scripts/plot_dem_bench.py "$csv" "$out/dem.png"
