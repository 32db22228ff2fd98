# Shared by the DEM benchmarks against LIGGGHTS 3.8 (bench_dem.sh, bench_dem_settled.sh): the
# anchor installed, the environment, and amphora's rate from bench_dem. Sourced, not run.
install_liggghts() {
  command -v liggghts > /dev/null && return
  [ "$(id -u)" = 0 ] || { echo "install Debian's liggghts (as root) for the anchor" >&2; exit 1; }
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends liggghts >&2
}
# The release build, the anchor, and output/bench, from the source root ($here).
bench_dem_setup() {
  bash "$here/scripts/build.sh" release
  install_liggghts
  cd "$here"
  out=output/bench
  mkdir -p "$out"
}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_PROC_BIND=spread OMP_PLACES=threads

amphora_rate() {  # FILTER threads ranks (rank 0 alone prints, see perf/bench_main.cpp)
  # One rank: unbound, so its threads spread over the cores. Several ranks: one core each
  # (unbound, every rank's single OpenMP thread would be pinned to the first core).
  local bind=none
  [ "$3" -gt 1 ] && bind=core
  OMP_NUM_THREADS=$2 mpiexec --bind-to $bind -n "$3" build/release/perf/bench_dem \
      --benchmark_filter="$1" --benchmark_format=json 2> /dev/null |
    python3 -c "import sys,json; d=json.load(sys.stdin); print(d['benchmarks'][0]['particle_steps_per_s'])"
}

liggghts_loop_time() {  # LOG: the last "Loop time of T" LIGGGHTS printed
  sed -n 's/^Loop time of \([0-9.e+-]*\) on.*/\1/p' "$1" | tail -1
}
