# DEM through the real binary: a settling bed gives the same bits on 1 and 2 threads and on 1
# and 2 ranks (a particle receives its pair forces in an order set by the particles alone: see
# dem_system.hpp), continues bit for bit from a checkpoint (contact history, insertion state and
# build positions included), so does a bed with periodic sides, and bad input is refused.
source "$(dirname "$0")/common.sh"
bed() {  # file output_dir [extra [dem] lines...]
  local file=$1 out=$2; shift 2
  {
    echo '[run]'
    echo 'name = "bed"'
    echo 'module = "dem"'
    echo "output_dir = \"$out\""
    echo 'end_time = 0.12'
    echo 'output_every = 2000'
    echo 'diagnostics_every = 500'
    echo '[dem]'
    echo 'box_x = 0.02'
    echo 'box_y = 0.02'
    echo 'box_z = 0.04'
    echo 'particle_count = 400'
    echo 'insertion_rate = 8000.0'
    echo 'radius_spread = 0.1'
    echo 'second_material_fraction = 0.3'
    echo 'restitution = 0.6'
    echo 'insertion_velocity = 1.0'
  } > "$file"
  for line in "$@"; do  # an extra line replaces the default of its key
    sed -i "/^${line%% *} = /d" "$file"
    echo "$line" >> "$file"
  done
}
bed one.toml t1
bed two.toml t2
bed ranks.toml r2
OMP_NUM_THREADS=1 KOKKOS_NUM_THREADS=1 "$AMPHORA" run one.toml > one.log
OMP_NUM_THREADS=2 KOKKOS_NUM_THREADS=2 "$AMPHORA" run two.toml > two.log
"$MPIEXEC" -n 2 "$AMPHORA" run ranks.toml > ranks.log
grep -q "ranks 2" ranks.log || fail "not run on 2 ranks"
grep -q "particles=400" one.log || { cat one.log; fail "insertion incomplete"; }
final=$(ls t1/fields_*.h5 | tail -1)
for dir in t2 r2; do
  for f in t1/fields_*.h5; do same_h5 "$f" "$dir/$(basename "$f")"; done
  same_h5 t1/checkpoint.h5 "$dir/checkpoint.h5"
done
close_csv t1/diagnostics.csv t2/diagnostics.csv  # sums over particles: round-off only
close_csv t1/diagnostics.csv r2/diagnostics.csv
echo "dem: identical bits on 1/2 threads and 1/2 ranks ($(basename "$final"))"

# Restart in the middle of insertion, with contacts and wall contacts carrying history.
bed split.toml sp
"$AMPHORA" run split.toml --max-steps 2500 > first.log
"$AMPHORA" run split.toml --restart sp/checkpoint.h5 > second.log
same_h5 "$final" "sp/$(basename "$final")"
same_h5 t1/checkpoint.h5 sp/checkpoint.h5
# ... and a 2-rank continuation of a 1-rank checkpoint.
bed split2.toml s2
"$AMPHORA" run split2.toml --max-steps 2500 > /dev/null
"$MPIEXEC" -n 2 "$AMPHORA" run split2.toml --restart s2/checkpoint.h5 > /dev/null
same_h5 "$final" "s2/$(basename "$final")"
echo "dem: restart bit for bit"

# Periodic sides (a bed longer along x, so that two ranks split it there and exchange images
# across the periodic faces): the same bits on 1/2 threads and 1/2 ranks, and a 2-rank
# continuation of a 1-rank checkpoint.
periodic=('box_sides = "periodic"' 'box_x = 0.05' 'box_z = 0.03')
for run in p1 p2 pr ps; do
  bed $run.toml $run "${periodic[@]}"
  sed -i 's/^end_time = 0.12/end_time = 0.06/' $run.toml
done
OMP_NUM_THREADS=1 KOKKOS_NUM_THREADS=1 "$AMPHORA" run p1.toml > /dev/null
OMP_NUM_THREADS=2 KOKKOS_NUM_THREADS=2 "$AMPHORA" run p2.toml > /dev/null
"$MPIEXEC" -n 2 "$AMPHORA" run pr.toml > /dev/null
"$AMPHORA" run ps.toml --max-steps 1700 > /dev/null
"$MPIEXEC" -n 2 "$AMPHORA" run ps.toml --restart ps/checkpoint.h5 > /dev/null
pfinal=$(ls p1/fields_*.h5 | tail -1)
for dir in p2 pr ps; do same_h5 "$pfinal" "$dir/$(basename "$pfinal")"; done
same_h5 p1/checkpoint.h5 pr/checkpoint.h5
echo "dem: periodic sides, identical bits on 1/2 threads and ranks and across a restart"

# Bad input: nothing written, one clear line.
bed bad_dt.toml bad 'youngs_modulus = 6e10'
sed -i 's/^end_time = 0.12/end_time = 0.12\ndt = 1e-5/' bad_dt.toml
expect_error 2 "time step 1e-05 s exceeds the DEM stability limit .* = min\(0.2 x Rayleigh time .*, 0.1 x Hertz contact time .*\); lower run.dt or set dem.allow_large_dt = true" \
  "$AMPHORA" run bad_dt.toml
[ ! -e bad ] || fail "output written for a too-large time step"
bed big_dt_ok.toml ok 'youngs_modulus = 6e10' 'allow_large_dt = true'
sed -i 's/^end_time = 0.12/end_time = 1e-4\ndt = 1e-5/' big_dt_ok.toml
"$AMPHORA" check big_dt_ok.toml > /dev/null || fail "allow_large_dt not honoured"
bed full.toml bad 'insertion_rate = 1e7'
expect_error 2 "random insertion cannot fit 400 particles per event" "$AMPHORA" run full.toml
printf '[run]\nmodule = "dem"\nend_time = 1.0\noutput_dir = "bad"\n[dem]\ngeometry = "drum"\nfill_level = 0.55\n' > drum_full.toml
expect_error 2 "lattice insertion cannot fit [0-9]+ particles in the drum" "$AMPHORA" run drum_full.toml
for kv in "particle_radius = 0.0" "density = -1.0" "youngs_modulus = 0.0" "restitution = 1.5" "restitution = 0.0"; do
  bed bad_value.toml bad "$kv"
  expect_error 2 "bad_value.toml:[0-9]+: key 'dem.${kv%% *}' = .* is out of range; allowed:" "$AMPHORA" run bad_value.toml
done
[ ! -e bad ] || fail "output written for bad input"
echo "dem: bad input refused"
