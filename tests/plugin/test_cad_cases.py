"""The shared CAD cases (cad_cases/cases.json) through the Python side: the host-independent
reader on plain records, and the Rhino adapter on a stand-in RhinoCommon document built from the
same cases. Both must give what each case expects (codes, texts, model parts, and alpha from a
closed form when the solver is there), and the adapter exactly what the reader gives. The web
suite runs the same cases through the .3dm exchange and compares it with this reader."""

import math
import os
import sys
import unittest

import _support
import fake_rhino as fr

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "cad_cases"))
import records  # noqa: E402

EXE = _support.solver_executable()
CASES = records.load_cases()


def polygon_area(pts):
    from rbla_cad import polygons
    return polygons.unit_normal(pts)[1]


def match(test, want, got, where):
    """got contains want: dicts key by key, lists element by element (same length), numbers
    to 1e-9; {"$polygon": {corners, area}} checks an interface polygon."""
    if isinstance(want, dict):
        test.assertIsInstance(got, dict, where)
        for k, v in want.items():
            if k == "$polygon":
                poly = got["polygon"]
                test.assertEqual(len(poly), v["corners"], where + "/polygon corners")
                test.assertTrue(math.isclose(polygon_area(poly), v["area"],
                                             rel_tol=v.get("area_rel", 1e-9)),
                                "%s/polygon area %r" % (where, polygon_area(poly)))
                continue
            if k == "vertices":   # the first vertices given
                for j, p in enumerate(v):
                    match(test, p, got[k][j], "%s/%s/%d" % (where, k, j))
                continue
            test.assertIn(k, got, where)
            match(test, v, got[k], "%s/%s" % (where, k))
    elif isinstance(want, list):
        test.assertEqual(len(got), len(want), where + " (length)")
        for j, (a, b) in enumerate(zip(want, got)):
            match(test, a, b, "%s/%d" % (where, j))
    elif isinstance(want, (int, float)) and not isinstance(want, bool):
        test.assertTrue(math.isclose(got, want, rel_tol=1e-9, abs_tol=1e-12),
                        "%s: %r != %r" % (where, got, want))
    else:
        test.assertEqual(got, want, where)


def check_expectation(test, case, model, messages):
    e = case["expect"]
    codes = lambda sev: [m["code"] for m in messages if m["severity"] == sev]  # noqa: E731
    test.assertEqual(codes("error"), e["errors"], [m["text"] for m in messages])
    test.assertEqual(codes("warning"), e["warnings"], [m["text"] for m in messages])
    texts = [m["text"] for m in messages]
    for t in e.get("texts", []):
        test.assertIn(t, texts)
    if e["errors"]:
        test.assertIsNone(model)
    else:
        test.assertIsNotNone(model)
        match(test, e.get("model", {}), model, "model")


def fake_document(case):
    """A stand-in Rhino document with the case's objects (blocks and open pieces as meshes,
    curves as polyline curves, points as point objects)."""
    d = case["document"]
    doc = fr.Doc(d["units"])
    doc.ModelAbsoluteTolerance = d["tolerance"]
    doc.Name = d.get("name")
    for k, v in d.get("user_text", {}).items():
        doc.Strings.SetString(k, v)
    for i, o in enumerate(case["objects"]):
        a = fr.ObjectAttributes()
        a.Name = o.get("name")
        for k, v in o.get("user_text", {}).items():
            a.SetUserString(k, v)
        layer = o.get("layer", "Default")
        idx = doc.Layers.FindByFullPath(layer, -1)
        if idx < 0:
            lay = fr.Layer()
            lay.Name = lay.FullPath = layer
            doc.Layers.append(lay)
            idx = len(doc.Layers) - 1
        a.LayerIndex = idx
        if "box" in o:
            g = fr.mesh_box(*o["box"])
        elif "solid" in o:
            g = fr.mesh_of(o["solid"]["vertices"], o["solid"]["faces"])
        elif "pieces" in o and o["as"] == "curve":
            g = fr.PolylineCurve(o["pieces"][0] + [o["pieces"][0][0]])
        elif "pieces" in o:
            verts, faces = [], []
            for piece in o["pieces"]:
                faces.append(list(range(len(verts), len(verts) + len(piece))))
                verts.extend(piece)
            g = fr.mesh_of(verts, faces)
        else:
            g = fr.Point(*o["point"])
        doc.Objects._add(g, a, "guid-%d" % i)
        doc.Objects[-1].IsHidden = bool(o.get("hidden"))
    return doc


class ReaderCasesTest(unittest.TestCase):
    """The Python reader on the records of every case."""

    def test_cases(self):
        self.assertGreaterEqual(len(CASES), 30)
        for case in CASES:
            with self.subTest(case=case["name"]):
                out = records.run(case)
                check_expectation(self, case, out["model"], out["messages"])

    @unittest.skipUnless(EXE, "set RBLA_EXE to the rbla executable")
    def test_alpha_from_closed_forms(self):
        from rbla_cad.runner import Runner
        solved = 0
        for case in CASES:
            if "alpha" not in case["expect"]:
                continue
            with self.subTest(case=case["name"]):
                res = Runner(EXE).solve(records.run(case)["model"], verbose=False).result
                self.assertTrue(math.isclose(res.load_multiplier, case["expect"]["alpha"],
                                             rel_tol=case["expect"].get("alpha_rel", 1e-5)),
                                res.load_multiplier)
                solved += 1
        self.assertGreaterEqual(solved, 9)


class AdapterCasesTest(unittest.TestCase):
    """The Rhino adapter (stand-in RhinoCommon) gives what the reader gives on every case."""

    @classmethod
    def setUpClass(cls):
        fr.install()
        from rbla_rhino import document
        cls.document = document

    @classmethod
    def tearDownClass(cls):
        fr.uninstall()

    def test_adapter_equals_reader(self):
        for case in CASES:
            with self.subTest(case=case["name"]):
                want = records.run(case)
                col = self.document.collect_model(fake_document(case))
                got = [m.as_dict() for m in col.messages]
                self.assertEqual(got, want["messages"])
                if want["model"] is None:
                    self.assertIsNone(col.model)
                else:
                    match(self, want["model"], col.model, "model")


if __name__ == "__main__":
    unittest.main()
