# The house rules hold on src/, and their checks catch what they are for: the layer rules of
# scripts/check_layers.py (a kernel header that includes mesh/, MPI or Eigen, a mesh file that
# includes physics/), namespaces that follow folders (scripts/check_namespaces.py) and no function
# over 150 lines (scripts/check_function_length.py).
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
python3 "$root/scripts/check_namespaces.py" "$root/src"
mkdir -p "$work/ns/mesh/hex" "$work/ns/base"
printf 'namespace amphora::mesh::hex {\nnamespace detail {}\n}  // namespace amphora::mesh::hex\n' > "$work/ns/mesh/hex/good.hpp"
printf 'namespace amphora {\n}  // namespace amphora\n' > "$work/ns/base/good.hpp"
python3 "$root/scripts/check_namespaces.py" "$work/ns" > /dev/null || { echo "FAIL: a clean namespace rejected"; exit 1; }
printf '// a\nnamespace amphora::mesh {\n}  // namespace amphora::mesh\n' > "$work/ns/mesh/hex/bad.hpp"
if out=$(python3 "$root/scripts/check_namespaces.py" "$work/ns"); then
  echo "FAIL: amphora::mesh in mesh/hex/ passed the namespace check"; exit 1
fi
grep -q "bad.hpp:2: namespace amphora::mesh" <<< "$out" || { echo "FAIL: no file:line for bad.hpp: $out"; exit 1; }
python3 "$root/scripts/check_function_length.py" "$root/src"
mkdir -p "$work/long"
{
  echo 'namespace a {'
  echo 'int short_one(int x) {'; echo '  return x;'; echo '}'
  echo 'int Long::too_long(int x) const {'
  for i in $(seq 1 150); do echo "  x += $i;  // {"; done
  echo '  if (x > 0) {'; echo '    x = 0;'; echo '  }'
  echo '  return x;'; echo '}'
  echo '}  // namespace a'
} > "$work/long/f.cpp"
if out=$(python3 "$root/scripts/check_function_length.py" "$work/long"); then
  echo "FAIL: a 156-line function passed the length check"; exit 1
fi
grep -q "f.cpp:5: Long::too_long (156 lines" <<< "$out" || { echo "FAIL: $out"; exit 1; }
grep -q "short_one" <<< "$out" && { echo "FAIL: short_one reported: $out"; exit 1; }
echo "house rules: ok"
