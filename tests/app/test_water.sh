# MAC water through the real binary: the dam break of scenes/water_dam_break.toml against
# Martin & Moyce (1952), and every kind of bad input the water module refuses.
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
water_scene solver.toml 'solver = "amg"'
expect_error 2 "key 'water_mac.solver' = \"amg\" is not an allowed value; allowed: one of: multigrid, hypre, mic0" \
  "$AMPHORA" run solver.toml; no_output solver

# The documented dam break against the experiment: inviscid, without the gate and without wall
# friction the simulated front runs ahead of Martin & Moyce's, by 11 % near T = 1.1 falling to 6 %
# at T = 3.3 (the issue's 5 % is not met; see the README). Bounded here so that it cannot drift
# unnoticed; water volume kept to 2 %.
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
assert worst <= 0.12, f"front error {worst:.3f} > 0.12"
assert abs(final) <= 0.065, f"front error at T = 3.3: {final:.3f} > 0.065"
v0, v1 = float(rows[0]["volume"]), float(rows[-1]["volume"])
assert abs(v1 - v0) <= 0.02 * v0, f"volume {v0} -> {v1}"
print(f"dam break: front error {worst:.3f} at worst over T = 1.1..3.3, {final:.3f} at T = 3.3, "
      f"volume change {100*(v1-v0)/v0:.2f} %")
PY


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
