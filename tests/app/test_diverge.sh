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
echo "diverge: stopped cleanly"
