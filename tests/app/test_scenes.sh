# Examples are tests: every scene under scenes/ is valid and runs to its end; those under
# scenes/studies/ (long runs) are valid.
source "$(dirname "$0")/common.sh"
for scene in "$AMPHORA_SOURCE_DIR"/scenes/*.toml; do
  name=$(basename "$scene" .toml)
  sed "s|^output_dir = .*|output_dir = \"$name\"|" "$scene" > "$name.toml"
  "$AMPHORA" check "$name.toml" > /dev/null
  "$AMPHORA" run "$name.toml" > "$name.log"
  grep -q "^\[done\]" "$name.log" || fail "$name did not finish"
  [ -s "$name/diagnostics.csv" ] && ls "$name"/*.xmf > /dev/null || fail "$name wrote no output"
done
# Study scenes (long runs) are only checked.
for scene in "$AMPHORA_SOURCE_DIR"/scenes/studies/*.toml; do
  "$AMPHORA" check "$scene" > /dev/null || fail "$(basename "$scene") does not check"
done
echo "scenes: ok"
