#!/usr/bin/env bash
# DEM throughput on a settled bed against LIGGGHTS 3.8, in one run on this machine: amphora
# pours and settles scenes/studies/dem_settled_bed.toml (55,566 beads of 2.5 mm; skipped when
# output/bench/settled_bed.data exists), the bed is written as a LIGGGHTS data file, and both
# codes time steps 21-220 from it at rest (perf/dem.cpp SettledBed, perf/liggghts/settled_bed.in:
# same particles, materials, step and skin, list rebuilds included), alternating, REPEATS times
# each on 1 core and 2 (amphora: 2 threads and 2 ranks). Writes output/bench/dem_settled.csv
# and prints the medians and their ratios.
#   scripts/bench_dem_settled.sh [REPEATS]   (default 5)
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
repeats=${1:-5}
source "$here/scripts/bench_dem_common.sh"
bench_dem_setup
bed=$out/settled_bed.data
if [ ! -s "$bed" ]; then
  sed "s|^output_dir = .*|output_dir = \"$out/settled_bed\"|" scenes/studies/dem_settled_bed.toml \
    > "$out/settled_bed.toml"
  OMP_NUM_THREADS=2 build/release/apps/amphora run "$out/settled_bed.toml" | grep -v '^\[progress\]'
  last=$(ls "$out"/settled_bed/fields_*.h5 | tail -1)
  python3 scripts/dem_bed_to_data.py "$last" "$bed" 0.1 0.1 fit
fi
atoms=$(sed -n 's/^\([0-9]*\) atoms$/\1/p' "$bed")
bed_path=$(cd "$(dirname "$bed")" && pwd)/$(basename "$bed")
export AMPHORA_SETTLED_BED=$bed_path

liggghts_rate() {  # ranks: particle-steps/s; the log kept in output/bench/liggghts_settled_RANKS.log
  local dir; dir=$(mktemp -d)
  (cd "$dir" && OMP_NUM_THREADS=1 mpiexec -n "$1" liggghts -var BED "$bed_path" -var STEPS 200 \
      -in "$here/perf/liggghts/settled_bed.in" > log.txt 2>&1)
  cp "$dir/log.txt" "$out/liggghts_settled_$1.log"
  python3 -c "print($atoms * 200 / $(liggghts_loop_time "$dir/log.txt"))"
  rm -rf "$dir"
}

csv=$out/dem_settled.csv
echo "code,threads,ranks,repeat,particle_steps_per_s" > "$csv"
for r in $(seq "$repeats"); do
  for cfg in "1 1" "2 1" "1 2"; do
    set -- $cfg
    echo "amphora,$1,$2,$r,$(amphora_rate '^SettledBed/' "$1" "$2")" | tee -a "$csv"
  done
  for ranks in 1 2; do
    echo "liggghts,1,$ranks,$r,$(liggghts_rate "$ranks")" | tee -a "$csv"
  done
done
# The workload, like for like: contacts per particle (each contact counted at both particles)
# at the end of the timed window, amphora's (pairs and walls) and LIGGGHTS' (compute contact/atom).
OMP_NUM_THREADS=2 build/release/perf/bench_dem --benchmark_filter='^SettledBed/' \
    --benchmark_format=json 2> /dev/null |
  python3 -c "import sys,json; b=json.load(sys.stdin)['benchmarks'][0]; print('amphora contacts per particle', 2 * b['contacts_per_particle'] + b['wall_contacts_per_particle'], 'rebuilds', b['rebuilds'])"
awk -v n="$atoms" '$1 == 220 && NF == 5 { print "LIGGGHTS contacts per particle", $4 / n }' \
  "$out/liggghts_settled_1.log"
python3 - "$csv" << 'PY'
import csv, statistics, sys
rows = list(csv.DictReader(open(sys.argv[1])))
med = {}
for key in {(r["code"], r["threads"], r["ranks"]) for r in rows}:
    med[key] = statistics.median(float(r["particle_steps_per_s"]) for r in rows
                                 if (r["code"], r["threads"], r["ranks"]) == key)
for key in sorted(med):
    print(f"{key[0]:8s} threads {key[1]} ranks {key[2]}: median {med[key]:.4g} particle-steps/s")
l1, l2 = med[("liggghts", "1", "1")], med[("liggghts", "1", "2")]
print(f"1 core: amphora / LIGGGHTS {med[('amphora', '1', '1')] / l1:.2f}")
print(f"2 cores: amphora 2 threads / LIGGGHTS 2 ranks {med[('amphora', '2', '1')] / l2:.2f}, "
      f"amphora 2 ranks / LIGGGHTS 2 ranks {med[('amphora', '1', '2')] / l2:.2f}")
PY
