"""The Taylor-Green vortex at Re = 1600 (scenes/studies/tgv_re1600.toml) over degrees and
meshes, against the 512^3 spectral reference (../shared/reference/tgv_re1600/): E_k(t) and
-dE_k/dt against time, and the work-precision chart (error against core-hours, one point per
(k, cells)), the Lethe talk's Q1/Q2/Q3 comparison measured.

Errors: the largest relative error of E_k over the run, the relative error of the peak of
-dE_k/dt and of its time (where the run reaches t = 8.97). Core-hours: stepping wall time times
threads. A run ending before t_end = 20 is labelled with its end time.

  python3 scripts/study_tgv.py --runs 2:8,2:16,3:8 --end-time 2 --threads 2 --out tgv_study
"""
import argparse
import csv
import os
import re
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from scene_variant import here, run_variant  # noqa: E402

reference = os.path.join(here, "..", "shared", "reference", "tgv_re1600", "spectral_Re1600_512.dat")


def measure(k, cells, end_time, threads, out, preconditioner="multigrid", reuse=False,
            tau=None, grad_div=None):
    """Runs Q_k on cells^3 (or, with reuse, reads the log a finished run of the same
    end time, threads, preconditioner, tau and grad-div left) and returns its E_k and
    -dE_k/dt."""
    d = os.path.join(out, f"q{k}_{cells}")
    log = os.path.join(d, "run.log")
    key = f"end_time={end_time} threads={threads} preconditioner={preconditioner} tau={tau}"
    key += f" grad_div={grad_div}\n" if grad_div is not None else "\n"
    if reuse and os.path.exists(log) and open(log).readline() == key:
        stdout = open(log).read()
    else:
        values = {"degree": str(k), "cells": str(cells), "end_time": str(end_time),
                  "checkpoint_every": "0", "preconditioner": f'"{preconditioner}"'}
        if tau:
            values["tau"] = f'"{tau}"'
        if grad_div is not None:
            values["grad_div"] = str(grad_div)
        stdout = key + run_variant("studies/tgv_re1600.toml", d, values, threads)["stdout"]
        open(log, "w").write(stdout)
    m = re.search(r"\[done\] (\d+) steps to t=\S+ in ([0-9.e+-]+) s stepping", stdout)
    rows = list(csv.DictReader(open(os.path.join(d, "diagnostics.csv"))))
    t = np.array([float(r["time"]) for r in rows])
    e = np.array([float(r["kinetic_energy"]) for r in rows])
    # -dE/dt of a step belongs to its midpoint
    rate = np.array([float(r["dissipation_rate"]) for r in rows])[1:]
    return {"k": k, "cells": cells, "steps": int(m.group(1)), "seconds": float(m.group(2)),
            "threads": threads, "t": t, "e": e, "t_mid": 0.5 * (t[1:] + t[:-1]), "rate": rate}


def errors(run, ref):
    e_ref = np.interp(run["t"], ref[:, 0], ref[:, 1])
    out = {"ek_linf_rel": float(np.max(np.abs(run["e"] - e_ref) / e_ref))}
    if run["t"][-1] >= 9.5:  # the peak is resolved
        i = int(np.argmax(run["rate"]))
        peak, t_peak = 0.0128575, 8.97
        out["peak_rel"] = float(abs(run["rate"][i] - peak) / peak)
        out["peak_time_error"] = float(abs(run["t_mid"][i] - t_peak))
    return out


def chart(runs, ref, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 3, figsize=(15, 4.5))
    t_end = max(r["t"][-1] for r in runs)
    sel = ref[:, 0] <= t_end
    ax[0].plot(ref[sel, 0], ref[sel, 1], "k-", lw=2, label="spectral 512^3")
    ax[1].plot(ref[sel, 0], ref[sel, 2], "k-", lw=2, label="spectral 512^3")
    for r in runs:
        label = f"Q{r['k']} {r['cells']}^3"
        ax[0].plot(r["t"], r["e"], label=label)
        ax[1].plot(r["t_mid"], r["rate"], label=label)
        colour = f"C{r['k'] - 1}"
        ax[2].loglog(r["core_hours"], r["ek_linf_rel"], "o", color=colour)
        ax[2].annotate(label, (r["core_hours"], r["ek_linf_rel"]), fontsize=7)
        if "peak_rel" in r:
            ax[2].loglog(r["core_hours"], max(r["peak_rel"], 1e-4), "s", mfc="none",
                         color=colour)
    ax[0].set(xlabel="t", ylabel="E_k", title="kinetic energy")
    ax[1].set(xlabel="t", ylabel="-dE_k/dt", title="dissipation rate")
    ax[2].set(xlabel="core-hours (stepping)", ylabel="relative error",
              title=f"work-precision, t in [0, {t_end:g}]: o max E_k, [] peak -dE_k/dt")
    for a in ax[:2]:
        a.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "tgv_study.png"), dpi=120)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--runs", default="2:8,2:16", help="k:cells pairs, comma separated")
    p.add_argument("--end-time", type=float, default=20.0)
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--out", default="tgv_study")
    p.add_argument("--preconditioner", default="multigrid", choices=["multigrid", "jacobi"])
    p.add_argument("--tau", choices=["steady", "transient"],
                   help="[ins_fem] tau, the SUPG/PSPG parameter without or with (2 / dt)^2 "
                        "(default: the scene's)")
    p.add_argument("--grad-div", type=float,
                   help="[ins_fem] grad_div, the grad-div weight gamma (default: the scene's)")
    p.add_argument("--reuse", action="store_true",
                   help="read runs already in --out with the same settings instead of rerunning")
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    ref = np.loadtxt(reference)
    runs = []
    for pair in a.runs.split(","):
        k, cells = (int(v) for v in pair.split(":"))
        r = measure(k, cells, a.end_time, a.threads, a.out, a.preconditioner, a.reuse, a.tau,
                    a.grad_div)
        r["core_hours"] = r["seconds"] * r["threads"] / 3600.0
        r.update(errors(r, ref))
        runs.append(r)
        print(f"Q{k} {cells}^3 to t={r['t'][-1]:g}: {r['steps']} steps, {r['seconds']:.1f} s x "
              f"{r['threads']} threads = {r['core_hours']:.4f} core-hours; max rel E_k error "
              f"{r['ek_linf_rel']:.2e}" +
              (f"; peak -dE/dt error {r['peak_rel']:.2%} at dt_peak {r['peak_time_error']:.2f}"
               if "peak_rel" in r else " (peak not reached)"), flush=True)
    keys = ["k", "cells", "steps", "seconds", "threads", "core_hours", "ek_linf_rel", "peak_rel",
            "peak_time_error"]
    with open(os.path.join(a.out, "tgv_study.csv"), "w") as f:
        f.write(",".join(keys) + ",end_time\n")
        for r in runs:
            f.write(",".join(str(r.get(k, "")) for k in keys) + f",{r['t'][-1]}\n")
    chart(runs, ref, a.out)
    print(f"wrote {a.out}/tgv_study.csv and {a.out}/tgv_study.png")


if __name__ == "__main__":
    main()
