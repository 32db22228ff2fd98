# Shared by the application tests: run the real amphora binary and check what it says and writes.
set -euo pipefail
: "${AMPHORA:?AMPHORA must point at the amphora binary}"
: "${AMPHORA_SOURCE_DIR:?}"
MPIEXEC=${MPIEXEC:-mpiexec}
work=$(mktemp -d "$PWD/$(basename "$0" .sh).XXXXXX")
trap 'rm -rf "$work"' EXIT
cd "$work"

fail() { echo "FAIL: $*" >&2; exit 1; }

# A small copy of the default scene with its output in `out/`, plus extra [run] lines.
make_scene() {  # file [extra run lines...]
  local file=$1; shift
  {
    echo '[run]'
    echo 'module = "advection_diffusion_1d"'
    echo 'output_dir = "out"'
    echo 'end_time = 0.5'
    echo 'diagnostics_every = 25'
    for line in "$@"; do echo "$line"; done
    echo '[advection_diffusion_1d]'
    echo 'cells = 40'
  } > "$file"
}

# A shipped scene (scenes/SOURCE.toml) as NAME.toml, its output in NAME/, with sed edits.
shipped_scene() {  # SOURCE NAME [SED_EXPR...]
  local src=$1 name=$2
  shift 2
  local edits=(-e "s|^output_dir = .*|output_dir = \"$name\"|")
  for e in "$@"; do edits+=(-e "$e"); done
  sed "${edits[@]}" "$AMPHORA_SOURCE_DIR/scenes/$src.toml" > "$name.toml"
}

# expect_error CODE REGEX CMD...: CMD exits with CODE and its stderr matches REGEX in one line.
expect_error() {
  local code=$1 regex=$2; shift 2
  local status=0
  "$@" > stdout.txt 2> stderr.txt || status=$?
  [ "$status" = "$code" ] || { cat stdout.txt stderr.txt; fail "'$*' exited $status, expected $code"; }
  grep -E -q -- "$regex" stderr.txt || { cat stderr.txt; fail "'$*': stderr lacks /$regex/"; }
  [ "$(grep -c 'amphora: error' stderr.txt)" = 1 ] || { cat stderr.txt; fail "expected one error line"; }
}

# same_h5 A B: identical datasets and attributes (h5diff without tolerance compares exactly).
csv_column() {  # NAME FILE: the values of the CSV column NAME, one per line
  local c
  c=$(head -1 "$2" | tr ',' '\n' | grep -n "^$1\$" | cut -d: -f1)
  [ -n "$c" ] || fail "$2 has no column $1"
  tail -n +2 "$2" | cut -d, -f"$c"
}
# same_h5 A B [OBJECT]: the same objects, shapes and values (h5diff's exit status alone
# passes datasets of different shapes as "not comparable").
same_h5() {
  local o=${3:-}
  h5diff -q "$1" "$2" ${o:+"$o" "$o"} || fail "$1 and $2 differ${o:+ in $o}"
  [ "$(h5ls -r "$1$o")" = "$(h5ls -r "$2$o")" ] || fail "$1 and $2 differ in shape${o:+ in $o}"
}

# close_csv A B [REL]: same shape, every number equal to REL (default 1e-12) relative.
close_csv() {  # A B [REL [ABS]]: every value within REL relative or ABS absolute
  paste -d'\n' "$1" "$2" | awk -F, -v rel="${3:-1e-12}" -v abs="${4:-0}" '
    NR % 2 == 1 { n = split($0, a, ","); next }
    { m = split($0, b, ","); if (m != n) { print "shape differs at row " NR/2; bad = 1; exit }
      for (i = 1; i <= n; ++i) {
        if (a[i] == b[i]) continue
        x = a[i] + 0; y = b[i] + 0; d = x - y; if (d < 0) d = -d
        s = (x < 0 ? -x : x); t = (y < 0 ? -y : y); if (t > s) s = t
        if (d > rel * s && d > abs) { print "row " NR/2 " column " i ": " a[i] " vs " b[i]; bad = 1 }
      } }
    END { exit bad }' || fail "$1 and $2 differ beyond ${3:-1e-12} relative"
}

# restart_matches SCENE NAME MAX_STEPS [SED_EXPR...]: the scene (edited by the sed expressions)
# run whole into NAME_full/ and run for MAX_STEPS then restarted from its checkpoint into
# NAME_split/ ends with the same checkpoint and diagnostics, bit for bit.
restart_matches() {
  local scene=$1 name=$2 max=$3 e
  shift 3
  local edits=(-e "s|^output_dir = .*|output_dir = \"${name}_full\"|")
  for e in "$@"; do edits+=(-e "$e"); done
  sed "${edits[@]}" "$scene" > "${name}_full.toml"
  sed "s|${name}_full|${name}_split|" "${name}_full.toml" > "${name}_split.toml"
  "$AMPHORA" run "${name}_full.toml" > "${name}_full.log"
  "$AMPHORA" run "${name}_split.toml" --max-steps "$max" > "${name}_first.log"
  "$AMPHORA" run "${name}_split.toml" --restart "${name}_split/checkpoint.h5" > "${name}_second.log"
  grep -q "(restart)" "${name}_second.log" || fail "$name: restart not announced"
  same_h5 "${name}_full/checkpoint.h5" "${name}_split/checkpoint.h5"
  cmp "${name}_full/diagnostics.csv" "${name}_split/diagnostics.csv" || fail "$name: diagnostics differ"
}
