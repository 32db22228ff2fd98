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
bash "$here/scripts/build.sh" release
if ! command -v liggghts > /dev/null; then
  [ "$(id -u)" = 0 ] || { echo "install Debian's liggghts (as root) for the anchor" >&2; exit 1; }
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends liggghts >&2
fi
cd "$here"
out=output/bench
mkdir -p "$out"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_PROC_BIND=spread OMP_PLACES=threads
csv=$out/dem.csv
echo "code,particles,threads,ranks,particle_steps_per_s" > "$csv"

liggghts_rate() {  # n ranks
  local n=$1 ranks=$2 nz nx
  nz=$(python3 -c "print(round(($n*0.64)**(1/3)))")
  nx=$(python3 -c "print(round(($n/$nz)**0.5))")
  local dir; dir=$(mktemp -d)
  (cd "$dir" && OMP_NUM_THREADS=1 mpiexec -n "$ranks" liggghts -var NX "$nx" -var NY "$nx" -var NZ "$nz" \
      -var STEPS "$steps" -in "$here/perf/liggghts/dense_bed.in" > log.txt 2>&1)
  local loop; loop=$(sed -n 's/^Loop time of \([0-9.e+-]*\) on.*/\1/p' "$dir/log.txt" | tail -1)
  python3 -c "print($nx*$nx*$nz*$steps/$loop)"
  rm -rf "$dir"
}

amphora_rate() {  # n threads ranks (rank 0 alone prints, see perf/bench_main.cpp)
  # One rank: unbound, so its threads spread over the cores. Several ranks: one core each
  # (unbound, every rank's single OpenMP thread would be pinned to the first core).
  local bind=none
  [ "$3" -gt 1 ] && bind=core
  OMP_NUM_THREADS=$2 mpiexec --bind-to $bind -n "$3" build/release/perf/bench_dem \
      --benchmark_filter="^DenseBed/$1/" --benchmark_format=json 2> /dev/null |
    python3 -c "import sys,json; d=json.load(sys.stdin); print(d['benchmarks'][0]['particle_steps_per_s'])"
}

for n in 10000 100000 1000000; do
  for cfg in "1 1" "2 1" "1 2"; do
    set -- $cfg
    a=$(amphora_rate "$n" "$1" "$2")
    echo "amphora,$n,$1,$2,$a" | tee -a "$csv"
  done
  for ranks in 1 2; do
    [ "$n" -le 100000 ] || [ "${LIGGGHTS_LARGE:-0}" = 1 ] || continue
    l=$(liggghts_rate "$n" "$ranks")
    echo "liggghts,$n,1,$ranks,$l" | tee -a "$csv"
  done
done
/usr/bin/python3 scripts/plot_dem_bench.py "$csv" "$out/dem.png"
