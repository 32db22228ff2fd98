#!/usr/bin/env bash
# Packs what scripts/gpu_check.sh runs on a GPU machine with no package registry (nvcc 13.0 and
# the driver there, none of amphora's dependencies): the test and benchmark executables of a
# build, and every shared library they load except the C/C++ runtime and the CUDA driver
# (Kokkos, amphora's layers, Open MPI with its plugins and helpers, hypre, HDF5, ...). Open MPI
# goes under ompi/ in its installed layout, so OPAL_PREFIX relocates it.
#   scripts/gpu_bundle.sh [BUILD_DIR [BUNDLE_DIR]]
# With GPU_BUNDLE_REFERENCE (default build/release) holding an amphora, a few shipped scenes are
# run with it, their diagnostics kept in reference/ for gpu_check.sh to compare the GPU's with.
# Defaults: build/cuda (scripts/build.sh cuda) -> build/gpu-bundle, packed as BUNDLE_DIR.tar.xz
# too (what travels to the device machine: its `carry`, at most 64 MiB). build/release rehearses
# the same on the OpenMP build.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=$(cd "${1:-$here/build/cuda}" && pwd)
bundle=${2:-$here/build/gpu-bundle}
[ -f "$build/CTestTestfile.cmake" ] || { echo "gpu_bundle.sh: $build is not a build tree (run scripts/build.sh cuda)" >&2; exit 1; }
rm -rf "$bundle"
mkdir -p "$bundle/bin" "$bundle/lib"
bundle=$(cd "$bundle" && pwd)

# The tests ctest would run, less the multi-rank and app ones (no mpiexec of several ranks, no
# matplotlib there): name, executable, arguments, environment, one per line.
(cd "$build" && ctest --show-only=json-v1) > "$bundle/ctest.json"
/usr/bin/python3 - "$build" "$bundle" <<'PY'
import json, os, shutil, sys
build, bundle = sys.argv[1], sys.argv[2]
tests = json.load(open(os.path.join(bundle, "ctest.json")))["tests"]
rows, skipped = [], []
for t in tests:
    cmd = t.get("command") or []
    props = {p["name"]: p["value"] for p in t.get("properties", [])}
    labels = props.get("LABELS", [])
    env = [e for e in props.get("ENVIRONMENT", []) if not e.startswith(("AMPHORA=", "AMPHORA_SOURCE_DIR=", "MPIEXEC=", "AMPHORA_PYTHON="))]
    if "slow" in labels or not cmd:
        continue
    if os.path.basename(cmd[0]).startswith("mpiexec") or os.path.basename(cmd[0]) == "orterun":
        n = cmd[cmd.index("-n") + 1] if "-n" in cmd else "1"
        if n != "1":
            skipped.append(t["name"]); continue
        exe = next(c for c in cmd[1:] if c.startswith(build))
        args = cmd[cmd.index(exe) + 1:]
    elif cmd[0].startswith(build):
        exe, args = cmd[0], cmd[1:]
    else:
        skipped.append(t["name"]); continue
    name = os.path.basename(exe)
    if not os.path.exists(os.path.join(bundle, "bin", name)):
        shutil.copy2(exe, os.path.join(bundle, "bin", name))
    rows.append("\t".join([t["name"], name, " ".join(args), ";".join(env)]))
open(os.path.join(bundle, "tests.tsv"), "w").write("\n".join(rows) + "\n")
open(os.path.join(bundle, "skipped.txt"), "w").write("\n".join(skipped) + "\n")
print(f"[bundle] {len(rows)} tests, {len(skipped)} left out (several ranks, app scripts)")
PY
rm -f "$bundle/ctest.json"
for exe in "$build"/perf/bench_* "$build"/apps/amphora; do
  [ -x "$exe" ] && [ -f "$exe" ] && cp "$exe" "$bundle/bin/"
done

# Shared libraries: what the executables load, less the system's runtime and the GPU driver.
keep_lib() {
  case "$(basename "$1")" in
    linux-vdso* | ld-linux* | libc.so* | libm.so* | libstdc++.so* | libgcc_s.so* | libpthread.so* | \
    libdl.so* | librt.so* | libcuda.so* | libnvidia*) return 1 ;;
  esac
  return 0
}
copy_deps() {  # copy_deps FILE...: every library FILE needs, recursively through ldd
  ldd "$@" 2>/dev/null | awk '/=> \// {print $3}' | sort -u | while read -r lib; do
    keep_lib "$lib" || continue
    [ -e "$bundle/lib/$(basename "$lib")" ] || cp -L "$lib" "$bundle/lib/"
  done
}
copy_deps "$bundle"/bin/*
# Open MPI's plugins and helpers are loaded at run time, not linked: its lib folder, help texts
# and orted, under ompi/ in the installed layout (prefix /usr).
ompi_lib=/usr/lib/x86_64-linux-gnu/openmpi
if [ -d "$ompi_lib" ]; then
  mkdir -p "$bundle/ompi/lib/x86_64-linux-gnu" "$bundle/ompi/share" "$bundle/ompi/bin"
  cp -a "$ompi_lib" "$bundle/ompi/lib/x86_64-linux-gnu/"
  rm -rf "$bundle/ompi/lib/x86_64-linux-gnu/openmpi/include" "$bundle/ompi/lib/x86_64-linux-gnu/openmpi/lib/pkgconfig"
  [ -d /usr/share/openmpi ] && cp -a /usr/share/openmpi "$bundle/ompi/share/"
  for b in orted orterun mpiexec; do [ -x "/usr/bin/$b" ] && cp -L "/usr/bin/$b" "$bundle/ompi/bin/"; done
  copy_deps "$ompi_lib"/lib/openmpi3/*.so "$bundle"/ompi/bin/*
fi
strip --strip-unneeded "$bundle"/bin/* "$bundle"/lib/* 2> /dev/null || true

# Reference diagnostics from another build (the OpenMP one): scene, run steps.
reference=${GPU_BUNDLE_REFERENCE:-$here/build/release}
if [ -x "$reference/apps/amphora" ]; then
  mkdir -p "$bundle/reference"
  scratch=$(mktemp -d)
  for spec in "poisson_curved 1" "water_dam_break 20" "dem_settling_bed 400"; do
    read -r name steps <<< "$spec"
    sed 's|^output_dir = .*|output_dir = "out"|' "$here/scenes/$name.toml" > "$bundle/reference/$name.toml"
    if (cd "$scratch" && rm -rf out && OMP_NUM_THREADS=2 OMP_PROC_BIND=false OMPI_ALLOW_RUN_AS_ROOT=1 \
          OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 "$reference/apps/amphora" run "$bundle/reference/$name.toml" \
          --max-steps "$steps" > run.log 2>&1); then
      cp "$scratch/out/diagnostics.csv" "$bundle/reference/$name.csv"
      echo "$name $steps" >> "$bundle/reference/scenes.txt"
    else
      echo "[bundle] the reference run of $name failed: $(tail -n 1 "$scratch/run.log")" >&2
    fi
  done
  rm -rf "$scratch"
  echo "[bundle] reference diagnostics from $reference: $(cat "$bundle/reference/scenes.txt" | tr '\n' ' ')"
fi
tar -C "$(dirname "$bundle")" -cf - "$(basename "$bundle")" | xz -T0 -6 > "$bundle.tar.xz"
echo "[bundle] $(ls "$bundle/bin" | wc -l) executables, $(ls "$bundle/lib" | wc -l) libraries, $(du -sh "$bundle" | cut -f1) in $bundle; packed: $(du -h "$bundle.tar.xz" | cut -f1) $bundle.tar.xz"
