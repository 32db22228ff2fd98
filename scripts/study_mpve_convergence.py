#!/usr/bin/env python3
"""MP-VE: max-norm convergence of AMP at h = 1/20, 1/40, 1/80, 1/160 for the heavy
solid (rho_bar / rho = 1e3, fluid viscosity mu = 0.02) and the very light one (rho_bar / rho =
1e-3, mu = 0.005), each through `amphora run` (scenes/mpve_amp.toml) from the exact traveling
wave to t = 0.3; the errors are the module's diagnostics at the end (p at t - dt/2, v, u of the
fluid; ubar, vbar of the solid's displacement; sigma_bar from centred differences of it).
Observed orders are log2 of successive error ratios.

Writes output/study_mpve_convergence/mpve_amp_convergence.csv and .png.

    /usr/bin/python3 scripts/study_mpve_convergence.py [--end-time 0.3]
"""
import argparse
import csv
import math
import os

from scene_variant import here, run_variant

out = os.path.join(here, "output", "study_mpve_convergence")
cases = [("heavy", 1000.0, 0.02), ("very light", 0.001, 0.005)]
grids = [20, 40, 80, 160]
fields = ["p", "v", "u", "ubar", "vbar", "sigma_bar"]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--end-time", type=float, default=0.3)
    args = ap.parse_args()
    os.makedirs(out, exist_ok=True)
    rows = []
    for name, ratio, mu in cases:
        previous = None
        for n in grids:
            d = os.path.join(out, f"{name.replace(' ', '_')}_n{n}")
            r = run_variant("mpve_amp.toml", d, {"rho_bar": ratio, "viscosity": mu, "cells": n, "end_time": args.end_time})
            if not r["stable"]:
                raise RuntimeError(f"AMP unstable: {name}, h = 1/{n}")
            last = list(csv.DictReader(open(os.path.join(d, "diagnostics.csv"))))[-1]
            row = {"case": name, "rho_bar_over_rho": ratio, "viscosity": mu, "h": 1.0 / n}
            for f in fields:
                e = float(last[f + "_error"])
                row[f + "_error"] = e
                row[f + "_order"] = math.log2(previous[f + "_error"] / e) if previous else ""
            rows.append(row)
            previous = row
            print(f"{name:10s} h = 1/{n:<4d} " + "  ".join(
                f"{f} {row[f + '_error']:.2e}" + (f" ({row[f + '_order']:.2f})" if row[f + "_order"] != "" else "")
                for f in fields), flush=True)
    with open(os.path.join(out, "mpve_amp_convergence.csv"), "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.4))
    for ax, (name, ratio, mu) in zip(axes, cases):
        case = [r for r in rows if r["case"] == name]
        h = [r["h"] for r in case]
        for f in fields:
            e = [r[f + "_error"] for r in case]
            ax.loglog(h, [x / e[0] for x in e], "o-", label=f"{f} ({case[-1][f + '_order']:.2f})")
        ax.loglog(h, [(x / h[0]) ** 2 for x in h], "k--", label="h^2")
        ax.set_xlabel("h")
        ax.set_ylabel("max-norm error / error at h = 1/20")
        ax.set_title(f"MP-VE by AMP, {name}: rho_bar/rho = {ratio:g}, mu = {mu:g}")
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "mpve_amp_convergence.png"), dpi=120)
    print("wrote", os.path.join(out, "mpve_amp_convergence.png"))


if __name__ == "__main__":
    main()
