"""The Runner reads only a result its own run wrote: a result file left at result_path by an
earlier run is never reported as this run's (a failed run with no new result has result None and
the solver's message).

Stand-in solvers (Python scripts), no rbla needed.
"""

import json
import os
import shutil
import tempfile
import unittest

import _support  # noqa: F401
from rbla_cad import runner as rn
from test_runner import _fake_solver

# The fake finds the result path after -o; it writes a new file and renames it into place, as rbla does.
WRITE_RESULT = (
    "import json, os\n"
    "out = sys.argv[sys.argv.index('-o') + 1]\n"
    "with open(out + '.tmp', 'w') as f:\n"
    "    json.dump({'status': 'time_limit', 'verdict': 'time limit reached (new run)'}, f)\n"
    "os.replace(out + '.tmp', out)\n")

OLD_RESULT = {"status": "collapse", "verdict": "collapse (OLD run)", "load_multiplier": 0.25}


class StaleResultTest(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp()
        self.model = {"schema_version": "1.0.0"}
        self.result_path = os.path.join(self.dir, "result.json")
        with open(self.result_path, "w") as f:
            json.dump(OLD_RESULT, f)

    def tearDown(self):
        shutil.rmtree(self.dir)

    def test_failed_run_without_result_does_not_attach_the_previous_one(self):
        fake = _fake_solver(self.dir, "sys.stderr.write('rbla: out of memory\\n'); sys.exit(3)")
        with self.assertRaises(rn.SolverFailureError) as cm:
            rn.Runner(fake).solve(self.model, result_path=self.result_path)
        e = cm.exception
        self.assertIsNone(e.result)
        self.assertIn("out of memory", str(e))
        self.assertNotIn("OLD", str(e))
        # the earlier result is left as it was
        with open(self.result_path) as f:
            self.assertEqual(json.load(f), OLD_RESULT)

    def test_successful_exit_without_result_is_an_error_not_the_old_result(self):
        fake = _fake_solver(self.dir, "sys.exit(0)")
        with self.assertRaises(rn.RblaError) as cm:
            rn.Runner(fake).solve(self.model, result_path=self.result_path)
        self.assertIn("wrote no result", str(cm.exception))

    def test_a_result_written_by_the_failed_run_is_attached(self):
        fake = _fake_solver(self.dir, WRITE_RESULT + "sys.stderr.write('rbla: time limit\\n'); sys.exit(3)")
        with self.assertRaises(rn.SolverFailureError) as cm:
            rn.Runner(fake).solve(self.model, result_path=self.result_path)
        self.assertIsNotNone(cm.exception.result)
        self.assertEqual(cm.exception.result.status, "time_limit")
        self.assertIn("new run", str(cm.exception))

    def test_a_result_written_over_the_old_one_is_returned(self):
        fake = _fake_solver(self.dir, WRITE_RESULT + "sys.exit(0)")
        out = rn.Runner(fake).solve(self.model, result_path=self.result_path)
        self.assertEqual(out.result.status, "time_limit")


if __name__ == "__main__":
    unittest.main()
