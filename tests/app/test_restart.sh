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
restart_matches "$AMPHORA_SOURCE_DIR/scenes/ins_lid_cavity.toml" ins 30 \
  's|^output_every = .*|output_every = 25\ncheckpoint_every = 20|'
same_h5 ins_full/fields_000050.h5 ins_split/fields_000050.h5
echo "restart: ins_fem bit for bit over 50 steps"

# With the multigrid: its smoothers' diagonals and eigenvalue bounds, refreshed every 10 steps
# and reused between, travel in the checkpoint too (a restart at step 15, between refreshes).
restart_matches "$AMPHORA_SOURCE_DIR/scenes/ins_taylor_green_2d.toml" tg 15 \
  's|^end_time = .*|end_time = 3.0|' 's|^output_every = .*|output_every = 100\ncheckpoint_every = 15|'
grep -q "multigrid=1" tg_full.log || fail "ins_fem: the Taylor-Green run left the multigrid"
echo "restart: ins_fem with the multigrid bit for bit"
