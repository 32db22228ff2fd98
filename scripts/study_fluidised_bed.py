"""The fluidised bed (scenes/cfd_dem_fluidised_bed.toml) over inlet velocities: the pressure
drop against the bed's buoyant weight (the force balance), the bed's void fraction against
Richardson-Zaki, and where a coupled step's time goes (void fraction, forces, DEM, fluid).
Means over the pseudo-steady part (t >= --average-from). Writes <out>/fluidised_bed.csv and
<out>/fluidised_bed.png.

  python3 scripts/study_fluidised_bed.py --threads 2 --out output/studies/fluidised_bed
"""
import argparse
import csv
import os
import re
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from scene_variant import run_variant  # noqa: E402

COLUMNS = ["pressure_drop", "weight_pressure", "pressure_drop_ratio", "fluid_force_ratio",
           "bed_void_fraction", "richardson_zaki_void_fraction", "cfl", "linear_iterations"]
PHASES = ["void fraction", "forces", "DEM", "fluid"]


def measure(u, args):
    d = os.path.join(args.out, f"u_{u:g}")
    values = {"inlet_velocity": f"{u!r}", "end_time": f"{args.end_time!r}",
              "diagnostics_every": "10"}
    result = run_variant("cfd_dem_fluidised_bed.toml", d, values, args.threads)
    if not result["stable"]:
        raise RuntimeError(f"u = {u}: stopped at t = {result['blowup_time']}")
    rows = [r for r in csv.DictReader(open(os.path.join(d, "diagnostics.csv")))
            if float(r["time"]) >= args.average_from]
    row = {"inlet_velocity": u}
    for key in COLUMNS:
        row[key] = statistics.mean(float(r[key]) for r in rows)
    steps = int(round(args.end_time / 0.005))
    for phase in PHASES:  # seconds per coupled step
        m = re.search(rf"^\[timing\] {phase} ([0-9.e+-]+) s", result["stdout"], re.M)
        row[f"{phase} [s/step]"] = float(m.group(1)) / steps if m else float("nan")
    m = re.search(r"([0-9.e+-]+) particle-steps/s", result["stdout"].split("[done]")[-1])
    row["particle_steps_per_s"] = float(m.group(1)) if m else float("nan")
    row["threads"] = args.threads
    # The fluid's force on the particles carries their whole weight when nothing else does:
    # sum F_z / (M g (1 - rho / rho_p)) = rho_p / (rho_p - rho) (alumina in water: 1.385).
    row["fluid_force_share"] = row["fluid_force_ratio"] / (3585.9 / (3585.9 - 997.0))
    print(f"U {u:.3f} m/s: dp/W {row['pressure_drop_ratio']:.4f}, fluid carries "
          f"{row['fluid_force_share']:.4f} of the weight, eps {row['bed_void_fraction']:.4f} "
          f"(Richardson-Zaki {row['richardson_zaki_void_fraction']:.4f}), "
          f"{row['particle_steps_per_s']:.3g} particle-steps/s on {args.threads} threads",
          flush=True)
    return row


def chart(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 3, figsize=(14, 4))
    u = [r["inlet_velocity"] for r in rows]
    ax[0].plot(u, [r["pressure_drop_ratio"] for r in rows], "o-", label="pressure drop")
    ax[0].plot(u, [r["fluid_force_share"] for r in rows], "s--", label="fluid force / weight")
    ax[0].axhline(1.0, color="k", lw=0.8)
    ax[0].axhspan(0.98, 1.02, color="g", alpha=0.15, label="2 %")
    ax[0].set(xlabel="inlet velocity [m/s]", ylabel="/ M g (1 - rho / rho_p) / A",
              title="force balance")
    ax[1].plot(u, [r["bed_void_fraction"] for r in rows], "o-", label="bed (2 x mean height)")
    ax[1].plot(u, [r["richardson_zaki_void_fraction"] for r in rows], "k--",
               label="Richardson-Zaki")
    ax[1].set(xlabel="inlet velocity [m/s]", ylabel="void fraction", title="bed expansion")
    bottom = [0.0] * len(rows)
    for phase in PHASES:
        h = [1e3 * r[f"{phase} [s/step]"] for r in rows]
        ax[2].bar([f"{x:g}" for x in u], h, bottom=bottom, label=phase)
        bottom = [b + x for b, x in zip(bottom, h)]
    ax[2].set(xlabel="inlet velocity [m/s]", ylabel="ms per coupled step",
              title="cost of a coupled step")
    for a in ax:
        a.grid(alpha=0.3)
        a.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--velocities", default="0.03,0.06,0.1,0.157,0.2")
    ap.add_argument("--end-time", type=float, default=2.0)
    ap.add_argument("--average-from", type=float, default=1.0)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--out", default="output/studies/fluidised_bed")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    rows = [measure(float(u), args) for u in args.velocities.split(",")]
    with open(os.path.join(args.out, "fluidised_bed.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    chart(rows, os.path.join(args.out, "fluidised_bed.png"))
    print(f"wrote {args.out}/fluidised_bed.csv and fluidised_bed.png")


if __name__ == "__main__":
    main()
