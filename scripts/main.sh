#!/usr/bin/env bash
# The main job, from a fresh machine: set up, build, run the default scene (HDF5 + XDMF fields,
# diagnostics.csv, checkpoint under output/overlap1d/), then its convergence study and chart
# (output/overlap1d_study.csv and .png).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bash "$here/scripts/build.sh" release
cd "$here"
export OMP_PROC_BIND=${OMP_PROC_BIND:-spread} OMP_PLACES=${OMP_PLACES:-threads}
amphora=build/release/apps/amphora
"$amphora" info
"$amphora" run scenes/overlap1d.toml
"$amphora" study scenes/overlap1d.toml --set advection_diffusion_1d.cells \
  --values 20,40,80,160,320,640 --csv output/overlap1d_study.csv
/usr/bin/python3 scripts/plot_study.py output/overlap1d_study.csv output/overlap1d_study.png \
  --title "1D overlapping grid, advection-diffusion: max-norm error"
echo "open output/overlap1d/overlap1d.xmf in ParaView; chart: output/overlap1d_study.png"
