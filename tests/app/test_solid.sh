# The invertible-FEM solid end to end: the squashed, inverted cube recovers (min det F and the
# volume back within 1 %), its output is a tetrahedral XDMF series; the standard model stops
# the same scene as a divergence; bad material input is one clear line.
source "$(dirname "$0")/common.sh"
sed 's|^output_dir = .*|output_dir = "out"|' "$AMPHORA_SOURCE_DIR/scenes/solid_squash.toml" > squash.toml
"$AMPHORA" run squash.toml > run.log
last=$(tail -1 out/diagnostics.csv)
header=$(head -1 out/diagnostics.csv)
col() { echo "$header" | tr ',' '\n' | grep -n "^$1\$" | cut -d: -f1; }
min_j=$(echo "$last" | cut -d, -f"$(col min_det_F)")
vol=$(echo "$last" | cut -d, -f"$(col volume_error)")
first_j=$(sed -n 2p out/diagnostics.csv | cut -d, -f"$(col min_det_F)")
awk -v a="$first_j" 'BEGIN { exit !(a < -0.29 && a > -0.31) }' || fail "starts at min det F $first_j, not -0.3"
awk -v j="$min_j" -v v="$vol" 'BEGIN { exit !(j > 0.99 && j < 1.01 && v < 0.01 && v > -0.01) }' \
  || fail "not recovered: min det F $min_j, volume error $vol"
grep -q 'TopologyType="Tetrahedron" NumberOfElements="3072"' out/solid_squash.xmf || fail "no tet topology"
grep -q 'Name="det_F" AttributeType="Scalar" Center="Cell"' out/solid_squash.xmf || fail "det_F not cell data"
h5dump -d /solid/topology_tets -c 4 "out/fields_000000.h5" > /dev/null || fail "connectivity unreadable"

# A ball squashed to 15 % of its diameter between plates, which inverts elements, and released:
# back to its shape within 1 % of its radius and to its volume within 1 %.
sed -e 's|^output_dir = .*|output_dir = "ball"|' -e 's/^cells = .*/cells = 4/' \
  "$AMPHORA_SOURCE_DIR/scenes/solid_ball_squash.toml" > ball.toml
"$AMPHORA" run ball.toml > ball.log
worst_j=$(csv_column min_det_F ball/diagnostics.csv | sort -g | head -1)
shape=$(csv_column shape_error ball/diagnostics.csv | tail -1)
bvol=$(csv_column volume_error ball/diagnostics.csv | tail -1)
awk -v j="$worst_j" -v s="$shape" -v v="$bvol" 'BEGIN { exit !(j < 0 && s < 0.01 && v < 0.01 && v > -0.01) }' \
  || fail "ball: min det F $worst_j (should go below 0), shape error $shape, volume error $bvol"
# The same squash by backward Euler (Newton-CG) at a step 20 times the explicit limit.
sed -e 's|^output_dir = .*|output_dir = "ball_be"|' -e 's/^cells = .*/cells = 4/' -e 's/^cfl = .*/dt = 4e-4/' \
  -e 's/^s_clamp = .*/s_clamp = 0.25\nintegrator = "backward_euler"\nnewton_tolerance = 1e-5/' \
  "$AMPHORA_SOURCE_DIR/scenes/solid_ball_squash.toml" > ball_be.toml
"$AMPHORA" run ball_be.toml > ball_be.log
shape=$(csv_column shape_error ball_be/diagnostics.csv | tail -1)
newton=$(csv_column newton_iterations ball_be/diagnostics.csv | sort -g | tail -1)
awk -v s="$shape" -v n="$newton" 'BEGIN { exit !(s < 0.01 && n >= 1 && n <= 50) }' \
  || fail "implicit ball: shape error $shape, at most $newton Newton iterations"
# A Newton solve that cannot reach its tolerance stops the run as a divergence.
sed -i -e 's|^output_dir = .*|output_dir = "ball_nt"|' \
  -e 's/^newton_tolerance = .*/newton_tolerance = 1e-12\nnewton_max_iterations = 2/' ball_be.toml
expect_error 3 "run diverged: the Newton solve did not converge \(gradient .* after 2 iterations\) in field 'position/velocity/force' of block 'solid' at \(x, y, z\) = .* at step [0-9]+, t = .*; last good output: ball_nt/fields_000000.h5 \(step 0\)" \
  "$AMPHORA" run ball_be.toml
# A torus dropped on a 25-degree ramp: it lands and slides down, its energy never grows (the
# contact is inelastic) and its elements stay upright.
sed -e 's|^output_dir = .*|output_dir = "torus"|' -e 's/^cells = .*/cells = 2/' \
  -e 's/^end_time = .*/end_time = 0.12/' "$AMPHORA_SOURCE_DIR/scenes/solid_torus_ramp.toml" > torus.toml
"$AMPHORA" run torus.toml > torus.log
e0=$(csv_column total_energy torus/diagnostics.csv | head -1)
emax=$(csv_column total_energy torus/diagnostics.csv | sort -g | tail -1)
tj=$(csv_column min_det_F torus/diagnostics.csv | sort -g | head -1)
z1=$(csv_column centroid_z torus/diagnostics.csv | tail -1)
awk -v a="$e0" -v b="$emax" -v j="$tj" -v z="$z1" 'BEGIN { exit !(b <= a * (1 + 1e-6) && j > 0.5 && z < -0.01) }' \
  || fail "torus: energy $e0 -> at most $emax, min det F $tj, centroid height $z1"

# A clay-like ball (plastic_yield) squashed to 40 % of its diameter and released keeps its
# flattened shape (shape error over 0.3 of its radius, against < 0.01 for the elastic ball),
# its volume within 1 %, and comes to rest.
sed -e 's|^output_dir = .*|output_dir = "plastic"|' -e 's/^cells = .*/cells = 4/' \
  "$AMPHORA_SOURCE_DIR/scenes/solid_ball_plastic.toml" > plastic.toml
"$AMPHORA" run plastic.toml > plastic.log
shape=$(csv_column shape_error plastic/diagnostics.csv | tail -1)
pvol=$(csv_column volume_error plastic/diagnostics.csv | tail -1)
ke=$(csv_column kinetic_energy plastic/diagnostics.csv | tail -1)
ep=$(csv_column max_plastic_strain plastic/diagnostics.csv | tail -1)
awk -v s="$shape" -v v="$pvol" -v k="$ke" -v e="$ep" \
  'BEGIN { exit !(s > 0.3 && v < 0.01 && v > -0.01 && k < 1e-6 && e > 0.5 && e <= log(3) + 1e-9) }' \
  || fail "plastic ball: shape error $shape, volume error $pvol, kinetic energy $ke, max plastic strain $ep"

# A muscle-like cylinder squeezed by plates with the per-node volume projection: the body's
# volume within 1e-6 and every node's within the tolerance (1e-8) at every diagnostic, while
# the plates flatten it. A projection that cannot reach its tolerance stops the run.
sed -e 's|^output_dir = .*|output_dir = "muscle"|' -e 's/^end_time = .*/end_time = 0.02/' \
  "$AMPHORA_SOURCE_DIR/scenes/solid_muscle_squeeze.toml" > muscle.toml
"$AMPHORA" run muscle.toml > muscle.log
vmax=$(csv_column volume_error muscle/diagnostics.csv | awk '{ v = $1 < 0 ? -$1 : $1; if (v > m) m = v } END { print m + 0 }')
nmax=$(csv_column node_volume_error muscle/diagnostics.csv | sort -g | tail -1)
shape=$(csv_column shape_error muscle/diagnostics.csv | tail -1)
awk -v v="$vmax" -v n="$nmax" -v s="$shape" 'BEGIN { exit !(v < 1e-6 && n <= 1e-8 && s > 0.1) }' \
  || fail "muscle: volume error up to $vmax, per node up to $nmax, shape error $shape"
sed -i -e 's|^output_dir = .*|output_dir = "muscle_nc"|' -e 's/^volume_preserving = true/volume_preserving = true\nvolume_tolerance = 1e-17/' muscle.toml
expect_error 3 "run diverged: the volume projection did not converge \(per-node volume error .* after 10 corrections, [0-9]+ conjugate-residual iterations\) in field 'position/velocity/force' of block 'solid' at \(x, y, z\) = .* at step 1, t = .*; last good output: muscle_nc/fields_000000.h5 \(step 0\)" \
  "$AMPHORA" run muscle.toml

# The standard model (no extrapolation) cannot stress an inverted element.
sed -e 's|^output_dir = .*|output_dir = "std"|' -e 's/^squash = .*/squash = -0.3\ns_clamp = 0.0/' \
  "$AMPHORA_SOURCE_DIR/scenes/solid_squash.toml" > standard.toml
expect_error 3 "run diverged: non-finite value \(an element inverted: the standard model has no stress there; set s_clamp > 0 for invertible FEM\) in field 'position/velocity/force' of block 'solid' at \(x, y, z\) = .* at step 1, t = .*; last good output: std/fields_000000.h5 \(step 0\)" \
  "$AMPHORA" run standard.toml

sed -e 's/^poisson = .*/poisson = 0.5/' "$AMPHORA_SOURCE_DIR/scenes/solid_squash.toml" > nu.toml
expect_error 2 "nu.toml:[0-9]+: key 'solid_fem.poisson' = 0.5 is out of range; allowed: a real number in \(-1, 0.5\)" \
  "$AMPHORA" run nu.toml
sed -e 's/^cfl = .*/dt = 1e-3/' "$AMPHORA_SOURCE_DIR/scenes/solid_squash.toml" > dt.toml
expect_error 2 "solid_fem: time step 0.001 is outside \(0, [0-9.e-]+\], the explicit limit" "$AMPHORA" run dt.toml
sed -e 's/^squash = .*/squash = 1.0\nintegrator = "backward_euler"\nviscosity = 1.0/' \
  "$AMPHORA_SOURCE_DIR/scenes/solid_squash.toml" > kv.toml
expect_error 2 "solid_fem: viscosity \(Kelvin-Voigt damping\) needs the explicit integrator" "$AMPHORA" run kv.toml
# A Gmsh mesh with three negatively oriented elements: refused, naming them.
cp "$AMPHORA_SOURCE_DIR/tests/mesh/kuhn_cube.msh" cube.msh
sed -e 's/^squash = .*/squash = 1.0\nmesh = "cube.msh"/' "$AMPHORA_SOURCE_DIR/scenes/solid_squash.toml" > msh.toml
expect_error 2 "solid_fem: 3 inverted or degenerate rest element\(s\): 1 2 5" "$AMPHORA" run msh.toml
sed -i 's/cube.msh/none.msh/' msh.toml
expect_error 2 "none.msh: cannot open the mesh file" "$AMPHORA" run msh.toml

# A restart half way ends bit for bit where the uninterrupted run ends (positions and
# velocities are the state; the forces are recomputed from the positions).
restart_matches "$AMPHORA_SOURCE_DIR/scenes/solid_squash.toml" solid 100 \
  's/^end_time = .*/end_time = 0.004/' 's|^output_every = .*|output_every = 50\ncheckpoint_every = 40|'
# ... and with plasticity, F_p is state too.
restart_matches "$AMPHORA_SOURCE_DIR/scenes/solid_squash.toml" plastic_restart 100 \
  's/^end_time = .*/end_time = 0.004/' 's|^output_every = .*|output_every = 50\ncheckpoint_every = 40|' \
  's/^squash = .*/squash = 0.5\nplastic_yield = 0.02/'
echo "solid: ok ($(grep '^\[done\]' run.log | cut -c1-60))"
