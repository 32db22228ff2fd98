# info, defaults and check work and say what they should.
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
echo "cli: ok"
