"""The squashed ball (scenes/solid_ball_squash.toml) side by side: the standard neo-Hookean
model (s_clamp = 0), invertible FEM with neo-Hookean and corotated stress (s_clamp = 0.25;
Irving, Teran & Fedkiw 2004), and invertible neo-Hookean with the per-node volume projection
(Irving, Schroeder & Fedkiw 2007). Charts min det F, the volume error, the energy (kinetic +
elastic) and the shape error against time; a run stopped as diverged ends with a cross.
Writes <out>/solid_squash.png and <out>/solid_squash.csv (one row per run).

  python3 scripts/study_solid_squash.py --cells 8 --threads 2 --out output/studies/solid_squash
"""
import argparse
import csv
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from scene_variant import run_variant  # noqa: E402

RUNS = [("standard neo-Hookean", {"model": '"neo_hookean"', "s_clamp": "0.0"}),
        ("invertible neo-Hookean", {"model": '"neo_hookean"', "s_clamp": "0.25"}),
        ("invertible corotated", {"model": '"corotated"', "s_clamp": "0.25"}),
        ("volume-preserving neo-Hookean",
         {"model": '"neo_hookean"', "s_clamp": "0.25", "volume_preserving": "true"})]
SERIES = [("min_det_F", "min det F"), ("volume_error", "volume error"),
          ("energy", "kinetic + elastic energy [J]"), ("shape_error", "shape error / radius")]


def measure(label, values, args):
    d = os.path.join(args.out, re.sub(r"\W+", "_", label))
    result = run_variant("solid_ball_squash.toml", d, dict(values, cells=str(args.cells)),
                         args.threads)
    rows = list(csv.DictReader(open(os.path.join(d, "diagnostics.csv"))))
    for r in rows:
        r["energy"] = float(r["kinetic_energy"]) + float(r["elastic_energy"])
    m = re.search(r"in ([0-9.e+-]+) s stepping", result["stdout"])
    return {"label": label, "rows": rows, "stable": result["stable"],
            "blowup_time": result.get("blowup_time", ""),
            "seconds": float(m.group(1)) if m else float("nan")}


def chart(runs, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(2, 2, figsize=(10, 7), sharex=True)
    for ax, (key, title) in zip(axes.flat, SERIES):
        for run in runs:
            t = [float(r["time"]) for r in run["rows"]]
            y = [float(r[key]) for r in run["rows"]]
            line, = ax.plot(t, y, "--" if not run["stable"] else "-", label=run["label"],
                            zorder=3 if not run["stable"] else 2)
            if not run["stable"]:
                ax.plot(t[-1:], y[-1:], "x", color=line.get_color(), markersize=10)
        ax.set_title(title)
        ax.grid(alpha=0.3)
        if key in ("energy", "shape_error"):
            ax.set_yscale("symlog", linthresh=1e-4)
    for ax in axes[1]:
        ax.set_xlabel("t [s]")
    axes[0, 0].legend(fontsize=8)
    fig.suptitle("Ball squashed to 15 % of its diameter between plates, then released")
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--cells", type=int, default=8)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--out", default="output/studies/solid_squash")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    runs = [measure(label, values, args) for label, values in RUNS]
    with open(os.path.join(args.out, "solid_squash.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["run", "completed", "stopped_at", "min_det_F", "max_abs_volume_error",
                    "final_shape_error", "final_volume_error", "stepping_seconds"])
        for run in runs:
            rows = run["rows"]
            w.writerow([run["label"], run["stable"], run["blowup_time"],
                        min(float(r["min_det_F"]) for r in rows),
                        max(abs(float(r["volume_error"])) for r in rows),
                        rows[-1]["shape_error"], rows[-1]["volume_error"], run["seconds"]])
    chart(runs, os.path.join(args.out, "solid_squash.png"))
    print(open(os.path.join(args.out, "solid_squash.csv")).read())


if __name__ == "__main__":
    main()
