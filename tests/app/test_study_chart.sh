# The study writes one CSV over the parameter values; the plotting script turns it into a PNG,
# and reports the observed orders it charts.
source "$(dirname "$0")/common.sh"
"$AMPHORA" study "$AMPHORA_SOURCE_DIR/scenes/overlap1d.toml" --set advection_diffusion_1d.cells \
  --values 20,40,80 --csv study.csv > study.log
[ "$(wc -l < study.csv)" = 4 ] || { cat study.csv; fail "study CSV rows"; }
head -1 study.csv | grep -q "^parameter,value,error,wall_time,steps,work_per_step,rate,unit,error_max,alpha,beta$" || fail "CSV header"
"${AMPHORA_PYTHON:-python3}" "$AMPHORA_SOURCE_DIR/scripts/plot_study.py" study.csv study.png > plot.log
[ -s study.png ] || fail "no chart"
head -c 8 study.png | od -An -c | grep -q "P   N   G" || fail "not a PNG"
grep -E "observed order" plot.log
echo "study chart: ok"
