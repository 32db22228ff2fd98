"""Charts and a summary of the matrix-free benchmarks (scripts/bench_matrix_free.sh)."""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def load(path):
    if not os.path.exists(path):
        return []
    with open(path) as f:
        return json.load(f)["benchmarks"]


def medians(rows):
    """Median rows when repetitions were aggregated, else the plain rows."""
    agg = [r for r in rows if r.get("aggregate_name") == "median"]
    return agg if agg else [r for r in rows if r.get("run_type") != "aggregate"]


def args(row):
    name = row["run_name"] if "run_name" in row else row["name"]
    return [int(a) for a in name.split("/")[1:] if a.isdigit()]


out = sys.argv[1] if len(sys.argv) > 1 else "output/bench"
lines = []

# CEED BPs: MDoF/s against DoFs, one panel per BP, one line per degree
bp = [r for r in load(f"{out}/matrix_free_bp_2threads.json") if r.get("run_type") != "aggregate"]
if bp:
    fig, axes = plt.subplots(2, 3, figsize=(13, 7.5), sharey=True)
    for b in range(1, 7):
        ax = axes[(b - 1) // 3][(b - 1) % 3]
        for p in range(1, 9):
            pts = sorted((r["DoFs"], r["MDoF/s"]) for r in bp if args(r)[:2] == [b, p])
            if pts:
                ax.plot([x for x, _ in pts], [y for _, y in pts], "o-", label=f"p={p}", ms=3)
        bound = [r["bound_MDoF/s"] for r in bp if args(r)[0] == b]
        if bound:
            ax.axhline(bound[0], color="k", ls="--", lw=0.8,
                       label="STREAM / 80 B" if b == 1 else None)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(f"BP{b}")
        ax.grid(True, which="both", alpha=0.3)
        if b > 3:
            ax.set_xlabel("DoFs")
        if b in (1, 4):
            ax.set_ylabel("MDoF x CG iterations / s")
    axes[0][0].legend(fontsize=7, ncol=2)
    fig.suptitle("amphora matrix-free CEED bake-off problems, 2 threads (Cartesian cells, 50 CG iterations)")
    fig.tight_layout()
    fig.savefig(f"{out}/matrix_free_bp.png", dpi=120)
    lines.append(f"wrote {out}/matrix_free_bp.png")
    # throughput against degree at the largest size
    best = {}
    for r in bp:
        b, p, e = args(r)
        if e == max(args(q)[2] for q in bp if args(q)[0] == b):
            best[(b, p)] = r["MDoF/s"]
    for r in bp:
        b, p, e = args(r)
        if b == 5 and e == 7:
            lines.append(f"BP5 p={p} {r['DoFs'] / 1e6:.1f}M DoFs: {r['MDoF/s']:.1f} MDoF/s = "
                         f"{100 * r['MDoF/s'] / r['bound_MDoF/s']:.0f}% of STREAM / 80 B ({r['bound_MDoF/s']:.0f})")
    lines.append("BP MDoF/s at the largest size, 2 threads: " + "; ".join(
        f"BP{b}: " + " ".join(f"p{p}={best[(b, p)]:.0f}" for p in range(1, 9) if (b, p) in best) for b in range(1, 7)))

# Geometry modes: throughput against bytes of geometry per DoF
geo = medians(load(f"{out}/matrix_free_geometry_2threads.json"))
if geo:
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    names = ["cartesian", "affine", "stored", "on the fly", "stored, team"]
    for mode in range(5):
        pts = sorted((r["geometry_B/DoF"], r["MDoF/s"], args(r)[1]) for r in geo if args(r)[0] == mode)
        if pts:
            ax.plot([x + 0.01 for x, _, _ in pts], [y for _, y, _ in pts], "o-", label=names[mode])
            for x, y, p in pts:
                ax.annotate(f"p{p}", (x + 0.01, y), fontsize=7)
    ax.set_xscale("log")
    ax.set_xlabel("geometry bytes per DoF read per application")
    ax.set_ylabel("MDoF/s (Laplace, ~2M DoFs, 2 threads)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(f"{out}/matrix_free_geometry.png", dpi=120)
    lines.append(f"wrote {out}/matrix_free_geometry.png")
    for r in geo:
        lines.append(f"geometry {names[args(r)[0]]:10s} p={args(r)[1]}: {r['MDoF/s']:.1f} MDoF/s, "
                     f"{r['geometry_B/DoF']:.1f} B/DoF geometry")

for r in medians(load(f"{out}/matrix_free_bpop_2threads.json")):
    b, p = args(r)[:2]
    lines.append(f"BPOperator BP{b} p={p} {r['DoFs'] / 1e6:.1f}M DoFs, 2 threads: {r['MDoF/s']:.1f} MDoF/s, "
                 f"{100 * r['MDoF/s'] / r['bound_MDoF/s']:.0f}% of the STREAM bound (16 B/DoF)")

for r in medians(load(f"{out}/matrix_free_stored_2threads.json")):
    if not r["name"].startswith("StoredGeometryLarge/"):
        continue
    op, p = args(r)[:2]
    lines.append(f"StoredGeometryLarge {'BP5' if op == 5 else 'Laplace Gauss p+1'} p={p} {r['DoFs'] / 1e6:.1f}M DoFs, "
                 f"2 threads: {r['MDoF/s']:.1f} MDoF/s, {100 * r['MDoF/s'] / r['bound_MDoF/s']:.0f}% of the STREAM bound "
                 f"({16 + r['geometry_B/DoF']:.0f} B/DoF with the stored geometry)")

for t in (1, 2):
    for r in medians(load(f"{out}/matrix_free_dealii_{t}threads.json")):
        p = args(r)[0]
        lines.append(f"LaplaceDealii p={p} {t} thread(s): {r['MDoF/s']:.1f} MDoF/s, "
                     f"x{r['vs_dealii_1core']:.2f} deal.II 1 core, x{r['vs_dealii_2ranks']:.2f} deal.II 2 ranks")
    for r in medians(load(f"{out}/matrix_free_large_{t}threads.json")):
        lines.append(f"LaplaceLarge p={args(r)[0]} {t} thread(s): {r['DoFs'] / 1e6:.1f}M DoFs, {r['MDoF/s']:.1f} MDoF/s, "
                     f"{100 * r['MDoF/s'] / r['bound_MDoF/s']:.0f}% of the STREAM bound (16 B/DoF)")
    solves = load(f"{out}/matrix_free_poisson_{t}threads.json")
    for k in (2, 4):
        mg = [r for r in solves if args(r)[:2] == [k, 0]]
        amg = [r for r in solves if args(r)[:2] == [k, 1]]
        if mg and amg:
            a, b = mg[0], amg[0]
            lines.append(f"Poisson Q{k} {a['DoFs'] / 1e6:.2f}M DoFs, {t} thread(s): multigrid-CG {a['total_s']:.2f} s "
                         f"({a['iterations']:.0f} it, setup {a['setup_s']:.2f} s), BoomerAMG-CG {b['total_s']:.2f} s "
                         f"({b['iterations']:.0f} it; assembly {b['assembly_s']:.1f} s apart), ratio {b['total_s'] / a['total_s']:.1f}")
for r in medians(load(f"{out}/matrix_free_dealii_2ranks.json")):
    lines.append(f"LaplaceDealii p={args(r)[0]} 2 ranks x 1 thread: {r['MDoF/s']:.1f} MDoF/s, "
                 f"x{r['vs_dealii_2ranks']:.2f} deal.II 2 ranks")
with open(f"{out}/matrix_free_summary.txt", "w") as f:
    f.write("\n".join(lines) + "\n")
print("\n".join(lines))
