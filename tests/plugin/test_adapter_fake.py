"""The Rhino adapter's code paths on a stand-in RhinoCommon (fake_rhino): collect blocks from a
document by User Text, write the model, draw a solved result on layers (undoable), clear it,
and the Grasshopper helpers. Checks our logic, not RhinoCommon."""

import json
import sys
import unittest

import _support
import fake_rhino as fr

EXE = _support.solver_executable()


def _obj(doc, geometry, name=None, **user):
    a = fr.ObjectAttributes()
    a.Name = name
    for k, v in user.items():
        a.SetUserString(k.replace("_", ".", 1), v)
    doc.Objects._add(geometry, a)


class AdapterTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        fr.install()
        from rbla_rhino import document, gh  # noqa: F401  (imported with the stubs)
        cls.document = document
        cls.gh = gh

    @classmethod
    def tearDownClass(cls):
        fr.uninstall()

    def make_doc(self, unit="Meters", k=1.0, flip=False):
        doc = fr.Doc(unit)
        _obj(doc, fr.mesh_box(-1 * k, 2 * k, -1 * k, 2 * k, -0.5 * k, 0), "base",
             rbla_role="fixed")
        m = fr.mesh_box(-0.5 * k, 0.5 * k, -0.5 * k, 0.5 * k, 0, 2 * k)
        if flip:
            m.Flip(True, True, True)
        _obj(doc, m, "block", rbla_unit_weight="18")
        return doc

    def test_collect(self):
        doc = self.make_doc(flip=True)   # an inward mesh is turned outward
        doc.Strings.SetString("rbla.default_friction", "0.6")
        col = self.document.collect_model(doc)
        self.assertEqual(col.issues, [])
        model = col.builder.to_dict()
        self.assertEqual([b["id"] for b in model["blocks"]], ["base", "block"])
        self.assertEqual(model["blocks"][0]["role"], "fixed")
        self.assertAlmostEqual(model["blocks"][1]["volume"], 2.0)
        self.assertEqual(model["defaults"]["friction"], 0.6)
        self.assertEqual(model["analysis"]["seismic"]["direction"], [1.0, 0.0, 0.0])

    def test_collect_reports_bad_objects_by_name(self):
        doc = self.make_doc()
        _obj(doc, fr.mesh_box(5, 6, 5, 6, 0, 1), "Stone 7", rbla_role="floating")
        _obj(doc, fr.mesh_box(5, 6, 5, 6, 1, 2), "block")   # name used twice -> GUID ids
        col = self.document.collect_model(doc)
        self.assertEqual(len(col.issues), 1)
        self.assertIn('object "Stone 7": rbla.role', col.issues[0])
        self.assertEqual(col.model, None)
        self.assertIn("duplicate_name", [m.code for m in col.messages])
        doc.Strings.SetString("rbla.analysis", "wind")
        col = self.document.collect_model(doc)
        self.assertIn("rbla.analysis", col.issues[0])

    def test_export_command(self):
        """RblaExport: warnings and every error with their codes; nothing written on an error;
        the model written next to the document otherwise."""
        import os
        import sys
        import tempfile
        from rbla_rhino import commands
        lines = []
        app = sys.modules["Rhino"].RhinoApp
        old, app.WriteLine = app.WriteLine, lines.append
        try:
            doc = self.make_doc()
            _obj(doc, fr.mesh_box(5, 6, 5, 6, 0, 1), "stone", rbla_rol="free")
            doc.Strings.SetString("rbla.seismic_direction", "0, 0, 1")
            with tempfile.TemporaryDirectory() as d:
                doc.Path = os.path.join(d, "vault.3dm")
                self.assertIsNone(commands._export(doc))
                self.assertIn('rbla: warning [unknown_key]: object "stone": unknown key rbla.rol '
                              'ignored; did you mean rbla.role?', lines)
                self.assertIn("  error [not_horizontal]: document: rbla.seismic_direction must "
                              "be perpendicular to gravity (-z), got \"0, 0, 1\"", lines)
                self.assertFalse(os.path.exists(os.path.join(d, "vault_rbla", "model.json")))
                doc.Strings.SetString("rbla.seismic_direction", "0, 1, 0")
                model, path, col = commands._export(doc)
                self.assertEqual(path, os.path.join(d, "vault_rbla", "model.json"))
                with open(path) as f:
                    self.assertEqual(json.load(f), model)
                self.assertEqual(model["title"], "test")
                self.assertEqual(model["analysis"]["seismic"]["direction"], [0.0, 1.0, 0.0])
        finally:
            app.WriteLine = old

    def test_collect_millimetres(self):
        doc = self.make_doc("Millimeters", 1000.0)
        model = self.document.collect_model(doc).builder.to_dict()
        self.assertEqual(model["units"]["length"], "mm")
        self.assertAlmostEqual(model["blocks"][1]["volume"], 2e9)

    @unittest.skipUnless(EXE, "set RBLA_EXE to the rbla executable")
    def test_draw_and_clear(self):
        from rbla_cad.runner import Runner
        doc = self.make_doc()
        model = self.document.collect_model(doc).builder.to_dict()
        res = Runner(EXE).solve(model, verbose=False).result
        self.assertAlmostEqual(res.load_multiplier, 0.5, places=6)
        n_before = len(doc.Objects)
        s = self.document.draw_result(doc, model, res)
        self.assertEqual(s, res.displacement_scale)
        self.assertEqual(doc.undo, ["rbla show mechanism"])
        paths = [l.FullPath for l in doc.Layers]
        for sub in ("Displaced blocks", "Contacts", "Labels"):
            self.assertIn("rbla results::" + sub, paths)
        drawn = doc.Objects[n_before:]
        # 2 block meshes, 1 contact mesh + outline, summary dot + 1 reaction dot
        self.assertEqual(len(drawn), 6)
        block = [o for o in drawn if o.Attributes.Name == "rbla:block"][0]
        c = block.Attributes.ObjectColor
        self.assertEqual((c.R, c.G, c.B), (244, 177, 131))
        dots = [o.Geometry.Text for o in drawn if isinstance(o.Geometry, fr.TextDot)]
        self.assertTrue(any("alpha = 0.5" in t for t in dots))
        self.assertTrue(any("N 36 | T 18 kN" in t for t in dots))
        # redraw replaces, never accumulates
        self.document.draw_result(doc, model, res, amplitude=1.0)
        self.assertEqual(len(doc.Objects), n_before + 6)
        self.assertEqual(self.document.clear_results(doc), 6)
        self.assertEqual(len(doc.Objects), n_before)

    @unittest.skipUnless(EXE, "set RBLA_EXE to the rbla executable")
    def test_grasshopper_helpers(self):
        from rbla_cad.runner import Runner
        doc = self.make_doc()
        model = self.document.collect_model(doc).builder.to_dict()
        res = Runner(EXE).solve(model, verbose=False).result
        out, s = self.gh.mechanism(json.dumps(model), json.dumps(res.data), amplitude=0.0)
        self.assertEqual(s, 0.0)
        self.assertEqual(out["ids"], ["base", "block"])
        self.assertEqual(out["states"], ["hinge"])
        t = out["transforms"][1]
        self.assertEqual((t.M00, t.M03, t.M33), (1.0, 0.0, 1.0))
        # The search components' helpers: the same block tips at 0.5 along its edge normals.
        text, res, log = self.gh.worst_direction(json.dumps(model), exe=EXE)
        self.assertAlmostEqual(res.data["worst_direction"]["load_multiplier"], 0.5, places=6)
        self.assertEqual(json.loads(text)["worst_direction"]["certified"], True)
        text, res, log = self.gh.critical_friction(json.dumps(model), exe=EXE, target_alpha=0.3)
        self.assertEqual(res.data["critical_friction"]["outcome"], "bracketed")
        with open(_support.sample("wall_settlement.json")) as f:
            settling = json.load(f)
        text, res, log = self.gh.worst_settlement(json.dumps(settling), exe=EXE, cone_angle=15)
        self.assertTrue(res.data["worst_settlement"]["certified"])
        self.assertLessEqual(res.data["worst_settlement"]["tilt_deg"], 15.0 + 1e-9)
        text, res, log = self.gh.worst_settlement(json.dumps(settling), exe=EXE, cone_angle=15,
                                                  candidate_groups=["base_moving", "base_fixed", " "])
        self.assertEqual(len(res.data["worst_settlement"]["candidate_groups"]["groups"]), 2)
        # Errors reach the component as runtime messages (a stand-in Grasshopper module here).
        import types
        levels = types.SimpleNamespace(Warning="warning", Error="error")
        fake_gh = types.SimpleNamespace(Kernel=types.SimpleNamespace(GH_RuntimeMessageLevel=levels))
        messages = []
        component = types.SimpleNamespace(AddRuntimeMessage=lambda level, text: messages.append((level, text)))
        saved = sys.modules.get("Grasshopper")
        sys.modules["Grasshopper"] = fake_gh
        try:
            from rbla_cad import runner as rrun
            lines = self.gh.report_error(component, rrun.CancelledError("cancelled\nby Esc"))
            self.gh.report_error(component, rrun.SolverFailureError("failed", 3, ""))
        finally:
            if saved is None:
                del sys.modules["Grasshopper"]
            else:
                sys.modules["Grasshopper"] = saved
        self.assertEqual(lines, ["cancelled", "by Esc"])
        self.assertEqual([level for level, _ in messages], ["warning", "error"])
        labels, colours, hexes, keys = self.gh.legend()
        self.assertEqual(len(labels), 8)
        self.assertEqual(hexes[1], "#d62728")


if __name__ == "__main__":
    unittest.main()
