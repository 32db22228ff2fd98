#!/usr/bin/env bash
# Set up (scripts/setup.sh) and build one CMake preset (default: release).
#   scripts/build.sh [release|debug|asan]
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
preset=${1:-release}
kokkos=$(bash "$here/scripts/setup.sh" | sed -n 's/^KOKKOS_PREFIX=//p')
cd "$here"
mkdir -p build
# A user's Kokkos_ROOT (a Kokkos 4.x with CUDA or HIP, say) wins over the one setup built.
cmake --preset "$preset" -DKokkos_ROOT="${Kokkos_ROOT:-$kokkos}" > "build/configure-$preset.log" \
  || { cat "build/configure-$preset.log"; exit 1; }
cmake --build --preset "$preset" -j "$(nproc)"
