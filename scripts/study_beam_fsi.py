#!/usr/bin/env python3
"""The beam studies (scenes/beam_channel_amp.toml, a beam over an inviscid channel):

(a) stability map: the traditional partitioned scheme (TP) and AMP over grid points
    n = 20..320 and beam-to-fluid density ratios rho_h / rho = 100 .. 0.01, each run for a fixed
    time from the exact traveling wave; "unstable" = the run stopped because max |eta| grew past
    10x the wave's amplitude (amphora's exit 3 with the reason);
(b) TP with Aitken sub-iterations: mean sub-iterations per step and wall time per step against
    AMP's, as rho_h / rho falls (n = 80).

Writes output/study_beam_fsi/beam_fsi_stability.csv, beam_fsi_cost.csv and beam_fsi_study.png.

    /usr/bin/python3 scripts/study_beam_fsi.py [--end-time 1.0]
"""
import argparse
import csv
import os
import re

from scene_variant import here, run_variant

out = os.path.join(here, "output", "study_beam_fsi")
ratios = [100.0, 10.0, 1.0, 0.1, 0.01]
grids = [20, 40, 80, 160, 320]


def run(scheme, ratio, n, end_time):
    d = os.path.join(out, f"{scheme}_r{ratio:g}_n{n}")
    r = run_variant("beam_channel_amp.toml", d, {"scheme": f'"{scheme}"', "rho_h": ratio, "points": n,
                                                 "fluid_rows": n // 2, "end_time": end_time})
    row = {"scheme": scheme, "rho_h_over_rho": ratio, "points": n, "stable": r["stable"]}
    if not r["stable"]:
        row.update(blowup_step=r["blowup_step"], blowup_time=r["blowup_time"])
        return row
    done = re.search(r"\[done\] (\d+) steps .* in ([0-9.e+-]+) s stepping", r["stdout"])
    steps, seconds = int(done.group(1)), float(done.group(2))
    rows = list(csv.DictReader(open(os.path.join(d, "diagnostics.csv"))))
    sub = [float(x["subiterations"]) for x in rows[1:]]
    row.update(steps=steps, seconds_per_step=seconds / steps, eta_error=float(rows[-1]["eta_error"]),
               mean_subiterations=sum(sub) / len(sub))
    return row


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--end-time", type=float, default=1.0)
    args = ap.parse_args()
    os.makedirs(out, exist_ok=True)
    stability = []
    for ratio in ratios:
        for n in grids:
            for scheme in ("tp", "amp"):
                r = run(scheme, ratio, n, args.end_time)
                stability.append(r)
                print(f"{scheme:4s} rho_h/rho {ratio:7g} n {n:4d}: "
                      + ("stable" if r["stable"] else f"UNSTABLE at step {r['blowup_step']}"), flush=True)
    cost = []
    for ratio in ratios:
        for scheme in ("tp_aitken", "amp"):
            r = run(scheme, ratio, 80, args.end_time)
            cost.append(r)
            print(f"{scheme:9s} rho_h/rho {ratio:7g}: {r['mean_subiterations']:.2f} sub-iterations/step, "
                  f"{1e3 * r['seconds_per_step']:.3f} ms/step, eta error {r['eta_error']:.3e}", flush=True)
    keys = ["scheme", "rho_h_over_rho", "points", "stable", "blowup_step", "blowup_time", "steps",
            "seconds_per_step", "eta_error", "mean_subiterations"]
    for name, rows in (("beam_fsi_stability.csv", stability), ("beam_fsi_cost.csv", cost)):
        with open(os.path.join(out, name), "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=keys)
            w.writeheader()
            for r in rows:
                w.writerow(r)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.2))
    for r in stability:
        dx = -0.12 if r["scheme"] == "tp" else 0.12
        y = ratios.index(r["rho_h_over_rho"])
        x = grids.index(r["points"]) + dx
        a.scatter(x, y, marker="o" if r["stable"] else "x", s=60,
                  color=("tab:blue" if r["scheme"] == "tp" else "tab:green") if r["stable"] else "tab:red")
    a.set_xticks(range(len(grids)), [f"1/{n}" for n in grids])
    a.set_yticks(range(len(ratios)), [f"{r:g}" for r in ratios])
    a.set_xlabel("grid spacing h (left marker TP, right AMP)")
    a.set_ylabel("rho_h / rho")
    a.set_title("stable (o) / unstable (x) after t = %g" % args.end_time)
    tpa = [r for r in cost if r["scheme"] == "tp_aitken"]
    amp = [r for r in cost if r["scheme"] == "amp"]
    b.semilogx([r["rho_h_over_rho"] for r in tpa], [r["mean_subiterations"] for r in tpa], "o-",
               label="TP-Aitken sub-iterations / step")
    b.semilogx([r["rho_h_over_rho"] for r in tpa],
               [t["seconds_per_step"] / m["seconds_per_step"] for t, m in zip(tpa, amp)], "s--",
               label="TP-Aitken time / AMP time per step")
    b.invert_xaxis()
    b.set_xlabel("rho_h / rho")
    b.set_title("cost of stabilising TP by sub-iteration (n = 80)")
    b.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(out, "beam_fsi_study.png"), dpi=120)
    print("wrote", os.path.join(out, "beam_fsi_study.png"))


if __name__ == "__main__":
    main()
