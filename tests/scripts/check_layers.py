#!/usr/bin/env python3
"""Checks that the solver's folders include only downwards.

Usage: check_layers.py REPO_ROOT

The floors, lowest first: model (typed model, no JSON), geometry, analysis, io's reading side
(read, validate and default the model JSON), io's writing side (result JSON, pictures, problem
files, atomic output; the files named in IO_WRITE), app (the command). A file may include headers
of its own floor and the floors below, headers of its own folder by their bare name, and the
public headers under solver/include/rbla/. The conic solver (solver/src/conic and
solver/include/rbla/conic) knows nothing about masonry: it includes only conic headers. Exit 0
when every include follows these rules, 1 with one line per include that does not.
"""
import os
import re
import sys

FLOORS = ["model", "geometry", "analysis", "io_read", "io_write", "app"]
IO_WRITE = {"result_writer", "svg_writer", "problem_file", "detection_json", "warning_summary",
            "atomic_file"}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')


def io_side(filename):
    stem = filename.split(".")[0]
    return "io_write" if stem in IO_WRITE else "io_read"


def floor_of(relpath):
    parts = relpath.split("/")
    if parts[:2] == ["solver", "app"]:
        return "app"
    if parts[:2] == ["solver", "src"] and len(parts) > 3:
        return io_side(parts[-1]) if parts[2] == "io" else parts[2]
    if parts[:3] == ["solver", "include", "rbla"] and len(parts) > 4 and parts[3] == "conic":
        return "conic"
    return None


def allowed(floor, header):
    if "/" not in header:
        return True  # a header of the same folder
    top = header.split("/")[0]
    if floor == "conic":
        return header.startswith("rbla/conic/")
    if top == "rbla":
        return True
    if top == "io":
        top = io_side(header.split("/")[-1])
    if top not in FLOORS:
        return False
    return FLOORS.index(top) <= FLOORS.index(floor)


def main(argv):
    if len(argv) != 2:
        print("usage: check_layers.py REPO_ROOT", file=sys.stderr)
        return 2
    root = argv[1]
    problems = []
    checked = 0
    for base in ("solver/src", "solver/app", "solver/include"):
        for folder, _, files in os.walk(os.path.join(root, base)):
            for name in sorted(files):
                if not name.endswith((".hpp", ".cpp", ".h", ".hpp.in")):
                    continue
                path = os.path.join(folder, name)
                rel = os.path.relpath(path, root).replace(os.sep, "/")
                floor = floor_of(rel)
                if floor is None:
                    continue
                checked += 1
                with open(path, encoding="utf-8") as source:
                    for number, line in enumerate(source, 1):
                        match = INCLUDE.match(line)
                        if match and not allowed(floor, match.group(1)):
                            problems.append(f"{rel}:{number}: {floor} includes \"{match.group(1)}\"")
    for problem in problems:
        print(problem)
    print(f"{checked} files, {len(problems)} upward includes", file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
