# The layer rules of scripts/check_layers.py hold on src/, and the check catches a wrong include
# (a kernel header that includes mesh/, one that includes MPI, a mesh file that includes physics/).
set -euo pipefail
root=$1
python3 "$root/scripts/check_layers.py" "$root/src"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/kernels/mac" "$work/mesh"
printf '#include <Kokkos_Core.hpp>\n#include <vector>\n#include "kernels/blas1.hpp"\n' > "$work/kernels/good.hpp"
python3 "$root/scripts/check_layers.py" "$work" > /dev/null || { echo "FAIL: a clean kernel header rejected"; exit 1; }
expect_wrong() {  # file text: the check must fail naming the file
  printf '%s\n' "$2" > "$work/$1"
  if out=$(python3 "$root/scripts/check_layers.py" "$work"); then
    echo "FAIL: $1 ($2) passed the layer check"; exit 1
  fi
  grep -q "$1:1: #include" <<< "$out" || { echo "FAIL: no file:line for $1: $out"; exit 1; }
  rm "$work/$1"
}
expect_wrong kernels/mac/a.hpp '#include "mesh/mac/lattice_halo.hpp"'
expect_wrong kernels/b.hpp '#include <mpi.h>'
expect_wrong kernels/c.hpp '#include <Eigen/Dense>'
expect_wrong mesh/d.cpp '#include "physics/module.hpp"'
echo "layers: ok"
