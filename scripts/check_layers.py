#!/usr/bin/env python3
"""Checks that every file under src/ includes only its own layer and the layers below it
(src/README or docs/layout.md: base and kernels at the bottom, then mesh, solvers, physics,
coupling, io), and that kernel headers include nothing but Kokkos, the C++ standard library and
other kernel headers. Prints one line per wrong include (file:line: the include, what is
allowed) and exits 1 if there is any.
  check_layers.py [SRC_DIR]"""
import pathlib
import re
import sys

# what each layer may include (its own folder included)
ALLOWED = {
    "base": {"base"},
    "kernels": {"kernels"},
    "mesh": {"base", "kernels", "mesh"},
    "solvers": {"base", "kernels", "mesh", "solvers"},
    "physics": {"base", "kernels", "mesh", "solvers", "physics"},
    "coupling": {"base", "kernels", "mesh", "solvers", "physics", "coupling"},
    "io": {"base", "kernels", "mesh", "solvers", "physics", "coupling", "io", "amphora"},
}
STANDARD = set("""algorithm any array atomic bit bitset cassert cctype cerrno cfloat charconv chrono
cinttypes climits clocale cmath complex condition_variable cstddef cstdint cstdio cstdlib cstring
ctime deque exception execution filesystem fstream functional future initializer_list iomanip ios
iosfwd iostream istream iterator limits list locale map memory mutex new numeric optional ostream
queue random ratio regex set shared_mutex sstream stack stdexcept streambuf string string_view
system_error thread tuple type_traits typeindex typeinfo unordered_map unordered_set utility
valarray variant vector""".split())
INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]')


def kernel_system_include_ok(name):
    return name in STANDARD or re.fullmatch(r"(Kokkos|impl/Kokkos)_\w+\.hpp", name) is not None


def check(src):
    bad = 0
    for path in sorted(src.rglob("*")):
        if path.suffix not in (".hpp", ".cpp", ".h", ".in"):
            continue
        layer = path.relative_to(src).parts[0]
        if layer not in ALLOWED:
            continue
        for number, line in enumerate(path.read_text().splitlines(), 1):
            m = INCLUDE.match(line)
            if not m:
                continue
            kind, name = m.groups()
            close = ">" if kind == "<" else '"'
            where = f"{path}:{number}: #include {kind}{name}{close}"
            if kind == '"':
                top = name.split("/")[0]
                if top not in ALLOWED[layer]:
                    print(f"{where}: {layer}/ may include only {', '.join(sorted(ALLOWED[layer]))}/")
                    bad += 1
            elif layer == "kernels" and not kernel_system_include_ok(name):
                print(f"{where}: kernels/ may include only Kokkos, the C++ standard library and kernels/")
                bad += 1
    return bad


if __name__ == "__main__":
    src = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).parent.parent / "src")
    n = check(src)
    print(f"check_layers: {n} wrong include(s) under {src}" if n else f"check_layers: ok ({src})")
    sys.exit(1 if n else 0)
