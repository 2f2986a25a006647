"""Result reading, rigid-body transforms (exact rotations) and contact-state colours."""

import json
import math
import random
import re
import unittest

import _support
from rbla_cad import result as R
from rbla_cad.result import (apply_transform, block_transform, rotation_matrix, legend,
                             state_colour)


def _dist(a, b):
    return math.sqrt(sum((x - y) ** 2 for x, y in zip(a, b)))


class TransformTest(unittest.TestCase):
    def setUp(self):
        self.rng = random.Random(7)

    def rand(self, scale=1.0):
        return [self.rng.uniform(-scale, scale) for _ in range(3)]

    def test_rotation_is_orthonormal(self):
        for theta in ([0, 0, 0], [1e-9, 0, 0], [1e-5, 2e-5, -3e-5], [0.3, -0.2, 0.9],
                      [0, 0, math.pi], [5.0, -4.0, 2.0]):
            Rm = rotation_matrix(theta)
            for i in range(3):
                for j in range(3):
                    d = sum(Rm[k][i] * Rm[k][j] for k in range(3))
                    self.assertAlmostEqual(d, 1.0 if i == j else 0.0, places=13)
            det = (Rm[0][0] * (Rm[1][1] * Rm[2][2] - Rm[1][2] * Rm[2][1])
                   - Rm[0][1] * (Rm[1][0] * Rm[2][2] - Rm[1][2] * Rm[2][0])
                   + Rm[0][2] * (Rm[1][0] * Rm[2][1] - Rm[1][1] * Rm[2][0]))
            self.assertAlmostEqual(det, 1.0, places=13)

    def test_quarter_turn_about_z(self):
        Rm = rotation_matrix([0, 0, math.pi / 2])
        p = [sum(Rm[i][j] * v for j, v in enumerate((1, 0, 0))) for i in range(3)]
        for a, b in zip(p, (0, 1, 0)):
            self.assertAlmostEqual(a, b, places=14)

    def test_distances_preserved_for_any_amplitude(self):
        g, u, th = self.rand(2), self.rand(), self.rand()
        pts = [self.rand(3) for _ in range(6)]
        for s in (0.1, 1.0, 7.5, 100.0):
            M = block_transform(g, u, th, s)
            q = [apply_transform(M, p) for p in pts]
            for i in range(len(pts)):
                for j in range(i + 1, len(pts)):
                    self.assertAlmostEqual(_dist(q[i], q[j]), _dist(pts[i], pts[j]), places=10)
            # the centroid moves by exactly s u
            gq = apply_transform(M, g)
            for k in range(3):
                self.assertAlmostEqual(gq[k], g[k] + s * u[k], places=10)

    def test_zero_amplitude_is_identity(self):
        M = block_transform(self.rand(), self.rand(), self.rand(), 0.0)
        for i in range(4):
            for j in range(4):
                self.assertAlmostEqual(M[i][j], 1.0 if i == j else 0.0, places=15)

    def test_small_angle_limit_is_virtual_velocity(self):
        g, u, th = self.rand(), self.rand(), self.rand()
        p = self.rand(2)
        r = [p[i] - g[i] for i in range(3)]
        v = [u[0] + th[1] * r[2] - th[2] * r[1], u[1] + th[2] * r[0] - th[0] * r[2],
             u[2] + th[0] * r[1] - th[1] * r[0]]
        for s in (1e-3, 1e-5):
            q = apply_transform(block_transform(g, u, th, s), p)
            for k in range(3):
                # (q - p)/s = v + O(s)
                self.assertAlmostEqual((q[k] - p[k]) / s, v[k], delta=10 * s)

    def test_screw_motion(self):
        g, u, th = self.rand(), self.rand(), self.rand()
        pts = [self.rand(2) for _ in range(4)]
        for s in (1e-6, 0.5, 3.0):
            M = block_transform(g, u, th, s, screw=True)
            q = [apply_transform(M, p) for p in pts]
            self.assertAlmostEqual(_dist(q[0], q[1]), _dist(pts[0], pts[1]), places=10)
        # a pure rotation about an axis through h: h stays fixed for any amplitude
        h = [1.0, 2.0, 0.0]
        th = [0.0, 0.7, 0.2]
        r = [g[i] - h[i] for i in range(3)]
        u = [th[1] * r[2] - th[2] * r[1], th[2] * r[0] - th[0] * r[2],
             th[0] * r[1] - th[1] * r[0]]          # velocity of g = theta x (g - h)
        for s in (0.1, 2.0):
            q = apply_transform(block_transform(g, u, th, s, screw=True), h)
            for k in range(3):
                self.assertAlmostEqual(q[k], h[k], places=12)
        # small amplitude: both modes agree with the virtual velocity to first order
        p = pts[0]
        a = apply_transform(block_transform(g, u, th, 1e-5, screw=True), p)
        b = apply_transform(block_transform(g, u, th, 1e-5), p)
        for k in range(3):
            self.assertAlmostEqual(a[k], b[k], delta=1e-9)

    def test_length_scale(self):
        # drawing in inches, model in mm: translation 25.4 mm draws as 1 inch
        M = block_transform([0, 0, 0], [25.4, 0, 0], [0, 0, 0], 1.0, length_scale=25.4)
        self.assertAlmostEqual(apply_transform(M, [1, 1, 1])[0], 2.0)


class ColourTest(unittest.TestCase):
    def test_colours_match_svg_writer(self):
        with open(_support.REPO + "/solver/src/io/svg_writer.cpp") as f:
            src = f.read()

        def const(name):
            return re.search(name + r'\s*=\s*"#([0-9a-fA-F]{6})"', src).group(1).lower()

        self.assertEqual(R.rgb_hex(state_colour("opening")), "#" + const("kOpeningColour"))
        self.assertEqual(R.rgb_hex(state_colour("sliding")), "#" + const("kSlidingColour"))
        self.assertEqual(R.rgb_hex(state_colour("opening_sliding")),
                         "#" + const("kOpeningSlidingColour"))
        self.assertEqual(R.rgb_hex(state_colour("hinge")), "#" + const("kHingeColour"))
        self.assertEqual(R.rgb_hex(state_colour("closed")), "#" + const("kGhostColour"))
        for key, name in (("moving", "kMovingRgb"), ("resting", "kRestingRgb"),
                          ("support", "kSupportRgb")):
            hexv = re.search(name + r"\s*=\s*0x([0-9a-fA-F]{6})", src).group(1).lower()
            self.assertEqual(R.rgb_hex(R.BLOCK_COLOURS[key]), "#" + hexv)
        self.assertEqual(state_colour("opening"), (214, 39, 40))
        self.assertEqual(state_colour("sliding"), (31, 119, 180))
        with self.assertRaises(ValueError):
            state_colour("melting")

    def test_legend(self):
        items = legend()
        self.assertEqual([i["key"] for i in items],
                         ["closed", "opening", "sliding", "opening_sliding", "hinge",
                          "moving", "resting", "support"])
        self.assertEqual(items[3]["label"], "opening + sliding")
        self.assertEqual(items[4]["hex"], "#ff7f0e")
        self.assertEqual(len(legend(include_closed=False, include_blocks=False)), 4)


class ResultParseTest(unittest.TestCase):
    DOC = {
        "schema_version": "1.1.0", "rbla_version": "0.1.0", "status": "collapse",
        "verdict": "Collapse at load multiplier alpha = 0.5.",
        "units": {"length": "m", "force": "kN"},
        "analysis": {"type": "load_multiplier", "friction_model": "associative",
                     "cone": "exact", "formulation": "3d"},
        "load_multiplier": 0.5, "solver": {"name": "rbla-conic", "status": "solved"},
        "mechanism": {"normalisation": "max_translation", "displacement_scale": 0.2},
        "model_summary": {"num_blocks": 2, "num_free_blocks": 1, "num_fixed_blocks": 1,
                          "num_moving_blocks": 0, "num_interfaces": 1,
                          "num_contact_points": 3, "num_detected_interfaces": 1},
        "blocks": [{"id": "base", "role": "fixed", "translation": [0, 0, 0],
                    "rotation": [0, 0, 0]},
                   {"id": "B", "role": "free", "translation": [1, 0, 0],
                    "rotation": [0, 0.5, 0]}],
        "interfaces": [{"id": "I0", "blocks": ["base", "B"], "normal": [0, 0, 1],
                        "tangents": [[1, 0, 0], [0, 1, 0]], "area": 0.5, "state": "hinge",
                        "cracked": True,
                        "points": [{"position": [0, 0, 0], "normal_force": 0.0,
                                    "shear_force": [0, 0]},
                                   {"position": [1, 0, 0], "normal_force": 10.0,
                                    "shear_force": [-5, 0]},
                                   {"position": [1, 1, 0], "normal_force": 10.0,
                                    "shear_force": [0, 0]}]}],
        "cracked_interfaces": ["I0"], "warnings": [],
    }

    def test_parse(self):
        from rbla_cad import jsonschema_lite
        self.assertEqual(jsonschema_lite.validate_result(self.DOC), [])
        r = R.Result(json.loads(json.dumps(self.DOC)))
        self.assertTrue(r.is_collapse)
        self.assertEqual(r.headline(), "alpha = 0.5000")
        self.assertEqual(r.moving_blocks(), ["B"])
        self.assertEqual(r.interfaces[0].colour, (255, 127, 14))
        self.assertEqual(r.state_counts()["hinge"], 1)
        reac = r.support_reactions()
        self.assertEqual(len(reac), 1)
        self.assertEqual(reac[0]["support"], "base")
        self.assertEqual(reac[0]["force"], (-5.0, 0.0, 20.0))
        self.assertEqual(reac[0]["point"], (1.0, 0.5, 0.0))
        T = r.transforms({"base": (0, 0, 0), "B": (0.5, 0.5, 0.5)})
        self.assertEqual(T["base"], R.identity())
        self.assertAlmostEqual(apply_transform(T["B"], (0.5, 0.5, 0.5))[0], 0.5 + 0.2)
        with self.assertRaises(ValueError):
            R.Result({"no": "status"})

    def test_influential_joints_from_sensitivities(self):
        from rbla_cad import jsonschema_lite
        doc = json.loads(json.dumps(self.DOC))
        self.assertEqual(R.influence_labels(doc), [])
        doc["analysis"]["type"] = "settlement"
        del doc["load_multiplier"]
        doc["base_reaction"] = {"at_collapse": 12.0, "moving_blocks": ["base"]}
        doc["sensitivities"] = {"d_base_reaction_d_friction_factor": -1.5,
                                "interfaces": [{"id": "I0", "d_base_reaction_d_friction": -2.5}],
                                "blocks": [{"id": "B", "d_base_reaction_d_unit_weight": 0.04}]}
        self.assertEqual(jsonschema_lite.validate_result(doc), [])
        r = R.Result(doc)
        self.assertEqual(r.influential_joints(), [("I0", -2.5, "dR/dmu")])
        (point, text), = R.influence_labels(r)
        self.assertEqual(text, "#1 I0: dR/dmu = -2.5 kN")
        self.assertEqual(point, R.geo.polygon_centroid(r.interfaces[0].polygon))
        # Both quantities in one section break the schema's either/or.
        doc["sensitivities"]["d_load_multiplier_d_friction_factor"] = 0.1
        self.assertNotEqual(jsonschema_lite.validate_result(doc), [])


if __name__ == "__main__":
    unittest.main()
