"""The table gpu_check.sh prints last: each benchmark's rate, its bound and the goal, from the
Google Benchmark JSON files in one folder (stream, launches, matrix_free, dem, mac_pressure)."""
import json
import os
import sys


def load(folder, prefix):
    """The iterations of every benchmark in the JSON files whose name starts with prefix."""
    out = []
    for name in sorted(os.listdir(folder)):
        if not (name.startswith(prefix) and name.endswith(".json")):
            continue
        try:
            out += [b for b in json.load(open(os.path.join(folder, name)))["benchmarks"]
                    if b.get("run_type", "iteration") == "iteration"]
        except (ValueError, KeyError):
            pass
    return out


def short(name):
    """A benchmark's name without Google Benchmark's suffixes (/iterations:1, /real_time, ...)."""
    return "/".join(p for p in name.split("/") if ":" not in p and p not in ("real_time", "manual_time"))


def row(what, rate, unit, bound=None, goal=""):
    share = f"{100.0 * rate / bound:5.1f} %" if bound else "     - "
    print(f"  {what:<34} {rate:11.4g} {unit:<12} {share}  {goal}")


def main(folder):
    print(f"  {'benchmark':<34} {'rate':>11} {'unit':<12} {'bound':>7}  goal")
    for b in load(folder, "stream"):
        row(short(b["name"]), b["bandwidth"] / 1e9, "GB/s")
    for b in load(folder, "launches"):
        row(short(b["name"]), 1e6 * b["s_per_launch"], "us/launch")
    for b in load(folder, "matrix_free"):
        name, c = short(b["name"]), b
        rate, bound = c["MDoF/s"] * 1e6, c["bound_MDoF/s"] * 1e6
        parts = name.split("/")
        goal = ""
        if parts[0] == "BPOperator" and parts[2] == "4":
            goal = "BP5 p=4: >= 1e10 DoF/s " + ("met" if rate >= 1e10 else "NOT met")
        if parts[0] == "StoredGeometryLarge" and 2 <= int(parts[2]) <= 6:
            goal = ">= 50 % of bound " + ("met" if rate >= 0.5 * bound else "NOT met")
        row(name, rate, "DoF/s", bound, goal)
    for b in load(folder, "dem"):
        rate = b["particle_steps_per_s"]
        goal = ">= 5e8 " + ("met" if rate >= 5e8 else "NOT met") if b["particles"] >= 1e6 else ""
        row(short(b["name"]), rate, "part-steps/s", None, goal)
    for b in load(folder, "mac_pressure"):
        rate = b["unknowns_per_s"]
        bound = b.get("bound_unknowns_per_s")
        goal = ">= 30 % of bound " + ("met" if bound and rate >= 0.3 * bound else "NOT met") if b["unknowns"] >= 256 ** 3 else ""
        name = f'{short(b["name"])} ({int(b["iterations"])} it)' if "iterations" in b else short(b["name"])
        row(name, rate, "unknowns/s", bound, goal)


if __name__ == "__main__":
    main(sys.argv[1])
