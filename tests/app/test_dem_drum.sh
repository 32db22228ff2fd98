# The rotating drum's regime: at Froude number 2 the bed centrifuges, at 0.006 it rolls
# (Mellmann 2001's map), classified from the time-averaged free surface and particle motion.
source "$(dirname "$0")/common.sh"
export OMP_NUM_THREADS=2 KOKKOS_NUM_THREADS=2
for case in "2 3 centrifuging" "0.006 0 rolling"; do
  set -- $case
  sed "s/^froude = .*/froude = $1/; s|^output_dir = .*|output_dir = \"fr$1\"|; s/^output_every = .*/output_every = 0/" \
    "$AMPHORA_SOURCE_DIR/scenes/dem_drum.toml" > "fr$1.toml"
  "$AMPHORA" run "fr$1.toml" > "fr$1.log"
  header=$(head -1 "fr$1/diagnostics.csv")
  col=$(echo "$header" | tr ',' '\n' | grep -n '^regime$' | cut -d: -f1)
  got=$(tail -1 "fr$1/diagnostics.csv" | cut -d, -f"$col")
  [ "$got" = "$2" ] || { tail -1 "fr$1.log"; fail "Froude $1: regime $got, expected $2 ($3)"; }
  echo "Froude $1: $3 ($(tail -1 "fr$1.log" | grep -o 'upper_fraction.*'))"
done
