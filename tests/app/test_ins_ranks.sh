# The flow module on 1 and 2 ranks (slabs along y): the 2D Taylor-Green vortex (periodic,
# multigrid with the coarse system gathered) and the curved channel (steady Picard, the outflow
# face across both slabs) give the same diagnostics to 1e-8 relative (the ranks' sums differ by
# round-off, which the numerical dissipation, a difference of nearly equal numbers, amplifies;
# 7e-11 measured), one output block per rank, and a 2-rank checkpoint continues on 1 rank to the
# 1-rank run's diagnostics.
source "$(dirname "$0")/common.sh"
shipped_scene ins_taylor_green_2d tgv_one
shipped_scene ins_taylor_green_2d tgv_two
shipped_scene ins_taylor_green_2d tgv_split
"$AMPHORA" run tgv_one.toml > tgv_one.log
"$MPIEXEC" -n 2 "$AMPHORA" run tgv_two.toml > tgv_two.log
grep -q "ranks 2" tgv_two.log || fail "the 2-rank run did not use 2 ranks"
close_csv tgv_one/diagnostics.csv tgv_two/diagnostics.csv 1e-8
f=$(ls tgv_two/fields_*.h5 | tail -1)
h5ls "$f" | grep -q "^flow_0" && h5ls "$f" | grep -q "^flow_1" || { h5ls "$f"; fail "no block per rank in $f"; }

# A 2-rank checkpoint (its fields in the whole box's DoF order) restarts on 1 rank.
"$MPIEXEC" -n 2 "$AMPHORA" run tgv_split.toml --max-steps 3 > tgv_first.log
"$AMPHORA" run tgv_split.toml --restart tgv_split/checkpoint.h5 > tgv_second.log
grep -q "steps 3\.\.8 .*(restart)" tgv_second.log || { cat tgv_second.log; fail "restart from step 3 not announced"; }
close_csv tgv_one/diagnostics.csv tgv_split/diagnostics.csv 1e-8

shipped_scene ins_channel channel_one
shipped_scene ins_channel channel_two
"$AMPHORA" run channel_one.toml > channel_one.log
"$MPIEXEC" -n 2 "$AMPHORA" run channel_two.toml > channel_two.log
close_csv channel_one/diagnostics.csv channel_two/diagnostics.csv 1e-8
echo "ins ranks: Taylor-Green and channel agree on 1 and 2 ranks; 2-rank checkpoint restarts on 1"
