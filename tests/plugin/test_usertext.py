"""User Text conventions (the Rhino adapter's attribute keys), parsed without Rhino."""

import unittest

import _support  # noqa: F401
from rbla_cad import usertext as ut
from rbla_cad.model import ModelBuilder, ModelError, box


class BlockKeysTest(unittest.TestCase):
    def test_defaults(self):
        a = ut.block_attributes({}, name="Wall 1", layer="Walls")
        self.assertEqual(a, {"role": "free", "unit_weight": None, "friction": None,
                             "label": "Wall 1", "id": None, "ignore": False})
        self.assertEqual(ut.block_attributes({}, layer="Walls::South")["label"], "Walls::South")

    def test_values_and_case(self):
        a = ut.block_attributes({"RBLA.Role": " Fixed ", "rbla.unit_weight": "20",
                                 "rbla.friction": "0,5", "rbla.label": "pier",
                                 "rbla.id": "P1", "other": "x"})
        self.assertEqual((a["role"], a["unit_weight"], a["friction"], a["label"], a["id"]),
                         ("fixed", 20.0, 0.5, "pier", "P1"))
        self.assertEqual(ut.block_attributes({"rbla.role": "moving support"})["role"],
                         "moving_support")
        self.assertTrue(ut.block_attributes({"rbla.ignore": "yes"})["ignore"])

    def test_errors_name_the_object(self):
        with self.assertRaises(ModelError) as cm:
            ut.block_attributes({"rbla.role": "floating"}, name="Stone 7")
        self.assertIn("'Stone 7'", str(cm.exception))
        self.assertIn("rbla.role", str(cm.exception))
        with self.assertRaises(ModelError) as cm:
            ut.block_attributes({"rbla.unit_weight": "heavy"}, name="Stone 8")
        self.assertIn("'Stone 8'", str(cm.exception))
        with self.assertRaises(ModelError):
            ut.block_attributes({"rbla.friction": "0"})


class OtherKeysTest(unittest.TestCase):
    def test_interface(self):
        self.assertTrue(ut.is_interface({"rbla.interface": ""}))
        a = ut.interface_attributes({"rbla.interface": "", "rbla.blocks": "A; B",
                                     "rbla.friction": "0.4"}, name="joint 3")
        self.assertEqual(a, {"label": "joint 3", "blocks": ["A", "B"], "friction": 0.4})
        with self.assertRaises(ModelError):
            ut.interface_attributes({"rbla.interface": "j", "rbla.blocks": "A"})

    def test_load(self):
        a = ut.load_attributes({"rbla.load": "live", "rbla.force": "[1, 0, -2]"})
        self.assertEqual(a["force"], [1.0, 0.0, -2.0])
        self.assertIsNone(a["block"])
        with self.assertRaises(ModelError):
            ut.load_attributes({"rbla.load": "wind", "rbla.force": "1,0,0"})
        with self.assertRaises(ModelError):
            ut.load_attributes({"rbla.load": "dead"})

    def test_document_settings_and_apply(self):
        s = ut.document_settings({})
        self.assertEqual((s["analysis"], s["seismic_direction"], s["force_unit"]),
                         ("seismic", [1.0, 0.0, 0.0], "kN"))
        s = ut.document_settings({"rbla.analysis": "settlement", "rbla.cone": "exact",
                                  "rbla.settlement_direction": "0 0 -1",
                                  "rbla.friction_model": "non_associative",
                                  "rbla.time_limit": "30", "rbla.force_unit": "N"})
        mb = ModelBuilder(force=s["force_unit"])
        mb.add_block("L", *box(0, 1, 0, 1, -0.5, 0), role="fixed")
        mb.add_block("R", *box(1.01, 2, 0, 1, -0.5, 0), role="moving_support")
        mb.add_block("W", *box(0, 2, 0, 1, 0, 1))
        ut.apply_settings(mb, s)
        doc = mb.to_dict()
        self.assertEqual(doc["analysis"]["type"], "settlement")
        self.assertEqual(doc["analysis"]["friction_model"], "non_associative")
        self.assertEqual(doc["analysis"]["time_limit"], 30.0)
        self.assertEqual(doc["units"]["force"], "N")
        with self.assertRaises(ModelError) as cm:
            ut.document_settings({"rbla.analysis": "wind"})
        self.assertIn("rbla.analysis", str(cm.exception))
        with self.assertRaises(ModelError):
            ut.document_settings({"rbla.seismic_direction": "1, 0"})


if __name__ == "__main__":
    unittest.main()
