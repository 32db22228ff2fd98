# Examples are tests: every scene under scenes/ is valid and runs to its end.
source "$(dirname "$0")/common.sh"
for scene in "$AMPHORA_SOURCE_DIR"/scenes/*.toml; do
  name=$(basename "$scene" .toml)
  sed "s|^output_dir = .*|output_dir = \"$name\"|" "$scene" > "$name.toml"
  "$AMPHORA" check "$name.toml" > /dev/null
  "$AMPHORA" run "$name.toml" > "$name.log"
  grep -q "^\[done\]" "$name.log" || fail "$name did not finish"
  [ -s "$name/diagnostics.csv" ] && ls "$name"/*.xmf > /dev/null || fail "$name wrote no output"
done
echo "scenes: ok"
