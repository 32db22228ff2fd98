"""Volumetric locking of incompressible linear tetrahedra: the cantilever of
tests/physics/locking_cantilever.hpp (clamped, under its own weight, lambda = 1e6 mu) on two
splits of the cubes into tetrahedra (Kuhn: 6 around the main diagonal; centred: 24 around the
cube's and faces' centres), with the incompressibility per element or per node (the one-ring
volumes of the volume projection), against Q2 hexahedra with reduced-integrated volumetric
term. Runs the slow test test_solid_locking_study and charts the tip deflection over the Q2
reference against the number of nodes. Writes <out>/solid_locking.csv and .png.

  python3 scripts/study_solid_locking.py --build build/release --out output/studies/solid_locking

(about 3.5 minutes on 2 cores; --table FILE charts a table kept from an earlier run.)
"""
import argparse
import csv
import os
import subprocess


def chart(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for split, marker in (("kuhn6", "o"), ("centred24", "s")):
        sel = [r for r in rows if r["split"] == split]
        n = [int(r["nodes"]) for r in sel]
        for key, style in (("per_element", "--"), ("per_node", "-")):
            y = [float(r[key]) / float(r["q2"]) for r in sel]
            ax.plot(n, y, style, marker=marker, label=f"{split}, {key.replace('_', ' ')}")
    ax.axhspan(0.95, 1.05, color="grey", alpha=0.2, label="Q2 reference +- 5 %")
    ax.set_xscale("log")
    ax.set_xlabel("nodes")
    ax.set_ylabel("tip deflection / Q2 reference")
    ax.set_ylim(0.0, 1.1)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title("Incompressible cantilever (L/h = 8): locking of linear tetrahedra")
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--build", default="build/release")
    ap.add_argument("--backend", default="openmp")
    ap.add_argument("--out", default="output/studies/solid_locking")
    ap.add_argument("--table", help="chart this table instead of running the study")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    table = args.table or os.path.abspath(os.path.join(args.out, "solid_locking.csv"))
    if not args.table:
        exe = os.path.join(args.build, "tests", f"test_solid_locking_study_{args.backend}")
        subprocess.run([exe], check=True, env=dict(os.environ, AMPHORA_LOCKING_CSV=table))
    rows = list(csv.DictReader(open(table)))
    chart(rows, os.path.join(args.out, "solid_locking.png"))
    print(open(table).read())


if __name__ == "__main__":
    main()
