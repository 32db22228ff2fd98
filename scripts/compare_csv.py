"""Compares two diagnostics CSVs (the same columns and rows): the largest difference of each
column relative to that column's largest magnitude in the reference. Prints one line per column
over the tolerance and a summary line last; exit 1 if any column is over it or the shapes differ.
  compare_csv.py REFERENCE OTHER TOLERANCE"""
import csv
import sys


def main(reference, other, tolerance):
    a = list(csv.reader(open(reference)))
    b = list(csv.reader(open(other)))
    if len(a) != len(b) or a[0] != b[0]:
        print(f"shapes differ: {len(a)} rows {a[0]} against {len(b)} rows {b[0]}")
        return 1
    worst, worst_column, bad = 0.0, "", 0
    for c, name in enumerate(a[0]):
        try:
            x = [float(r[c]) for r in a[1:]]
            y = [float(r[c]) for r in b[1:]]
        except ValueError:
            continue
        scale = max((abs(v) for v in x), default=0.0) or 1.0
        d = max((abs(p - q) for p, q in zip(x, y)), default=0.0) / scale
        if d > tolerance:
            print(f"{name}: {d:.3g} relative")
            bad += 1
        if d > worst:
            worst, worst_column = d, name
    print(f"{'FAIL' if bad else 'ok'}: {len(a) - 1} rows, largest difference {worst:.3g} relative"
          f" ({worst_column or '-'}), tolerance {tolerance:g}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2], float(sys.argv[3])))
