#!/usr/bin/env bash
# The GPU check, on a machine with an NVIDIA GPU and no package registry: the CUDA test suite and
# the GPU benchmarks from the bundle scripts/gpu_bundle.sh made, a short table printed last.
#   scripts/gpu_check.sh [BUNDLE]     (a folder or its .tar.xz; default build/gpu-bundle[.tar.xz])
# Settings (environment): GPU_CHECK_DEADLINE (seconds for everything, 450), GPU_CHECK_PARALLEL
# (tests at once: 4 on a GPU, 1 otherwise), GPU_CHECK_QUICK=1 (small benchmark sizes: the
# OpenMP rehearsal on 2 cores; never for reported figures), OUT (where logs and the JSON results
# go; default output/gpu_check). Exit status: 0 if every test passed and every benchmark ran.
# Last, kernel profiles (AMPHORA_KERNEL_PROFILE) of the MAC solve and the stored-geometry
# operator, as time allows; the summary prints their longest kernels.
set -uo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
given=${1:-$here/build/gpu-bundle}
[ ! -d "$given" ] && [ -f "$given.tar.xz" ] && given=$given.tar.xz
if [ -f "$given" ]; then  # a packed bundle: unpacked beside the machine's temporary files
  unpacked=$(mktemp -d /tmp/amphora-gpu-bundle.XXXXXX)
  tar -C "$unpacked" -xJf "$given" || { echo "gpu_check.sh: cannot unpack $given"; exit 2; }
  given=$(ls -d "$unpacked"/*/ | head -n1)
fi
bundle=$(cd "$given" 2> /dev/null && [ -f tests.tsv ] && pwd) ||
  { echo "gpu_check.sh: no bundle at $given (make one with scripts/gpu_bundle.sh)"; exit 2; }
out=${OUT:-$here/output/gpu_check}
deadline=${GPU_CHECK_DEADLINE:-450}
quick=${GPU_CHECK_QUICK:-0}
start=$(date +%s)
mkdir -p "$out/tests" "$out/bench"
say() { printf '[gpu_check %4ss] %s\n' "$(( $(date +%s) - start ))" "$*"; }
left() { echo $(( deadline - ($(date +%s) - start) )); }

# --- the machine, and the bundle's libraries ---------------------------------------------------
export LD_LIBRARY_PATH="$bundle/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
if [ -d "$bundle/ompi" ]; then
  export OPAL_PREFIX="$bundle/ompi" PATH="$bundle/ompi/bin:$PATH"
  export LD_LIBRARY_PATH="$bundle/ompi/lib/x86_64-linux-gnu/openmpi/lib:$LD_LIBRARY_PATH"
fi
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl_vader_single_copy_mechanism=none
export OMP_PROC_BIND=false
gpu=$(nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader 2> /dev/null | head -n1)
backend=$("$bundle/bin/amphora" info 2> /dev/null | sed -n 's/^default execution space *//p')
{
  echo "date:    $(date -u '+%Y-%m-%d %H:%M UTC')"
  echo "gpu:     ${gpu:-none visible}"
  echo "host:    $(nproc) cores; $(uname -r)"
  "$bundle/bin/amphora" info 2>&1 | sed 's/^/amphora: /'
} | tee "$out/machine.txt"
cuda_build=0
case "$backend" in *Cuda*) cuda_build=1 ;; esac
if [ "$cuda_build" = 1 ]; then parallel=${GPU_CHECK_PARALLEL:-4}; threads=1; else parallel=${GPU_CHECK_PARALLEL:-1}; threads=2; fi

# --- tests: each executable of tests.tsv under a timeout, `parallel` at a time -----------------
run_test() {  # name exe args env
  local name=$1 exe=$2 args=$3 envs=$4 log=$out/tests/$1.log rc s
  s=$(date +%s)
  ( IFS=';'; for e in $envs; do export "$e"; done
    export OMP_NUM_THREADS=${OMP_NUM_THREADS_OVERRIDE:-$OMP_NUM_THREADS} 2> /dev/null
    cd "$out/tests" && exec timeout -k 5 "$TEST_TIMEOUT" "$BUNDLE/bin/$exe" $args ) > "$log" 2>&1
  rc=$?
  local passed failed res
  passed=$(grep -oE '^\[  PASSED  \] [0-9]+' "$log" | grep -oE '[0-9]+$' | tail -n1)
  failed=$(grep -oE '^\[  FAILED  \] [0-9]+ test' "$log" | grep -oE '[0-9]+' | tail -n1)
  if [ "$rc" -eq 0 ]; then res="PASS ${passed:-?}"
  elif [ "$rc" -eq 124 ] || [ "$rc" -eq 137 ]; then res=TIMEOUT
  elif [ -n "$failed" ]; then res="FAIL $failed"
  else res="CRASH rc$rc"; fi
  printf '%s\t%s\t%s\n' "$name" "$res" "$(( $(date +%s) - s ))" > "$out/tests/$name.result"
}
export -f run_test
export out BUNDLE="$bundle" TEST_TIMEOUT=$(( $(left) > 240 ? 120 : 60 ))
rm -f "$out"/tests/*.result
ntests=$(grep -c . "$bundle/tests.tsv")
say "running $ntests tests, $parallel at a time ($(left) s left)"
# The tests get at most 45 % of the time; the benchmarks the rest.
timeout -k 5 $(( deadline * 45 / 100 )) bash -c '
  while IFS=$'"'"'\t'"'"' read -r name exe args envs; do
    printf "%s\0%s\0%s\0%s\0" "$name" "$exe" "$args" "$envs"
  done < "$1" | xargs -0 -n 4 -P "$2" bash -c '"'"'run_test "$@"'"'"' _' _ "$bundle/tests.tsv" "$parallel"
ran=$(ls "$out"/tests/*.result 2> /dev/null | wc -l)
npass=$(cat "$out"/tests/*.result 2> /dev/null | awk -F'\t' '$2 ~ /^PASS/' | wc -l)
say "tests: $npass of $ntests passed ($ran ran)"

# --- the same scenes as the reference build (OpenMP), diagnostics compared ---------------------
# Tolerance 1e-6 relative (of each column's largest magnitude): the solvers stop at a relative
# residual of 1e-8, so sums that round differently on the device may take an iteration more or
# less, and DEM contacts amplify round-off step by step; a wrong kernel is off by far more.
scenes_ok=1
if [ -f "$bundle/reference/scenes.txt" ]; then
  while read -r name steps; do
    dir=$out/scenes/$name
    rm -rf "$dir" && mkdir -p "$dir"
    if (cd "$dir" && OMP_NUM_THREADS=$threads timeout -k 5 120 "$bundle/bin/amphora" run \
          "$bundle/reference/$name.toml" --max-steps "$steps" > run.log 2>&1); then
      python3 "$here/scripts/compare_csv.py" "$bundle/reference/$name.csv" "$dir/out/diagnostics.csv" 1e-6 \
        > "$dir/compare.txt" 2>&1 || scenes_ok=0
      say "scene $name against the reference: $(tail -n 1 "$dir/compare.txt")"
    else
      scenes_ok=0
      say "scene $name did not run: $(tail -n 1 "$dir/run.log")"
    fi
  done < "$bundle/reference/scenes.txt"
fi

# --- benchmarks --------------------------------------------------------------------------------
# name|executable|filter, one process each (a run cut short by the deadline loses only its own
# results); the quick filters are the OpenMP rehearsal's.
if [ "$quick" = 1 ]; then
  benches=("stream|bench_stream|^StreamTriad/1048576/"
           "launches|bench_stream|^Launches/"
           "matrix_free_bp5|bench_matrix_free|^BP/5/[24]/5/"
           "matrix_free_stored|bench_matrix_free|^GeometryModes/[24]/[24]/"
           "dem|bench_dem|^DenseBed/10000/"
           "mac_pressure|bench_mac_pressure|^Uniform/[03]/64/")
else
  benches=("stream|bench_stream|^Stream(Copy|Triad)/67108864/"
           "launches|bench_stream|^Launches/"
           "dem|bench_dem|^DenseBed/1000000/"
           "mac_pressure|bench_mac_pressure|^Uniform/[03]/256/")
  for p in 2 3 4 5 6 7 8; do benches+=("matrix_free_bp5_p$p|bench_matrix_free|^BPOperator/5/$p/"); done
  for p in 2 3 4 5 6; do benches+=("matrix_free_stored_p$p|bench_matrix_free|^StoredGeometryLarge/[05]/$p/"); done
fi
bench_ok=1
for b in "${benches[@]}"; do
  IFS='|' read -r name exe filter <<< "$b"
  t=$(( $(left) - 20 ))
  if [ "$t" -lt 20 ]; then say "no time left for $name"; bench_ok=0; continue; fi
  say "benchmark $name ($filter, at most ${t}s)"
  ( cd "$out/bench" && OMP_NUM_THREADS=$threads OMP_PROC_BIND=spread OMP_PLACES=threads \
      timeout -k 5 "$t" "$bundle/bin/$exe" --benchmark_filter="$filter" \
      --benchmark_out="$out/bench/$name.json" --benchmark_out_format=json ) > "$out/bench/$name.log" 2>&1 ||
    { say "$name failed (rc $?): $(tail -n 2 "$out/bench/$name.log" | tr '\n' ' ')"; bench_ok=0; }
done

# --- kernel profiles of the goals not met: each kernel fenced and timed by label and by region
# (the multigrid's levels), so the rates above stay the ones to report -------------------------
if [ "$quick" = 1 ]; then
  profiles=("mac_pressure|bench_mac_pressure|^Uniform/0/64/"
            "mac_pressure_team|bench_mac_pressure|^Uniform/3/64/"
            "matrix_free_stored_p4|bench_matrix_free|^GeometryModes/2/4/")
else
  profiles=("mac_pressure|bench_mac_pressure|^Uniform/0/256/"
            "mac_pressure_team|bench_mac_pressure|^Uniform/3/256/"
            "matrix_free_stored_p4|bench_matrix_free|^StoredGeometryLarge/0/4/0/")
fi
mkdir -p "$out/profile"
for b in "${profiles[@]}"; do
  IFS='|' read -r name exe filter <<< "$b"
  t=$(( $(left) - 15 ))
  if [ "$t" -lt 30 ]; then say "no time left for the profile of $name"; continue; fi
  say "profile $name ($filter, at most ${t}s)"
  ( cd "$out/bench" && AMPHORA_KERNEL_PROFILE="$out/profile/$name.csv" OMP_NUM_THREADS=$threads \
      timeout -k 5 "$t" "$bundle/bin/$exe" --benchmark_filter="$filter" ) > "$out/profile/$name.log" 2>&1 ||
    say "profile $name failed (rc $?): $(tail -n 2 "$out/profile/$name.log" | tr '\n' ' ')"
done

# --- the table ---------------------------------------------------------------------------------
{
  echo
  echo "== amphora GPU check: ${gpu:-no GPU} ($backend), $(( $(date +%s) - start )) s"
  echo "tests: $npass of $ntests passed"
  for f in "$out"/scenes/*/compare.txt; do
    [ -f "$f" ] && echo "scene $(basename "$(dirname "$f")") against the reference build: $(tail -n 1 "$f")"
  done
  cat "$out"/tests/*.result 2> /dev/null | awk -F'\t' '$2 !~ /^PASS/ {printf "  %-44s %s\n", $1, $2}'
  python3 "$here/scripts/gpu_check_table.py" "$out/bench" 2>&1
  for f in "$out"/profile/*.csv; do
    [ -s "$f" ] || continue
    echo "kernel profile $(basename "$f" .csv) (fenced; the benchmark's STREAM run left out):"
    python3 "$here/scripts/kernel_profile_table.py" "$f" 8 'stream' 2>&1
  done
} | tee "$out/summary.txt"
[ "$npass" -eq "$ntests" ] && [ "$bench_ok" = 1 ] && [ "$scenes_ok" = 1 ]
