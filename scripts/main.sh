#!/usr/bin/env bash
# The showcase, from a fresh machine: set up, build, then
#  1. the rotating drum of glass beads (scenes/dem_drum.toml): particles for ParaView in
#     output/dem_drum/dem_drum.xmf, diagnostics in output/dem_drum/diagnostics.csv;
#  2. its regime map over the Froude number: output/dem_drum_study.csv and .png;
#  3. the splash of a ball of water into a pool (scenes/water_splash.toml): the level set and
#     velocity for ParaView in output/water_splash/water_splash.xmf.
# About a minute and a half on 2 cores (after the build).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bash "$here/scripts/build.sh" release
cd "$here"
export OMP_PROC_BIND=${OMP_PROC_BIND:-spread} OMP_PLACES=${OMP_PLACES:-threads}
amphora=build/release/apps/amphora
"$amphora" info
"$amphora" run scenes/dem_drum.toml
"$amphora" study scenes/dem_drum.toml --set dem.froude --values 0.006,0.03,0.1,0.3,0.8,2 \
  --csv output/dem_drum_study.csv
/usr/bin/python3 scripts/plot_drum_regimes.py output/dem_drum_study.csv output/dem_drum_study.png
"$amphora" run scenes/water_splash.toml
cat <<DONE
[main] open in ParaView: output/dem_drum/dem_drum.xmf (the drum's particles)
[main]                   output/water_splash/water_splash.xmf (the splash)
[main] chart: output/dem_drum_study.png (the drum's regime against the Froude number)
[main] diagnostics: output/dem_drum/diagnostics.csv, output/water_splash/diagnostics.csv
DONE
