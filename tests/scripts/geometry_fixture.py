#!/usr/bin/env python3
"""Irregular blocks and their volume and centroid by the Python core (plugin/rbla_cad/geometry.py).

Usage: geometry_fixture.py [-o tests/data/geometry/irregular_blocks.json]

Writes the blocks (planar faces, counter-clockwise seen from outside) with the volume and centroid
that rbla_cad.geometry.volume_centroid gives. Three tests read the file: the Python one checks the
file is what this script writes today (tests/plugin/test_geometry_agreement.py), the C++ one
compares the solver's geometry::mass_properties with it (tests/unit/test_geometry_agreement.cpp),
and the JavaScript one the exchange's and viewer's polyhedronMassProps
(tests/web/geometry_agreement.test.mjs): so the three implementations agree on every block.
"""
import argparse
import json
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, os.pardir, os.pardir, "plugin"))
from rbla_cad.geometry import volume_centroid  # noqa: E402

DEFAULT_OUTPUT = os.path.join(HERE, os.pardir, "data", "geometry", "irregular_blocks.json")


def rotation(yaw, pitch, roll):
    cy, sy, cp, sp, cr, sr = (math.cos(yaw), math.sin(yaw), math.cos(pitch), math.sin(pitch),
                              math.cos(roll), math.sin(roll))
    return [[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
            [-sp, cp * sr, cp * cr]]


def moved(vertices, matrix, offset):
    return [[sum(matrix[i][j] * v[j] for j in range(3)) + offset[i] for i in range(3)] for v in vertices]


def prism(outline, height, shear=(0.0, 0.0)):
    """A prism over a counter-clockwise outline in the x-y plane, its top shifted by `shear`."""
    n = len(outline)
    vertices = [[x, y, 0.0] for x, y in outline]
    vertices += [[x + shear[0], y + shear[1], height] for x, y in outline]
    faces = [list(range(n - 1, -1, -1)), list(range(n, 2 * n))]
    faces += [[i, (i + 1) % n, n + (i + 1) % n, n + i] for i in range(n)]
    return vertices, faces


def cut_pyramid():
    """A square pyramid cut by a tilted plane: every face planar, no two faces parallel."""
    base = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [2.0, 1.5, 0.0], [0.0, 1.5, 0.0]]
    apex = [0.7, 0.6, 3.0]
    # the plane z = 1.2 + 0.2 x + 0.1 y cuts each edge base -> apex at t
    top = []
    for b in base:
        d = [apex[i] - b[i] for i in range(3)]
        t = (1.2 + 0.2 * b[0] + 0.1 * b[1] - b[2]) / (d[2] - 0.2 * d[0] - 0.1 * d[1])
        top.append([b[i] + t * d[i] for i in range(3)])
    faces = [[3, 2, 1, 0], [4, 5, 6, 7]] + [[i, (i + 1) % 4, 4 + (i + 1) % 4, 4 + i] for i in range(4)]
    return base + top, faces


def blocks():
    out = []
    # A tetrahedron of no symmetry.
    tet = [[0.1, 0.2, 0.0], [1.3, -0.1, 0.2], [0.4, 1.1, -0.1], [0.5, 0.4, 1.7]]
    out.append(("tetrahedron", tet, [[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]]))
    # A sheared hexahedron far from the origin (round-off of the reference point).
    v, f = prism([(0.0, 0.0), (0.44, 0.0), (0.5, 0.38), (0.06, 0.38)], 0.25, shear=(0.05, -0.02))
    out.append(("sheared_hexahedron_far", moved(v, rotation(0.3, 0.0, 0.0), [1200.0, -850.0, 310.0]), f))
    # A non-convex L-shaped prism, turned about all three axes.
    v, f = prism([(0, 0), (3, 0), (3, 1), (1, 1), (1, 2.5), (0, 2.5)], 0.8)
    out.append(("l_prism_rotated", moved(v, rotation(0.4, -0.7, 1.1), [5.0, 2.0, -1.0]), f))
    # A five-pointed star prism: non-convex caps of ten corners.
    star = []
    for k in range(10):
        r = 1.0 if k % 2 == 0 else 0.45
        a = math.pi / 2 + k * math.pi / 5
        star.append((r * math.cos(a), r * math.sin(a)))
    v, f = prism(star, 0.3)
    out.append(("star_prism", moved(v, rotation(-0.2, 0.5, 0.3), [0.0, 0.0, 0.0]), f))
    # A square pyramid cut by a tilted plane.
    v, f = cut_pyramid()
    out.append(("cut_pyramid", v, f))
    # A voussoir: a ring segment between radii 4.6 and 5.4 over 11.25 degrees, 1 m deep along y.
    a0, a1 = math.radians(33.75), math.radians(45.0)
    ring = [(r * math.cos(a), r * math.sin(a)) for r, a in ((4.6, a0), (5.4, a0), (5.4, a1), (4.6, a1))]
    v = [[x, 0.0, z] for x, z in ring] + [[x, 1.0, z] for x, z in ring]
    f = [[0, 1, 2, 3], [7, 6, 5, 4], [0, 4, 5, 1], [1, 5, 6, 2], [2, 6, 7, 3], [3, 7, 4, 0]]
    out.append(("voussoir", v, f))
    return out


def fixture():
    entries = []
    for name, vertices, faces in blocks():
        volume, centroid = volume_centroid(vertices, faces)
        entries.append({"id": name, "vertices": vertices, "faces": faces,
                        "volume": volume, "centroid": list(centroid)})
    return {"description": "Irregular blocks with the volume and centroid of plugin/rbla_cad/geometry.py; "
                           "written by tests/scripts/geometry_fixture.py.",
            "blocks": entries}


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("-o", "--output", default=DEFAULT_OUTPUT)
    args = parser.parse_args(argv)
    with open(args.output, "w") as out:
        json.dump(fixture(), out, indent=1)
        out.write("\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
