# The same scene on 1 and 2 ranks gives the same output, bit for bit (the interpolation sums
# exact zeros across ranks; every other operation is rank-local and identical).
source "$(dirname "$0")/common.sh"
make_scene one.toml 'output_every = 50' 'name = "ranks"'
sed 's|output_dir = "out"|output_dir = "two"|' one.toml > two.toml
"$AMPHORA" run one.toml > one.log
"$MPIEXEC" -n 2 "$AMPHORA" run two.toml > two.log
grep -q "ranks 2" two.log || fail "second run did not use 2 ranks"
n=0
for f in out/fields_*.h5; do same_h5 "$f" "two/$(basename "$f")"; n=$((n+1)); done
[ "$n" -ge 3 ] || fail "too few outputs compared ($n)"
same_h5 out/checkpoint.h5 two/checkpoint.h5
cmp out/diagnostics.csv two/diagnostics.csv || fail "diagnostics differ"
# A 2-rank checkpoint continues on 1 rank.
"$AMPHORA" run one.toml --restart two/checkpoint.h5 > /dev/null
echo "ranks: $n outputs identical on 1 and 2 ranks"
