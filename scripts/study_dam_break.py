#!/usr/bin/env python3
"""The dam break of scenes/water_dam_break.toml (Martin & Moyce 1952, n^2 = 2) at several grid
spacings (h = a/8, a/16, a/32 by default: --cells 64,128,256 along x, the height scaled alike) and
CFL numbers (--cfl 1): the front Z = x/a against T = t sqrt(2g/a), its error against the
experiment (the run's own front_error diagnostic, so the experiment's table lives only in the
module) and the water volume, with the shallow-water estimate beside them (Ritter 1892: the front
of a dam break on a dry bed runs at 2 sqrt(g H), H = 2a, so Z = 1 + 2T). Prints, per run, the
largest error over T = 1.1-3.3, the error at the end (against the experiment and the shallow-water
estimate), the volume's largest change, and the time lag that brings the run closest to the
experiment (the experiment's front at T against the run's at T - lag: a constant lag, such as a gate
opening in the experiment would cause, leaves a small error; a speed difference does not); writes output/study_dam_break/dam_break_study.csv (one row
per run) and dam_break_study.png (Z(T) per run with the experiment, and the error).

    /usr/bin/python3 scripts/study_dam_break.py [--cells 64,128,256] [--cfl 1] [--threads 2]
"""
import argparse
import csv
import os
import re

import numpy as np

from scene_variant import here, run_variant

out = os.path.join(here, "output", "study_dam_break")
scene = "water_dam_break.toml"


def shallow_water_front(T):
    """Ritter's front Z = x/a at T = t sqrt(2g/a): x = a + 2 sqrt(g 2a) t."""
    return 1.0 + 2.0 * T


def best_lag(T, Z, exp, lags):
    """The lag dT (of those given) for which the run's front at T - dT is closest to the experiment's
    at T over T = 1.1-3.34 (largest relative error), with that error."""
    measured = [(t, z) for t, z in zip(T, exp) if z and 1.1 <= t <= 3.34]
    best = None
    for lag in lags:
        worst = max(abs(np.interp(t - lag, T, Z) / z - 1) for t, z in measured)
        if best is None or worst < best[1]:
            best = (lag, worst)
    return best


def run(base, cells, cfl, threads):
    nx0 = int(re.search(r"^cells_x = (\d+)", base, re.M).group(1))
    ny0 = int(re.search(r"^cells_y = (\d+)", base, re.M).group(1))
    d = os.path.join(out, f"nx_{cells}_cfl_{cfl:g}")
    run_variant(scene, d, {"cells_x": cells, "cells_y": ny0 * cells // nx0, "cfl": f"{cfl:g}"}, threads)
    rows = list(csv.DictReader(open(os.path.join(d, "diagnostics.csv"))))
    T = [float(r["front_T"]) for r in rows]
    Z = [float(r["front_Z"]) for r in rows]
    err = [float(r["front_error"]) for r in rows]
    vol = [float(r["volume"]) / float(rows[0]["volume"]) - 1 for r in rows]
    checked = [e for t, e in zip(T, err) if 1.1 <= t <= 3.34]
    # the experiment at the run's times, from the run's relative error (0 where not measured)
    exp = [z / (1 + e) if e else None for z, e in zip(Z, err)]
    a = float(re.search(r"^column_width = (\S+)", base, re.M).group(1))
    lx = float(re.search(r"^length_x = (\S+)", base, re.M).group(1))
    lag, lag_error = best_lag(T, Z, exp, [0.005 * n for n in range(161)])  # T = 0-0.8
    return {"lag": lag, "lag_ms": 1e3 * lag * float(rows[-1]["time"]) / T[-1], "lag_error": lag_error,
            "cells": cells, "cfl": cfl, "h_over_a": lx / cells / a, "T": T, "Z": Z, "err": err, "exp": exp,
            "worst": max(checked, key=abs), "final": err[-1], "final_swe": Z[-1] / shallow_water_front(T[-1]) - 1,
            "volume": max(vol, key=abs),
            "substeps": int(rows[-1]["substeps"])}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cells", default="64,128,256")
    ap.add_argument("--cfl", default="1")
    ap.add_argument("--threads", type=int, default=2)
    args = ap.parse_args()
    os.makedirs(out, exist_ok=True)
    base = open(os.path.join(here, "scenes", scene)).read()
    runs = []
    for cfl in (float(c) for c in args.cfl.split(",")):
        for cells in (int(n) for n in args.cells.split(",")):
            r = run(base, cells, cfl, args.threads)
            runs.append(r)
            print(f"h = a/{1 / r['h_over_a']:.0f}, CFL {cfl:g} ({r['substeps']} sub-steps): front error "
                  f"{100 * r['worst']:+.1f} % at worst over T = 1.1-3.3, {100 * r['final']:+.1f} % at T = "
                  f"{r['T'][-1]:.2f} ({100 * r['final_swe']:+.1f} % against the shallow-water front); volume changed by {100 * r['volume']:+.2f} % at most; "
                  f"the experiment lags by T = {r['lag']:.3f} ({r['lag_ms']:.1f} ms), behind which it is within "
                  f"{100 * r['lag_error']:.1f} %", flush=True)
    with open(os.path.join(out, "dam_break_study.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["cells_x", "h_over_a", "cfl", "substeps", "worst_front_error", "final_front_error",
                    "largest_volume_change", "final_front_error_vs_shallow_water", "experiment_lag_T",
                    "experiment_lag_ms", "worst_front_error_after_lag"])
        for r in runs:
            w.writerow([r["cells"], f"{r['h_over_a']:.5f}", f"{r['cfl']:g}", r["substeps"], f"{r['worst']:.4e}",
                        f"{r['final']:.4e}", f"{r['volume']:.4e}", f"{r['final_swe']:.4e}", f"{r['lag']:.3f}",
                        f"{r['lag_ms']:.2f}", f"{r['lag_error']:.4e}"])
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(10, 4.2))
    for n, r in enumerate(runs):
        label = f"h = a/{1 / r['h_over_a']:.0f}, CFL {r['cfl']:g}"
        ax.plot(r["T"], r["Z"], color=f"C{n}", label=label)
        measured = [(t, 100 * e) for t, e, z in zip(r["T"], r["err"], r["exp"]) if z]  # from T = 0.83 on
        bx.plot([t for t, _ in measured], [e for _, e in measured], color=f"C{n}", label=label)
        # the same run behind its best lag: the experiment at T against the run at T - lag
        lagged = [(t, 100 * (np.interp(t - r["lag"], r["T"], r["Z"]) / z - 1)) for t, z in zip(r["T"], r["exp"])
                  if z and t >= r["lag"]]
        bx.plot([t for t, _ in lagged], [e for _, e in lagged], color=f"C{n}", ls=":",
                label=f"{label}, run {r['lag_ms']:.1f} ms later")
    finest = min(runs, key=lambda r: r["h_over_a"])
    ax.plot([t for t, z in zip(finest["T"], finest["exp"]) if z], [z for z in finest["exp"] if z], "k--",
            label="Martin & Moyce (1952)")
    ax.plot(finest["T"], [shallow_water_front(t) for t in finest["T"]], "k:", label="shallow water (Ritter): Z = 1 + 2T")
    ax.set_xlabel("T = t sqrt(2g/a)")
    ax.set_ylabel("front Z = x/a")
    ax.legend(fontsize=8)
    bx.axhspan(-5, 5, color="grey", alpha=0.15, lw=0)
    bx.set_xlabel("T = t sqrt(2g/a)")
    bx.set_ylabel("front error against the experiment [%]")
    bx.legend(fontsize=7)
    fig.suptitle("Dam break (n^2 = 2): inviscid MAC water with a level set")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "dam_break_study.png"), dpi=120)
    print("wrote", os.path.join(out, "dam_break_study.csv"), "and dam_break_study.png")


if __name__ == "__main__":
    main()
