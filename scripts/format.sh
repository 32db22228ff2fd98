#!/usr/bin/env bash
# Applies .clang-format to the C++ sources (src/, apps/, perf/, tests/), or with --check lists
# the files it would change and exits 1 if there is any (CI runs the check). The layout is
# clang-format 14's (Debian bookworm's, installed by scripts/setup.sh); other versions differ
# in details, so the check insists on 14.
#   scripts/format.sh [--check]
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$here"
tool=$(command -v clang-format-14 || command -v clang-format || true)
if [ -z "$tool" ]; then
  echo "format.sh: clang-format not found (bash scripts/setup.sh installs it)" >&2; exit 2
fi
version=$("$tool" --version | sed -n 's/.*version \([0-9]*\)\..*/\1/p')
mapfile -t files < <(git ls-files 'src/*.hpp' 'src/*.cpp' 'apps/*.cpp' 'perf/*.hpp' 'perf/*.cpp' \
                                  'tests/*.hpp' 'tests/*.cpp')
if [ "${1:-}" = --check ]; then
  if [ "$version" != 14 ]; then
    echo "format.sh: $tool is version $version; the check needs clang-format 14" >&2; exit 2
  fi
  bad=0
  for f in "${files[@]}"; do
    if ! "$tool" --dry-run -Werror "$f" > /dev/null 2>&1; then
      echo "format.sh: $f is not formatted (bash scripts/format.sh fixes it)"; bad=$((bad + 1))
    fi
  done
  echo "format.sh: ${#files[@]} files checked, $bad not formatted"
  [ "$bad" = 0 ]
else
  "$tool" -i "${files[@]}"
  echo "format.sh: ${#files[@]} files formatted with clang-format $version"
fi
