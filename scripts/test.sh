#!/usr/bin/env bash
# The test suite, from a fresh machine: set up, build, run every test not labelled slow.
#   scripts/test.sh [release|asan]   (extra ctest arguments may follow)
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
preset=${1:-release}
shift || true
bash "$here/scripts/build.sh" "$preset"
cd "$here"
ctest --preset "$preset" -j 2 "$@"
