# A run stopped half way and continued from its checkpoint ends bit for bit where an
# uninterrupted run ends: fields, checkpoint state and diagnostics.
source "$(dirname "$0")/common.sh"
make_scene full.toml 'output_every = 25' 'checkpoint_every = 30' 'name = "restart"'
sed 's|output_dir = "out"|output_dir = "split"|' full.toml > split.toml
"$AMPHORA" run full.toml > full.log
"$AMPHORA" run split.toml --max-steps 40 > first.log
steps=$(sed -n 's/.*steps 0\.\.\([0-9]*\).*/\1/p' full.log)
[ "$steps" -gt 40 ] || fail "scene too short for the test ($steps steps)"
[ ! -e "split/fields_$(printf %06d "$steps").h5" ] || fail "interrupted run wrote the final output"
"$AMPHORA" run split.toml --restart split/checkpoint.h5 > second.log
grep -q "(restart)" second.log || fail "restart not announced"
final=$(printf %06d "$steps")
same_h5 out/fields_$final.h5 split/fields_$final.h5
same_h5 out/checkpoint.h5 split/checkpoint.h5
cmp out/diagnostics.csv split/diagnostics.csv || fail "diagnostics differ"
cmp <(sed 's/split/out/g' split/restart.xmf) out/restart.xmf || fail "series files differ"
for f in out/fields_*.h5; do same_h5 "$f" "split/$(basename "$f")"; done
echo "restart: bit for bit over $steps steps"

# The flow solver's two-step history (previous velocity and step) travels in its checkpoint.
sed -e 's|^output_dir = .*|output_dir = "ins_full"|' \
    -e 's|^output_every = .*|output_every = 25\ncheckpoint_every = 20|' \
    "$AMPHORA_SOURCE_DIR/scenes/ins_lid_cavity.toml" > ins_full.toml
sed 's|ins_full|ins_split|' ins_full.toml > ins_split.toml
"$AMPHORA" run ins_full.toml > ins_full.log
"$AMPHORA" run ins_split.toml --max-steps 30 > ins_first.log
"$AMPHORA" run ins_split.toml --restart ins_split/checkpoint.h5 > ins_second.log
grep -q "(restart)" ins_second.log || fail "ins_fem: restart not announced"
same_h5 ins_full/checkpoint.h5 ins_split/checkpoint.h5
same_h5 ins_full/fields_000050.h5 ins_split/fields_000050.h5
cmp ins_full/diagnostics.csv ins_split/diagnostics.csv || fail "ins_fem: diagnostics differ"
echo "restart: ins_fem bit for bit over 50 steps"

# With the multigrid: its smoothers' diagonals and eigenvalue bounds, refreshed every 10 steps
# and reused between, travel in the checkpoint too (a restart at step 15, between refreshes).
sed -e 's|^output_dir = .*|output_dir = "tg_full"|' -e 's|^end_time = .*|end_time = 3.0|' \
    -e 's|^output_every = .*|output_every = 100\ncheckpoint_every = 15|' \
    "$AMPHORA_SOURCE_DIR/scenes/ins_taylor_green_2d.toml" > tg_full.toml
sed 's|tg_full|tg_split|' tg_full.toml > tg_split.toml
"$AMPHORA" run tg_full.toml > tg_full.log
"$AMPHORA" run tg_split.toml --max-steps 15 > tg_first.log
"$AMPHORA" run tg_split.toml --restart tg_split/checkpoint.h5 > tg_second.log
grep -q "multigrid=1" tg_full.log || fail "ins_fem: the Taylor-Green run left the multigrid"
cmp tg_full/diagnostics.csv tg_split/diagnostics.csv || fail "ins_fem multigrid: diagnostics differ"
same_h5 tg_full/checkpoint.h5 tg_split/checkpoint.h5
echo "restart: ins_fem with the multigrid bit for bit"
