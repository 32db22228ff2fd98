#!/usr/bin/env python3
"""Checks that namespaces follow folders: code in src/<a>/<b>/file is in amphora::<a>::<b> (or a
namespace inside it), src/base/ is amphora itself. Prints each file:line that opens another
namespace at file scope and exits 1 if there is any.
  check_namespaces.py [SRC_DIR]"""
import pathlib
import re
import sys

OPEN = re.compile(r"^namespace ([\w:]+) \{")
CHARS = re.compile(r'"(?:[^"\\]|\\.)*"|\'(?:[^\'\\]|\\.)*\'')  # literals hold no braces
LAYERS = {"base", "kernels", "mesh", "solvers", "physics", "coupling", "io"}


def folder_namespace(src, path):
    parts = path.relative_to(src).parts[:-1]
    if not parts or parts[0] == "base":
        return "amphora"
    return "::".join(("amphora",) + parts)


def allowed(expected, name):
    if name == expected:
        return True
    if not name.startswith(expected + "::"):
        return False
    # amphora::<x> under base/ must not take a layer's name
    return expected != "amphora" or name.split("::")[1] not in LAYERS


def check(src):
    bad = 0
    for path in sorted(src.rglob("*")):
        if path.suffix not in (".hpp", ".cpp", ".h") or path.relative_to(src).parts[0] not in LAYERS:
            continue
        expected = folder_namespace(src, path)
        depth = 0
        for number, line in enumerate(path.read_text().splitlines(), 1):
            m = OPEN.match(line)
            at_file_scope = depth == 0
            code = CHARS.sub("", line.split("//")[0])
            depth += code.count("{") - code.count("}")
            if m and at_file_scope and not allowed(expected, m.group(1)):
                print(f"{path}:{number}: namespace {m.group(1)}: files in this folder are in {expected}")
                bad += 1
    return bad


if __name__ == "__main__":
    src = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).parent.parent / "src")
    n = check(src)
    print(f"check_namespaces: {n} namespace(s) off their folder under {src}" if n else f"check_namespaces: ok ({src})")
    sys.exit(1 if n else 0)
