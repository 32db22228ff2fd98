#!/usr/bin/env bash
# Checks a CUDA build for the nvcc lambda-wrapper hazard (cmake/nvcc_lambda_wrappers.sh): no
# library or executable may hold a global or weak host symbol of __nv_hdl_wrapper_t without the
# per-object suffix, since such a symbol is merged across files and can run with another file's
# unset function pointers (the host then jumps to address 0). Prints each offender and a count.
#   scripts/check_lambda_wrappers.sh [BUILD_DIR]     (default build/cuda)
set -uo pipefail
build=${1:-build/cuda}
bad=0
checked=0
while IFS= read -r f; do
  [ "$(head -c 4 "$f" | tail -c 3)" = ELF ] || continue
  checked=$((checked + 1))
  n=$(nm "$f" 2> /dev/null | awk '$2 ~ /^[A-Zu]$/ && $3 ~ /__nv_hdl_wrapper_t/ && $3 !~ /\.amphora_tu[0-9]+$/' | wc -l)
  if [ "$n" -gt 0 ]; then
    echo "$f: $n shared host symbol(s) of __nv_hdl_wrapper_t (built without cmake/nvcc_lambda_wrappers.sh?)"
    bad=$((bad + 1))
  fi
done < <(find "$build/src" "$build/apps" "$build/tests" "$build/perf" -maxdepth 1 -type f \( -name '*.so' -o -perm -u+x \) 2> /dev/null | sort)
[ "$checked" -gt 0 ] || { echo "check_lambda_wrappers: no binaries under $build"; exit 2; }
if [ "$bad" -gt 0 ]; then
  echo "check_lambda_wrappers: $bad of $checked binaries share lambda wrappers across files"
  exit 1
fi
echo "check_lambda_wrappers: ok ($checked binaries under $build)"
