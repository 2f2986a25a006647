#!/usr/bin/env python3
"""Error against run time: rbla's methods and Debian's peers on the samples and a church façade.

One command writes the raw results (JSON), the report (markdown) and its SVG plots:

    python3 bench/report/run_report.py --rbla build-bench/solver/rbla --out docs/benchmark
    python3 bench/report/run_report.py --rbla build-bench/solver/rbla --out /tmp/bench --quick

Standard library only (the CVXOPT peer runs in a child process of the Debian python that has
python3-cvxopt and python3-numpy, --peer-python, default /usr/bin/python3).

What runs (see PLAN_FULL / PLAN_QUICK below):
  * scenes: the bundled samples (samples/*.json) and the church façade of
    samples/generate_samples.py (settlement of the right half of the base, seismic in plane x,
    seismic out of plane y), in the planar and the 3-D formulation where the scene allows both;
  * rbla methods: the exact cone (the LP in the planar formulation) at solver tolerances
    1e-3 ... 1e-9; inscribed and circumscribed pyramids of 4, 8, 16, 32 faces (3-D); associative
    and non-associative friction;
  * peers on the problem rbla dumps (--dump-problem): CLP barrier (`clp X.mps -barrier`, with its
    default crossover, and with `-crossover off`) on the planar LP, and CVXOPT conelp on the CBF
    (bench/report/cvxopt_cbf.py) at a few tolerances;
  * references: rbla's exact cone at tolerance 1e-10 for every scene and formulation, and the
    closed form where one exists (samples/expected.json);
  * a scaling series of the church façade from ~300 to ~31000 blocks (planar settlement and
    in-plane seismic; 3-D out-of-plane seismic until a run exceeds its cap) with rbla at its
    default settings and the peers at theirs.

The full plan runs every method on the default church façade in both formulations, for all
three loads (PLAN_FULL: "church_3d_loads", "non_associative_3d_church"; "church_3d_light" can
give a load a lighter 3-D method set when a run must be shorter). The quick plan (--quick) is a
smoke test of the harness on a ~300-block church.

Every child process is timed by the wall clock and its peak memory read by /usr/bin/time;
a run that exceeds its cap is killed and recorded as "did not finish".
Times are medians of repeats when a run is short (REPEAT_BELOW seconds).
"""
import argparse
import datetime
import json
import math
import os
import platform
import re
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
import svg_plots  # noqa: E402  (bench/report/svg_plots.py)

REPEAT_BELOW = 2.0   # s: runs shorter than this are repeated ...
REPEATS = 3          # ... this many times in all, and the median is reported
REFERENCE_TOL = 1e-10

PLAN_FULL = {
    "samples": ["block", "column", "arch", "wall_opening", "wall_settlement"],
    "church_loads": ["settlement", "seismic-x", "seismic-y"],
    "church_blocks": None,  # default scale (22 x 19 m)
    "tolerances": [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9],
    "tolerances_church_3d": [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9],
    "pyramids": [4, 8, 16, 32],
    "pyramids_church_3d": [4, 8, 16, 32],
    "cvxopt_tols": [1e-4, 1e-7, 1e-9],
    "non_associative_3d_church": ["settlement", "seismic-x", "seismic-y"],
    # church loads whose 3-D formulation gets a lighter method set, (tolerances, pyramid faces)
    "church_3d_light": {},
    "church_3d_loads": ["settlement", "seismic-x", "seismic-y"],
    "light_cvxopt_tols": [1e-7],
    "cap": 240.0,             # s, any single run
    "cap_non_associative": 120.0,
    "cap_cvxopt": 150.0,
    "scaling_sizes": [300, 1000, 3000, 10000, 31000],
    "scaling_loads_planar": ["settlement", "seismic-x"],
    "scaling_3d": ["seismic-y"],
    "scaling_cap": 600.0,     # s, rbla in the scaling series (planar)
    "scaling_cap_3d": 240.0,  # s, rbla in the 3-D scaling series
    "scaling_peer_cap": 60.0,
    "scaling_cvxopt_planar_max_blocks": 4000,  # CVXOPT on the planar LP (needs an extra dump run)
}

PLAN_QUICK = {
    "samples": ["block", "column", "wall_settlement"],
    "church_loads": ["settlement", "seismic-x", "seismic-y"],
    "church_blocks": 300,
    "tolerances": [1e-3, 1e-6, 1e-8, 1e-9],
    "tolerances_church_3d": [1e-3, 1e-8],
    "pyramids": [4, 16],
    "pyramids_church_3d": [8],
    "cvxopt_tols": [1e-7],
    "non_associative_3d_church": [],
    "church_3d_light": {"seismic-x": ([1e-3], [4])},
    "church_3d_loads": ["settlement", "seismic-x", "seismic-y"],
    "light_cvxopt_tols": [1e-7],
    "cap": 60.0,
    "cap_non_associative": 60.0,
    "cap_cvxopt": 60.0,
    "scaling_sizes": [300, 1000],
    "scaling_loads_planar": ["settlement", "seismic-x"],
    "scaling_3d": ["seismic-y"],
    "scaling_cap": 60.0,
    "scaling_cap_3d": 60.0,
    "scaling_peer_cap": 60.0,
    "scaling_cvxopt_planar_max_blocks": 500,
}

# closed forms (samples/expected.json says which are closed forms)
CLOSED_FORM_SAMPLES = ("block", "column")


def log(msg):
    sys.stderr.write("[%s] %s\n" % (time.strftime("%H:%M:%S"), msg))
    sys.stderr.flush()


# ----------------------------------------------------------------------------------------------
# Child processes: wall time, peak memory, cap
# ----------------------------------------------------------------------------------------------

def run_child(cmd, cap, cwd=None):
    """Run cmd; return wall seconds, peak RSS (KiB), exit code, output.

    Peak RSS comes from /usr/bin/time (%M), which reads the rusage of its own child. The rusage
    that os.wait4 gives for a direct child is not usable: Linux keeps the RSS high-water mark
    across fork and exec, so it reports max(child, this harness's RSS at the fork).
    The child gets its own process group; past `cap` seconds that group is killed (SIGKILL)
    and the run is recorded as timed out.
    """
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err, \
            tempfile.NamedTemporaryFile(mode="r", suffix=".time") as tfile:
        t0 = time.perf_counter()
        proc = subprocess.Popen(["/usr/bin/time", "-f", "%M", "-o", tfile.name] + list(cmd),
                                stdout=out, stderr=err, cwd=cwd, start_new_session=True)
        timed_out = False
        while True:
            pid, status, ru = os.wait4(proc.pid, os.WNOHANG)
            if pid:
                break
            if time.perf_counter() - t0 > cap:
                timed_out = True
                try:
                    os.killpg(proc.pid, signal.SIGKILL)
                except ProcessLookupError:
                    pass
                pid, status, ru = os.wait4(proc.pid, 0)
                break
            time.sleep(0.01)
        wall = time.perf_counter() - t0
        proc.returncode = os.waitstatus_to_exitcode(status)
        out.seek(0)
        err.seek(0)
        try:
            peak = int(tfile.read().strip().splitlines()[-1])
        except (ValueError, IndexError):
            peak = None  # killed, or time could not write
        return {"wall_seconds": wall, "peak_rss_kib": peak,
                "peak_rss_source": "/usr/bin/time %M" if peak is not None else None,
                "exit_code": proc.returncode,
                "timed_out": timed_out, "stdout": out.read().decode("utf-8", "replace"),
                "stderr": err.read().decode("utf-8", "replace")}


def repeated(fn, cap):
    """Call fn(cap) (one run); repeat short successful runs; median of their times."""
    first = fn(cap)
    runs = [first]
    if first.get("ok") and first["wall_seconds"] < REPEAT_BELOW:
        for _ in range(REPEATS - 1):
            runs.append(fn(cap))
    ok_runs = [r for r in runs if r.get("ok")]
    rec = dict(runs[-1] if not ok_runs else ok_runs[-1])
    if ok_runs:
        for key in ("wall_seconds", "solve_seconds"):
            vals = [r[key] for r in ok_runs if r.get(key) is not None]
            if vals:
                rec[key] = statistics.median(vals)
                rec[key + "_all"] = vals
        peaks = [r["peak_rss_kib"] for r in ok_runs if r.get("peak_rss_kib") is not None]
        rec["peak_rss_kib"] = max(peaks) if peaks else None
        rec["peak_rss_source"] = "/usr/bin/time %M" if peaks else None
    rec["repeats"] = len(runs)
    return rec


# ----------------------------------------------------------------------------------------------
# rbla
# ----------------------------------------------------------------------------------------------

def model_value(result):
    if "load_multiplier" in result:
        return result["load_multiplier"]
    br = result.get("base_reaction") or {}
    return br.get("at_collapse")


def run_rbla(rbla, model, analysis_patch, workdir, tag, cap, dump=None):
    """Solve `model` (a dict) with its analysis updated by analysis_patch; one run."""
    m = json.loads(json.dumps(model))
    m.setdefault("analysis", {}).update(analysis_patch)
    mpath = os.path.join(workdir, tag + ".model.json")
    rpath = os.path.join(workdir, tag + ".result.json")
    with open(mpath, "w") as fh:
        json.dump(m, fh)
    if os.path.exists(rpath):
        os.remove(rpath)
    cmd = [rbla, "solve", mpath, "-o", rpath, "-q"]
    if dump:
        cmd += ["--dump-problem", dump]
    r = run_child(cmd, cap)
    rec = {"wall_seconds": r["wall_seconds"], "peak_rss_kib": r["peak_rss_kib"],
           "peak_rss_source": r["peak_rss_source"],
           "exit_code": r["exit_code"], "timed_out": r["timed_out"], "ok": False,
           "analysis": m["analysis"], "wrote_dump": bool(dump)}
    if r["timed_out"]:
        rec["outcome"] = "did not finish within %.0f s (killed)" % cap
        return rec
    if r["exit_code"] != 0 or not os.path.exists(rpath):
        rec["outcome"] = "failed (exit %d): %s" % (r["exit_code"], r["stderr"].strip()[-300:])
        return rec
    with open(rpath) as fh:
        res = json.load(fh)
    solver = res.get("solver", {})
    conv = res.get("convergence", {})
    na = conv.get("non_associative") or []
    rec.update({
        "status": res.get("status"),
        "value": model_value(res),
        "solver_status": solver.get("status"),
        "iterations": (sum(row.get("interior_point_iterations", 0) for row in na) if na
                       else solver.get("iterations")),
        "outer_iterations": len(na) if na else None,
        "non_associative_converged": conv.get("non_associative_converged"),
        "primal_objective": solver.get("primal_objective"),
        "solve_seconds": res.get("timings", {}).get("solve_seconds"),
        "total_seconds": res.get("timings", {}).get("total_seconds"),
        "num_variables": solver.get("num_variables"),
        "num_equality_rows": solver.get("num_equality_rows"),
        "num_cones": solver.get("num_cones"),
        "formulation": res.get("analysis", {}).get("formulation"),
        "model_summary": {k: res.get("model_summary", {}).get(k) for k in
                          ("num_blocks", "num_interfaces", "num_contact_points")},
        "warnings": [w.get("code") for w in res.get("warnings", [])],
    })
    rec["ok"] = res.get("status") == "collapse" and rec["value"] is not None
    if not rec["ok"]:
        rec["outcome"] = "status %s (solver %s)" % (res.get("status"), solver.get("status"))
    else:
        rec["outcome"] = "collapse" if solver.get("status") == "solved" else \
            "collapse (solver: %s)" % solver.get("status")
        if conv.get("non_associative_converged") is False:
            rec["outcome"] += "; non-associative iteration stopped at its cap, not converged"
    if tag.endswith("reference"):
        # blocks that touch nothing (the church check); supports are exempt
        touched = set()
        for itf in res.get("interfaces", []):
            touched.update(itf.get("blocks", []))
        rec["blocks_without_contacts"] = sorted(
            b["id"] for b in model["blocks"]
            if b.get("role", "free") == "free" and b["id"] not in touched)
    os.remove(rpath)
    return rec


# ----------------------------------------------------------------------------------------------
# Peers
# ----------------------------------------------------------------------------------------------

CLP_DUAL_TIGHT = ["-primalT", "1e-10", "-dualT", "1e-10", "-dualsimplex"]


def run_clp(mps, crossover, cap, args=None):
    """CLP on an MPS file: barrier (with or without crossover) or the given arguments."""
    cmd = ["clp", mps] + (args if args else
                          ([] if crossover else ["-crossover", "off"]) + ["-barrier"])
    r = run_child(cmd, cap)
    rec = {"wall_seconds": r["wall_seconds"], "peak_rss_kib": r["peak_rss_kib"],
           "peak_rss_source": r["peak_rss_source"],
           "exit_code": r["exit_code"], "timed_out": r["timed_out"], "ok": False}
    if r["timed_out"]:
        rec["outcome"] = "did not finish within %.0f s (killed)" % cap
        return rec
    out = r["stdout"]
    its = [int(m.group(1)) for m in re.finditer(r"^(\d+) Primal [-+0-9.eE]+ Dual", out, re.M)]
    rec["iterations"] = (max(its) if its else None)  # barrier iterations (crossover pivots not counted)
    if args:
        m = re.search(r"Optimal objective\s+[-+0-9.eE]+ - (\d+) iterations", out)
        rec["iterations"] = int(m.group(1)) if m else None  # simplex pivots
    imp = re.search(r"imported from .* in ([0-9.eE+-]+) seconds", out)
    read = float(imp.group(1)) if imp else 0.0
    rec["read_seconds"] = read
    rec["solve_seconds"] = max(r["wall_seconds"] - read, 0.0)
    m = re.search(r"Optimal objective\s+([-+0-9.eE]+)", out)
    if m and "Optimal" in out:
        rec["objective"] = float(m.group(1))
        rec["ok"] = True
        rec["outcome"] = "optimal"
    else:
        tail = [ln for ln in out.strip().splitlines()[-3:]]
        rec["outcome"] = "no optimum: " + " | ".join(tail)
    return rec


def run_cvxopt(python, cbf, tol, cap):
    cmd = [python, os.path.join(HERE, "cvxopt_cbf.py"), cbf, "--tol", repr(tol)]
    r = run_child(cmd, cap)
    rec = {"wall_seconds": r["wall_seconds"], "peak_rss_kib": r["peak_rss_kib"],
           "peak_rss_source": r["peak_rss_source"],
           "exit_code": r["exit_code"], "timed_out": r["timed_out"], "ok": False, "tol": tol}
    if r["timed_out"]:
        rec["outcome"] = "did not finish within %.0f s (killed)" % cap
        return rec
    try:
        res = json.loads(r["stdout"].strip().splitlines()[-1])
    except (ValueError, IndexError):
        rec["outcome"] = "failed (exit %d): %s" % (r["exit_code"], r["stderr"].strip()[-300:])
        return rec
    rec.update({"iterations": res.get("iterations"), "solve_seconds": res.get("solve_seconds"),
                "read_seconds": res.get("read_seconds"), "cvxopt_status": res.get("status"),
                "objective": res.get("primal_objective"),
                "dual_objective": res.get("dual_objective"),
                "primal_infeasibility": res.get("primal_infeasibility")})
    if res.get("status") == "optimal":
        rec["ok"] = True
        rec["outcome"] = "optimal"
    else:
        # CVXOPT stopped without meeting its tolerances: the numbers are kept, marked as such
        rec["outcome"] = "not solved (CVXOPT status %s%s)" % (
            res.get("status"), ", " + res["message"] if res.get("message") else "")
    return rec


# ----------------------------------------------------------------------------------------------
# Scenes
# ----------------------------------------------------------------------------------------------

def church_model(workdir, load, blocks=None):
    path = os.path.join(workdir, "church_%s_%s.json" % (load, blocks or "default"))
    cmd = [sys.executable, os.path.join(ROOT, "samples", "generate_samples.py"), "church",
           "--load", load, "-o", path, "--self-check"]
    if blocks:
        cmd += ["--blocks", str(blocks)]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise SystemExit("church generation failed: %s" % r.stderr)
    with open(path) as fh:
        gen = "python3 samples/generate_samples.py church --load %s%s" % (
            load, " --blocks %d" % blocks if blocks else "")
        return json.load(fh), gen, [ln for ln in r.stderr.splitlines() if ln.startswith("church:")]


def rel_err(v, ref):
    if v is None or ref is None or ref == 0:
        return None
    return abs(v - ref) / abs(ref)


class Bench(object):
    def __init__(self, args, plan):
        self.args, self.plan = args, plan
        self.rbla = os.path.abspath(args.rbla)
        self.work = args.work or tempfile.mkdtemp(prefix="rbla_report_")
        os.makedirs(self.work, exist_ok=True)
        self.results = {"scenes": [], "scaling": []}

    # one scene in one formulation: reference, rbla methods, peers
    def scene(self, name, model, formulation, closed_form=None, gen_cmd=None, church=False):
        P = self.plan
        tag0 = "%s_%s" % (name, formulation)
        log("scene %s (%s)" % (name, formulation))
        entry = {"scene": name, "formulation": formulation, "closed_form": closed_form,
                 "generator": gen_cmd, "runs": []}
        base = {"formulation": formulation, "friction_model": "associative", "cone": "exact"}
        mps = os.path.join(self.work, tag0 + ".mps") if formulation == "planar" else None
        cbf = os.path.join(self.work, tag0 + ".cbf")
        cap = P["cap"]
        ref = run_rbla(self.rbla, model, dict(base, tolerances={
            "relative_gap": REFERENCE_TOL, "feasibility": REFERENCE_TOL}), self.work,
            tag0 + "_reference", cap, dump=cbf)
        if mps:
            # a second, untimed run only to write the MPS of the same problem
            run_rbla(self.rbla, model, base, self.work, tag0 + "_mps", cap, dump=mps)
        entry["reference"] = ref
        refv = ref.get("value") if ref.get("ok") else None
        # solver objective -> value: value = k * objective (k = -1 for alpha, F_s for R)
        k = (refv / ref["primal_objective"]) if refv is not None and ref.get("primal_objective") \
            else None
        entry["objective_to_value"] = k
        if ref.get("model_summary"):
            entry["model_summary"] = ref["model_summary"]
        log("  reference %s: %s %s (%.2f s)" % (tag0, ref.get("outcome"), refv, ref["wall_seconds"]))

        def add(method, rec, **kw):
            rec = dict(rec)
            rec.update(kw)
            rec["method"] = method
            v = rec.get("value")
            rec["error_vs_reference"] = rel_err(v, refv) if rec.get("ok") or v is not None else None
            rec["error_vs_closed_form"] = rel_err(v, closed_form) if closed_form else None
            entry["runs"].append(rec)
            log("  %-34s %-12s value %-14s err %-9s %6.2f s  %s" % (
                method, rec.get("param", ""), "%.10g" % v if v is not None else "-",
                "%.2e" % rec["error_vs_reference"] if rec.get("error_vs_reference") is not None
                else "-", rec.get("solve_seconds") or rec["wall_seconds"], rec.get("outcome")))

        light = church and formulation == "3d" and name.split(":")[-1] in P["church_3d_light"]
        entry["light_method_set"] = light
        tols = P["tolerances"]
        if church and formulation == "3d":
            tols = P["church_3d_light"][name.split(":")[-1]][0] if light \
                else P["tolerances_church_3d"]
        for tol in tols:
            tag = "%s_tol%g" % (tag0, tol)
            rec = repeated(lambda c: run_rbla(self.rbla, model, dict(base, tolerances={
                "relative_gap": tol, "feasibility": tol}), self.work, tag, c), cap)
            add("rbla exact cone" if formulation == "3d" else "rbla LP (planar)", rec,
                family="rbla_tolerance", tol=tol, param="tol %g" % tol)
        if formulation == "3d":
            pyr = P["pyramids"]
            if church:
                pyr = P["church_3d_light"][name.split(":")[-1]][1] if light \
                    else P["pyramids_church_3d"]
            for kind in ("pyramid_inscribed", "pyramid_circumscribed"):
                for m_ in pyr:
                    tag = "%s_%s%d" % (tag0, kind, m_)
                    rec = repeated(lambda c: run_rbla(self.rbla, model, dict(
                        base, cone=kind, pyramid_faces=m_), self.work, tag, c), cap)
                    add("rbla %s" % kind.replace("_", " "), rec, family=kind, faces=m_,
                        param="%d faces" % m_)
        # non-associative friction: its own answer (no uniqueness), shown against associative
        run_na = formulation == "planar" or not church or name.split(":")[-1] in \
            P["non_associative_3d_church"]
        if run_na:
            capna = P["cap_non_associative"]
            tag = "%s_nonassoc" % tag0
            rec = repeated(lambda c: run_rbla(self.rbla, model, dict(
                base, friction_model="non_associative", time_limit=0), self.work, tag, c), capna)
            add("rbla non-associative", rec, family="non_associative", param="default")
        else:
            entry["non_associative_skipped"] = ("3-D non-associative not run for this church load "
                                                "(run time budget)")
        # peers
        if mps and os.path.exists(mps):
            for crossover in (True, False):
                rec = repeated(lambda c: run_clp(mps, crossover, c), cap)
                if rec.get("ok") and k is not None:
                    rec["value"] = k * rec["objective"]
                add("CLP barrier" + ("" if crossover else " (no crossover)"), rec,
                    family="clp_barrier" if crossover else "clp_barrier_nocross", param="default")
            # an independent high-accuracy value: dual simplex at tolerances 1e-10, as
            # tests/crosscheck/sample_references.py computes the samples' expected values
            rec = repeated(lambda c: run_clp(mps, True, c, args=CLP_DUAL_TIGHT), cap)
            if rec.get("ok") and k is not None:
                rec["value"] = k * rec["objective"]
            add("CLP dual simplex", rec, family="clp_dual_tight", param="tol 1e-10")
        if os.path.exists(cbf):
            for tol in (P["light_cvxopt_tols"] if light else P["cvxopt_tols"]):
                rec = repeated(lambda c: run_cvxopt(self.args.peer_python, cbf, tol, c),
                               P["cap_cvxopt"])
                if rec.get("objective") is not None and k is not None:
                    rec["value"] = k * rec["objective"]
                add("CVXOPT conelp", rec, family="cvxopt", param="tol %g" % tol)
        for f in (mps, cbf):
            if f and os.path.exists(f):
                os.remove(f)
        self.results["scenes"].append(entry)
        self.save()

    def scaling(self):
        P = self.plan
        series = []
        for load in P["scaling_loads_planar"] + P["scaling_3d"]:
            formulation = "3d" if load in P["scaling_3d"] else "planar"
            dead = set()  # methods that exceeded their cap: not run at larger sizes
            for n in P["scaling_sizes"]:
                model, gen_cmd, gen_log = church_model(self.work, load, n)
                nb = len(model["blocks"])
                tag0 = "scale_%s_%s_%d" % (load, formulation, n)
                log("scaling %s %s ~%d blocks (%d)" % (load, formulation, n, nb))
                mps = os.path.join(self.work, tag0 + ".mps") if formulation == "planar" else None
                cbf = os.path.join(self.work, tag0 + ".cbf")
                point = {"load": load, "formulation": formulation, "target_blocks": n,
                         "num_blocks": nb, "generator": gen_cmd, "runs": []}
                if "rbla" not in dead:
                    # the timed run writes the problem for the peers (rbla's solve_seconds does
                    # not include writing it; its wall time does)
                    alive = [p for p in (["clp", "clp_nocross"] if mps else []) + ["cvxopt"]
                             if p not in dead]
                    if mps and nb > P["scaling_cvxopt_planar_max_blocks"]:
                        alive = [p for p in alive if p != "cvxopt"]
                    dump = (mps if any(p.startswith("clp") for p in alive) else None) if mps \
                        else (cbf if alive else None)
                    rec = repeated(lambda c: run_rbla(
                        self.rbla, model, {"formulation": formulation}, self.work, tag0, c,
                        dump=dump), P["scaling_cap_3d"] if formulation == "3d" else P["scaling_cap"])
                    rec["method"] = "rbla"
                    point["runs"].append(rec)
                    if rec.get("model_summary"):
                        point["model_summary"] = rec["model_summary"]
                    if rec.get("timed_out"):
                        dead.add("rbla")
                    k = (rec["value"] / rec["primal_objective"]) if rec.get("ok") and \
                        rec.get("primal_objective") else None
                    log("  rbla %s %s %.2f s" % (rec.get("outcome"), rec.get("value"),
                                                 rec.get("solve_seconds") or rec["wall_seconds"]))
                    peers = alive
                    if not rec.get("ok"):
                        peers = []
                    if mps and "cvxopt" in peers:
                        # the CBF of the planar LP: one more (untimed) rbla run
                        run_rbla(self.rbla, model, {"formulation": formulation}, self.work,
                                 tag0 + "_dumpcbf", P["scaling_cap"], dump=cbf)
                    for p in peers:
                        cap = P["scaling_peer_cap"]
                        if p.startswith("clp"):
                            prec = repeated(lambda c: run_clp(mps, p == "clp", c), cap)
                            name = "CLP barrier" + ("" if p == "clp" else " (no crossover)")
                            obj = prec.get("objective")
                        else:
                            prec = repeated(lambda c: run_cvxopt(self.args.peer_python, cbf,
                                                                 1e-7, c), cap)
                            name = "CVXOPT conelp"
                            obj = prec.get("objective")
                        prec["method"] = name
                        if obj is not None and k is not None:
                            prec["value"] = k * obj
                            prec["difference_vs_rbla"] = rel_err(prec["value"], rec["value"])
                        if prec.get("timed_out"):
                            dead.add(p)
                        point["runs"].append(prec)
                        log("  %s %s %.2f s" % (name, prec.get("outcome"),
                                                prec.get("solve_seconds") or prec["wall_seconds"]))
                for f in (mps, cbf, os.path.join(self.work, "church_%s_%s.json" % (load, n))):
                    if f and os.path.exists(f):
                        os.remove(f)
                series.append(point)
                self.results["scaling"] = series
                self.save()

    def save(self):
        os.makedirs(self.args.out, exist_ok=True)
        with open(os.path.join(self.args.out, "results.json"), "w") as fh:
            json.dump(self.results, fh, indent=1, sort_keys=True)


# ----------------------------------------------------------------------------------------------
# Machine
# ----------------------------------------------------------------------------------------------

def machine_info(rbla):
    info = {"date_utc": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
            "nproc": os.cpu_count(), "platform": platform.platform(),
            "python": platform.python_version()}
    try:
        with open("/proc/cpuinfo") as fh:
            m = re.search(r"^model name\s*:\s*(.*)$", fh.read(), re.M)
            info["cpu_model"] = m.group(1).strip() if m else "unknown"
        with open("/proc/meminfo") as fh:
            m = re.search(r"^MemTotal:\s*(\d+) kB", fh.read(), re.M)
            info["ram_gib"] = round(int(m.group(1)) / 1024.0 / 1024.0, 1)
        with open("/proc/loadavg") as fh:
            info["load_average_start"] = fh.read().split()[:3]
    except OSError:
        pass

    def cmd(c):
        try:
            return subprocess.run(c, capture_output=True, text=True, cwd=ROOT).stdout.strip()
        except OSError:
            return ""
    info["git_commit"] = cmd(["git", "rev-parse", "HEAD"])
    try:
        dirty = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"],
                               capture_output=True, text=True, cwd=ROOT).stdout
    except OSError:
        dirty = ""
    info["git_uncommitted_files"] = [ln[3:] for ln in dirty.splitlines() if len(ln) > 3]
    info["rbla"] = os.path.relpath(os.path.abspath(rbla), ROOT)
    info["rbla_binary_mtime_utc"] = datetime.datetime.fromtimestamp(
        os.path.getmtime(rbla), datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    info["clp_version"] = next((ln for ln in cmd(["clp", "-quit"]).splitlines()
                                if "version" in ln.lower()), "")
    return info


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter,
                                 epilog=__doc__.split("\n", 2)[2])
    ap.add_argument("--rbla", required=True, help="the rbla binary")
    ap.add_argument("--out", required=True, help="output directory (report.md, results.json, *.svg)")
    ap.add_argument("--quick", action="store_true", help="a small plan, for debugging (minutes)")
    ap.add_argument("--work", default=None, help="scratch directory (default: a new temporary one)")
    ap.add_argument("--peer-python", default="/usr/bin/python3",
                    help="python with cvxopt and numpy for the CVXOPT peer")
    ap.add_argument("--only", choices=["scenes", "scaling"], default=None,
                    help="run one part only (the other part is left empty)")
    ap.add_argument("--report-only", action="store_true",
                    help="rewrite report.md and the plots from OUT/results.json, run nothing")
    args = ap.parse_args()
    plan = PLAN_QUICK if args.quick else PLAN_FULL
    if args.report_only:
        with open(os.path.join(args.out, "results.json")) as fh:
            results = json.load(fh)
        import report_md
        report_md.write(results, args.out)
        return 0
    for tool in ("clp", "/usr/bin/time"):
        if not shutil.which(tool):
            raise SystemExit("%s not found (Debian packages coinor-clp, time)" % tool)
    bench = Bench(args, plan)
    t_start = time.time()
    bench.results["machine"] = machine_info(args.rbla)
    bench.results["plan"] = dict(plan, quick=args.quick, reference_tol=REFERENCE_TOL,
                                 repeat_below_seconds=REPEAT_BELOW, repeats=REPEATS)
    with open(os.path.join(ROOT, "samples", "expected.json")) as fh:
        expected = json.load(fh)["samples"]
    if args.only != "scaling":
        for s in plan["samples"]:
            with open(os.path.join(ROOT, "samples", s + ".json")) as fh:
                model = json.load(fh)
            exp = expected.get(s + ".json", {})
            cf = (exp.get("load_multiplier") or exp.get("base_reaction")) \
                if s in CLOSED_FORM_SAMPLES else None
            for formulation in ("planar", "3d"):
                bench.scene(s, model, formulation, closed_form=cf, gen_cmd="samples/%s.json" % s)
        for load in plan["church_loads"]:
            model, gen_cmd, gen_log = church_model(bench.work, load, plan["church_blocks"])
            bench.results.setdefault("church_generator_log", {})[load] = gen_log
            forms = ([] if load == "seismic-y" else ["planar"]) + \
                (["3d"] if load in plan["church_3d_loads"] else [])
            for formulation in forms:
                bench.scene("church:" + load, model, formulation, gen_cmd=gen_cmd, church=True)
    if args.only != "scenes":
        bench.scaling()
    with open("/proc/loadavg") as fh:
        bench.results["machine"]["load_average_end"] = fh.read().split()[:3]
    bench.results["machine"]["run_minutes"] = round((time.time() - t_start) / 60.0, 1)
    bench.save()
    import report_md
    report_md.write(bench.results, args.out)
    log("done in %.1f min; %s" % ((time.time() - t_start) / 60.0, args.out))
    if not args.work:
        shutil.rmtree(bench.work, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
