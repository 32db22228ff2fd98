#!/usr/bin/env bash
# Compiler launcher of the CUDA build: compiles, then renames, in the object just written, every
# defined host symbol of nvcc's __host__ __device__ lambda wrapper (__nv_hdl_wrapper_t, which
# KOKKOS_LAMBDA makes) with a suffix unique to that object.
# Why: nvcc keeps the wrapper's function pointers (copy, delete, call) in an anonymous namespace,
# one set per translation unit, but emits the wrapper's members and every template instantiated
# on it (Kokkos::parallel_for, ...) as weak symbols. A header function with a KOKKOS_LAMBDA
# compiled in two .cpp files (MatrixFreeOperator's, DEM's, the MAC kernels') then links one
# file's members against the other file's never-set pointers, and the host jumps to address 0
# (a known nvcc bug: see docs/gpu.md). With the suffix, each object keeps its own, consistent
# copy. Usage (CMake sets it): nvcc_lambda_wrappers.sh [--fast-compile] COMPILER ARGS... -o OBJECT
# --fast-compile: nvcc compiles device code at -Ofc max (NVCC_APPEND_FLAGS: nvcc_wrapper would
# hand an unknown flag to the host compiler), for the cuda-check preset.
if [ "${1:-}" = --fast-compile ]; then
  shift
  export NVCC_APPEND_FLAGS="${NVCC_APPEND_FLAGS:+$NVCC_APPEND_FLAGS }-Ofc max"
fi
"$@" || exit $?
out=
prev=
for a in "$@"; do
  [ "$prev" = "-o" ] && out=$a
  prev=$a
done
[ -n "$out" ] && [ -f "$out" ] || exit 0
suffix=$(printf '%s' "$out" | cksum | cut -d' ' -f1)
map=$(mktemp)
trap 'rm -f "$map"' EXIT
nm --defined-only "$out" 2> /dev/null | awk -v s=".amphora_tu$suffix" \
  '$3 ~ /__nv_hdl_wrapper_t/ && $3 !~ /\.amphora_tu/ {print $3, $3 s}' | sort -u > "$map"
[ -s "$map" ] || exit 0
objcopy --redefine-syms="$map" "$out"
