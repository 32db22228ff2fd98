#!/usr/bin/env python3
"""The wet-bed dam break of scenes/water_dam_break_wet.toml (h1 / h0 = 0.1) at several grid
spacings (h = h0/8, h0/16, h0/32 by default: --cells 176,352,704 along x, the height scaled
alike) and CFL numbers (--cfl 1): the bore's distance from the dam against Stoker's shallow-water
bore S t (the run's own bore_error diagnostic, so the solution lives only in the module), over
T = t sqrt(g / h0). Prints, per run, the largest error once the bore has run 4 reservoir depths
(T >= 4; before, the column is still collapsing), the error at the end and the volume's largest
change; writes output/study_dam_break_wet/dam_break_wet_study.csv (one row per run) and
dam_break_wet_study.png (the bore's position per run with Stoker's, and the error).

    /usr/bin/python3 scripts/study_dam_break_wet.py [--cells 176,352,704] [--cfl 1] [--threads 2]
"""
import argparse
import csv
import os
import re

from scene_variant import here, run_variant

out = os.path.join(here, "output", "study_dam_break_wet")
scene = "water_dam_break_wet.toml"


def run(cells, cfl, threads):
    base = open(os.path.join(here, "scenes", scene)).read()
    nx0 = int(re.search(r"^cells_x = (\d+)", base, re.M).group(1))
    ny0 = int(re.search(r"^cells_y = (\d+)", base, re.M).group(1))
    h0 = float(re.search(r"^reservoir_depth = (\S+)", base, re.M).group(1))
    ly = ny0 * float(re.search(r"^length_x = (\S+)", base, re.M).group(1)) / nx0
    d = os.path.join(out, f"nx_{cells}_cfl_{cfl:g}")
    run_variant(scene, d, {"cells_x": cells, "cells_y": ny0 * cells // nx0, "cfl": f"{cfl:g}"}, threads)
    rows = list(csv.DictReader(open(os.path.join(d, "diagnostics.csv"))))
    col = {k: [float(r[k]) for r in rows] for k in ("time", "bore_x", "bore_T", "bore_error", "volume")}
    checked = [e for t, e in zip(col["bore_T"], col["bore_error"]) if t >= 4.0]
    return dict(col, cells=cells, cfl=cfl, h0_over_h=h0 / (ly / (ny0 * cells // nx0)),
                worst=max(checked, key=abs), final=col["bore_error"][-1],
                volume=max((v / col["volume"][0] - 1 for v in col["volume"]), key=abs))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cells", default="176,352,704")
    ap.add_argument("--cfl", default="1")
    ap.add_argument("--threads", type=int, default=2)
    args = ap.parse_args()
    os.makedirs(out, exist_ok=True)
    runs = []
    for cfl in (float(c) for c in args.cfl.split(",")):
        for cells in (int(n) for n in args.cells.split(",")):
            r = run(cells, cfl, args.threads)
            runs.append(r)
            print(f"h = h0/{r['h0_over_h']:.0f}, CFL {cfl:g}: bore error {100 * r['worst']:+.2f} % at worst over "
                  f"T = 4-{r['bore_T'][-1]:.1f}, {100 * r['final']:+.2f} % at the end; volume changed by "
                  f"{100 * r['volume']:+.2f} % at most", flush=True)
    with open(os.path.join(out, "dam_break_wet_study.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["cells_x", "h0_over_h", "cfl", "worst_bore_error_T_ge_4", "final_bore_error",
                    "largest_volume_change"])
        for r in runs:
            w.writerow([r["cells"], f"{r['h0_over_h']:.0f}", f"{r['cfl']:g}", f"{r['worst']:.4e}",
                        f"{r['final']:.4e}", f"{r['volume']:.4e}"])
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(10, 4.2))
    for n, r in enumerate(runs):
        label = f"h = h0/{r['h0_over_h']:.0f}, CFL {r['cfl']:g}"
        ax.plot(r["bore_T"], r["bore_x"], color=f"C{n}", label=label)
        bx.plot(r["bore_T"], [100 * e for e in r["bore_error"]], color=f"C{n}", label=label)
    # Stoker's bore from the finest run's own error: x / (1 + error) = S t
    finest = max(runs, key=lambda r: r["h0_over_h"])
    ax.plot(finest["bore_T"], [x / (1 + e) for x, e in zip(finest["bore_x"], finest["bore_error"])], "k--",
            label="Stoker (1957): S t")
    ax.set_xlabel("T = t sqrt(g/h0)")
    ax.set_ylabel("bore's distance from the dam [m]")
    ax.legend(fontsize=8)
    bx.axhspan(-5, 5, color="grey", alpha=0.15, lw=0)
    bx.axvline(4.0, color="k", lw=0.5)
    bx.set_ylim(-40, 20)
    bx.set_xlabel("T = t sqrt(g/h0)")
    bx.set_ylabel("bore position error against Stoker [%]")
    bx.legend(fontsize=7)
    fig.suptitle("Wet-bed dam break (h1/h0 = 0.1): inviscid MAC water with a level set")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "dam_break_wet_study.png"), dpi=120)
    print("wrote", os.path.join(out, "dam_break_wet_study.csv"), "and dam_break_wet_study.png")


if __name__ == "__main__":
    main()
