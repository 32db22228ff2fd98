# CFD-DEM on 1 and 2 ranks (the flow's slabs along z, the particles split at the same planes):
# the fluidised bed with QCM (ghost particles within a reference sphere's reach) and with
# smoothed PCM, and the spouted bed's jet, give the same diagnostics to 1e-8 relative; one flow
# block per rank; a 2-rank checkpoint continues on 1 rank to the 1-rank run's diagnostics.
source "$(dirname "$0")/common.sh"
compare_ranks() {  # SOURCE NAME [SED_EXPR...]: 1 rank against 2
  shipped_scene "$@"
  local name=$2
  sed "s|^output_dir = .*|output_dir = \"${name}_two\"|" "$name.toml" > "${name}_two.toml"
  "$AMPHORA" run "$name.toml" > "$name.log"
  "$MPIEXEC" -n 2 "$AMPHORA" run "${name}_two.toml" > "${name}_two.log"
  grep -q "ranks 2" "${name}_two.log" || fail "the 2-rank run of $name did not use 2 ranks"
  close_csv "$name/diagnostics.csv" "${name}_two/diagnostics.csv" 1e-8 1e-12
}
compare_ranks cfd_dem_fluidised_bed qcm
f=$(ls qcm_two/fields_*.h5 | tail -1)
h5ls "$f" | grep -q "^flow_0" && h5ls "$f" | grep -q "^flow_1" || { h5ls "$f"; fail "no flow block per rank in $f"; }
compare_ranks cfd_dem_fluidised_bed smoothed 's|^bed = .*|&\nvoid_fraction = "pcm"\nsmoothing_length = 2.0|'
compare_ranks cfd_dem_spouted_bed spout 's|^end_time = .*|end_time = 0.0025|'

# A 2-rank checkpoint (the flow in the whole box's DoF order, the particles by gid) restarts on
# 1 rank.
shipped_scene cfd_dem_fluidised_bed split
"$MPIEXEC" -n 2 "$AMPHORA" run split.toml --max-steps 4 > split_first.log
"$AMPHORA" run split.toml --restart split/checkpoint.h5 > split_second.log
grep -q "steps 4\.\.10 .*(restart)" split_second.log || { cat split_second.log; fail "restart from step 4 not announced"; }
close_csv qcm/diagnostics.csv split/diagnostics.csv 1e-8 1e-12
echo "cfd_dem ranks: fluidised (QCM, PCM) and spouted beds agree on 1 and 2 ranks; 2-rank checkpoint restarts on 1"
