# The CUDA set-up's bad input: no nvcc, or a Kokkos without Cuda, stops it with one line that
# says what is missing (exit 1, nothing built). A machine with no GPU meets the CUDA build in CI
# (.ci/run: the binary says no GPU is visible and exits 1).
source "$(dirname "$0")/common.sh"
setup=$AMPHORA_SOURCE_DIR/scripts/setup_kokkos_cuda.sh
expect_setup_error() {  # REGEX ENV...: the setup exits 1 with one line matching REGEX
  local regex=$1 status=0; shift
  env "$@" bash "$setup" > stdout.txt 2> stderr.txt || status=$?
  [ "$status" = 1 ] || { cat stdout.txt stderr.txt; fail "setup with $* exited $status, expected 1"; }
  [ "$(wc -l < stderr.txt)" = 1 ] || { cat stderr.txt; fail "setup with $*: expected one line"; }
  grep -E -q -- "$regex" stderr.txt || { cat stderr.txt; fail "setup with $*: stderr lacks /$regex/"; }
  [ ! -s stdout.txt ] || fail "setup with $* printed a Kokkos prefix"
}
expect_setup_error "^amphora cuda setup: no nvcc \(looked in PATH and /nonexistent/bin\)" \
  PATH=/usr/bin:/bin AMPHORA_CUDA_HOME=/nonexistent BUILD_ROOT="$work/build"
# a Kokkos without Cuda: this build's own (Serial + OpenMP)
kokkos=$(sed -n 's/^Kokkos_DIR:PATH=\(.*\)\/lib[^/]*\/cmake\/Kokkos$/\1/p' "$AMPHORA_BUILD_DIR/CMakeCache.txt")
[ -n "$kokkos" ] || fail "no Kokkos_DIR in $AMPHORA_BUILD_DIR/CMakeCache.txt"
expect_setup_error "^amphora cuda setup: the Kokkos in Kokkos_ROOT=$kokkos has no Cuda backend" \
  Kokkos_ROOT="$kokkos" BUILD_ROOT="$work/build"
echo "cuda setup: ok"
