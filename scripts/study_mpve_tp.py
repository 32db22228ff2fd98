#!/usr/bin/env python3
"""Issue 5 (b) for MP-VE (scenes/mpve_tp.toml): where the traditional partitioned scheme (TP)
is stable, over grid spacing dy = 1/20 .. 1/320 and solid-to-fluid density ratio
rho_bar / rho = 800 .. 1 (fluid viscosity 0.02), each run from the exact traveling wave to a
fixed time; "unstable" = amphora stopped the run because max |v| grew past 10x its start
(exit 3, with the step). For the stable runs the max-norm error of the solid's vbar is kept.
AMP for the bulk solid is not built yet, so the map has TP only.

Writes output/study_mpve_tp/mpve_tp_stability.csv and mpve_tp_stability.png.

    /usr/bin/python3 scripts/study_mpve_tp.py [--end-time 0.3] [--max-cells 320]
"""
import argparse
import csv
import os

from scene_variant import here, run_variant

out = os.path.join(here, "output", "study_mpve_tp")
ratios = [800.0, 400.0, 200.0, 100.0, 10.0, 1.0]


def run(ratio, cells, end_time):
    d = os.path.join(out, f"r{ratio:g}_n{cells}")
    r = run_variant("mpve_tp.toml", d, {"rho_bar": ratio, "cells": cells, "end_time": end_time})
    row = {"rho_bar_over_rho": ratio, "dy": 1.0 / cells, "cells": cells, "stable": r["stable"]}
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
    args = ap.parse_args()
    grids = [n for n in (20, 40, 80, 160, 320) if n <= args.max_cells]
    os.makedirs(out, exist_ok=True)
    rows = []
    for ratio in ratios:
        for n in grids:
            r = run(ratio, n, args.end_time)
            rows.append(r)
            print(f"rho_bar/rho {ratio:6g} dy 1/{n:<4d}: " +
                  (f"stable, vbar error {r['vbar_error']:.3e}" if r["stable"]
                   else f"UNSTABLE at step {r['blowup_step']} (t = {r['blowup_time']:.4g})"), flush=True)
    keys = ["rho_bar_over_rho", "dy", "cells", "stable", "blowup_step", "blowup_time", "vbar_error", "v_error"]
    with open(os.path.join(out, "mpve_tp_stability.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        for r in rows:
            w.writerow(r)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    for r in rows:
        x, y = grids.index(r["cells"]), ratios.index(r["rho_bar_over_rho"])
        ax.scatter(x, y, marker="o" if r["stable"] else "x", s=70, color="tab:blue" if r["stable"] else "tab:red")
    ax.set_xticks(range(len(grids)), [f"1/{n}" for n in grids])
    ax.set_yticks(range(len(ratios)), [f"{r:g}" for r in ratios])
    ax.set_xlabel("grid spacing dy")
    ax.set_ylabel("rho_bar / rho")
    ax.set_title(f"MP-VE, traditional partitioned: stable (o) / unstable (x) at t = {args.end_time:g}")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "mpve_tp_stability.png"), dpi=120)
    print("wrote", os.path.join(out, "mpve_tp_stability.png"))


if __name__ == "__main__":
    main()
