"""ModelBuilder: building, units, checks (bad blocks named in the errors), schema validation."""

import json
import os
import stat
import tempfile
import unittest

import _support  # noqa: F401
from rbla_cad import geometry, jsonschema_lite
from rbla_cad.model import (ModelBuilder, ModelError, box, block_centroids, check_block_geometry,
                            host_length_unit, force_unit)


def column_builder(n=3, b=0.5, h=0.5, **kw):
    mb = ModelBuilder(**kw)
    v, f = box(-1, 2, -1, 2, -0.5, 0)
    mb.add_block("base", v, f, role="fixed")
    for i in range(n):
        v, f = box(0, b, 0, b, i * h, (i + 1) * h)
        mb.add_block("B%d" % i, v, f)
    mb.set_seismic([1, 0, 0])
    return mb


class GeometryTest(unittest.TestCase):
    def test_box_volume_centroid(self):
        v, f = box(0, 1, 0, 2, 0, 3)
        vol, c = geometry.volume_centroid(v, f)
        self.assertAlmostEqual(vol, 6.0)
        for a, b in zip(c, (0.5, 1.0, 1.5)):
            self.assertAlmostEqual(a, b)

    def test_tetrahedron_and_non_convex_prism(self):
        v = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]]
        f = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]]
        vol, c = check_block_geometry("tet", v, f)
        self.assertAlmostEqual(vol, 1.0 / 6.0)
        for a in c:
            self.assertAlmostEqual(a, 0.25)
        # L-shaped prism (non-convex faces), area 3 x height 2
        pts = [(0, 0), (2, 0), (2, 1), (1, 1), (1, 2), (0, 2)]
        n = len(pts)
        v = [[x, y, 0] for x, y in pts] + [[x, y, 2] for x, y in pts]
        f = [list(reversed(range(n))), [n + j for j in range(n)]]
        for j in range(n):
            k = (j + 1) % n
            f.append([j, k, n + k, n + j])
        vol, c = check_block_geometry("L", v, f)
        self.assertAlmostEqual(vol, 6.0)
        self.assertAlmostEqual(c[2], 1.0)
        self.assertAlmostEqual(c[0], (2 * 1.0 + 1 * 0.5) / 3)
        self.assertAlmostEqual(c[1], (2 * 0.5 + 1 * 1.5) / 3)

    def test_polygon_centroid(self):
        c = geometry.polygon_centroid([(0, 0, 0), (2, 0, 0), (2, 1, 0), (0, 1, 0)])
        self.assertAlmostEqual(c[0], 1.0)
        self.assertAlmostEqual(c[1], 0.5)


class BuildTest(unittest.TestCase):
    def test_column_document(self):
        mb = column_builder(title="column")
        doc = mb.to_dict()
        self.assertEqual(doc["schema_version"], "1.0.0")
        self.assertEqual(doc["units"], {"length": "m", "force": "kN", "unit_weight": "kN/m3"})
        self.assertEqual([b["id"] for b in doc["blocks"]], ["base", "B0", "B1", "B2"])
        self.assertEqual(doc["blocks"][0]["role"], "fixed")
        self.assertAlmostEqual(doc["blocks"][2]["volume"], 0.125)
        self.assertAlmostEqual(doc["blocks"][2]["centroid"][2], 0.75)
        self.assertEqual(doc["analysis"], {"type": "load_multiplier",
                                           "seismic": {"direction": [1.0, 0.0, 0.0]}})
        self.assertNotIn("interfaces", doc)
        self.assertEqual(jsonschema_lite.validate_model(doc), [])

    def test_given_centroid_volume_kept(self):
        mb = ModelBuilder()
        v, f = box(0, 1, 0, 1, 0, 1)
        b = mb.add_block("A", v, f, centroid=[0.5, 0.5, 0.5], volume=1.0, unit_weight=20,
                         label="Layer::A")
        self.assertEqual(b["centroid"], [0.5, 0.5, 0.5])
        self.assertEqual(b["volume"], 1.0)
        self.assertEqual(b["unit_weight"], 20.0)
        self.assertEqual(b["label"], "Layer::A")

    def test_write_and_reload(self):
        mb = column_builder()
        with tempfile.TemporaryDirectory() as d:
            p = mb.write(os.path.join(d, "m.json"))
            with open(p) as f:
                doc = json.load(f)
        self.assertEqual(len(doc["blocks"]), 4)
        self.assertEqual(block_centroids(doc)["B0"][2], 0.25)

    def test_write_follows_the_solvers_rules_for_outputs(self):
        # one place for them (rbla_cad.safe_files): permission bits kept, a link's target written,
        # a folder refused with an OSError naming it and no temporary file left
        mb = column_builder()
        with tempfile.TemporaryDirectory() as d:
            target = os.path.join(d, "target.json")
            with open(target, "w") as f:
                f.write("old\n")
            os.chmod(target, 0o640)
            os.symlink("target.json", os.path.join(d, "link.json"))
            self.assertEqual(mb.write(os.path.join(d, "link.json")), os.path.join(d, "link.json"))
            self.assertTrue(os.path.islink(os.path.join(d, "link.json")))
            self.assertEqual(stat.S_IMODE(os.stat(target).st_mode), 0o640)
            with open(target) as f:
                self.assertEqual(len(json.load(f)["blocks"]), 4)
            folder = os.path.join(d, "folder")
            os.mkdir(folder)
            with self.assertRaises(OSError) as ctx:
                mb.write(folder)
            self.assertIn(folder, str(ctx.exception))
            self.assertEqual(sorted(os.listdir(d)), ["folder", "link.json", "target.json"])

    def test_interfaces_labels_and_friction(self):
        mb = column_builder(default_friction=0.7)
        mb.add_block("top", *box(0, 0.5, 0, 0.5, 1.5, 2.0), friction=0.4)
        mb.add_interface(["B2", "top"], [[0, 0, 1.5], [0.5, 0, 1.5], [0.5, 0.5, 1.5],
                                         [0, 0.5, 1.5]], label="mortar joint")
        mb.add_interface(["B1", "B2"], [[0, 0, 1], [0.5, 0, 1], [0.5, 0.5, 1]], id="J1",
                         friction=0.3)
        mb.add_interface(["B0", "B1"], [[0, 0, 0.5], [0.5, 0, 0.5], [0.5, 0.5, 0.5]])
        doc = mb.to_dict()
        self.assertEqual(doc["detection"], {"mode": "merge"})
        self.assertEqual(doc["interfaces"][0]["friction"], 0.4)   # min of the blocks given
        self.assertEqual(doc["interfaces"][0]["label"], "mortar joint")
        self.assertEqual(doc["interfaces"][1]["friction"], 0.3)
        # the detected interfaces take the smallest block value (the model has one friction
        # for them); a given interface between blocks without one keeps the model default
        self.assertEqual(doc["defaults"]["friction"], 0.4)
        self.assertEqual(doc["interfaces"][2]["friction"], 0.7)
        self.assertTrue(any(w.startswith("friction:") for w in mb.warnings))
        mb.set_detection(mode="off")     # no detected interfaces: the default stays
        doc = mb.to_dict()
        self.assertEqual(doc["defaults"]["friction"], 0.7)
        self.assertNotIn("friction", doc["interfaces"][2])
        self.assertFalse(any(w.startswith("friction:") for w in mb.warnings))

    def test_settlement_and_live_loads(self):
        mb = ModelBuilder()
        mb.add_block("L", *box(0, 1, 0, 1, -0.5, 0), role="fixed")
        mb.add_block("R", *box(1.01, 2, 0, 1, -0.5, 0))
        mb.add_block("W", *box(0, 2, 0, 1, 0, 1))
        mb.set_settlement(moving=["R"], direction=[0, 0, -1])
        mb.set_analysis(friction_model="non_associative", cone="pyramid_inscribed",
                        pyramid_faces=8, formulation="3d", time_limit=10,
                        non_associative={"max_iterations": 20, "damping": 0.5, "trajectories": 3})
        doc = mb.to_dict()
        self.assertEqual(doc["blocks"][1]["role"], "moving_support")
        self.assertEqual(doc["analysis"]["type"], "settlement")
        self.assertEqual(doc["analysis"]["settlement"]["direction"], [0.0, 0.0, -1.0])
        self.assertEqual(doc["analysis"]["non_associative"]["max_iterations"], 20)
        self.assertEqual(doc["analysis"]["non_associative"]["trajectories"], 3)
        with self.assertRaises(ModelError):
            mb.set_analysis(non_associative={"trajectories": 7})
        mb2 = column_builder()
        mb2.add_live_load("B2", force=[1, 0, 0], point=[0.25, 0.25, 1.5])
        mb2.add_dead_load("B1", force=[0, 0, -2])
        mb2.set_load_multiplier()
        doc = mb2.to_dict()
        self.assertEqual(doc["loads"]["live"][0]["block"], "B2")
        self.assertEqual(doc["loads"]["dead"][0]["force"], [0.0, 0.0, -2.0])


class UnitsTest(unittest.TestCase):
    def test_host_units(self):
        self.assertEqual(host_length_unit("Millimeters"), ("mm", 1.0))
        self.assertEqual(host_length_unit("UnitSystem.Meters"), ("m", 1.0))
        self.assertEqual(host_length_unit("cm"), ("cm", 1.0))
        self.assertEqual(host_length_unit("Inches"), ("mm", 25.4))
        self.assertEqual(force_unit("newtons"), "N")
        self.assertEqual(force_unit("kN"), "kN")
        self.assertEqual(host_length_unit("Microns"), ("mm", 0.001))
        self.assertEqual(host_length_unit("feet"), ("mm", 304.8))
        with self.assertRaises(ModelError) as cm:
            host_length_unit("Parsecs")
        self.assertEqual(cm.exception.pointer, "/units/length")
        with self.assertRaises(ModelError):
            force_unit("lbf")
        with self.assertRaises(ModelError):
            ModelBuilder(unit_weight_unit="kg/m3")

    def test_millimetre_model_and_inch_scaling(self):
        mb = ModelBuilder(length="mm", force="N", unit_weight_unit="kN/m3")
        mb.add_block("base", *box(-1000, 2000, -1000, 2000, -500, 0), role="fixed")
        mb.add_block("B", *box(0, 1000, 0, 1000, 0, 2000))
        doc = mb.to_dict()
        self.assertEqual(doc["units"], {"length": "mm", "force": "N", "unit_weight": "kN/m3"})
        self.assertAlmostEqual(doc["blocks"][1]["volume"], 2e9)
        mi = ModelBuilder(length="Inches")
        self.assertEqual((mi.length, mi.length_scale), ("mm", 25.4))
        b = mi.add_block("A", *box(0, 1, 0, 1, 0, 1))
        self.assertAlmostEqual(b["vertices"][6][0], 25.4)
        self.assertAlmostEqual(b["volume"], 25.4 ** 3)


class CheckTest(unittest.TestCase):
    def assertBlockError(self, fn, block_id, words, pointer=None):
        with self.assertRaises(ModelError) as cm:
            fn()
        e = cm.exception
        self.assertEqual(e.block_id, block_id)
        self.assertIn(repr(block_id), str(e))
        self.assertIn(words, str(e))
        if pointer is not None:
            self.assertEqual(e.pointer, pointer)
        return e

    def test_duplicate_id(self):
        mb = ModelBuilder()
        mb.add_block("A", *box(0, 1, 0, 1, 0, 1))
        self.assertBlockError(lambda: mb.add_block("A", *box(0, 1, 0, 1, 1, 2)), "A",
                              "used twice", "/blocks/1/id")

    def test_bad_index(self):
        v, f = box(0, 1, 0, 1, 0, 1)
        f[2] = [0, 1, 9, 4]
        self.assertBlockError(lambda: ModelBuilder().add_block("W1", v, f), "W1",
                              "refers to vertex 9", "/blocks/0/faces/2/2")

    def test_inverted(self):
        v, f = box(0, 1, 0, 1, 0, 1)
        f = [list(reversed(x)) for x in f]
        self.assertBlockError(lambda: ModelBuilder().add_block("inv", v, f), "inv", "inverted")

    def test_open(self):
        v, f = box(0, 1, 0, 1, 0, 1)
        self.assertBlockError(lambda: ModelBuilder().add_block("open", v, f[:-1]), "open",
                              "not closed")

    def test_one_face_flipped(self):
        v, f = box(0, 1, 0, 1, 0, 1)
        f[1] = list(reversed(f[1]))
        self.assertBlockError(lambda: ModelBuilder().add_block("flip", v, f), "flip",
                              "not closed")

    def test_inconsistent_orientation_balanced(self):
        # a face given twice, once each way: the areas balance, the edges do not
        v, f = box(0, 1, 0, 1, 0, 1)
        f2 = f + [f[0], list(reversed(f[0]))]
        self.assertBlockError(lambda: ModelBuilder().add_block("dup", v, f2), "dup",
                              "inconsistently oriented")

    def test_flat_and_degenerate(self):
        v = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]
        f = [[0, 1, 2, 3], [3, 2, 1, 0], [0, 1, 2], [2, 1, 0]]
        with self.assertRaises(ModelError) as cm:
            ModelBuilder().add_block("flat", v, f)
        self.assertEqual(cm.exception.block_id, "flat")
        v, f = box(0, 1, 0, 1, 0, 1)
        f[0] = [0, 0, 3]
        self.assertBlockError(lambda: ModelBuilder().add_block("deg", v, f), "deg",
                              "fewer than 3 distinct")

    def test_bad_role_and_unit_weight(self):
        v, f = box(0, 1, 0, 1, 0, 1)
        self.assertBlockError(lambda: ModelBuilder().add_block("R", v, f, role="support"), "R",
                              "role must be")
        self.assertBlockError(lambda: ModelBuilder().add_block("U", v, f, unit_weight=-1), "U",
                              "unit weight")

    def test_duplicated_vertices_accepted(self):
        # a mesh export: every face has its own vertices (24 vertices, unwelded)
        v, f = box(0, 1, 0, 1, 0, 1)
        v2, f2 = [], []
        for face in f:
            f2.append([len(v2) + k for k in range(len(face))])
            v2.extend(v[i] for i in face)
        b = ModelBuilder().add_block("mesh", v2, f2)
        self.assertAlmostEqual(b["volume"], 1.0)

    def test_model_level_checks(self):
        mb = ModelBuilder()
        mb.add_block("A", *box(0, 1, 0, 1, 0, 1))
        mb.add_interface(["A", "ghost"], [[0, 0, 1], [1, 0, 1], [1, 1, 1]])
        mb.add_live_load("nobody", force=[1, 0, 0])
        with self.assertRaises(ModelError) as cm:
            mb.to_dict()
        text = str(cm.exception)
        self.assertIn("no support", text)
        self.assertIn("'ghost'", text)
        self.assertIn("'nobody'", text)
        self.assertEqual(len(cm.exception.issues), 3)

    def test_moving_support_held_in_load_multiplier(self):
        mb = column_builder()
        mb.add_block("M", *box(3, 4, 0, 1, -0.5, 0), role="moving_support")
        mb.to_dict()
        self.assertTrue(any(w.startswith("role:") and "'M'" not in w and "M" in w
                            for w in mb.warnings))
        mb2 = ModelBuilder()
        mb2.add_block("F", *box(0, 1, 0, 1, -1, 0), role="fixed")
        mb2.add_block("A", *box(0, 1, 0, 1, 0, 1))
        mb2.set_settlement()
        with self.assertRaises(ModelError) as cm:
            mb2.to_dict()
        self.assertIn("moving_support", str(cm.exception))

    def test_schema_validator_catches(self):
        doc = column_builder().to_dict()
        doc["blocks"][1]["role"] = "bogus"
        doc["analysis"]["cone"] = 3
        doc["extra"] = 1
        errors = jsonschema_lite.validate_model(doc)
        pointers = [p for p, _ in errors]
        self.assertIn("/blocks/1/role", pointers)
        self.assertIn("/analysis/cone", pointers)
        self.assertIn("/extra", pointers)

    def test_samples_pass_schema(self):
        for name in ("block.json", "arch.json", "column.json", "wall_settlement.json"):
            with open(_support.sample(name)) as f:
                self.assertEqual(jsonschema_lite.validate_model(json.load(f)), [], name)

    def test_bundled_schemas_match(self):
        # Byte for byte: the plugin's copy is the schema, not an equivalent rewrite of it.
        for name in ("model.schema.json", "result.schema.json"):
            with open(os.path.join(_support.SCHEMA, name), "rb") as a, \
                    open(os.path.join(_support.PLUGIN, "rbla_cad", "data", name), "rb") as b:
                self.assertEqual(a.read(), b.read(),
                                 "plugin/rbla_cad/data/%s differs from schema/%s: copy it" %
                                 (name, name))


if __name__ == "__main__":
    unittest.main()
