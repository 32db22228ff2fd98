"""The longest kernels of a profile (AMPHORA_KERNEL_PROFILE's CSV, kernels/kernel_profile.hpp):
  python3 scripts/kernel_profile_table.py FILE [ROWS [SKIP]]
(SKIP: a regular expression of labels to leave out, such as a benchmark's own STREAM run), one
line each: total ms, share of the run's wall time (less the kernels left out), calls, mean and
shortest call in us; then the totals of each region (a multigrid's levels), and what the kernels
did not cover."""
import csv
import re
import sys


def main(path, rows=6, skip=None):
    with open(path, newline="") as f:
        table = list(csv.DictReader(f))
    kernels = [r for r in table if r["label"] != "(outside kernels)"
               and not (skip and re.search(skip, r["label"]))]
    outside = [r for r in table if r["label"] == "(outside kernels)"]
    # shares of the run's wall time less the kernels left out
    wall = sum(float(r["seconds"]) for r in kernels + outside)
    for r in kernels + outside:
        r["share"] = float(r["seconds"]) / wall if wall > 0 else 0.0
    print(f"    {'kernel':<60} {'ms':>9} {'share':>6} {'calls':>7} {'mean us':>9} {'min us':>8}")
    for r in kernels[:rows]:
        name = ((r["region"] + ": " if r.get("region") else "") + r["label"]).replace("amphora::", "")
        print(f"    {name[:60]:<60} {1e3 * float(r['seconds']):9.2f} "
              f"{100 * float(r['share']):5.1f}% {int(r['calls']):7d} {float(r['mean_us']):9.1f} "
              f"{float(r['min_us']):8.1f}")
    rest = kernels[rows:]
    if rest:
        s = sum(float(r["seconds"]) for r in rest)
        share = sum(float(r["share"]) for r in rest)
        calls = sum(int(r["calls"]) for r in rest)
        print(f"    {'(' + str(len(rest)) + ' other kernels)':<60} {1e3 * s:9.2f} {100 * share:5.1f}% {calls:7d}")
    regions = {}
    for r in kernels:
        if r.get("region"):
            t = regions.setdefault(r["region"], [0.0, 0.0, 0])
            t[0] += float(r["seconds"]); t[1] += float(r["share"]); t[2] += int(r["calls"])
    for region, (s, share, calls) in regions.items():
        print(f"    {'(all of ' + region.replace('amphora::', '') + ')':<60} {1e3 * s:9.2f} "
              f"{100 * share:5.1f}% {calls:7d}")
    for r in outside:
        print(f"    {'(outside kernels: host, copies, MPI)':<60} {1e3 * float(r['seconds']):9.2f} "
              f"{100 * float(r['share']):5.1f}%")


if __name__ == "__main__":
    main(sys.argv[1], int(sys.argv[2]) if len(sys.argv) > 2 else 6,
         sys.argv[3] if len(sys.argv) > 3 else None)
