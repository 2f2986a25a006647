"""Real solver runs through the Runner, and its error paths (exit codes, timeout, cancel).

Needs the solver: set RBLA_EXE to the rbla executable (these tests are skipped otherwise).
"""

import json
import os
import shutil
import stat
import sys
import tempfile
import threading
import time
import unittest

import _support
from rbla_cad import jsonschema_lite
from rbla_cad import runner as rn
from rbla_cad.model import ModelBuilder, box, block_centroids, load_model
from rbla_cad.result import apply_transform

EXE = _support.solver_executable()
needs_solver = unittest.skipUnless(EXE, "set RBLA_EXE to the rbla executable")


def _fake_solver(folder, body):
    """A stand-in executable (a Python script) for timeout/cancel/exit-code tests."""
    path = os.path.join(folder, "fake_rbla")
    with open(path, "w") as f:
        f.write("#!%s\nimport sys, time\n%s\n" % (sys.executable, body))
    os.chmod(path, os.stat(path).st_mode | stat.S_IXUSR | stat.S_IXGRP | stat.S_IXOTH)
    return path


class FindExecutableTest(unittest.TestCase):
    def test_missing(self):
        with self.assertRaises(rn.SolverNotFoundError):
            rn.find_executable("/nonexistent/rbla")

    def test_env_var(self):
        d = tempfile.mkdtemp()
        try:
            fake = _fake_solver(d, "print('rbla 9')")
            old = os.environ.get(rn.ENV_VAR)
            os.environ[rn.ENV_VAR] = fake
            try:
                self.assertEqual(rn.find_executable(), fake)
                self.assertEqual(rn.Runner().version(), "rbla 9")
            finally:
                if old is None:
                    del os.environ[rn.ENV_VAR]
                else:
                    os.environ[rn.ENV_VAR] = old
        finally:
            shutil.rmtree(d)

    def test_parse_lines(self):
        e = rn.parse_stderr_line("rbla: model: 2 blocks, 1 interfaces\n")
        self.assertEqual((e.kind, e.text), ("stage", "model: 2 blocks, 1 interfaces"))
        e = rn.parse_stderr_line("rbla: warning [small_interface] at /blocks/1: tiny")
        self.assertEqual((e.kind, e.data["code"]), ("warning", "small_interface"))
        e = rn.parse_stderr_line("   6  -5.000000003e-01  -5.000000000e-01  2.48e-09  9.70e-10"
                                 "  2.78e-10  8.26e-10  1.33e+00  4.17e-10  0.9900  0.0000    1")
        self.assertEqual(e.kind, "iteration")
        self.assertEqual(e.data["iteration"], 6)
        self.assertAlmostEqual(e.data["relative_gap"], 2.48e-9)
        self.assertAlmostEqual(e.data["step"], 0.99)
        self.assertEqual(rn.parse_stderr_line("iter  primal obj  dual obj").kind, "log")
        issues = rn.parse_invalid_report("rbla: reading x\nrbla: invalid input:\n"
                                         "  /blocks/0/role: bad enum\n  (document): broken\n")
        self.assertEqual(issues, [("/blocks/0/role", "bad enum"), ("", "broken")])


class FakeSolverTest(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp()
        self.model = {"schema_version": "1.0.0"}

    def tearDown(self):
        shutil.rmtree(self.dir)

    def test_timeout(self):
        fake = _fake_solver(self.dir, "sys.stderr.write('rbla: reading\\n'); sys.stderr.flush()\n"
                                      "time.sleep(30)")
        events = []
        t0 = time.time()
        with self.assertRaises(rn.SolverTimeoutError) as cm:
            rn.Runner(fake, grace=1.0).solve(self.model, timeout=0.5, progress=events.append)
        self.assertLess(time.time() - t0, 5.0)
        self.assertIn("0.5", str(cm.exception))
        self.assertEqual(events[0].kind, "stage")

    def test_cancel_event_and_callable(self):
        fake = _fake_solver(self.dir, "time.sleep(30)")
        stop = threading.Event()
        threading.Timer(0.3, stop.set).start()
        t0 = time.time()
        with self.assertRaises(rn.CancelledError):
            rn.Runner(fake).solve(self.model, cancel=stop)
        self.assertLess(time.time() - t0, 5.0)
        calls = []

        def cancel():
            calls.append(1)
            return len(calls) > 3
        with self.assertRaises(rn.CancelledError):
            rn.Runner(fake).solve(self.model, cancel=cancel)

    def test_callback_error_stops_the_solver(self):
        fake = _fake_solver(self.dir, "sys.stderr.write('rbla: reading\\n'); sys.stderr.flush()\n"
                                      "time.sleep(30)")

        def progress(ev):
            raise RuntimeError("host UI failed")
        t0 = time.time()
        with self.assertRaises(RuntimeError):
            rn.Runner(fake, grace=1.0).solve(self.model, progress=progress)
        self.assertLess(time.time() - t0, 5.0)

    def test_unknown_exit_code(self):
        fake = _fake_solver(self.dir, "sys.stderr.write('boom\\n'); sys.exit(7)")
        with self.assertRaises(rn.RblaError) as cm:
            rn.Runner(fake).solve(self.model)
        self.assertEqual(cm.exception.exit_code, 7)
        self.assertIn("boom", str(cm.exception))


@needs_solver
class SolverRunTest(unittest.TestCase):
    def setUp(self):
        self.runner = rn.Runner(EXE, timeout=60)

    def test_block_sample(self):
        events = []
        out = self.runner.solve(_support.sample("block.json"), progress=events.append)
        res = out.result
        self.assertEqual(out.exit_code, 0)
        self.assertEqual(res.status, "collapse")
        self.assertAlmostEqual(res.load_multiplier, 0.5, places=6)
        self.assertIn("0.5", out.verdict_line)
        kinds = set(e.kind for e in events)
        self.assertIn("stage", kinds)
        self.assertIn("iteration", kinds)
        self.assertTrue(any(e.text.startswith("solved in") for e in events))
        self.assertEqual(jsonschema_lite.validate_result(res.data), [])
        self.assertEqual(res.moving_blocks(), ["block"])
        hinge = [i for i in res.interfaces if i.cracked]
        self.assertEqual(len(hinge), 1)
        self.assertEqual(hinge[0].state, "hinge")
        # the block rocks about its x = +0.5 bottom edge: drawn as a screw motion that edge
        # stays exactly put; drawn about the centroid (default) it moves by O(s^2) only
        model = load_model(_support.sample("block.json"))
        g = block_centroids(model)["block"]
        s = 0.3
        edge = (0.5, -0.5, 0.0)
        T = res.transform("block", g, amplitude=s, screw=True)
        for a, b in zip(apply_transform(T, edge), edge):
            self.assertAlmostEqual(a, b, places=6)
        self.assertGreater(apply_transform(T, (-0.5, 0, 0))[2], 0.05)
        T0 = res.transform("block", g, amplitude=s)
        moved = max(abs(a - b) for a, b in zip(apply_transform(T0, edge), edge))
        self.assertLess(moved, s * s)
        self.assertGreater(moved, 1e-4)
        reac = res.support_reactions()
        self.assertAlmostEqual(reac[0]["force"][2], 36.0, places=4)   # weight 2 m3 x 18
        self.assertAlmostEqual(reac[0]["force"][0], -18.0, places=4)  # -alpha W
        self.assertAlmostEqual(reac[0]["point"][0], 0.5, places=4)    # at the hinge edge

    def test_detail_leaves_out_contact_points_and_the_reader_copes(self):
        full = self.runner.solve(_support.sample("block.json")).result
        for detail in ("interfaces", "blocks"):
            res = self.runner.solve(_support.sample("block.json"), detail=detail).result
            self.assertEqual(jsonschema_lite.validate_result(res.data), [])
            self.assertEqual(res.data["detail"], detail)
            self.assertEqual(res.load_multiplier, full.load_multiplier)
            self.assertEqual(res.moving_blocks(), ["block"])
            self.assertEqual(res.support_reactions(), [])  # no contact points, no force vectors
            if detail == "interfaces":
                self.assertEqual(len(res.interfaces), len(full.interfaces))
                self.assertTrue(all(not i.points for i in res.interfaces))
            else:
                self.assertEqual(res.interfaces, [])
        with self.assertRaises(ValueError):
            self.runner.solve(_support.sample("block.json"), detail="forces")

    def test_worst_direction_and_critical_friction(self):
        # The 1 x 1 x 2 block tips at alpha = 0.5 along its four edge normals; sliding needs mu.
        out = self.runner.worst_direction(_support.sample("block.json"), verbose=False)
        search = out.result.data["worst_direction"]
        self.assertAlmostEqual(search["load_multiplier"], 0.5, places=6)
        self.assertTrue(search["certified"])
        self.assertEqual(jsonschema_lite.validate_result(out.result.data), [])
        out = self.runner.critical_friction(_support.sample("block.json"), target_alpha=0.3,
                                            tolerance=1e-6, verbose=False)
        self.assertAlmostEqual(out.result.data["critical_friction"]["friction"], 0.3, places=5)
        out = self.runner.critical_friction(_support.sample("block.json"), target_alpha=0.3,
                                            interfaces_of="block", verbose=False)
        self.assertEqual(len(out.result.data["critical_friction"]["scaled_interfaces"]), 1)
        with self.assertRaises(ValueError):
            self.runner.critical_friction(_support.sample("block.json"), interfaces=["a,b"])
        with self.assertRaises(TypeError):
            self.runner.critical_friction(_support.sample("block.json"), target=0.3)

    def test_worst_settlement(self):
        out = self.runner.worst_settlement(_support.sample("wall_settlement.json"), cone_angle=20,
                                           verbose=False)
        search = out.result.data["worst_settlement"]
        self.assertTrue(search["certified"])
        self.assertLessEqual(search["tilt_deg"], 20.0 + 1e-9)
        self.assertGreaterEqual(search["upper_bound"], search["ratio"])
        self.assertEqual(jsonschema_lite.validate_result(out.result.data), [])

    def test_worst_settlement_ranks_candidate_groups(self):
        out = self.runner.worst_settlement(_support.sample("wall_settlement.json"), cone_angle=20,
                                           candidate_groups=[["base_moving"], "base_fixed"],
                                           verbose=False)
        groups = out.result.data["worst_settlement"]["candidate_groups"]
        self.assertEqual([g["supports"] for g in groups["groups"]], [["base_moving"], ["base_fixed"]])
        self.assertEqual(sum(g["most_harmful"] for g in groups["groups"]), 1)
        self.assertEqual(jsonschema_lite.validate_result(out.result.data), [])
        with self.assertRaises(ValueError):
            self.runner.worst_settlement(_support.sample("wall_settlement.json"), candidate_groups=[[]])

    def test_arch_sample(self):
        d = tempfile.mkdtemp()
        try:
            out = self.runner.solve(_support.sample("arch.json"),
                                    result_path=os.path.join(d, "r.json"),
                                    svg_dir=os.path.join(d, "svg"), verbose=False)
            self.assertTrue(os.path.isfile(out.result_path))
            self.assertTrue(os.path.isfile(os.path.join(d, "svg", "mechanism.svg")))
        finally:
            shutil.rmtree(d)
        res = out.result
        self.assertEqual(res.status, "collapse")
        self.assertAlmostEqual(res.load_multiplier, 0.1774597765, places=6)
        self.assertEqual(res.state_counts()["hinge"] + res.state_counts()["opening"], 4)
        self.assertEqual(len(res.cracked_interfaces), 4)

    def test_builder_column(self):
        b, h, n, mu = 0.5, 0.5, 3, 0.6
        mb = ModelBuilder(length="m", force="kN", default_friction=mu, title="3-block column")
        mb.add_block("base", *box(-1, 2, -1, 2, -0.5, 0), role="fixed")
        for i in range(n):
            mb.add_block("B%d" % i, *box(0, b, 0, b, i * h, (i + 1) * h))
        mb.set_seismic([1, 0, 0])
        self.assertEqual(self.runner.validate(mb).split(":")[0], "valid")
        res = self.runner.solve(mb).result
        self.assertAlmostEqual(res.load_multiplier, min(b / (n * h), mu), places=6)
        self.assertEqual(sorted(res.moving_blocks()), ["B0", "B1", "B2"])
        # in millimetres and newtons: same alpha
        mm = ModelBuilder(length="mm", force="N", default_friction=mu)
        mm.add_block("base", *box(-1000, 2000, -1000, 2000, -500, 0), role="fixed")
        for i in range(n):
            mm.add_block("B%d" % i, *box(0, 500, 0, 500, i * 500, (i + 1) * 500))
        mm.set_seismic([1, 0, 0])
        res_mm = self.runner.solve(mm, verbose=False).result
        self.assertEqual(res_mm.length_unit, "mm")
        self.assertAlmostEqual(res_mm.load_multiplier, res.load_multiplier, places=6)

    def test_sliding_column(self):
        # low friction: alpha = mu (sliding), state sliding
        mb = ModelBuilder(default_friction=0.2)
        mb.add_block("base", *box(-1, 2, -1, 2, -0.5, 0), role="fixed")
        mb.add_block("B", *box(0, 1, 0, 1, 0, 0.5))
        mb.set_seismic([1, 0, 0])
        res = self.runner.solve(mb, verbose=False).result
        self.assertAlmostEqual(res.load_multiplier, 0.2, places=5)
        self.assertIn(res.interfaces[0].state, ("sliding", "opening_sliding"))

    def test_invalid_model_exit_2(self):
        model = load_model(_support.sample("block.json"))
        model["blocks"][0]["role"] = "bogus"
        with self.assertRaises(rn.InvalidModelError) as cm:
            self.runner.solve(model)
        e = cm.exception
        self.assertEqual(e.exit_code, 2)
        self.assertIn("/blocks/0/role", str(e))
        self.assertEqual(e.issues[0][0], "/blocks/0/role")
        model = load_model(_support.sample("block.json"))
        model["blocks"][1]["faces"][0].reverse()
        with self.assertRaises(rn.InvalidModelError) as cm:
            self.runner.validate(model)
        self.assertIn("/blocks/1/faces", str(cm.exception))
        self.assertIn("'block'", str(cm.exception))

    def test_output_not_writable_exit_4(self):
        with self.assertRaises(rn.OutputError) as cm:
            self.runner.solve(_support.sample("block.json"),
                              result_path="/nonexistent-dir/sub/result.json")
        self.assertEqual(cm.exception.exit_code, 4)

    def test_usage_exit_1(self):
        with self.assertRaises(rn.UsageError):
            code, _, err = self.runner._run(["solve", "--no-such-option"], None, None, 30, None)
            self.runner._raise_for(code, err, None)

    def test_time_limit_exit_3(self):
        model = load_model(_support.sample("wall_opening.json"))
        model["analysis"]["formulation"] = "3d"
        # A limit about a tenth of what this sample's 3-D solve takes on a fast machine, so
        # the limit is reached before the solve ends.
        model["analysis"]["time_limit"] = 0.005
        with self.assertRaises(rn.SolverFailureError) as cm:
            self.runner.solve(model, verbose=False)
        e = cm.exception
        self.assertEqual(e.exit_code, 3)
        if e.result is not None:
            self.assertEqual(e.result.status, "time_limit")
        else:
            # on a loaded machine the model stage can use up the whole budget; the solver then
            # stops before the conic solve without writing a result (exit 3 all the same)
            self.assertIn("time_limit", e.stderr)

    def test_cancel_real_run(self):
        # cancel before the first poll: the run is stopped whatever its speed
        with self.assertRaises(rn.CancelledError):
            self.runner.solve(_support.sample("arch.json"), cancel=lambda: True)


if __name__ == "__main__":
    unittest.main()
