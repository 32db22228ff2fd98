#!/usr/bin/env python3
"""Chart a study CSV (written by `amphora study`) as a PNG: error against wall time, and error
against the varied parameter with the observed order of each refinement.

usage: plot_study.py STUDY.csv OUT.png [--title TEXT]
"""
import argparse
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("csv")
    ap.add_argument("png")
    ap.add_argument("--title", default=None)
    args = ap.parse_args()

    with open(args.csv, newline="") as f:
        rows = list(csv.DictReader(f))
    if len(rows) < 2:
        print(f"{args.csv}: need at least two rows to chart", file=sys.stderr)
        return 2
    param = rows[0]["parameter"]
    value = [float(r["value"]) for r in rows]
    error = [float(r["error"]) for r in rows]
    wall = [max(float(r["wall_time"]), 1e-9) for r in rows]
    rate = [float(r["rate"]) for r in rows]
    unit = rows[0]["unit"]

    orders = [math.log(error[i - 1] / error[i]) / math.log(value[i] / value[i - 1])
              for i in range(1, len(rows))]
    for i, p in enumerate(orders, start=1):
        print(f"{param} {value[i - 1]:g} -> {value[i]:g}: observed order {p:.3f}")

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.5))
    ax1.loglog(wall, error, "o-")
    for w, e, v, r in zip(wall, error, value, rate):
        ax1.annotate(f"{v:g}\n{r:.2e} {unit}/s", (w, e), fontsize=7,
                     textcoords="offset points", xytext=(5, 5))
    ax1.set_xlabel("wall time of the stepping [s]")
    ax1.set_ylabel("max-norm error")
    ax1.set_title("error against wall time")
    ax1.grid(True, which="both", alpha=0.3)

    ax2.loglog(value, error, "o-", label="measured")
    ref = [error[0] * (value[0] / v) ** 2 for v in value]
    ax2.loglog(value, ref, "k--", alpha=0.5, label="order 2")
    for i, p in enumerate(orders, start=1):
        ax2.annotate(f"{p:.2f}", (math.sqrt(value[i - 1] * value[i]),
                                  math.sqrt(error[i - 1] * error[i])), fontsize=8)
    ax2.set_xlabel(param)
    ax2.set_ylabel("max-norm error")
    ax2.set_title("convergence (observed orders annotated)")
    ax2.legend()
    ax2.grid(True, which="both", alpha=0.3)

    fig.suptitle(args.title or f"study over {param}")
    fig.tight_layout()
    fig.savefig(args.png, dpi=120)
    print(f"wrote {args.png}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
