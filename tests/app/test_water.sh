# MAC water through the real binary: the dam break of scenes/water_dam_break.toml against
# Martin & Moyce (1952), the wet-bed dam break of scenes/water_dam_break_wet.toml against Stoker's
# shallow-water bore, every kind of bad input the water module refuses, runs split over 2
# ranks against 1 rank, and restarts (bit for bit; across rank counts to round-off).
source "$(dirname "$0")/common.sh"

water_scene() {  # file [extra water_mac lines...]
  local file=$1; shift
  {
    echo '[run]'
    echo 'module = "water_mac"'
    echo 'output_dir = "out"'
    echo 'end_time = 0.01'
    echo 'dt = 0.005'
    echo '[water_mac]'
    echo 'scene = "still"'
    echo 'cells_x = 16'
    echo 'cells_y = 16'
    echo 'cells_z = 16'
    echo 'length_x = 1.0'
    for line in "$@"; do echo "$line"; done
  } > "$file"
}
no_output() { [ ! -e out ] || fail "output written for bad input ($1)"; }

water_scene band.toml 'optical_depth = 2' 'cfl = 1.5'
expect_error 2 "optical_depth = 2 is below the band the advection needs: .* must be at least 4" "$AMPHORA" run band.toml
no_output band
water_scene terrain.toml 'terrain_base = 0.7' 'pool_depth = 0.5'
expect_error 2 "terrain .* is above the water .* everywhere" "$AMPHORA" run terrain.toml; no_output terrain
water_scene cfl.toml 'cfl = 3.0'
expect_error 2 "key 'water_mac.cfl' = 3 is out of range; allowed: a real number in \(0, 2\]" "$AMPHORA" run cfl.toml
no_output cfl
water_scene size.toml && sed -i 's/^cells_x = 16/cells_x = 98/; s/^cells_y = 16/cells_y = 64/; s/^cells_z = 16/cells_z = 64/' size.toml
expect_error 2 "multigrid cannot coarsen the 98x64x64 grid: .* nx = 98 can be halved 1 times; valid sizes .* nx = 96 or 112" \
  "$AMPHORA" run size.toml; no_output size
water_scene wet.toml 'column_width = 0.5' 'reservoir_depth = 0.1' 'tailwater_depth = 0.1' &&
  sed -i 's/^scene = "still"/scene = "wet_dam_break"/' wet.toml
expect_error 2 "water_mac.tailwater_depth = 0.100000 m must be below water_mac.reservoir_depth = 0.100000 m" \
  "$AMPHORA" run wet.toml; no_output wet
water_scene solver.toml 'solver = "amg"'
expect_error 2 "key 'water_mac.solver' = \"amg\" is not an allowed value; allowed: one of: multigrid, hypre, mic0" \
  "$AMPHORA" run solver.toml; no_output solver
# On several ranks: MIC(0) is refused (it solves on one rank), and blocks narrower than a
# semi-Lagrangian trace reaches are a decomposition error.
water_scene mic2.toml 'solver = "mic0"'
expect_error 2 "solver = \"mic0\" runs on one rank" "$MPIEXEC" -n 2 "$AMPHORA" run mic2.toml; no_output mic2
water_scene narrow.toml && sed -i 's/^cells_x = 16/cells_x = 4/; s/^cells_z = 16/cells_z = 4/; s/^solver.*//' narrow.toml
echo 'solver = "hypre"' >> narrow.toml
expect_error 2 "more ranks \(2\) than blocks" "$MPIEXEC" -n 2 "$AMPHORA" run narrow.toml; no_output narrow

# A run split over 2 ranks is the 1-rank run to round-off (the CG sums in another order):
# the dam break (split along x) and the splash (terrain, a falling ball), each back end.
same_csv() {  # a.csv b.csv tolerance [iterations apart, default 1]
  /usr/bin/python3 - "$@" <<'PY'
import csv, sys
a, b = (list(csv.DictReader(open(f))) for f in sys.argv[1:3])
assert len(a) == len(b) > 3, (len(a), len(b))
# CG may stop one iteration apart when the residual lands on the tolerance (BoomerAMG's
# coarsening depends on the partition: a few more)
allowed = float(sys.argv[4]) if len(sys.argv) > 4 else 1
its = max(abs(float(r["pressure_iterations"]) - float(q["pressure_iterations"])) for r, q in zip(a, b))
assert its <= allowed, f"{sys.argv[1]} vs {sys.argv[2]}: pressure iterations {its} apart"
worst = max(abs(float(r[k]) - float(q[k])) / max(abs(float(r[k])), abs(float(q[k])), 1e-300)
            for r, q in zip(a, b) for k in r if k != "pressure_iterations")
assert worst <= float(sys.argv[3]), f"{sys.argv[1]} vs {sys.argv[2]}: {worst:.3g}"
print(f"{sys.argv[2]}: largest relative difference {worst:.2g}, pressure iterations at most {its:.0f} apart")
PY
}
for solver in multigrid hypre; do
  water_scene s1.toml "solver = \"$solver\"" 'terrain_base = 0.05' 'terrain_amplitude = 0.04' 'drop_height = 0.75' \
    'tolerance = 1e-10'
  sed -i 's/^end_time = 0.01/end_time = 0.04\ndiagnostics_every = 1/; s|output_dir = "out"|output_dir = "s1"|; s/^scene = "still"/scene = "splash"/' s1.toml
  sed 's|output_dir = "s1"|output_dir = "s2"|' s1.toml > s2.toml
  "$AMPHORA" run s1.toml > /dev/null
  OMP_NUM_THREADS=1 "$MPIEXEC" -n 2 "$AMPHORA" run s2.toml > /dev/null
  same_csv s1/diagnostics.csv s2/diagnostics.csv 1e-8
  rm -rf s1 s2
done
# tall cells split over 2 ranks (the blocks' tall-cell rows; BoomerAMG-CG, and the tall-cell
# multigrid-CG over both ranks) against 1 rank; with the ghost ring's tall cells ignored at the
# block faces the difference is 8e-8 (32^3, BoomerAMG), with them ~1e-11
for solver in multigrid hypre; do
  water_scene t1.toml "solver = \"$solver\"" 'optical_depth = 4' 'terrain_base = 0.05' 'terrain_amplitude = 0.04' \
    'drop_height = 0.75' 'tolerance = 1e-10'
  sed -i 's/^end_time = 0.01/end_time = 0.06\ndiagnostics_every = 1/; s|output_dir = "out"|output_dir = "t1"|; s/^scene = "still"/scene = "splash"/; s/^cells_\([xyz]\) = 16/cells_\1 = 32/' t1.toml
  sed 's|output_dir = "t1"|output_dir = "t2"|' t1.toml > t2.toml
  "$AMPHORA" run t1.toml > /dev/null
  OMP_NUM_THREADS=1 "$MPIEXEC" -n 2 "$AMPHORA" run t2.toml > /dev/null
  same_csv t1/diagnostics.csv t2/diagnostics.csv 1e-9 3
  rm -rf t1 t2
done
# a checkpoint written on 2 ranks holds the whole grid: the run continues on 1 rank
sed 's|output_dir = "s1"|output_dir = "rs"|; s/^diagnostics_every = 1/diagnostics_every = 1\ncheckpoint_every = 4/' s1.toml > rs.toml
OMP_NUM_THREADS=1 "$MPIEXEC" -n 2 "$AMPHORA" run rs.toml --max-steps 4 > /dev/null
"$AMPHORA" run rs.toml --restart rs/checkpoint.h5 > rs.log
grep -q "ranks 1 .*(restart)" rs.log || fail "the 2-rank checkpoint did not restart on 1 rank"
"$AMPHORA" run s1.toml > /dev/null
same_csv s1/diagnostics.csv rs/diagnostics.csv 1e-8

# The documented dam break against the experiment: inviscid, without the gate and without wall
# friction the simulated front runs ahead of Martin & Moyce's, by 13.5 % near T = 1.2 falling to
# 11 % at T = 3.3, and further ahead on finer grids (the issue's 5 % is not met; see the README).
# Bounded here so that it cannot drift unnoticed; the water volume is kept to 0.5 % at every step
# (the reinitialisation's subcell fix; without it 1 % is lost by the end).
sed 's|output_dir = "output/water_dam_break"|output_dir = "dam"|; s/^output_every = 4/output_every = 0/' \
  "$AMPHORA_SOURCE_DIR/scenes/water_dam_break.toml" > dam.toml
OMP_NUM_THREADS=2 "$AMPHORA" run dam.toml > run.txt
/usr/bin/python3 - dam/diagnostics.csv <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
checked = [r for r in rows if 1.1 <= float(r["front_T"]) <= 3.34]
assert len(checked) >= 20, len(checked)
worst = max(abs(float(r["front_error"])) for r in checked)
final = float(rows[-1]["front_error"])
assert worst <= 0.145, f"front error {worst:.3f} > 0.145"
assert abs(final) <= 0.12, f"front error at T = 3.3: {final:.3f} > 0.12"
v0 = float(rows[0]["volume"])
for r in rows:
    assert abs(float(r["volume"]) - v0) <= 0.005 * v0, f"volume {v0} -> {r['volume']} at step {r['step']}"
v1 = float(rows[-1]["volume"])
print(f"dam break: front error {worst:.3f} at worst over T = 1.1..3.3, {final:.3f} at T = 3.3, "
      f"volume change {100*(v1-v0)/v0:.2f} %")
PY

# The documented wet-bed dam break (h1 / h0 = 0.1, h = h0 / 32) against Stoker's shallow-water
# bore: once the bore has run 4 reservoir depths (T = t sqrt(g / h0) >= 4) its front, where the
# depth is halfway from h1 to hm, stays within the issue's 5 % of S t (4.5 % at worst, at
# T = 6.5, the front of a breaking bore advancing in jumps; 1 and 2 threads alike to 1e-15).
# Before, the column is still collapsing (-35 % at T = 1, -10 % at T = 2).
sed 's|output_dir = "output/water_dam_break_wet"|output_dir = "wet"|; s/^output_every = 10/output_every = 0/' \
  "$AMPHORA_SOURCE_DIR/scenes/water_dam_break_wet.toml" > wet.toml
OMP_NUM_THREADS=2 "$AMPHORA" run wet.toml > wet.txt
/usr/bin/python3 - wet/diagnostics.csv <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
checked = [r for r in rows if float(r["bore_T"]) >= 4.0]
assert len(checked) >= 50 and float(checked[-1]["bore_T"]) > 9.8, len(checked)
worst = max(abs(float(r["bore_error"])) for r in checked)
assert worst <= 0.05, f"bore error {worst:.4f} > 0.05"
v0 = float(rows[0]["volume"])
drift = max(abs(float(r["volume"]) - v0) / v0 for r in rows)
assert drift <= 0.015, f"volume drift {drift:.4f} > 0.015"
print(f"wet dam break: bore error {worst:.4f} at worst over T = 4..9.9, volume drift {100 * drift:.2f} %")
PY
# the bore on 2 ranks (x halves; h = h0/8, 0.3 s) is the 1-rank bore to round-off: the depths
# summed over both blocks' columns
sed 's/^cells_x = 704/cells_x = 176/; s/^cells_y = 48/cells_y = 12/; s/^end_time = 1.0/end_time = 0.3/' wet.toml > wet1.toml
sed 's|output_dir = "wet"|output_dir = "wet2"|' wet1.toml > wet2.toml
sed -i 's|output_dir = "wet"|output_dir = "wet1"|' wet1.toml
OMP_NUM_THREADS=1 "$AMPHORA" run wet1.toml > /dev/null
OMP_NUM_THREADS=1 "$MPIEXEC" -n 2 "$AMPHORA" run wet2.toml > wet2.log
grep -q "ranks 2" wet2.log || fail "the wet dam break did not run on 2 ranks"
same_csv wet1/diagnostics.csv wet2/diagnostics.csv 1e-9
# the closing [timing] lines split the stepping time over the module's phases, in order: laps
# of advance(), which is part of the stepping, so together no more than it
/usr/bin/python3 - run.txt <<'PY'
import re, sys
log = open(sys.argv[1]).read()
stepping = float(re.search(r"\[done\] \d+ steps to t=\S+ in (\S+) s stepping", log).group(1))
phases = re.findall(r"\[timing\] (\S+) (\S+) s (\S+) %", log)
names = [p for p, _, _ in phases]
assert names == ["step_control", "advection", "reinitialisation", "cell_types", "pressure_setup", "pressure_solve",
                 "projection", "extrapolation"], names
seconds = [float(t) for _, t, _ in phases]
assert min(seconds) >= 0 and 0 < sum(seconds) <= stepping * 1.001 + 1e-3, (seconds, stepping)
for _, t, pct in phases:
    assert abs(float(pct) - 100 * float(t) / stepping) < 0.01 * float(pct) + 1e-6, (t, pct, stepping)
print(f"dam break: phases {sum(seconds):.3f} s of {stepping:.3f} s stepping")
PY
# the same on 2 ranks (x halves: the front crosses into the second block near the end)
sed 's|output_dir = "dam"|output_dir = "dam2"|; s/^output_every = 0/output_every = 12/' dam.toml > dam2.toml
OMP_NUM_THREADS=1 "$MPIEXEC" -n 2 "$AMPHORA" run dam2.toml > dam2.log
grep -q "ranks 2" dam2.log || fail "the dam break did not run on 2 ranks"
same_csv dam/diagnostics.csv dam2/diagnostics.csv 1e-9
grep -q 'Grid Name="water_1"' dam2/water_dam_break.xmf || fail "no piece of rank 1 in the output"


# Checkpoint and restart continue bit for bit: a splash stopped after 3 steps and continued
# ends where the uninterrupted run ends (fields, checkpoint, diagnostics), with uniform cells and
# with tall cells (whose grid the restart rebuilds from the level set).
for depth in 0 4; do
cat > full.toml <<TOML
[run]
name = "restart"
module = "water_mac"
output_dir = "out"
end_time = 0.03
dt = 0.005
output_every = 2
checkpoint_every = 3
[water_mac]
scene = "splash"
cells_x = 16
cells_y = 16
cells_z = 16
length_x = 1.0
drop_height = 0.75
optical_depth = $depth
TOML
sed 's|output_dir = "out"|output_dir = "split"|' full.toml > split.toml
rm -rf out split
"$AMPHORA" run full.toml > full.log
"$AMPHORA" run split.toml --max-steps 3 > first.log
"$AMPHORA" run split.toml --restart split/checkpoint.h5 > second.log
grep -q "(restart)" second.log || fail "restart not announced"
same_h5 out/fields_000006.h5 split/fields_000006.h5
same_h5 out/checkpoint.h5 split/checkpoint.h5
cmp out/diagnostics.csv split/diagnostics.csv || fail "diagnostics differ after the restart (optical_depth $depth)"
echo "water: restart bit for bit (optical_depth $depth)"
done
echo "water: ok"
