#!/usr/bin/env bash
# Installs everything amphora needs on a Debian bookworm machine (run as root; idempotent).
#   scripts/setup.sh [cpu|cuda]
#   1. Debian packages: compilers, CMake, Eigen, hypre, Open MPI, parallel HDF5,
#      Google Benchmark, GoogleTest, toml++, CLI11, matplotlib, ccache.
#   2. A Kokkos. If Kokkos_ROOT is set, that Kokkos is used and nothing is built (for `cuda`
#      it must have the Cuda backend). Otherwise, for `cpu` (the default), Kokkos 3.4.1 with
#      Serial+OpenMP is built from Debian's `trilinos` source package (Debian's binary Kokkos
#      is Serial-only); for `cuda`, Kokkos 4.6.99 with Serial+Cuda is built with nvcc from
#      AMPHORA_KOKKOS_SOURCE (default ../shared/kokkos: the source tarball and its CUDA 13
#      patch) for AMPHORA_CUDA_ARCH (a Kokkos_ARCH_* name, default HOPPER90). Either is
#      installed under BUILD_ROOT/_deps, where later runs find and reuse it.
# Prints the Kokkos prefix as the last line: `KOKKOS_PREFIX=<path>`.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_root=${BUILD_ROOT:-$here/build}
deps=$build_root/_deps
target=${1:-cpu}
log() { echo "[setup] $*" >&2; }
case "$target" in
  cpu | cuda) ;;
  *) echo "setup.sh: unknown target '$target' (allowed: cpu, cuda)" >&2; exit 2 ;;
esac

packages=(
  g++ cmake ninja-build make pkg-config git ccache dpkg-dev xz-utils clang-format
  libeigen3-dev libhypre-dev libopenmpi-dev openmpi-bin
  libhdf5-openmpi-dev hdf5-tools
  libbenchmark-dev libgtest-dev libgmock-dev
  libtomlplusplus-dev libcli11-dev
  python3 python3-matplotlib python3-numpy
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  if [ "$(id -u)" != 0 ]; then
    log "missing Debian packages: ${missing[*]}; run this script as root to install them"; exit 1
  fi
  log "installing Debian packages: ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq >&2
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
else
  log "Debian packages present"
fi

# --- Kokkos -------------------------------------------------------------------------------
kokkos_has() {  # $1 = prefix, $2 = backend (OPENMP, CUDA)
  local cfg
  cfg=$(find "$1" -name KokkosCore_config.h -print -quit 2>/dev/null) || return 1
  [ -n "$cfg" ] && grep -q "define KOKKOS_ENABLE_$2" "$cfg"
}
kokkos_has_openmp() { kokkos_has "$1" OPENMP; }

if [ "$target" = cuda ]; then
  exec bash "$here/scripts/setup_kokkos_cuda.sh"
fi

if [ -n "${Kokkos_ROOT:-}" ]; then
  log "using the Kokkos given by Kokkos_ROOT=$Kokkos_ROOT (nothing built)"
  echo "KOKKOS_PREFIX=$Kokkos_ROOT"; exit 0
fi

prefix=$deps/kokkos-install
if kokkos_has_openmp "$prefix"; then
  log "reusing Kokkos (OpenMP) in $prefix"
  echo "KOKKOS_PREFIX=$prefix"; exit 0
fi

log "building Kokkos 3.4.1 (Serial+OpenMP) from Debian's trilinos source package"
work=$deps/kokkos-src
mkdir -p "$work"
if [ ! -f "$work/packages/kokkos/CMakeLists.txt" ]; then
  # A temporary deb-src list derived from the system's own sources, so apt's configuration
  # is left untouched and no host is named here.
  apt_tmp=$(mktemp -d)
  trap 'rm -rf "$apt_tmp"' EXIT
  mkdir -p "$apt_tmp/sources.list.d" "$apt_tmp/lists/partial"
  for f in /etc/apt/sources.list.d/*.sources; do
    [ -f "$f" ] && sed 's/^Types: deb$/Types: deb-src/' "$f" > "$apt_tmp/sources.list.d/$(basename "$f")"
  done
  if [ -f /etc/apt/sources.list ]; then
    sed -n 's/^deb /deb-src /p' /etc/apt/sources.list > "$apt_tmp/sources.list"
  else
    : > "$apt_tmp/sources.list"
  fi
  apt_opts=(-o "Dir::Etc::sourceparts=$apt_tmp/sources.list.d"
            -o "Dir::Etc::sourcelist=$apt_tmp/sources.list"
            -o "Dir::State::Lists=$apt_tmp/lists")
  apt-get "${apt_opts[@]}" update -qq >&2
  (cd "$apt_tmp" && apt-get "${apt_opts[@]}" source --download-only trilinos >&2)
  orig=$(ls "$apt_tmp"/trilinos_*.orig.tar.* | head -1)
  log "extracting packages/kokkos from $(basename "$orig")"
  tar -xf "$orig" -C "$work" --strip-components=1 --wildcards '*/packages/kokkos/*'
fi
cmake -S "$work/packages/kokkos" -B "$work/build" -G Ninja \
  -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_STANDARD=17 \
  -DKokkos_ENABLE_SERIAL=ON -DKokkos_ENABLE_OPENMP=ON \
  -DCMAKE_INSTALL_PREFIX="$prefix" >&2
cmake --build "$work/build" -j "$(nproc)" >&2
cmake --install "$work/build" >&2
kokkos_has_openmp "$prefix" || { log "Kokkos build did not produce an OpenMP backend"; exit 1; }
echo "KOKKOS_PREFIX=$prefix"
