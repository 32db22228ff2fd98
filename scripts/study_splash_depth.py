#!/usr/bin/env python3
"""How the tall cells' gain grows with the depth of the water: the same splash over
pools of several depths (--scenes, default the 1.6 m, 3.6 m and 7.6 m pools), each run uniform
and with tall cells below optical depth D (--depths, one per scene), as scripts/study_splash.py
runs them. Per pool: fewer pressure unknowns, less time per step, the surface error at the end
(% of the splash amplitude), and the time ratio of an ideal tall-cell run, against which the
measured one is read:

    ideal = t_u / (m_u * rows / ny + p_u * unknowns_t / unknowns_u)

with t_u the uniform run's time per step, p_u its pressure set-up and solve, m_u = t_u - p_u the
rest, rows the rows a column would keep if its fields were stored per column (the tall run's
unknowns per column, i.e. the band and the two tall-cell samples, plus the air rows above the
still surface) out of ny, and the tall-cell pressure at the uniform multigrid's cost per unknown.
It is what fields stored per column (Chentanez & Mueller 2011's restricted tall cells) with a
pressure solve as cheap per unknown as the uniform one would give at best: no part of the step
is assumed cheaper per stored row or unknown than in the uniform run.
Writes output/study_splash_depth/splash_depth.csv and splash_depth.png.

    /usr/bin/python3 scripts/study_splash_depth.py [--scenes A,B,C] [--depths 20,20,28] [--threads 2]
"""
import argparse
import csv
import os
import re
import sys

import numpy as np

import study_splash

here = study_splash.here
out = os.path.join(here, "output", "study_splash_depth")
pressure_phases = ("pressure_setup", "pressure_solve")


def key(text, name):
    return float(re.search(rf"^{name} = (\S+)", text, re.M).group(1))


def pool(scene, depth, threads):
    """Uniform and tall runs of one scene: the figures of one row of the study."""
    base = open(scene).read()
    nx, ny, nz = (int(key(base, f"cells_{a}")) for a in "xyz")
    h = key(base, "length_x") / nx
    water = key(base, "pool_depth")
    uniform = study_splash.run(0, threads, base, 0, out_dir=out)
    tall = study_splash.run(depth, threads, base, 0, out_dir=out)
    amplitude = np.max(np.abs(uniform["eta"] - water))
    error = np.max(np.abs(tall["eta"] - uniform["eta"])) / amplitude
    t_u = uniform["seconds_per_step"]
    p_u = sum(uniform["phases"].get(p, 0.0) for p in pressure_phases)
    rows = min(ny, tall["unknowns"] / (nx * nz) + (ny - water / h))
    ideal = t_u / ((t_u - p_u) * rows / ny + p_u * tall["unknowns"] / uniform["unknowns"])
    p_t = sum(tall["phases"].get(p, 0.0) for p in pressure_phases)
    return {"scene": os.path.basename(scene), "pool_depth": water, "optical_depth": depth,
            "unknowns_ratio": uniform["unknowns"] / tall["unknowns"], "time_ratio": t_u / tall["seconds_per_step"],
            "surface_error": error, "ideal_time_ratio": ideal, "rows_kept": rows / ny,
            "uniform_seconds_per_step": t_u, "uniform_pressure": p_u, "tall_seconds_per_step": tall["seconds_per_step"],
            "tall_pressure": p_t}


def main():
    ap = argparse.ArgumentParser()
    scenes = ",".join(os.path.join(here, "scenes", f"water_splash_{s}.toml") for s in ("deep", "deeper", "deepest"))
    ap.add_argument("--scenes", default=scenes)
    ap.add_argument("--depths", default="20,20,28", help="the optical depth D of each scene's tall run")
    ap.add_argument("--threads", type=int, default=2)
    args = ap.parse_args()
    scene_list, depths = args.scenes.split(","), [int(d) for d in args.depths.split(",")]
    if len(depths) != len(scene_list) or min(depths) < 1:
        sys.exit("--depths needs one optical depth of at least 1 per scene of --scenes")
    os.makedirs(out, exist_ok=True)
    rows = []
    for scene, depth in zip(scene_list, depths):
        r = pool(scene, depth, args.threads)
        rows.append(r)
        print(f"{r['scene']} ({r['pool_depth']:g} m), D = {depth}: unknowns x{r['unknowns_ratio']:.2f} fewer, "
              f"time per step x{r['time_ratio']:.2f} less ({r['uniform_seconds_per_step']:.3f} -> "
              f"{r['tall_seconds_per_step']:.3f} s; pressure {r['uniform_pressure']:.3f} -> {r['tall_pressure']:.3f} s), "
              f"surface error {100 * r['surface_error']:.2f} %; ideal x{r['ideal_time_ratio']:.2f} "
              f"({100 * r['rows_kept']:.0f} % of the rows kept)", flush=True)
    with open(os.path.join(out, "splash_depth.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.ticker
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    x = [r["pool_depth"] for r in rows]
    ax.plot(x, [r["unknowns_ratio"] for r in rows], "s-", color="C2", label="fewer pressure unknowns")
    ax.plot(x, [r["time_ratio"] for r in rows], "o-", color="C0", label="less time per step, measured")
    ax.plot(x, [r["ideal_time_ratio"] for r in rows], "o--", color="C1", label="less time per step, ideal")
    for r in rows:
        ax.annotate(f"D = {r['optical_depth']}, {100 * r['surface_error']:.1f} %", (r["pool_depth"], r["time_ratio"]),
                    textcoords="offset points", xytext=(6, -12), fontsize=8)
    for target in (3, 4):
        ax.axhline(target, color="grey", lw=0.8, ls=":")
    ax.set_yscale("log")
    ax.set_yticks([1, 1.5, 2, 3, 4, 6, 8, 12, 16, 24])
    ax.yaxis.set_major_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
    ax.yaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax.set_xlabel("pool depth [m]")
    ax.set_ylabel("uniform / tall cells")
    ax.set_title("Splash: tall cells' gain against the water's depth")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "splash_depth.png"), dpi=120)
    print("wrote", os.path.join(out, "splash_depth.csv"), "and splash_depth.png")


if __name__ == "__main__":
    main()
