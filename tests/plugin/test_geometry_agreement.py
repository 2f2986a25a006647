"""One block geometry per language, and the three agree: the Python core's volume and centroid
(plugin/rbla_cad/geometry.py) of the irregular blocks in tests/data/geometry/irregular_blocks.json
are what the file says; tests/unit/test_geometry_agreement.cpp holds the solver to the same file,
tests/web/geometry_agreement.test.mjs the JavaScript exchange and viewer."""

import importlib.util
import json
import os
import unittest

import _support
from rbla_cad.geometry import volume_centroid

FIXTURE = os.path.join(_support.REPO, "tests", "data", "geometry", "irregular_blocks.json")
SCRIPT = os.path.join(_support.REPO, "tests", "scripts", "geometry_fixture.py")


class GeometryAgreementTest(unittest.TestCase):
    def test_fixture_is_what_the_script_writes(self):
        spec = importlib.util.spec_from_file_location("geometry_fixture", SCRIPT)
        script = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(script)
        with open(FIXTURE) as f:
            stored = json.load(f)
        self.assertEqual(json.loads(json.dumps(script.fixture())), stored,
                         "regenerate with: python3 tests/scripts/geometry_fixture.py")

    def test_volume_and_centroid_of_each_block(self):
        with open(FIXTURE) as f:
            blocks = json.load(f)["blocks"]
        self.assertGreaterEqual(len(blocks), 6)
        for b in blocks:
            volume, centroid = volume_centroid(b["vertices"], b["faces"])
            self.assertAlmostEqual(volume, b["volume"], delta=1e-12 * abs(b["volume"]), msg=b["id"])
            for i in range(3):
                self.assertAlmostEqual(centroid[i], b["centroid"][i], delta=1e-9, msg=b["id"])

    def test_the_sample_generator_uses_the_core(self):
        # samples/generate_samples.py has no volume and centroid of its own any more.
        with open(os.path.join(_support.SAMPLES, "generate_samples.py")) as f:
            text = f.read()
        self.assertNotIn("def volume_centroid", text)
        self.assertIn("from rbla_cad.geometry import", text)


if __name__ == "__main__":
    unittest.main()
