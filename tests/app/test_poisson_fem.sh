# The poisson_fem scene: matrix-free Q_k on curved hexahedra through `amphora run`. Its error
# matches the order of the method, multigrid and Jacobi CG give the same solution, output opens
# as a curvilinear grid, and bad input is refused with the key and the allowed values.
source "$(dirname "$0")/common.sh"
scene() {  # file degree cells solver [extra poisson_fem lines]
  local file=$1 degree=$2 cells=$3 solver=$4; shift 4
  {
    echo '[run]'; echo 'module = "poisson_fem"'; echo "output_dir = \"${file%.toml}\""
    echo 'end_time = 1.0'; echo 'dt = 1.0'
    echo '[poisson_fem]'; echo "degree = $degree"; echo "cells = $cells"; echo "solver = \"$solver\""
    for line in "$@"; do echo "$line"; done
  } > "$file"
}
col() { awk -F, -v k="$2" 'NR==1{for(i=1;i<=NF;i++) if($i==k) c=i} END{print $c}' "$1"; }

# Q3 on 4^3 and 8^3 curved cells: L2 error falls by 2^4 (order 4 within 0.3)
scene c4.toml 3 4 multigrid
scene c8.toml 3 8 multigrid
"$AMPHORA" run c4.toml > c4.log
"$AMPHORA" run c8.toml > c8.log
e4=$(col c4/diagnostics.csv l2_error); e8=$(col c8/diagnostics.csv l2_error)
order=$("$AMPHORA_PYTHON" -c "import math; print(math.log($e4/$e8, 2))")
"$AMPHORA_PYTHON" -c "import sys; sys.exit(0 if abs($order - 4) < 0.3 else 1)" || fail "L2 order $order, expected 4"
iters=$(col c8/diagnostics.csv iterations)
[ "${iters%.*}" -le 12 ] || fail "multigrid CG took $iters iterations"
grep -q 'TopologyType="3DSMesh" Dimensions="25 25 25"' c8/c8.xmf || fail "no curvilinear grid in c8.xmf"

# Jacobi CG reaches the same discrete solution
scene j8.toml 3 8 jacobi
"$AMPHORA" run j8.toml > j8.log
ej=$(col j8/diagnostics.csv l2_error)
"$AMPHORA_PYTHON" -c "import sys; sys.exit(0 if abs($ej - $e8) <= 1e-6 * $e8 else 1)" || fail "jacobi $ej vs multigrid $e8"

# stored and on-the-fly geometry give the same solution; 2D works
scene f8.toml 3 8 multigrid 'geometry = "on_the_fly"'
"$AMPHORA" run f8.toml > f8.log
ef=$(col f8/diagnostics.csv l2_error)
"$AMPHORA_PYTHON" -c "import sys; sys.exit(0 if abs($ef - $e8) <= 1e-6 * $e8 else 1)" || fail "on_the_fly $ef vs stored $e8"
scene d2.toml 5 6 multigrid 'dim = 2'
"$AMPHORA" run d2.toml > d2.log
e2=$(col d2/diagnostics.csv l2_error)
"$AMPHORA_PYTHON" -c "import sys; sys.exit(0 if $e2 < 1e-7 else 1)" || fail "2D Q5 error $e2"

# 2 ranks (slabs along z): the same error and iteration count as 1 rank, one curvilinear piece
# per rank in the output; a checkpoint written on 2 ranks (the solution in global DoF order) is
# read back by a 1-rank run
scene m8.toml 3 8 multigrid 'deformation = 0.05'
sed -i 's/^end_time = 1.0/end_time = 2.0\ncheckpoint_every = 1/' m8.toml
"$MPIEXEC" -n 2 "$AMPHORA" run m8.toml > m8.log
em=$(col m8/diagnostics.csv l2_error); im=$(col m8/diagnostics.csv iterations)
"$AMPHORA_PYTHON" -c "import sys; sys.exit(0 if abs($em - $e8) <= 1e-9 * $e8 else 1)" || fail "2 ranks $em vs 1 rank $e8"
[ "${im%.*}" = "${iters%.*}" ] || fail "2 ranks: $im multigrid-CG iterations, 1 rank $iters"
grep -q 'Grid Name="solution_1"' m8/m8.xmf || fail "no rank-1 piece in m8.xmf"
grep -q 'TopologyType="3DSMesh" Dimensions="13 25 25"' m8/m8.xmf || fail "rank pieces are not 12-cell slabs"
"$AMPHORA" run m8.toml --restart m8/checkpoint.h5 > m8r.log 2>&1 || fail "1-rank restart of a 2-rank checkpoint: $(tail -3 m8r.log)"
er=$(col m8/diagnostics.csv l2_error)
"$AMPHORA_PYTHON" -c "import sys; sys.exit(0 if abs($er - $e8) <= 1e-9 * $e8 else 1)" || fail "restarted error $er"
scene c2.toml 3 2 multigrid
expect_error 2 "more ranks \(3\) than cells \(2\)" "$MPIEXEC" -n 3 "$AMPHORA" run c2.toml

# bad input
scene bad.toml 3 4 multigrid 'geometry = "cartesian"'
expect_error 2 "cartesian.*deformation = 0" "$AMPHORA" run bad.toml
scene bad2.toml 9 4 multigrid
expect_error 2 "poisson_fem.degree.*\[1, 8\]" "$AMPHORA" check bad2.toml
scene bad3.toml 3 4 gauss_seidel
expect_error 2 "one of: multigrid, jacobi" "$AMPHORA" check bad3.toml
echo "poisson_fem: ok (L2 order $order, $iters multigrid-CG iterations)"
