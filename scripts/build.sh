#!/usr/bin/env bash
# Set up (scripts/setup.sh) and build one CMake preset (default: release).
#   scripts/build.sh [release|debug|asan|cuda|cuda-check] [cmake --build arguments, e.g. -- -k 0]
# cuda: Kokkos with Serial + Cuda (Kokkos_ROOT, or built once from ../shared/kokkos: see
# scripts/setup_kokkos_cuda.sh), compiled with that Kokkos' nvcc_wrapper (or $CXX when set);
# it needs nvcc but no GPU. cuda-check: the same targets with nvcc's fastest device mode and
# host -O0 (build/cuda-check, what CI compiles: every kernel through nvcc, not fast to run).
# ccache (when installed) rewrites paths below the checkout as relative ones, so another clone
# of the same commit on this machine reuses its objects.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
preset=${1:-release}
shift || true
case "$preset" in
  release | debug | asan) target=cpu ;;
  cuda | cuda-check) target=cuda ;;
  *) echo "build.sh: unknown preset '$preset' (allowed: release, debug, asan, cuda, cuda-check)" >&2; exit 2 ;;
esac
kokkos=$(bash "$here/scripts/setup.sh" "$target" | sed -n 's/^KOKKOS_PREFIX=//p')
[ -n "$kokkos" ] || exit 1
cd "$here"
export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$here}
mkdir -p build
extra=()
if [ "$target" = cuda ]; then
  cxx=${CXX:-$kokkos/bin/nvcc_wrapper}
  [ -x "$cxx" ] || { echo "build.sh cuda: no compiler: $cxx is missing (set CXX to the compiler your Kokkos was built with)" >&2; exit 1; }
  export PATH="$PATH:${AMPHORA_CUDA_HOME:-/usr/local/cuda}/bin"  # nvcc_wrapper calls nvcc
  extra=(-DCMAKE_CXX_COMPILER="$cxx")
fi
# A user's Kokkos_ROOT (a Kokkos 4.x with CUDA or HIP, say) wins over the one setup built.
cmake --preset "$preset" -DKokkos_ROOT="${Kokkos_ROOT:-$kokkos}" "${extra[@]}" > "build/configure-$preset.log" \
  || { cat "build/configure-$preset.log"; exit 1; }
cmake --build --preset "$preset" -j "$(nproc)" "$@"
# The CUDA build's objects must each keep their own lambda wrappers (cmake/nvcc_lambda_wrappers.sh).
if [ "$target" = cuda ]; then bash "$here/scripts/check_lambda_wrappers.sh" "build/$preset"; fi
