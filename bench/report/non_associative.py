#!/usr/bin/env python3
"""Non-associative friction against associative, whole runs of `rbla solve`, in one session.

    python3 bench/report/non_associative.py --rbla build/solver/rbla --out docs/benchmark

For each scene (the generated 1920-block facade and the 1674-block church facade, half the base
settling and in-plane seismic, planar LP and 3-D cones), the associative and the non-associative
run of the same model are timed in turn (A B A B ..., --repeat pairs), so that their ratio is
measured in the same minutes on a shared machine. The report gives per case: both values, the
median wall times and the median of the per-pair ratios, the scheme's steps, fixed-point tests,
interior-point iterations, whether it converged, the range of compatible states, and the error of
each step's state against the value reported, with the time spent up to it (error against run
time). Standard library only; writes non_associative.md and non_associative.json into --out.
"""
import argparse
import datetime
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
GENERATOR = os.path.join(ROOT, "samples", "generate_samples.py")

# Imperfections of a CAD export (samples/README.md): vertex noise, warped and split faces, joint
# gaps and overlaps, the model rotated about the vertical.
IMPERFECT = ["--noise", "0.0005", "--warp", "0.002", "--joint-gap", "0.0005", "--split-faces", "0.3", "--rotate", "30"]
# (scene, load, generator arguments, formulations): the shells are 3-D only.
SCENES = [
    ("facade", "settlement", ["facade", "--settling-fraction", "0.5"], None),
    ("facade", "seismic", ["facade", "--seismic", "x"], None),
    ("church", "settlement", ["church", "--load", "settlement"], None),
    ("church", "seismic", ["church", "--load", "seismic-x"], None),
    ("dome, imperfect", "seismic", ["dome"] + IMPERFECT, ["3d"]),
    ("vault, imperfect", "seismic", ["vault"] + IMPERFECT, ["3d"]),
]


def generate(args, path):
    subprocess.run([sys.executable, GENERATOR] + args + ["-o", path], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


def variant(path, out, friction, formulation):
    with open(path) as f:
        model = json.load(f)
    model["analysis"]["friction_model"] = friction
    model["analysis"]["formulation"] = formulation
    with open(out, "w") as f:
        json.dump(model, f)


def run(rbla, model, result):
    start = time.perf_counter()
    done = subprocess.run([rbla, "solve", model, "-o", result, "-q"], stdout=subprocess.DEVNULL,
                          stderr=subprocess.DEVNULL)
    seconds = time.perf_counter() - start
    if done.returncode != 0:
        raise RuntimeError("%s exited with %d" % (model, done.returncode))
    with open(result) as f:
        return seconds, json.load(f)


def value_of(result):
    if "load_multiplier" in result:
        return result["load_multiplier"]
    return result["base_reaction"]["at_collapse"]


def case(rbla, work, scene, load, formulation, repeat):
    base = os.path.join(work, "%s_%s.json" % (scene, load))
    paths = {}
    for friction in ("associative", "non_associative"):
        paths[friction] = os.path.join(work, "%s_%s_%s_%s.json" % (scene, load, formulation, friction))
        variant(base, paths[friction], friction, formulation)
    times = {"associative": [], "non_associative": []}
    results = {}
    for _ in range(repeat):
        for friction in ("associative", "non_associative"):
            seconds, results[friction] = run(rbla, paths[friction], paths[friction] + ".result")
            times[friction].append(seconds)
    n = results["non_associative"]
    conv = n["convergence"]
    final = value_of(n)
    elapsed, steps = 0.0, []
    for row in conv["non_associative"]:
        elapsed += row.get("seconds", 0.0)
        steps.append({"step": row["iteration"] - 1, "value": row["load_multiplier"],
                      "error": abs(row["load_multiplier"] - final) / abs(final), "seconds": elapsed,
                      "dilatancy": row.get("dilatancy"), "ipm": row["interior_point_iterations"]})
    return {
        "scene": scene, "load": load, "formulation": formulation,
        "blocks": n["model_summary"]["num_blocks"] if "model_summary" in n else None,
        "associative": value_of(results["associative"]), "non_associative": final,
        "seconds_associative": statistics.median(times["associative"]),
        "seconds_non_associative": statistics.median(times["non_associative"]),
        "ratio": statistics.median(b / a for a, b in zip(times["associative"], times["non_associative"])),
        "steps": len(conv["non_associative"]) - 1, "tests": conv.get("non_associative_checks", 0),
        "converged": conv["non_associative_converged"], "stop": conv.get("non_associative_stop", ""),
        "gap": conv.get("non_associative_gap"), "range": conv.get("non_associative_range"),
        "pointwise": conv.get("non_associative_pointwise"),
        "open_force": conv.get("non_associative_open_force"),
        "ipm_associative": conv["non_associative"][0]["interior_point_iterations"],
        "ipm": sum(r["interior_point_iterations"] for r in conv["non_associative"][1:]),
        "ipm_tests": reported_run(conv).get("test_iterations"),
        "per_step": steps,
    }


def pointwise_text(c):
    """Whether the reported state matches its mechanism point by point, or how far it is from it."""
    if c.get("pointwise") is None:
        return "not checked"
    if c["pointwise"]:
        return "point by point"
    return "in work only (open points carry %.2g %% of max N)" % (100.0 * (c.get("open_force") or 0.0))


def reported_run(conv):
    return next(r for r in conv["non_associative_trajectories"] if r["reported"])


def markdown(cases, meta):
    out = ["# Non-associative friction: whole runs against associative", "",
           "Written by `bench/report/non_associative.py` (%s, %s; load average %s at the start, %s at "
           "the end). Each case's associative and non-associative runs alternate %d times; times are "
           "medians, the ratio is the median of the per-pair ratios. Values: α (seismic) or R in kN "
           "(settlement)." % (meta["date"], meta["rbla"], meta["load_start"], meta["load_end"], meta["repeat"]),
           "",
           "| scene | load | formulation | associative | non-associative | range of compatible states | "
           "time assoc. | time non-assoc. | ratio | steps | tests | IPM iterations: associative solve | steps | "
           "tests | converged | matches its mechanism |",
           "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for c in cases:
        rng = c["range"]
        rng_text = "%.6g – %.6g" % (rng["low"], rng["high"]) if rng else "–"
        out.append("| %s | %s | %s | %.6g | %.6g | %s | %.2f s | %.2f s | %.1f× | %d | %d | %d | %d | %d | %s | %s |" % (
            c["scene"], c["load"], c["formulation"], c["associative"], c["non_associative"], rng_text,
            c["seconds_associative"], c["seconds_non_associative"], c["ratio"], c["steps"], c["tests"],
            c["ipm_associative"], c["ipm"], c["ipm_tests"], "yes" if c["converged"] else "no: " + c["stop"],
            pointwise_text(c)))
    out += ["", "Matches its mechanism: whether an equilibrated state carries no force where the mechanism opens "
            "and the full friction where it slides (convergence.non_associative_pointwise, docs/method.md, "
            "\"How compatible a certified state is\"); when none does, the largest normal force at an opening "
            "point of the state reported.", ""]
    out += ["", "IPM iterations: of the associative solve the run starts from; of its steps; and of its other "
            "solves (the selections of the conservative state on a step's optimal face, the fixed-point tests "
            "and the range of compatible states). (associative solve + tests) / associative solve is what a run "
            "would cost in iterations if its steps were free:", ""]
    out.append(", ".join("%s %s %s %.1f×" % (c["scene"], c["load"], c["formulation"],
                                            (c["ipm_associative"] + c["ipm_tests"]) / c["ipm_associative"])
                         for c in cases) + ".")
    out += ["", "## Error of each step against the value reported", "",
            "Step 0 is the associative solve. Every step's state satisfies Coulomb's condition; the error "
            "is |value of the step's state − value reported| / value reported; time is the solves' time up "
            "to that step (the fixed-point tests and the final selection come after the last step).", ""]
    for c in cases:
        out.append("**%s, %s, %s** (%d steps):" % (c["scene"], c["load"], c["formulation"], c["steps"]))
        out.append("")
        out.append("| step | value | error | dilatancy | IPM iterations | time |")
        out.append("|---|---|---|---|---|---|")
        for s in c["per_step"]:
            out.append("| %d | %.8g | %.2e | %.1e | %d | %.2f s |" % (
                s["step"], s["value"], s["error"], s["dilatancy"] or 0.0, s["ipm"], s["seconds"]))
        out.append("")
    return "\n".join(out) + "\n"


def load_average():
    with open("/proc/loadavg") as f:
        return f.read().split()[0]


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--rbla", required=True)
    parser.add_argument("--out", required=True)
    parser.add_argument("--repeat", type=int, default=2, help="associative / non-associative pairs per case")
    parser.add_argument("--formulations", default="planar,3d")
    args = parser.parse_args(argv)
    rbla = os.path.abspath(args.rbla)
    meta = {"date": datetime.datetime.utcnow().strftime("%Y-%m-%d %H:%M UTC"), "repeat": args.repeat,
            "load_start": load_average(), "rbla": subprocess.run([rbla, "--version"], capture_output=True,
                                                                 text=True).stdout.strip()}
    cases = []
    with tempfile.TemporaryDirectory() as work:
        for scene, load, gen_args, formulations in SCENES:
            generate(gen_args, os.path.join(work, "%s_%s.json" % (scene, load)))
            for formulation in formulations or args.formulations.split(","):
                c = case(rbla, work, scene, load, formulation, args.repeat)
                print("%s %s %s: %.6g -> %.6g, ratio %.1f, %d steps, converged %s" % (
                    scene, load, formulation, c["associative"], c["non_associative"], c["ratio"], c["steps"],
                    c["converged"]), flush=True)
                cases.append(c)
    meta["load_end"] = load_average()
    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, "non_associative.json"), "w") as f:
        json.dump({"meta": meta, "cases": cases}, f, indent=1)
    with open(os.path.join(args.out, "non_associative.md"), "w") as f:
        f.write(markdown(cases, meta))


if __name__ == "__main__":
    main()
