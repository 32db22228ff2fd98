#!/usr/bin/env python3
"""Chart the rotating drum's regime map over the Froude number from a study CSV
(`amphora study scenes/dem_drum.toml --set dem.froude ...`): the classified regime with
Mellmann's (2001) bands behind it, and the metrics it is decided from.

usage: plot_drum_regimes.py STUDY.csv OUT.png
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

NAMES = ["rolling", "cascading", "cataracting", "centrifuging"]
# Mellmann (2001), Fig. 4 (typical Froude ranges; they overlap and move with fill and friction)
BANDS = [(1e-4, 1e-2), (1e-3, 1e-1), (1e-1, 1.0), (1.0, 10.0)]


def main() -> int:
    rows = list(csv.DictReader(open(sys.argv[1])))
    fr = [float(r["froude"]) for r in rows]
    regime = [int(float(r["regime"])) for r in rows]
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
    for k, (lo, hi) in enumerate(BANDS):
        ax1.fill_between([lo, hi], k - 0.3, k + 0.3, color="0.85", zorder=0)
    ax1.semilogx(fr, regime, "o", ms=9, zorder=2, label="amphora (classified)")
    ax1.set_yticks(range(4))
    ax1.set_yticklabels(NAMES)
    ax1.set_title("rotating drum: regime against Froude number (grey: Mellmann 2001)")
    ax1.grid(True, which="both", alpha=0.3)
    ax1.legend(loc="upper left", fontsize=8)
    for key, label in (("upper_fraction", "riding the wall, upper half"),
                       ("airborne_fraction", "in flight above the bed"),
                       ("surface_deviation", "surface S-bending [d]")):
        ax2.semilogx(fr, [float(r[key]) for r in rows], "o-", label=label)
    ax2.set_xlabel("Froude number  omega^2 R / g")
    ax2.set_ylabel("time-averaged metric")
    ax2.grid(True, which="both", alpha=0.3)
    ax2.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=120)
    for f, g in zip(fr, regime):
        print(f"Froude {f:g}: {NAMES[g]}")
    print(f"wrote {sys.argv[2]}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
