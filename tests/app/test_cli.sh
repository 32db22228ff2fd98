# info, defaults, check, --help, --version and a bare `run` work and say what they should.
source "$(dirname "$0")/common.sh"
"$AMPHORA" info > info.txt
for row in "Kokkos backends *Serial OpenMP" "MPI ranks *1" "HDF5 .*parallel" "hypre *2\." "git revision" "threads *1"; do
  grep -E -q "$row" info.txt || { cat info.txt; fail "info lacks /$row/"; }
done
"$AMPHORA" defaults advection_diffusion_1d > defaults.txt
grep -E -q '^nu = 0.05 +# \[m\^2/s\] a real number > 0' defaults.txt || { cat defaults.txt; fail "defaults"; }
"$AMPHORA" defaults run | grep -q '^cfl = 0.8' || fail "run defaults"
expect_error 2 "unknown module 'fluid'; known: run, advection_diffusion_1d" "$AMPHORA" defaults fluid
make_scene scene.toml
"$AMPHORA" check scene.toml | grep -q "scene.toml: ok" || fail "check of a good scene"
[ ! -e out ] || fail "check wrote output"
# --help is amphora's alone (Kokkos' stays under --kokkos-help), on stdout, nothing on stderr
"$AMPHORA" --help > help.txt 2> help.err
grep -q "^Usage: .*amphora \[OPTIONS\] SUBCOMMAND" help.txt || { cat help.txt; fail "--help"; }
! grep -qi "kokkos command line\|kokkos-help\|WARNING" help.txt help.err || { cat help.txt help.err; fail "--help prints Kokkos' text"; }
"$AMPHORA" run --help | grep -q "scene file (TOML)" || fail "run --help"
"$AMPHORA" --version | grep -E -q '^amphora [0-9]+\.[0-9]+\.[0-9]+ \(.+\)$' || fail "--version"
# `run` without a scene lists the shipped scenes with a summary each
(cd "$AMPHORA_SOURCE_DIR" && "$AMPHORA" run) > scenes.txt
shipped=$(ls "$AMPHORA_SOURCE_DIR"/scenes/*.toml | wc -l)
[ "$(grep -c '^  scenes/.*\.toml  ' scenes.txt)" = "$shipped" ] || { cat scenes.txt; fail "run lists $shipped scenes"; }
grep -q "scenes/dem_drum.toml *A thin rotating drum" scenes.txt || { cat scenes.txt; fail "scene summary"; }
# --kernel-profile: the steps' kernels timed into a CSV; a path it cannot write fails first
"$AMPHORA" run scene.toml --no-output --max-steps 20 --kernel-profile profile.csv > /dev/null
head -n 1 profile.csv | grep -q '^region,label,calls,seconds,mean_us,min_us,share$' || { cat profile.csv; fail "profile header"; }
grep -q '^"amphora::step",".*",20,' profile.csv || { cat profile.csv; fail "profile of 20 steps"; }
grep -q '^"","(outside kernels)",0,' profile.csv || { cat profile.csv; fail "profile's outside row"; }
expect_error 2 "^amphora: error: --kernel-profile: cannot write nowhere/p.csv$" "$AMPHORA" run scene.toml --kernel-profile nowhere/p.csv
[ ! -e out ] || fail "a run whose profile cannot be written wrote output"
echo "cli: ok"
