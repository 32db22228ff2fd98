#!/usr/bin/env bash
# The Kokkos of the CUDA build (called by `scripts/setup.sh cuda` once the Debian packages are
# in). Kokkos_ROOT, when set, must be a Kokkos with the Cuda backend and is used as it is.
# Otherwise Kokkos 4.6.99 (Serial + Cuda) is built with nvcc from AMPHORA_KOKKOS_SOURCE
# (a folder holding kokkos-4.6.99-src.tar.gz and kokkos-4.6.99-cuda13.patch; default
# ../shared/kokkos) for AMPHORA_CUDA_ARCH (Kokkos_ARCH_<name>, default HOPPER90) into
# BUILD_ROOT/_deps/kokkos-cuda-install, once, as shared libraries (the CUDA build's test and
# benchmark executables share one copy of Kokkos and of amphora's kernels, so they travel to a
# GPU machine as a small bundle: scripts/gpu_bundle.sh). Prints `KOKKOS_PREFIX=<path>` last.
# AMPHORA_CUDA_HOME: the CUDA toolkit's folder when nvcc is not on PATH (default /usr/local/cuda).
# Anything missing stops it with one line saying what.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_root=${BUILD_ROOT:-$here/build}
deps=$build_root/_deps
arch=${AMPHORA_CUDA_ARCH:-HOPPER90}
log() { echo "[setup] $*" >&2; }
die() { echo "amphora cuda setup: $*" >&2; exit 1; }

kokkos_has_cuda() {  # $1 = prefix
  local cfg
  cfg=$(find "$1" -name KokkosCore_config.h -print -quit 2>/dev/null) || return 1
  [ -n "$cfg" ] && grep -q "define KOKKOS_ENABLE_CUDA$" "$cfg"
}

if [ -n "${Kokkos_ROOT:-}" ]; then
  kokkos_has_cuda "$Kokkos_ROOT" ||
    die "the Kokkos in Kokkos_ROOT=$Kokkos_ROOT has no Cuda backend (no KOKKOS_ENABLE_CUDA in its KokkosCore_config.h); give a Kokkos >= 4.7 built with -DKokkos_ENABLE_CUDA=ON, or unset Kokkos_ROOT to build one"
fi
cuda_home=${AMPHORA_CUDA_HOME:-/usr/local/cuda}
nvcc=$(command -v nvcc || true)
[ -z "$nvcc" ] && [ -x "$cuda_home/bin/nvcc" ] && nvcc=$cuda_home/bin/nvcc
[ -n "$nvcc" ] || die "no nvcc (looked in PATH and $cuda_home/bin): install the CUDA toolkit, or set AMPHORA_CUDA_HOME to its folder"
if [ -n "${Kokkos_ROOT:-}" ]; then
  log "using the Kokkos given by Kokkos_ROOT=$Kokkos_ROOT (nothing built)"
  echo "KOKKOS_PREFIX=$Kokkos_ROOT"; exit 0
fi

prefix=$deps/kokkos-cuda-install
stamp=$prefix/.amphora-arch
if kokkos_has_cuda "$prefix" && [ "$(cat "$stamp" 2>/dev/null)" = "$arch shared" ]; then
  log "reusing Kokkos (Cuda, $arch) in $prefix"
  echo "KOKKOS_PREFIX=$prefix"; exit 0
fi

source_dir=${AMPHORA_KOKKOS_SOURCE:-$here/../shared/kokkos}
tarball=$source_dir/kokkos-4.6.99-src.tar.gz
patch_file=$source_dir/kokkos-4.6.99-cuda13.patch
[ -f "$tarball" ] && [ -f "$patch_file" ] ||
  die "no Kokkos source in $source_dir (kokkos-4.6.99-src.tar.gz and kokkos-4.6.99-cuda13.patch); set AMPHORA_KOKKOS_SOURCE to that folder, or Kokkos_ROOT to a Kokkos >= 4.7 built with Cuda"

log "building Kokkos 4.6.99 (Serial+Cuda, Kokkos_ARCH_$arch) with $nvcc"
work=$deps/kokkos-cuda-src
rm -rf "$work" "$prefix"
mkdir -p "$work"
tar -xzf "$tarball" -C "$work"
(cd "$work/kokkos" && patch -p1 -s < "$patch_file") || die "the CUDA 13 patch did not apply to $tarball"
export PATH="$(dirname "$nvcc"):$PATH"
cmake -S "$work/kokkos" -B "$work/build" -G Ninja \
  -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_STANDARD=17 -DCMAKE_CXX_EXTENSIONS=OFF \
  -DCMAKE_CXX_COMPILER="$work/kokkos/bin/nvcc_wrapper" \
  -DKokkos_ENABLE_SERIAL=ON -DKokkos_ENABLE_CUDA=ON -DKokkos_ENABLE_CUDA_LAMBDA=ON \
  -DKokkos_ARCH_"$arch"=ON -DBUILD_SHARED_LIBS=ON -DCMAKE_INSTALL_PREFIX="$prefix" > "$work/configure.log" 2>&1 ||
  die "Kokkos did not configure for Kokkos_ARCH_$arch: $(grep -m1 -iE 'error' "$work/configure.log") (log: $work/configure.log)"
cmake --build "$work/build" -j "$(nproc)" >&2
cmake --install "$work/build" >&2
kokkos_has_cuda "$prefix" || die "the Kokkos build in $prefix has no Cuda backend"
echo "$arch shared" > "$stamp"
echo "KOKKOS_PREFIX=$prefix"
