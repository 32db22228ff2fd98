# The Taylor-Green vortex at Re = 1600 on Q2, 8^3 and 16^3 cells, t in [0, 2], against the
# 512^3 spectral E_k (../shared/reference/tgv_re1600). The tolerance is derived from the
# coarse run: E_k's error converges at order k + 1 = 3 (velocity in L2), so the 16^3 error
# must be at most the 8^3 error / 2^(3 - 0.2); measured 1.74e-2 and 1.71e-3 (order 3.35).
source "$(dirname "$0")/common.sh"
"${AMPHORA_PYTHON:-python3}" "$AMPHORA_SOURCE_DIR/scripts/study_tgv.py" --runs 2:8,2:16 \
  --end-time 2 --threads 2 --out tgv > tgv.log || { cat tgv.log; fail "study_tgv.py failed"; }
[ -s tgv/tgv_study.png ] || fail "no chart"
"${AMPHORA_PYTHON:-python3}" - tgv/tgv_study.csv <<'PY' || fail "E_k does not converge at order k + 1"
import csv, math, sys
rows = list(csv.DictReader(open(sys.argv[1])))
coarse, fine = (float(r["ek_linf_rel"]) for r in rows)
bound = coarse / 2 ** 2.8
print(f"max relative E_k error: 8^3 {coarse:.3e}, 16^3 {fine:.3e} (bound {bound:.3e}), "
      f"order {math.log2(coarse / fine):.2f}")
sys.exit(0 if fine <= bound else 1)
PY
echo "tgv: ok"
