# Every kind of bad input: one clear error line, exit code 2, and nothing written.
source "$(dirname "$0")/common.sh"
no_output() { [ ! -e out ] || fail "output written for bad input ($1)"; }

expect_error 2 "missing.toml: scene file not found" "$AMPHORA" run missing.toml

printf '[run]\nmodule = "advection_diffusion_1d"\nend_time = 1.0 1\n' > syntax.toml
expect_error 2 "syntax.toml:3:[0-9]+: TOML syntax error" "$AMPHORA" run syntax.toml; no_output syntax

make_scene module.toml && sed -i 's/^module = .*/module = "ocean"/' module.toml
expect_error 2 "module.toml:2: key 'run.module' = \"ocean\" is not an allowed value; allowed: one of: advection_diffusion_1d" \
  "$AMPHORA" run module.toml; no_output module

make_scene key.toml 'end_tme = 2.0'
expect_error 2 "key.toml:6: unknown key 'run.end_tme'; valid keys in \[run\]: name, module, output_dir, end_time" \
  "$AMPHORA" run key.toml; no_output key

make_scene type.toml 'cfl = "fast"'
expect_error 2 "type.toml:6: key 'run.cfl' must be a real number in \(0, 1\] \(real\), got a string" \
  "$AMPHORA" run type.toml; no_output type

make_scene res.toml && sed -i 's/^cells = 40/cells = 0/' res.toml
expect_error 2 "res.toml:7: key 'advection_diffusion_1d.cells' = 0 is out of range; allowed: an integer in \[8, " \
  "$AMPHORA" run res.toml; no_output resolution

make_scene dt.toml 'dt = -1e-3'
expect_error 2 "dt.toml:6: key 'run.dt' = -0.001 is out of range; allowed: a real number > 0" \
  "$AMPHORA" run dt.toml; no_output dt

make_scene end.toml && sed -i 's/^end_time = 0.5/end_time = 0/' end.toml
expect_error 2 "end.toml:4: key 'run.end_time' = 0 is out of range; allowed: a real number > 0" \
  "$AMPHORA" run end.toml; no_output end_time

touch afile
make_scene unwritable.toml && sed -i 's|^output_dir = "out"|output_dir = "afile/out"|' unwritable.toml
expect_error 2 "output directory 'afile/out' cannot be created" "$AMPHORA" run unwritable.toml

make_scene good.toml
expect_error 2 "restart file 'nothere.h5' not found" "$AMPHORA" run good.toml --restart nothere.h5
no_output restart-missing
echo "not hdf5" > bogus.h5
expect_error 2 "restart file 'bogus.h5' is not an amphora checkpoint" "$AMPHORA" run good.toml --restart bogus.h5
no_output restart-bogus

# A checkpoint from another scene (other physics) is refused, and nothing of this run is written.
make_scene other.toml && sed -i 's|^output_dir = "out"|output_dir = "other"|; s/^cells = 40/cells = 48/' other.toml
"$AMPHORA" run other.toml > /dev/null
expect_error 2 "restart file 'other/checkpoint.h5' was written by scene 'other' .* not by this scene 'good'" \
  "$AMPHORA" run good.toml --restart other/checkpoint.h5
no_output restart-other-scene

# More ranks than blocks: the overlapping grid has two component grids.
expect_error 2 "more ranks \(3\) than blocks \(2\)" "$MPIEXEC" -n 3 "$AMPHORA" run good.toml
no_output ranks
echo "bad input: ok"

# The flow solver: viscosity, degree (with the compiled range) and a step over its CFL limit.
ins_scene() {
  sed -e 's|^output_dir = .*|output_dir = "out"|' -e "$2" \
    "$AMPHORA_SOURCE_DIR/scenes/ins_lid_cavity.toml" > "$1"
}
ins_scene ins_nu.toml 's/^nu = .*/nu = 0.0/'
expect_error 2 "ins_nu.toml:[0-9]+: key 'ins_fem.nu' = 0 is out of range; allowed: a real number > 0" \
  "$AMPHORA" run ins_nu.toml; no_output ins_nu
ins_scene ins_degree.toml 's/^degree = .*/degree = 9/'
expect_error 2 "ins_degree.toml:[0-9]+: key 'ins_fem.degree' = 9 is out of range; allowed: an integer in \[1, [0-9]\]" \
  "$AMPHORA" run ins_degree.toml; no_output ins_degree
ins_scene ins_cfl.toml 's/^dt = .*/dt = 0.2/'
expect_error 2 "ins_cfl.toml: ins_fem: time step 0.2.* gives a CFL number of 4.8.*, above max_cfl = 2" \
  "$AMPHORA" run ins_cfl.toml; no_output ins_cfl

# An adaptive step: only for a module that takes a variable step, and not beside a fixed dt.
make_scene adaptive.toml 'time_step = "adaptive"'
expect_error 2 "adaptive.toml:6: key 'run.time_step' = \"adaptive\" needs a module that takes a variable step; module 'advection_diffusion_1d' allows only \"fixed\"" \
  "$AMPHORA" run adaptive.toml; no_output adaptive
ins_scene ins_adaptive.toml 's/^dt = .*/dt = 0.01\ntime_step = "adaptive"/'
expect_error 2 "ins_adaptive.toml:[0-9]+: key 'run.time_step' = \"adaptive\" takes its step from cfl; remove run.dt" \
  "$AMPHORA" run ins_adaptive.toml; no_output ins_adaptive
echo "bad input: flow solver ok"
