#!/usr/bin/env python3
"""Lists the functions under src/ longer than a limit (default 150 lines, the house rule), by
a brace-matching scan: a function is a '{' that closes a line with a parameter list ')' (and
optionally const/override/noexcept or an initialiser list) outside another function's body.
Prints file:line: name (N lines) for each and exits 1 if there is any.
  check_function_length.py [SRC_DIR] [LIMIT]"""
import pathlib
import re
import sys

HEAD = re.compile(r"\)\s*(const)?\s*(override|final|noexcept)?\s*(->\s*[\w:<>,\s*&]+)?\s*\{\s*(//.*)?$")
CONTROL = re.compile(r"^\s*(\}?\s*(if|for|while|switch|catch|else)\b|.*\b(KOKKOS_LAMBDA|\[[=&\w, ]*\]\s*\())")


def strip(line):
    line = re.sub(r'"(\\.|[^"\\])*"', '""', line)
    line = re.sub(r"'(\\.|[^'\\])*'", "''", line)
    return line.split("//")[0]


def functions(path):
    lines = path.read_text().splitlines()
    depth, start, name, fdepth = 0, None, "", None
    for n, raw in enumerate(lines, 1):
        line = strip(raw)
        if start is None and HEAD.search(raw.split("//")[0] + ("" if "{" in raw else "")) and not CONTROL.match(raw):
            m = re.search(r"([~\w:]+)\s*\(", raw)
            if m and m.group(1) not in ("if", "for", "while", "switch", "return", "sizeof"):
                start, name, fdepth = n, m.group(1), depth
        depth += line.count("{") - line.count("}")
        if start is not None and depth <= fdepth:
            yield name, start, n - start + 1
            start = None


def main(src, limit):
    bad = 0
    for path in sorted(src.rglob("*.[ch]pp")):
        for name, line, length in functions(path):
            if length > limit:
                print(f"{path}:{line}: {name} ({length} lines, limit {limit})")
                bad += 1
    print(f"check_function_length: {bad} function(s) over {limit} lines under {src}")
    return 1 if bad else 0


if __name__ == "__main__":
    root = pathlib.Path(__file__).resolve().parent.parent
    src = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else root / "src"
    sys.exit(main(src, int(sys.argv[2]) if len(sys.argv) > 2 else 150))
