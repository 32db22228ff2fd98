#!/usr/bin/env bash
# Regime map of the rotating drum over the Froude number (scenes/dem_drum.toml): one run per
# value, the time-averaged regime metrics in output/dem_drum_study.csv, the chart in
# output/dem_drum_study.png. Builds first.
#   scripts/study_drum.sh [comma-separated Froude numbers]
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
values=${1:-0.006,0.03,0.1,0.3,0.8,2}
bash "$here/scripts/build.sh" release
cd "$here"
export OMP_PROC_BIND=${OMP_PROC_BIND:-spread} OMP_PLACES=${OMP_PLACES:-threads}
mkdir -p output
build/release/apps/amphora study scenes/dem_drum.toml --set dem.froude --values "$values" \
  --csv output/dem_drum_study.csv
/usr/bin/python3 scripts/plot_drum_regimes.py output/dem_drum_study.csv output/dem_drum_study.png
