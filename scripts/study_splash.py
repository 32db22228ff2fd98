#!/usr/bin/env python3
"""The tall-cell study: the deep-water splash of scenes/water_splash_deep.toml (or
another splash scene, --scene) with uniform cells everywhere (optical_depth = 0) and with tall
cells below several optical depths. For each run:
pressure unknowns (mean over the run), wall time per step, and the surface-height error against
the uniform run at the end (max and root mean square over the columns of |eta - eta_uniform|,
relative to the largest surface displacement of the uniform run), and where the time per step goes
(the run's [timing] lines: advection, pressure setup and solve, ...). One more uniform run, at the
CFL number times --noise-cfl (default 0.95; 0 skips it), measures how far the uniform surface itself
moves under a change that is no error: its substeps differ, and the central jet that rises out of the
crater leaves at a slightly different time. With --reference-refine N (N > 1) one more uniform run
on a grid N times finer along each axis (its surface averaged over each coarse column's N x N
columns) gives every run's error against a better solution too: whether the tall cells' departure
from the uniform run matters beside the uniform run's own discretisation error. The surfaces are
compared every --every steps as well (default 5; the fields written then), not only at the end,
so an error that comes and goes (the jet) is told from one that grows. Writes
output/study_splash/splash_study.csv and splash_study.png (error against time per step, and the
error over the run), and splash_error_history.csv (every run's error at every compared step).

    /usr/bin/python3 scripts/study_splash.py [--depths 0,24,16,8] [--threads 2] [--scene FILE]
                                             [--noise-cfl 0.95] [--reference-refine 2] [--every 5]
"""
import argparse
import csv
import os
import re
import subprocess
import sys

import numpy as np

here = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
amphora = os.path.join(here, "build", "release", "apps", "amphora")
out = os.path.join(here, "output", "study_splash")


def read_dataset(path, name):
    tmp = os.path.join(os.path.dirname(path), "dataset.bin")
    subprocess.run(["h5dump", "-d", name, "-b", "LE", "-o", tmp, path], check=True, stdout=subprocess.DEVNULL)
    return np.fromfile(tmp, dtype="<f8")


def surface(fields):
    """eta(x, z): the highest zero crossing of phi in each column."""
    x, y, z = (read_dataset(fields, f"/water/{c}") for c in "xyz")
    phi = read_dataset(fields, "/water/phi").reshape(len(z), len(y), len(x))
    eta = np.zeros((len(z), len(x)))
    for j in range(len(y) - 1):
        p0, p1 = phi[:, j, :], phi[:, j + 1, :]
        cross = (p0 < 0) & (p1 >= 0)
        eta = np.where(cross, y[j] + (y[j + 1] - y[j]) * p0 / np.where(cross, p0 - p1, 1.0), eta)
    return eta


def run(depth, threads, base, every, cfl_factor=1.0, refine=1, out_dir=out):
    """One run of the splash scene text `base` at optical depth `depth`, its scene and fields in
    out_dir."""
    name = f"depth_{depth}" if cfl_factor == 1.0 else f"depth_{depth}_cfl_x{cfl_factor:g}"
    if refine != 1:
        name += f"_refined_x{refine}"
    d = os.path.join(out_dir, name)
    scene = os.path.join(out_dir, f"splash_{name}.toml")
    text = re.sub(r'output_dir = ".*"', f'output_dir = "{d}"', base)
    text = re.sub(r"optical_depth = \d+", f"optical_depth = {depth}", text)
    for axis in "xyz":
        text = re.sub(rf"^cells_{axis} = (\d+)", lambda m: f"cells_{axis} = {int(m.group(1)) * refine}", text, flags=re.M)
    if cfl_factor != 1.0:
        cfl = float(re.search(r"^cfl = (\S+)", text, re.M).group(1))
        text = re.sub(r"^cfl = \S+", f"cfl = {cfl * cfl_factor:g}", text, flags=re.M)
    text = re.sub(r"output_every = \d+", f"output_every = {every}", text)
    open(scene, "w").write(text)
    if os.path.isdir(d):  # fields of an earlier run with other output steps would be read as this run's
        for f in os.listdir(d):
            if re.fullmatch(r"fields_\d+\.h5", f):
                os.remove(os.path.join(d, f))
    env = dict(os.environ, OMP_NUM_THREADS=str(threads), OMP_PROC_BIND="spread", OMP_PLACES="threads")
    log = subprocess.run([amphora, "run", scene], check=True, capture_output=True, text=True, env=env).stdout
    m = re.search(r"\[done\] (\d+) steps to t=\S+ in (\S+) s stepping", log)
    steps, seconds = int(m.group(1)), float(m.group(2))
    # the module's own split of the stepping time ([timing] lines), per step
    phases = {p: float(t) / steps for p, t in re.findall(r"\[timing\] (\S+) (\S+) s", log)}
    rows = list(csv.DictReader(open(os.path.join(d, "diagnostics.csv"))))
    unknowns = np.mean([float(r["pressure_unknowns"]) for r in rows[1:]])
    # the surface at every written step (fields_<step>.h5), the last one the run's end
    etas = {}
    for f in sorted(f for f in os.listdir(d) if re.fullmatch(r"fields_\d+\.h5", f)):
        eta = surface(os.path.join(d, f))
        if refine != 1:  # the mean over each coarse column's refine x refine fine columns
            eta = eta.reshape(eta.shape[0] // refine, refine, eta.shape[1] // refine, refine).mean(axis=(1, 3))
        etas[int(f[7:-3])] = eta
    return {"depth": depth, "cfl_factor": cfl_factor, "unknowns": unknowns, "seconds_per_step": seconds / steps, "phases": phases,
            "eta": etas[max(etas)], "etas": etas}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--depths", default="0,24,16,8")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--scene", default=os.path.join(here, "scenes", "water_splash_deep.toml"))
    ap.add_argument("--noise-cfl", type=float, default=0.95)
    ap.add_argument("--reference-refine", type=int, default=0)
    ap.add_argument("--every", type=int, default=5, help="compare the surfaces every this many steps too")
    args = ap.parse_args()
    if args.every < 1:
        sys.exit("--every must be at least 1")
    os.makedirs(out, exist_ok=True)
    base = open(args.scene).read()
    pool = float(re.search(r"pool_depth = (\S+)", base).group(1))
    depths = [int(v) for v in args.depths.split(",")]
    if depths[0] != 0:
        sys.exit("the first depth must be 0 (the uniform reference)")
    runs = []
    for depth in depths:
        r = run(depth, args.threads, base, args.every)
        runs.append(r)
        print(f"optical depth {depth:3d}: {r['unknowns']:9.0f} pressure unknowns, {r['seconds_per_step']:.3f} s/step",
              "(" + ", ".join(f"{p} {t:.3f}" for p, t in r["phases"].items()) + ")", flush=True)
    if args.noise_cfl > 0:
        runs.append(run(0, args.threads, base, args.every, args.noise_cfl))
    ref = runs[0]
    amplitude = np.max(np.abs(ref["eta"] - pool))
    fine = None
    if args.reference_refine > 1:
        fine = run(0, args.threads, base, args.every, refine=args.reference_refine)
        print(f"uniform, {args.reference_refine}x finer: {fine['unknowns']:9.0f} pressure unknowns, "
              f"{fine['seconds_per_step']:.3f} s/step", flush=True)
    with open(os.path.join(out, "splash_study.csv"), "w", newline="") as f:
        w = csv.writer(f)
        phase_names = list(ref["phases"])
        w.writerow(["optical_depth", "pressure_unknowns", "unknowns_ratio", "seconds_per_step", "time_ratio",
                    "surface_error", "surface_error_rms", "cfl_factor"] + [f"seconds_per_step_{p}" for p in phase_names] +
                   ["surface_error_vs_finer", "surface_error_vs_finer_rms"])
        for r in runs:
            r["error"] = np.max(np.abs(r["eta"] - ref["eta"])) / amplitude
            r["error_rms"] = np.sqrt(np.mean((r["eta"] - ref["eta"]) ** 2)) / amplitude
            if fine:
                r["error_fine"] = np.max(np.abs(r["eta"] - fine["eta"])) / amplitude
                r["error_fine_rms"] = np.sqrt(np.mean((r["eta"] - fine["eta"]) ** 2)) / amplitude
            w.writerow([r["depth"], f"{r['unknowns']:.0f}", f"{ref['unknowns'] / r['unknowns']:.3f}",
                        f"{r['seconds_per_step']:.4f}", f"{ref['seconds_per_step'] / r['seconds_per_step']:.3f}",
                        f"{r['error']:.4e}", f"{r['error_rms']:.4e}", f"{r['cfl_factor']:g}"] +
                       [f"{r['phases'].get(p, 0.0):.4f}" for p in phase_names] +
                       ([f"{r['error_fine']:.4e}", f"{r['error_fine_rms']:.4e}"] if fine else ["", ""]))
            label = f"optical depth {r['depth']:3d}" + ("" if r["cfl_factor"] == 1.0 else f", CFL x{r['cfl_factor']:g}")
            print(f"{label}: unknowns x{ref['unknowns'] / r['unknowns']:.2f} fewer, "
                  f"time per step x{ref['seconds_per_step'] / r['seconds_per_step']:.2f} less, "
                  f"surface error {100 * r['error']:.2f} % (max), {100 * r['error_rms']:.2f} % (rms) "
                  f"of the splash amplitude {amplitude:.4f} m" +
                  (f"; against the {args.reference_refine}x finer uniform run {100 * r['error_fine']:.2f} % (max), "
                   f"{100 * r['error_fine_rms']:.2f} % (rms)" if fine else ""))
    # the error at every compared step (the initial state, the same in every run, left out)
    dt = float(re.search(r"^dt = (\S+)", base, re.M).group(1))
    steps = [n for n in sorted(ref["etas"]) if n > 0]
    with open(os.path.join(out, "splash_error_history.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["optical_depth", "cfl_factor", "step", "time", "surface_error", "surface_error_rms"] +
                   (["surface_error_vs_finer", "surface_error_vs_finer_rms"] if fine else []))
        for r in runs:
            r["history"] = []
            for n in steps:
                diff = r["etas"][n] - ref["etas"][n]
                e, e_rms = np.max(np.abs(diff)) / amplitude, np.sqrt(np.mean(diff ** 2)) / amplitude
                r["history"].append((n * dt, e))
                row = [r["depth"], f"{r['cfl_factor']:g}", n, f"{n * dt:g}", f"{e:.4e}", f"{e_rms:.4e}"]
                if fine:
                    diff = r["etas"][n] - fine["etas"][n]
                    row += [f"{np.max(np.abs(diff)) / amplitude:.4e}", f"{np.sqrt(np.mean(diff ** 2)) / amplitude:.4e}"]
                w.writerow(row)
    print("surface error vs uniform, max over the columns [% of amplitude], at t =",
          " ".join(f"{n * dt:g}" for n in steps))
    for r in runs[1:]:
        label = f"optical depth {r['depth']:3d}" + ("" if r["cfl_factor"] == 1.0 else f", CFL x{r['cfl_factor']:g}")
        print(f"  {label}:", " ".join(f"{100 * e:.2f}" for _, e in r["history"]))
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    # against the uniform run; with a finer run, against it too (a second panel)
    panels = [("error", "surface error vs uniform, max [% of amplitude]")]
    if fine:
        panels.append(("error_fine", f"surface error vs {args.reference_refine}x finer uniform, max [% of amplitude]"))
    fig, axes = plt.subplots(1, len(panels) + 1, figsize=(6.4 * (len(panels) + 1), 4.4), squeeze=False)
    # labels right and left of their points in turn, in order of time per step, so neighbours do not overlap
    order = sorted(range(len(runs)), key=lambda m: runs[m]["seconds_per_step"])
    for ax, (key, ylabel) in zip(axes[0], panels):
        for n, r in enumerate(runs[m] for m in order):
            ax.plot(r["seconds_per_step"], 100 * r[key], "o" if r["cfl_factor"] == 1.0 else "s",
                    color="C0" if r["depth"] else "C3")
            label = (f"D = {r['depth']}" if r["depth"] else "uniform") + \
                ("" if r["cfl_factor"] == 1.0 else f", CFL x{r['cfl_factor']:g}")
            ax.annotate(f"{label}\n{r['unknowns'] / 1e3:.0f}k unknowns", (r["seconds_per_step"], 100 * r[key]),
                        textcoords="offset points", xytext=(-7 if n % 2 else 7, -9), fontsize=8,
                        ha="right" if n % 2 else "left")
        if key == "error":
            ax.axhline(5, color="grey", lw=0.8, ls="--")
        ax.margins(0.2)
        ax.set_xlabel("wall time per step [s]")
        ax.set_ylabel(ylabel)
    axes[0][0].set_title("Splash: tall cells below optical depth D (pressure on tall cells)")
    ax = axes[0][len(panels)]  # the error over the run
    for n, r in enumerate(runs[1:]):
        t, e = zip(*r["history"])
        ax.plot(t, 100 * np.array(e), "o-" if r["cfl_factor"] == 1.0 else "s--", color=f"C{n}",
                label=(f"D = {r['depth']}" if r["depth"] else "uniform") +
                ("" if r["cfl_factor"] == 1.0 else f", CFL x{r['cfl_factor']:g}"))
    ax.axhline(5, color="grey", lw=0.8, ls="--")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("surface error vs uniform, max [% of amplitude]")
    ax.set_title("over the run")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "splash_study.png"), dpi=120)
    print("wrote", os.path.join(out, "splash_study.csv"), "and splash_study.png")


if __name__ == "__main__":
    main()
