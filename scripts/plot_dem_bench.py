#!/usr/bin/env python3
"""Chart DEM throughput (particle-steps/s) against particle count for amphora and LIGGGHTS,
per thread/rank configuration, from scripts/bench_dem.sh's CSV; print the ratios.

usage: plot_dem_bench.py dem.csv dem.png
"""
import csv
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main() -> int:
    rows = list(csv.DictReader(open(sys.argv[1])))
    series = defaultdict(list)
    rate = {}
    for r in rows:
        key = (r["code"], int(r["threads"]), int(r["ranks"]))
        n, v = int(r["particles"]), float(r["particle_steps_per_s"])
        series[key].append((n, v))
        rate[key + (n,)] = v
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for (code, threads, ranks), pts in sorted(series.items()):
        pts.sort()
        style = "o-" if code == "amphora" else "s--"
        ax.loglog([p[0] for p in pts], [p[1] for p in pts], style,
                  label=f"{code}, {threads} thread(s) x {ranks} rank(s)")
    ax.set_xlabel("particles (dense bed)")
    ax.set_ylabel("particle-steps per second")
    ax.set_title("DEM throughput, Hertz-Mindlin with history (higher is better)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=120)
    for n in sorted({int(r["particles"]) for r in rows}):
        lig1 = rate.get(("liggghts", 1, 1, n))
        lig2 = rate.get(("liggghts", 1, 2, n))
        for key, lig in (((("amphora", 1, 1), lig1)), (("amphora", 2, 1), lig2), (("amphora", 1, 2), lig2)):
            a = rate.get(key + (n,))
            if a and lig:
                cores = key[1] * key[2]
                print(f"n={n}: amphora {key[1]} thread(s) x {key[2]} rank(s) {a:.3e} vs "
                      f"LIGGGHTS {cores} core(s) {lig:.3e}: ratio {a / lig:.2f}")
    print(f"wrote {sys.argv[2]}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
