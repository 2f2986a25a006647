"""Interface pieces merged into one polygon, and points near blocks (rbla_cad.polygons), on
inputs made the way CAD exports make them: fine triangulations with random diagonals,
T-junctions, pieces in random order and orientation, rotated and tilted planes, noise, and
millimetre coordinates. Expectations are geometric facts (the union's corner count and area),
not earlier output. The JS twin (plugin/exchange/lib/cad-geometry.mjs) is held equal to this one
by the shared cases (tests/web/cad_cases.test.mjs)."""

import math
import random
import unittest

import _support  # noqa: F401
from rbla_cad import polygons
from rbla_cad.model import box


def rotation(rnd):
    """A random rotation matrix (from a random unit quaternion)."""
    q = [rnd.gauss(0, 1) for _ in range(4)]
    n = math.sqrt(sum(x * x for x in q))
    w, x, y, z = (c / n for c in q)
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]


def apply(R, p, shift=(0.0, 0.0, 0.0)):
    return [sum(R[i][k] * p[k] for k in range(3)) + shift[i] for i in range(3)]


def grid_triangles(cells, h, rnd):
    """Triangles of the unit cells (i, j) of size h, each split along a random diagonal."""
    out = []
    for i, j in cells:
        a, b = [i * h, j * h, 0.0], [(i + 1) * h, j * h, 0.0]
        c, d = [(i + 1) * h, (j + 1) * h, 0.0], [i * h, (j + 1) * h, 0.0]
        out += [[a, b, c], [a, c, d]] if rnd.random() < 0.5 else [[a, b, d], [b, c, d]]
    return out


def area(poly):
    return polygons.unit_normal(poly)[1]


class MergeTest(unittest.TestCase):
    def check_shape(self, cells, corners, seed, scale=1.0, noise=0.0, tol=1e-6):
        rnd = random.Random(seed)
        h = 0.25 * scale
        pieces = grid_triangles(cells, h, rnd)
        rnd.shuffle(pieces)
        pieces = [p if rnd.random() < 0.5 else list(reversed(p)) for p in pieces]
        R, shift = rotation(rnd), [rnd.uniform(-10, 10) * scale for _ in range(3)]
        moved = {}

        def jitter(p):
            key = tuple(p)
            if key not in moved:
                moved[key] = [c + rnd.uniform(-noise, noise) for c in apply(R, p, shift)]
            return moved[key]
        pieces = [[jitter(p) for p in piece] for piece in pieces]
        groups = polygons.merge_coplanar(pieces, tol, 0.005)
        self.assertEqual(len(groups), 1, "seed %d" % seed)
        g = groups[0]
        self.assertFalse(g["hull"])
        self.assertEqual(sorted(g["pieces"]), list(range(len(pieces))))
        self.assertEqual(len(g["polygon"]), corners, "seed %d" % seed)
        want = len(cells) * h * h
        # noise moves each corner by at most noise * sqrt(3); the area by at most that times
        # the perimeter
        slack = 1e-9 * want + 4 * noise * math.sqrt(3) * 4 * math.sqrt(len(cells)) * h
        self.assertLess(abs(area(g["polygon"]) - want), slack, "seed %d" % seed)
        n, _ = polygons.unit_normal(g["polygon"])
        for p in g["polygon"]:   # the outline lies on one plane
            self.assertLess(abs(sum((p[k] - g["polygon"][0][k]) * n[k] for k in range(3))),
                            1e-9 * scale)

    def test_rectangle_triangulated(self):
        cells = [(i, j) for i in range(4) for j in range(2)]
        for seed in range(20):
            self.check_shape(cells, 4, seed)

    def test_l_shape_is_not_its_hull(self):
        cells = [(i, j) for i in range(3) for j in range(3) if not (i > 0 and j > 0)]
        for seed in range(20):
            self.check_shape(cells, 6, seed)

    def test_millimetres_with_export_noise(self):
        cells = [(i, j) for i in range(4) for j in range(2)]
        for seed in range(20):   # 1 m x 0.5 m joint in mm, vertices moved by 0.5 mm
            self.check_shape(cells, 4, 100 + seed, scale=1000.0, noise=0.5, tol=0.01)

    def test_t_junctions(self):
        big = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]
        small = [[[1, 0, 0], [2, 0, 0], [2, 0.5, 0], [1, 0.5, 0]],
                 [[1, 0.5, 0], [2, 0.5, 0], [2, 1, 0], [1, 1, 0]]]
        g = polygons.merge_coplanar([big] + small, 1e-9)
        self.assertEqual(len(g), 1)
        self.assertEqual(len(g[0]["polygon"]), 4)
        self.assertAlmostEqual(area(g[0]["polygon"]), 2.0)

    def test_separate_overlapping_and_bent(self):
        a = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]
        far = [[3, 0, 0], [4, 0, 0], [4, 1, 0], [3, 1, 0]]
        self.assertEqual(len(polygons.merge_coplanar([a, far], 1e-9)), 2)
        lap = [[0.5, 0, 0], [1.5, 0, 0], [1.5, 1, 0], [0.5, 1, 0]]
        g = polygons.merge_coplanar([a, lap], 1e-9)
        self.assertEqual(len(g), 1)
        self.assertTrue(g[0]["hull"])
        self.assertAlmostEqual(area(g[0]["polygon"]), 1.5)
        ring = [[[0, 0, 0], [3, 0, 0], [3, 1, 0], [0, 1, 0]], [[0, 2, 0], [3, 2, 0], [3, 3, 0],
                [0, 3, 0]], [[0, 1, 0], [1, 1, 0], [1, 2, 0], [0, 2, 0]],
                [[2, 1, 0], [3, 1, 0], [3, 2, 0], [2, 2, 0]]]   # a frame with a hole
        g = polygons.merge_coplanar(ring, 1e-9)
        self.assertEqual(len(g), 1)
        self.assertTrue(g[0]["hull"])
        self.assertAlmostEqual(area(g[0]["polygon"]), 9.0)
        wall = [[1, 0, 0], [1, 0, 1], [1, 1, 1], [1, 1, 0]]   # a bed and a head joint
        self.assertEqual(len(polygons.merge_coplanar([a, wall], 1e-9)), 2)

    def test_degenerate_pieces_are_left_out(self):
        a = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]
        sliver = [[0, 0, 0], [1, 0, 0], [2, 0, 0]]
        g = polygons.merge_coplanar([sliver, a], 1e-9)
        self.assertEqual([x["pieces"] for x in g], [[1]])
        self.assertEqual(polygons.merge_coplanar([], 1e-9), [])


class PointsTest(unittest.TestCase):
    def setUp(self):
        # an L-prism (non-convex caps): the square [0, 2]^2 minus [1, 2]^2, height 1
        L = [[0, 0], [2, 0], [2, 1], [1, 1], [1, 2], [0, 2]]
        self.v = [[x, y, 0.0] for x, y in L] + [[x, y, 1.0] for x, y in L]
        self.f = [[5, 4, 3, 2, 1, 0], [6, 7, 8, 9, 10, 11]] + \
            [[k, (k + 1) % 6, (k + 1) % 6 + 6, k + 6] for k in range(6)]

    def test_winding_and_containment(self):
        self.assertAlmostEqual(polygons.winding_number([0.5, 0.5, 0.5], self.v, self.f), 1.0)
        self.assertAlmostEqual(polygons.winding_number([1.5, 1.5, 0.5], self.v, self.f), 0.0)
        self.assertTrue(polygons.contains([1.5, 0.5, 0.5], self.v, self.f, 1e-9))
        self.assertFalse(polygons.contains([1.5, 1.5, 0.5], self.v, self.f, 1e-9))
        self.assertTrue(polygons.contains([1.5, 1.5, 1.0 + 1e-4], self.v, self.f, 0.8))
        self.assertTrue(polygons.contains([0.5, 0.5, 1.0 + 1e-4], self.v, self.f, 1e-3))

    def test_surface_distance_in_the_notch(self):
        # above the notch of the non-convex cap: the nearest surface point is the corner edge
        d = polygons.surface_distance([1.5, 1.5, 1.0], self.v, self.f)
        self.assertAlmostEqual(d, 0.5)
        d = polygons.surface_distance([1.5, 1.5, 2.0], self.v, self.f)
        self.assertAlmostEqual(d, math.sqrt(0.25 + 1.0))
        v, f = box(0, 1, 0, 1, 0, 1)
        self.assertAlmostEqual(polygons.surface_distance([0.5, 0.5, 0.5], v, f), 0.5)
        self.assertAlmostEqual(polygons.surface_distance([2, 0.5, 0.5], v, f), 1.0)


if __name__ == "__main__":
    unittest.main()
