# The pseudo-2D spouted bed through the real binary (the shipped scene run to 0.3 s): the jet
# opens a spout through the bed. Once open (t in [0.2, 0.3] s), the beads over the jet rise at
# a mean speed of more than 0.3 m/s, at least five times the annulus's mean vertical speed,
# and the fountain rises above the settled bed (0.07 m).
source "$(dirname "$0")/common.sh"
scene="$AMPHORA_SOURCE_DIR/scenes/cfd_dem_spouted_bed.toml"
sed -e 's|^output_dir = .*|output_dir = "spout"|' -e 's|^end_time = .*|end_time = 0.3|' \
  -e 's|^output_every = .*|output_every = 400|' -e 's|^diagnostics_every = .*|diagnostics_every = 4|' \
  "$scene" > spout.toml
OMP_NUM_THREADS=2 "$AMPHORA" run spout.toml > spout.log
grep -q "^\[done\]" spout.log || fail "the spouted bed did not finish"
mean_over() {  # COLUMN: the mean of the column over rows with 0.2 <= time <= 0.3
  paste -d, <(csv_column time spout/diagnostics.csv) <(csv_column "$1" spout/diagnostics.csv) |
    awk -F, '$1 >= 0.2 { s += $2; n += 1 } END { printf "%.6f\n", s / n }'
}
spout=$(mean_over spout_particle_velocity)
annulus=$(mean_over annulus_particle_velocity)
fountain=$(mean_over fountain_height)
echo "spout $spout m/s, annulus $annulus m/s, fountain height $fountain m"
awk -v s="$spout" -v a="$annulus" 'BEGIN { exit !(s > 0.3 && s > 5 * (a < 0 ? -a : a)) }' ||
  fail "no spout: beads over the jet at $spout m/s, the annulus at $annulus m/s"
awk -v f="$fountain" 'BEGIN { exit !(f > 0.07) }' || fail "the fountain stays at $fountain m"
echo "cfd_dem spouted: ok"
