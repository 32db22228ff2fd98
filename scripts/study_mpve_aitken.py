#!/usr/bin/env python3
"""MP-VE: how many Aitken sub-iterations the traditional partitioned scheme needs
to stay stable as the solid gets lighter (rho_bar / rho = 800 .. 0.001, fluid viscosity 0.02,
dy = 1/40 by default), and what a step then costs against AMP, which needs none. Each run goes
from the exact traveling wave to a fixed time through `amphora run` (scene scenes/mpve_tp.toml
with scheme = tp_aitken or amp), single thread; sub-iterations are the mean of the
'subiterations' diagnostic, the cost is the run's stepping time per step as amphora reports it
(set-up excluded; one run each on this machine: a study, not a benchmark - perf/fsi.cpp
measures the step with repetitions).

Writes output/study_mpve_aitken/mpve_aitken.csv and mpve_aitken.png.

    /usr/bin/python3 scripts/study_mpve_aitken.py [--cells 40] [--end-time 0.3]
"""
import argparse
import csv
import os
import re

from scene_variant import here, run_variant

out = os.path.join(here, "output", "study_mpve_aitken")
ratios = [800.0, 100.0, 10.0, 1.0, 0.1, 0.01, 0.001]


def run(scheme, ratio, cells, end_time):
    d = os.path.join(out, f"{scheme}_r{ratio:g}_n{cells}")
    r = run_variant("mpve_tp.toml", d, {"scheme": f'"{scheme}"', "rho_bar": ratio, "cells": cells, "end_time": end_time})
    m = re.search(r"in ([0-9.e+-]+) s stepping", r["stdout"])
    seconds = float(m.group(1)) if m else float("nan")
    row = {"scheme": scheme, "rho_bar_over_rho": ratio, "cells": cells, "stable": r["stable"]}
    rows = list(csv.DictReader(open(os.path.join(d, "diagnostics.csv"))))
    steps = int(rows[-1]["step"]) if r["stable"] else r["blowup_step"]
    its = [float(x["subiterations"]) for x in rows[1:]] or [1.0]
    row.update(steps=steps, seconds_per_step=seconds / max(steps, 1), mean_subiterations=sum(its) / len(its),
               max_subiterations=max(its), vbar_error=float(rows[-1]["vbar_error"]) if r["stable"] else "")
    return row


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cells", type=int, default=40)
    ap.add_argument("--end-time", type=float, default=0.3)
    args = ap.parse_args()
    os.makedirs(out, exist_ok=True)
    rows = []
    for ratio in ratios:
        for scheme in ("tp_aitken", "amp"):
            r = run(scheme, ratio, args.cells, args.end_time)
            rows.append(r)
            print(f"{scheme:9s} rho_bar/rho {ratio:6g}: {'stable' if r['stable'] else 'UNSTABLE'}, "
                  f"{r['mean_subiterations']:.1f} sub-iterations/step (max {r['max_subiterations']:.0f}), "
                  f"{1e3 * r['seconds_per_step']:.2f} ms/step, vbar error {r['vbar_error']}", flush=True)
    keys = ["scheme", "rho_bar_over_rho", "cells", "stable", "steps", "mean_subiterations", "max_subiterations",
            "seconds_per_step", "vbar_error"]
    with open(os.path.join(out, "mpve_aitken.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        for r in rows:
            w.writerow(r)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    tpa = [r for r in rows if r["scheme"] == "tp_aitken"]
    amp = {r["rho_bar_over_rho"]: r for r in rows if r["scheme"] == "amp"}
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.2))
    a.loglog([r["rho_bar_over_rho"] for r in tpa], [r["mean_subiterations"] for r in tpa], "o-", label="TP-Aitken")
    a.loglog(ratios, [1] * len(ratios), "s--", label="AMP (none)")
    a.set_xlabel("rho_bar / rho")
    a.set_ylabel("sub-iterations per step")
    a.invert_xaxis()
    a.legend()
    a.set_title(f"MP-VE, dy = 1/{args.cells}")
    b.loglog([r["rho_bar_over_rho"] for r in tpa],
             [r["seconds_per_step"] / amp[r["rho_bar_over_rho"]]["seconds_per_step"] for r in tpa], "o-")
    b.set_xlabel("rho_bar / rho")
    b.set_ylabel("TP-Aitken / AMP stepping time per step")
    b.invert_xaxis()
    b.set_title("cost per step against AMP (one run each)")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "mpve_aitken.png"), dpi=120)
    print("wrote", os.path.join(out, "mpve_aitken.png"))


if __name__ == "__main__":
    main()
