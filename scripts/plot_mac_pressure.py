#!/usr/bin/env python3
"""Charts and ratios of scripts/bench_mac_pressure.sh: solve time (setup included) per back end
and grid, uniform and tall-cell, 1 and 2 threads, PFMG on 2 ranks; and the ratios against
PFMG-CG (2 ranks) and MIC(0)-CG from the same run. Usage: plot_mac_pressure.py output/bench"""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

out = sys.argv[1] if len(sys.argv) > 1 else "output/bench"


def load(name):
    path = os.path.join(out, name)
    if not os.path.exists(path):
        return {}
    res = {}
    for b in json.load(open(path))["benchmarks"]:
        if b.get("run_type") == "aggregate" and b.get("aggregate_name") != "median":
            continue
        parts = b["run_name"].split("/")
        key = (parts[0], int(parts[1]), int(parts[2]))
        res[key] = b
    return res


def seconds(b):
    unit = {"ms": 1e-3, "s": 1.0, "us": 1e-6, "ns": 1e-9}[b["time_unit"]]
    return b["real_time"] * unit


runs = {}
for t in (1, 2):
    runs[f"{t}t"] = {**load(f"mac_pressure_uniform_{t}t1r.json"), **load(f"mac_pressure_tall_{t}t1r.json")}
runs["pfmg2r"] = load("mac_pressure_pfmg_1t2r.json")
runs["mg2r"] = load("mac_pressure_mg_1t2r.json")
runs["tall2r"] = load("mac_pressure_tall_1t2r.json")
names = {("Uniform", 0): "multigrid-CG", ("Uniform", 1): "PFMG-CG", ("Uniform", 2): "MIC(0)-CG",
         ("TallCells", 0): "tall multigrid-CG", ("TallCells", 1): "tall BoomerAMG-CG", ("TallCells", 2): "tall IC(0)-CG"}
sizes = sorted({k[2] for r in runs.values() for k in r})
fig, axes = plt.subplots(1, 2, figsize=(11, 4.4), sharey=True)
for ax, kind in zip(axes, ("Uniform", "TallCells")):
    for (k, backend), label in names.items():
        if k != kind:
            continue
        for t, style in (("1t", "--"), ("2t", "-")):
            xs = [n for n in sizes if (kind, backend, n) in runs[t]]
            if xs:
                ax.plot(xs, [seconds(runs[t][(kind, backend, n)]) for n in xs], style, marker="o",
                        color=f"C{backend}", label=f"{label}, {t[0]} thread(s)")
    if kind == "Uniform":
        xs = [n for n in sizes if ("Uniform", 1, n) in runs["pfmg2r"]]
        ax.plot(xs, [seconds(runs["pfmg2r"][("Uniform", 1, n)]) for n in xs], ":", marker="s", color="C1",
                label="PFMG-CG, 2 ranks")
        xs = [n for n in sizes if ("Uniform", 0, n) in runs["mg2r"]]
        ax.plot(xs, [seconds(runs["mg2r"][("Uniform", 0, n)]) for n in xs], ":", marker="s", color="C0",
                label="multigrid-CG, 2 ranks")
    else:
        for backend in (0, 1):
            xs = [n for n in sizes if ("TallCells", backend, n) in runs["tall2r"]]
            ax.plot(xs, [seconds(runs["tall2r"][("TallCells", backend, n)]) for n in xs], ":", marker="s",
                    color=f"C{backend}", label=f"{names[('TallCells', backend)]}, 2 ranks")
    ax.set_xscale("log", base=2)
    ax.set_yscale("log")
    ax.set_xlabel("n (n^3 footprint)")
    ax.set_title("uniform 7-point, p = 0 on the box" if kind == "Uniform" else "tall cells, deep water, D = n/8")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
axes[0].set_ylabel("time to 1e-8, setup included [s]")
fig.tight_layout()
fig.savefig(os.path.join(out, "mac_pressure.png"), dpi=120)

lines = ["MAC pressure solves (relative residual 1e-8, setup included), medians of this run", ""]
for n in sizes:
    mg = runs["2t"].get(("Uniform", 0, n))
    pf = runs["pfmg2r"].get(("Uniform", 1, n))
    mic = runs["1t"].get(("Uniform", 2, n))
    if mg:
        s = f"{n}^3: multigrid-CG 2 threads {seconds(mg):.3f} s ({int(mg['iterations'])} its)"
        if pf:
            s += f"; PFMG-CG 2 ranks {seconds(pf):.3f} s ({int(pf['iterations'])} its) -> x{seconds(pf) / seconds(mg):.2f}"
        if mic:
            s += f"; MIC(0)-CG {seconds(mic):.3f} s ({int(mic['iterations'])} its) -> x{seconds(mic) / seconds(mg):.2f}"
        mg2 = runs["mg2r"].get(("Uniform", 0, n))
        if mg2:
            s += f"; multigrid-CG 2 ranks {seconds(mg2):.3f} s ({int(mg2['iterations'])} its)"
            if pf:
                s += f" -> x{seconds(pf) / seconds(mg2):.2f} PFMG 2 ranks"
        lines.append(s)
lines.append("")
for n in sizes:
    row = [f"{n}^3 tall cells:"]
    for b in (0, 1, 2):
        r = runs["2t"].get(("TallCells", b, n))
        if r:
            row.append(f"{names[('TallCells', b)]} {seconds(r):.3f} s ({int(r['iterations'])} its, "
                       f"{r['unknowns'] / 1e3:.0f}k unknowns = uniform / {r['reduction']:.2f})")
    for b in (0, 1):
        r = runs["tall2r"].get(("TallCells", b, n))
        if r:
            row.append(f"{names[('TallCells', b)]} 2 ranks {seconds(r):.3f} s ({int(r['iterations'])} its)")
    if len(row) > 1:
        lines.append(" ".join(row))
open(os.path.join(out, "mac_pressure_summary.txt"), "w").write("\n".join(lines) + "\n")
print("\n".join(lines))
