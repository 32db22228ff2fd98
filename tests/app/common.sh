# Shared by the application tests: run the real amphora binary and check what it says and writes.
set -euo pipefail
: "${AMPHORA:?AMPHORA must point at the amphora binary}"
: "${AMPHORA_SOURCE_DIR:?}"
MPIEXEC=${MPIEXEC:-mpiexec}
work=$(mktemp -d "$PWD/$(basename "$0" .sh).XXXXXX")
trap 'rm -rf "$work"' EXIT
cd "$work"

fail() { echo "FAIL: $*" >&2; exit 1; }

# A small copy of the default scene with its output in `out/`, plus extra [run] lines.
make_scene() {  # file [extra run lines...]
  local file=$1; shift
  {
    echo '[run]'
    echo 'module = "advection_diffusion_1d"'
    echo 'output_dir = "out"'
    echo 'end_time = 0.5'
    echo 'diagnostics_every = 25'
    for line in "$@"; do echo "$line"; done
    echo '[advection_diffusion_1d]'
    echo 'cells = 40'
  } > "$file"
}

# expect_error CODE REGEX CMD...: CMD exits with CODE and its stderr matches REGEX in one line.
expect_error() {
  local code=$1 regex=$2; shift 2
  local status=0
  "$@" > stdout.txt 2> stderr.txt || status=$?
  [ "$status" = "$code" ] || { cat stdout.txt stderr.txt; fail "'$*' exited $status, expected $code"; }
  grep -E -q -- "$regex" stderr.txt || { cat stderr.txt; fail "'$*': stderr lacks /$regex/"; }
  [ "$(grep -c 'amphora: error' stderr.txt)" = 1 ] || { cat stderr.txt; fail "expected one error line"; }
}

# same_h5 A B: identical datasets and attributes (h5diff without tolerance compares exactly).
same_h5() { h5diff -q "$1" "$2" || fail "$1 and $2 differ"; }
