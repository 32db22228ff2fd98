# The beam-channel FSI scene through the real binary: AMP follows the exact wave for a beam
# 16x lighter than the fluid's added mass, the traditional scheme on the same scene stops with
# a message saying when and why (exit 3, output kept), a restart continues bit for bit, and
# bad input is refused naming the allowed values.
source "$(dirname "$0")/common.sh"
scene() {  # file output_dir scheme [extra [beam_channel] lines...]
  local file=$1 out=$2 scheme=$3; shift 3
  sed -e "s|output/beam_channel_amp|$out|" -e "s|scheme = \"amp\"|scheme = \"$scheme\"|" \
    "$AMPHORA_SOURCE_DIR/scenes/beam_channel_amp.toml" > "$file"
  for line in "$@"; do
    sed -i "/^${line%% *} = /d" "$file"
    echo "$line" >> "$file"
  done
}
scene amp.toml amp amp
"$AMPHORA" run amp.toml > amp.log
python3 - amp/diagnostics.csv <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
last = rows[-1]
# Second order: at h = 1/80 the eta error is ~2e-3 of the unit amplitude (test_beam_channel_fsi).
assert float(last["eta_error"]) < 5e-3, last
assert max(float(r["max_eta"]) for r in rows) < 1.01, "AMP grew"
print("beam_channel: amp eta_error", last["eta_error"], "max_eta", max(float(r["max_eta"]) for r in rows))
PY

scene tp.toml tp tp
expect_error 3 "tp coupling is unstable at rho_h / rho = 0.01 .* at step [0-9]+, t = .*last good output: tp/fields_000000.h5" \
  "$AMPHORA" run tp.toml
[ -f tp/fields_000000.h5 ] || fail "the unstable run lost its output"
scene heavy.toml heavy tp "rho_h = 100.0"
"$AMPHORA" run heavy.toml > heavy.log || fail "tp with a heavy beam should be stable"
echo "beam_channel: tp unstable for the light beam, stable for the heavy one"

# Restart: stop after 100 steps, continue, compare with the straight run.
scene split.toml split amp
"$AMPHORA" run split.toml --max-steps 100 > /dev/null
"$AMPHORA" run split.toml --restart split/checkpoint.h5 > /dev/null
final=$(ls amp/fields_*.h5 | tail -1)
same_h5 "$final" "split/$(basename "$final")"
echo "beam_channel: restart bit for bit"

scene bad.toml bad aitken
expect_error 2 "beam_channel.*scheme.*one of: amp, tp, tp_aitken" "$AMPHORA" run bad.toml
scene bad2.toml bad2 amp "mode = 40"
expect_error 2 "mode = 40 is not resolved by points = 80" "$AMPHORA" run bad2.toml
scene bad3.toml bad3 amp "rho_h = 0.0"
expect_error 2 "rho_h" "$AMPHORA" run bad3.toml
echo "beam_channel: bad input refused"
