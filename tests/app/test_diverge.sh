# A run whose step is over the stability limit stops with a message naming the field, place,
# step and time, exits 3, and keeps its last good output intact.
source "$(dirname "$0")/common.sh"
# dt = 0.01 is 1.6x the FTCS limit h1^2 / (2 nu) = 0.00625 of grid 1 (h1 = 1/40, nu = 0.05).
make_scene diverge.toml 'dt = 0.01' 'output_every = 100'
sed -i 's/^end_time = 0.5/end_time = 20.0/' diverge.toml
expect_error 3 "run diverged: non-finite value in field 'u' of block 'grid[12]' at x = .* \(index [0-9]+\) at step [0-9]+, t = [0-9.e+-]+ \(dt = 0.01\); last good output: out/fields_[0-9]{6}.h5 \(step [0-9]+\)" \
  "$AMPHORA" run diverge.toml
last=$(sed -n 's/.*last good output: \(out\/fields_[0-9]*\.h5\).*/\1/p' stderr.txt)
h5dump -a step "$last" > /dev/null || fail "last good output $last unreadable"
# Its data are finite, and the series names no file that does not exist.
! h5dump -d /grid1/u "$last" | grep -qiE "nan|inf" || fail "last good output has non-finite data"
for f in $(grep -o 'fields_[0-9]*\.h5' out/diverge.xmf | sort -u); do [ -f "out/$f" ] || fail "series names missing $f"; done
cat stderr.txt

# The flow solver: the cavity at nu = 1e-7 and CFL 50 (max_cfl raised to allow it), GMRES
# capped at 200 iterations. The failed solve stops the run the same way, naming the place.
sed -e 's|^output_dir = .*|output_dir = "out_ins"|' -e 's/^dt = .*/dt = 2.0/' \
  -e 's/^end_time = .*/end_time = 40.0/' -e 's/^nu = .*/nu = 1e-7/' -e 's/^output_every = .*/output_every = 1/' \
  "$AMPHORA_SOURCE_DIR/scenes/ins_lid_cavity.toml" > ins.toml
printf 'max_cfl = 1000\nmax_iterations = 200\n' >> ins.toml
expect_error 3 "run diverged: the flow solve failed: GMRES did not reach its relative tolerance \(residual [0-9.e+-]+ after [0-9]+ iterations\) in field 'velocity' of block 'flow' at \(x, y\) = \(0\.[0-9]+, 0\.[0-9]+\) \(index [0-9]+\) at step [0-9]+, t = [0-9.]+ \(dt = 2\); last good output: out_ins/fields_[0-9]{6}.h5 \(step [0-9]+\)" \
  "$AMPHORA" run ins.toml
last=$(sed -n 's/.*last good output: \(out_ins\/fields_[0-9]*\.h5\).*/\1/p' stderr.txt)
! h5dump "$last" | grep -qiE "nan|inf" || fail "last good flow output has non-finite data"
cat stderr.txt
echo "diverge: stopped cleanly"
