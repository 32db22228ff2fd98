#!/usr/bin/env python3
"""MP-VE (scenes/mpve_tp.toml, scenes/mpve_amp.toml): where the traditional
partitioned scheme (TP) and the added-mass partitioned scheme (AMP) are stable, over grid
spacing dy = 1/20 .. 1/320 and solid-to-fluid density ratio rho_bar / rho = 800 .. 0.001 (fluid
viscosity 0.02), each run from the exact traveling wave to a fixed time; "unstable" = amphora
stopped the run because max |v| grew past 10x its start (exit 3, with the step). For the stable
runs the max-norm errors of the solid's vbar and the fluid's v are kept.

Writes output/study_mpve_fsi/mpve_stability.csv and mpve_stability.png (the two maps side by
side).

    /usr/bin/python3 scripts/study_mpve_fsi.py [--end-time 0.3] [--max-cells 320] [--amp-max-cells 160]
"""
import argparse
import csv
import os

from scene_variant import here, run_variant

out = os.path.join(here, "output", "study_mpve_fsi")
ratios = [800.0, 400.0, 200.0, 100.0, 10.0, 1.0, 0.1, 0.01, 0.001]
schemes = ["tp", "amp"]


def run(scheme, ratio, cells, end_time):
    d = os.path.join(out, f"{scheme}_r{ratio:g}_n{cells}")
    r = run_variant("mpve_tp.toml", d, {"scheme": f'"{scheme}"', "rho_bar": ratio, "cells": cells, "end_time": end_time})
    row = {"scheme": scheme, "rho_bar_over_rho": ratio, "dy": 1.0 / cells, "cells": cells, "stable": r["stable"]}
    if not r["stable"]:
        row.update(blowup_step=r["blowup_step"], blowup_time=r["blowup_time"])
    else:
        last = list(csv.DictReader(open(os.path.join(d, "diagnostics.csv"))))[-1]
        row.update(vbar_error=float(last["vbar_error"]), v_error=float(last["v_error"]))
    return row


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--end-time", type=float, default=0.3)
    ap.add_argument("--max-cells", type=int, default=320)
    ap.add_argument("--amp-max-cells", type=int, default=160, help="AMP runs to the end: its finest grids cost minutes")
    args = ap.parse_args()
    grids = [n for n in (20, 40, 80, 160, 320) if n <= args.max_cells]
    os.makedirs(out, exist_ok=True)
    rows = []
    for scheme in schemes:
      for ratio in ratios:
        for n in grids:
            if scheme == "amp" and n > args.amp_max_cells:
                continue
            r = run(scheme, ratio, n, args.end_time)
            rows.append(r)
            print(f"{scheme:3s} rho_bar/rho {ratio:6g} dy 1/{n:<4d}: " +
                  (f"stable, vbar error {r['vbar_error']:.3e}" if r["stable"]
                   else f"UNSTABLE at step {r['blowup_step']} (t = {r['blowup_time']:.4g})"), flush=True)
    keys = ["scheme", "rho_bar_over_rho", "dy", "cells", "stable", "blowup_step", "blowup_time", "vbar_error", "v_error"]
    with open(os.path.join(out, "mpve_stability.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        for r in rows:
            w.writerow(r)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.6), sharey=True)
    for ax, scheme in zip(axes, schemes):
        for r in rows:
            if r["scheme"] != scheme:
                continue
            x, y = grids.index(r["cells"]), ratios.index(r["rho_bar_over_rho"])
            ax.scatter(x, y, marker="o" if r["stable"] else "x", s=70, color="tab:blue" if r["stable"] else "tab:red")
        ax.set_xticks(range(len(grids)), [f"1/{n}" for n in grids])
        ax.set_yticks(range(len(ratios)), [f"{r:g}" for r in ratios])
        ax.set_xlabel("grid spacing dy")
        ax.set_title(f"MP-VE, {scheme.upper()}: stable (o) / unstable (x), t = {args.end_time:g}")
    axes[0].set_ylabel("rho_bar / rho")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "mpve_stability.png"), dpi=120)
    print("wrote", os.path.join(out, "mpve_stability.png"))


if __name__ == "__main__":
    main()
