#!/usr/bin/env python3
"""A DEM output (fields_*.h5 of the dem module) as a LIGGGHTS data file (atom_style granular:
id type diameter density x y z), the bed both codes' benchmarks read.
  dem_bed_to_data.py FIELDS.h5 OUT.data BOX_X BOX_Y BOX_Z [DENSITY]
BOX_Z = fit: the bed's top plus two diameters, so that a domain decomposition splits the bed
and not the empty space above it."""
import os
import subprocess
import sys
import tempfile


def dataset(path, name):
    """The values of /particles/NAME, through h5dump (h5py is not a dependency)."""
    with tempfile.TemporaryDirectory() as tmp:
        raw = os.path.join(tmp, "values.txt")
        subprocess.run(["h5dump", "-y", "-w", "0", "-m", "%.17g", "-o", raw, "-d", f"/particles/{name}", path],
                       check=True, capture_output=True)
        with open(raw) as f:
            return [float(v) for v in f.read().replace(",", " ").split()]


def main():
    if len(sys.argv) < 6:
        sys.exit(__doc__)
    src, out = sys.argv[1], sys.argv[2]
    density = float(sys.argv[6]) if len(sys.argv) > 6 else 2500.0
    x, y, z, r = (dataset(src, n) for n in ("x", "y", "z", "radius"))
    top = max(zi + ri for zi, ri in zip(z, r)) + 4 * max(r)
    box = [float(v) if v != "fit" else top for v in sys.argv[3:6]]
    with open(out, "w") as f:
        f.write(f"LIGGGHTS data file: the bed of {src}\n\n{len(r)} atoms\n1 atom types\n\n")
        for lo_hi, length in zip(("xlo xhi", "ylo yhi", "zlo zhi"), box):
            f.write(f"0 {length!r} {lo_hi}\n")
        f.write("\nAtoms\n\n")
        for i in range(len(r)):
            f.write(f"{i + 1} 1 {2 * r[i]!r} {density!r} {x[i]!r} {y[i]!r} {z[i]!r}\n")


if __name__ == "__main__":
    main()
