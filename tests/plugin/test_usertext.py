"""Values of CAD attributes (usertext: the convention's value types), parsed without Rhino."""

import unittest

import _support  # noqa: F401
from rbla_cad import usertext as ut
from rbla_cad.model import ModelError


def entry(kind, key):
    return ut.KEYS[kind][key]


class ValuesTest(unittest.TestCase):
    def test_numbers(self):
        e = entry("document", "rbla.default_friction")
        self.assertEqual(ut.parse_value(e, "0.6"), 0.6)
        self.assertEqual(ut.parse_value(e, " 0,45 "), 0.45)      # one decimal comma
        self.assertEqual(ut.parse_value(e, "6e-1"), 0.6)
        for bad in ("0.6 kN", "1,000.5", "inf", "nan", "0x1", "", "1_0", "١"):
            with self.assertRaises(ut.Bad, msg=bad) as cm:
                ut.parse_value(e, bad)
            self.assertEqual(cm.exception.code, "bad_number")
        with self.assertRaises(ut.Bad) as cm:
            ut.parse_value(e, "0")
        self.assertEqual((cm.exception.code, cm.exception.fields["range"]),
                         ("out_of_range", "> 0 and <= 100"))
        with self.assertRaises(ut.Bad) as cm:
            ut.parse_value(entry("document", "rbla.pyramid_faces"), "7.5")
        self.assertEqual(cm.exception.code, "bad_integer")
        self.assertEqual(ut.parse_value(entry("document", "rbla.pyramid_faces"), "8.0"), 8)

    def test_vectors(self):
        e = entry("load", "rbla.force")
        for text in ("1, 0, -2", "1 0 -2", "[1, 0, -2]", "(1,0,-2)", "1; 0; -2"):
            self.assertEqual(ut.parse_value(e, text), [1.0, 0.0, -2.0], text)
        self.assertEqual(ut.parse_value(e, "0,5; 1; 0"), [0.5, 1.0, 0.0])
        for bad in ("1, 0", "1, 0, 0, 0", "0,5, 1, 0", "a, b, c"):
            with self.assertRaises(ut.Bad, msg=bad) as cm:
                ut.parse_value(e, bad)
            self.assertEqual(cm.exception.code, "bad_vector")
        with self.assertRaises(ut.Bad) as cm:
            ut.parse_value(entry("document", "rbla.seismic_direction"), "0, 0, 0")
        self.assertEqual(cm.exception.code, "zero_vector")

    def test_choices_and_synonyms(self):
        role = entry("block", "rbla.role")
        for text, want in (("Fixed", "fixed"), ("support", "fixed"), (" Moving Support ",
                           "moving_support"), ("moving-support", "moving_support"),
                           ("settling", "moving_support"), ("FREE", "free")):
            self.assertEqual(ut.parse_value(role, text), want, text)
        with self.assertRaises(ut.Bad) as cm:
            ut.parse_value(role, "floating")
        self.assertEqual(cm.exception.fields["allowed"], "free, fixed, moving_support")
        self.assertEqual(ut.parse_value(entry("document", "rbla.gravity"), "-Z"), "-z")
        self.assertEqual(ut.parse_value(entry("document", "rbla.force_unit"), "kilonewtons"),
                         "kN")
        self.assertEqual(ut.parse_value(entry("document", "rbla.unit_weight_unit"), "kN/m³"),
                         "kN/m3")

    def test_json_booleans_pairs_text(self):
        an = entry("document", "rbla.analysis")
        self.assertEqual(ut.parse_value(an, "Seismic"), "seismic")
        self.assertEqual(ut.parse_value(an, '{"type": "settlement"}'), {"type": "settlement"})
        for bad in ("wind", "[1]", "{bad json", '{"a": NaN}'):
            with self.assertRaises(ut.Bad, msg=bad) as cm:
                ut.parse_value(an, bad)
            self.assertEqual(cm.exception.code, "bad_json")
        ign = entry("block", "rbla.ignore")
        self.assertTrue(ut.parse_value(ign, "Yes"))
        self.assertFalse(ut.parse_value(ign, "off"))
        with self.assertRaises(ut.Bad):
            ut.parse_value(ign, "maybe")
        pair = entry("interface", "rbla.blocks")
        self.assertEqual(ut.parse_value(pair, "A, B"), ["A", "B"])
        self.assertEqual(ut.parse_value(pair, "wall, left; B"), ["wall, left", "B"])
        for bad in ("A", "A, A", "A, B, C", ", B"):
            with self.assertRaises(ut.Bad, msg=bad):
                ut.parse_value(pair, bad)
        with self.assertRaises(ut.Bad) as cm:
            ut.parse_value(entry("block", "rbla.id"), "x" * 201)
        self.assertEqual(cm.exception.code, "bad_text")

    def test_numbers_print_as_percent_g(self):
        self.assertEqual([ut.fmt(x) for x in (0.6, 1e12, 25.4, 0.001, 1e-5, 3, 100)],
                         ["0.6", "1e+12", "25.4", "0.001", "1e-05", "3", "100"])


class KeysTest(unittest.TestCase):
    def test_messages_name_object_and_key(self):
        rep = ut.Report()
        got = ut.read_keys("block", {"RBLA.Role": "floating", "rbla.unit_weight": "20",
                                     "rbla.frction": "0.4", "rbla.blocks": "A, B",
                                     "other": "x", "rbla.label": ""},
                           'object "Stone 7"', rep, "guid-1")
        self.assertEqual(got, {"rbla.unit_weight": 20.0})
        self.assertEqual([(m.code, m.key) for m in rep.messages],
                         [("misplaced_key", "rbla.blocks"), ("unknown_key", "rbla.frction"),
                          ("empty_value", "rbla.label"), ("bad_choice", "rbla.role")])
        self.assertEqual(rep.messages[1].text, 'object "Stone 7": unknown key rbla.frction '
                                               'ignored; did you mean rbla.friction?')
        self.assertTrue(all(m.object == "guid-1" for m in rep.messages))

    def test_old_names(self):
        rep = ut.Report()
        got = ut.read_keys("document", {"rbla.friction": "0.5"}, "document", rep)
        self.assertEqual(got, {"rbla.default_friction": 0.5})
        self.assertEqual(rep.codes(), ["old_key"])
        rep = ut.Report()
        ut.read_keys("document", {"rbla.friction": "0.5", "rbla.default_friction": "0.4"},
                     "document", rep)
        self.assertEqual(rep.codes(), ["conflict"])

    def test_host_only_keys(self):
        rep = ut.Report()
        self.assertEqual(ut.read_keys("document", {"rbla.exe": "/x"}, "document", rep,
                                      host="exchange"), {})
        self.assertEqual(ut.read_keys("document", {"rbla.exe": "/x"}, "document", rep,
                                      host="rhino"), {"rbla.exe": "/x"})
        self.assertEqual(rep.messages, [])

    def test_read_value_for_other_inputs(self):
        self.assertEqual(ut.read_value("block", "rbla.role", "support", "port"), "fixed")
        with self.assertRaises(ModelError) as cm:
            ut.read_value("document", "rbla.analysis", "wind", "analysis input")
        self.assertIn("analysis input: rbla.analysis must be one of seismic", str(cm.exception))


if __name__ == "__main__":
    unittest.main()
