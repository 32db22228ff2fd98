#!/usr/bin/env python3
"""Normal-mode analysis of amphora's traditional partitioned scheme (TP) for MP-VE, on the model
problem of Banks, Henshaw & Schwendeman (J. Comput. Phys. 269, 2014, Part I, sec. 5): the x-
independent mode, where the fluid column -H < y < 0 (inviscid in effect: its velocity is
uniform) has p = 0 at y = -H, so its pressure on the interface is p = -rho H a (added mass rho H
per unit area), over the solid 0 < y < Hbar fixed at Hbar.

amphora's TP discretised exactly as in src/coupling/fsi/mpve_partitioned.cpp, in 1D:
  solid   leapfrog on nodes y_j = j dy; the interface node carries half a cell,
          (rho_bar dy / 2) (u0^{n+1} - 2 u0^n + u0^{n-1}) / dt^2 = E (u1^n - u0^n) / dy - s^n,
          E = lambda_bar + 2 mu_bar = rho_bar cp^2, s^n = -p^n the fluid's traction;
  fluid   wall velocity V^{n+1} = (3 u0^{n+1} - 4 u0^n + u0^{n-1}) / (2 dt) (one-sided),
          p^{n+1/2} = -rho H (V^{n+1} - V^n) / dt, p^n = (3 p^{n-1/2} - p^{n-3/2}) / 2.
One step is a linear map of (u^n, u^{n-1}, V^n, p^{n-1/2}, p^{n-3/2}); its eigenvalues are the
normal modes' amplification factors A. The scheme is called unstable on a grid when
|A|_max^(t_end/dt) exceeds the study's blow-up factor (10 at t_end = 0.3), the criterion of
scripts/study_mpve_fsi.py.

Closed form in the limit dt -> 0 (the interface node alone: its stiffness term is O(dt^2)):
with u0^n = A^n, m = rho_bar dy / 2 (half a cell) and M = rho H,
    4 m A^3 + M (3 A - 1)^2 = 0,
whose roots leave the unit circle through A = -1 when m / M = 4: TP needs
    dy >= 8 rho H / rho_bar   (as dt -> 0; finite dt makes it stricter).
BHS's scheme (a whole cell on the interface, no time extrapolation) needs dy >= rho H / rho_bar
at dt -> 0 (their theorem: dt <= (2 / cp)(dy - rho H / rho_bar)); here the half cell costs a
factor 2 and the pressure extrapolated to t_n and the one-sided wall velocity a factor 4.
The 2D channel's added mass is smaller than the column's rho H (wall-bounded, the k = 2 pi wave:
rho coth(kH) / k = 0.16 rho), so this 1D boundary is conservative for the 2D study.

Writes output/study_mpve_fsi/tp_normal_modes.csv and, if the study's CSV is there, compares:
    /usr/bin/python3 scripts/mpve_tp_normal_modes.py [--cfl 0.7]
"""
import argparse
import csv
import math
import os

import numpy as np

here = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
out = os.path.join(here, "output", "study_mpve_fsi")


def amplification(ratio, dy, dt, H=1.0, Hbar=0.5, rho=1.0, cp=math.sqrt(3.0)):
    """Largest |A| of one TP step (rho_bar = ratio * rho)."""
    rb = ratio * rho
    E = rb * cp * cp
    N = int(round(Hbar / dy))          # nodes 0..N-1 free, node N fixed
    n = 2 * N + 3
    iu, io, iV, ip, ipp = 0, N, 2 * N, 2 * N + 1, 2 * N + 2
    M = np.zeros((n, n))
    # traction s^n = -p^n = -(3 p^{n-1/2} - p^{n-3/2}) / 2 as a row over the state
    s = np.zeros(n)
    s[ip], s[ipp] = -1.5, 0.5
    a = dt * dt / rb
    for j in range(N):
        row = np.zeros(n)
        row[iu + j] += 2.0
        row[io + j] -= 1.0
        if j == 0:  # half cell: u0' = 2u0 - u0o + (2 dt^2 / (rb dy)) (E (u1 - u0) / dy - s)
            c = 2 * dt * dt / (rb * dy)
            row[iu + 0] -= c * E / dy
            if N > 1:
                row[iu + 1] += c * E / dy
            row -= c * s
        else:
            k = a * E / (dy * dy)
            row[iu + j] -= 2 * k
            row[iu + j - 1] += k
            if j + 1 < N:
                row[iu + j + 1] += k
        M[iu + j] = row
    for j in range(N):
        M[io + j, iu + j] = 1.0
    # V^{n+1} = (3 u0^{n+1} - 4 u0^n + u0^{n-1}) / (2 dt)
    V = (3 * M[iu + 0]) / (2 * dt)
    V[iu + 0] -= 4 / (2 * dt)
    V[io + 0] += 1 / (2 * dt)
    M[iV] = V
    P = -rho * H * (V.copy()) / dt   # p^{n+1/2} = -rho H (V^{n+1} - V^n) / dt
    P[iV] += rho * H / dt
    M[ip] = P
    M[ipp, ip] = 1.0
    return max(abs(np.linalg.eigvals(M)))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cfl", type=float, default=0.7)
    ap.add_argument("--end-time", type=float, default=0.3)
    args = ap.parse_args()
    ratios = [800.0, 400.0, 200.0, 100.0, 10.0, 1.0, 0.1, 0.01, 0.001]
    cells = [20, 40, 80, 160, 320]
    study = {}
    path = os.path.join(out, "mpve_stability.csv")
    if os.path.exists(path):
        for r in csv.DictReader(open(path)):
            if r["scheme"] == "tp":
                study[(float(r["rho_bar_over_rho"]), int(r["cells"]))] = int(r["stable"])
    os.makedirs(out, exist_ok=True)
    rows, agree, total = [], 0, 0
    for ratio in ratios:
        line = []
        for n in cells:
            dy = 1.0 / n
            dt = args.cfl * dy / (math.sqrt(3.0) * math.sqrt(2.0))  # the scene's step (the solid's 2D limit)
            A = amplification(ratio, dy, dt)
            growth = A ** (args.end_time / dt)
            stable = int(growth <= 10.0)
            seen = study.get((ratio, n))
            if seen is not None:
                total += 1
                agree += int(seen == stable)
            rows.append({"rho_bar_over_rho": ratio, "cells": n, "amplification": A, "growth": growth,
                         "predicted_stable": stable, "study_stable": "" if seen is None else seen})
            line.append(("S" if stable else "U") + ("" if seen is None else ("=" if seen == stable else "!")))
        print(f"rho_bar/rho {ratio:6g}: " + " ".join(f"{x:3s}" for x in line))
    with open(os.path.join(out, "tp_normal_modes.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    print("columns dy = " + ", ".join(f"1/{n}" for n in cells) + "; S/U predicted; = agrees with the 2D study, ! does not")
    if total:
        print(f"agreement with the 2D study: {agree} of {total}")


if __name__ == "__main__":
    main()
