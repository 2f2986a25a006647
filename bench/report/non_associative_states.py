#!/usr/bin/env python3
"""Which non-associative collapse state each test schedule certifies, on the benchmark scenes.

    python3 bench/report/non_associative_states.py --rbla build/solver/rbla --out docs/benchmark

Non-associative collapse is not unique: the scheme certifies the state its steps reach, and where
it tests its candidates decides which. Each scene of non_associative.py (planar for the facades,
3-D for the shells) is solved once with analysis.non_associative.trajectories = 6, which runs the
six test schedules in turn and lists every run's value; the report gives the values, the spread
of the certified ones, how far the first run (the default) and the best of the first k runs are
from the most conservative state found, and the seconds of each run. Standard library only;
writes non_associative_states.md and non_associative_states.json into --out.
"""
import argparse
import datetime
import json
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from non_associative import SCENES, generate, load_average  # noqa: E402

RUNS = 6


def solve(rbla, path, formulation, work):
    with open(path) as f:
        model = json.load(f)
    model["analysis"]["friction_model"] = "non_associative"
    model["analysis"]["formulation"] = formulation
    model["analysis"]["non_associative"] = {"trajectories": RUNS}
    variant = os.path.join(work, "states.json")
    with open(variant, "w") as f:
        json.dump(model, f)
    out = os.path.join(work, "states_result.json")
    subprocess.run([rbla, "solve", variant, "-o", out, "-q"], check=True, stdout=subprocess.DEVNULL,
                   stderr=subprocess.DEVNULL)
    with open(out) as f:
        return json.load(f)


def summarise(scene, load, formulation, result):
    runs = result["convergence"]["non_associative_trajectories"]
    settlement = load == "settlement"
    certified = [r["value"] for r in runs if r["certified"]]
    best = (max if settlement else min)(certified) if certified else None

    def shortfall(values):
        # How far the most conservative of `values` is on the unsafe side of the best, relative.
        if best is None or not values:
            return None
        chosen = (max if settlement else min)(values)
        return abs(best - chosen) / abs(best)

    first_k = [shortfall([r["value"] for r in runs[:k] if r["certified"]]) for k in range(1, RUNS + 1)]
    return {"scene": scene, "load": load, "formulation": formulation, "runs": runs,
            "spread": (max(certified) - min(certified)) / abs(best) if certified else None,
            "best": best, "first_k_shortfall": first_k}


def cell(run):
    """A run's value: * certified, † certified in work only (no state matches its mechanism point by
    point), bold the run reported."""
    mark = ("*" + ("†" if run.get("pointwise") is False else "")) if run["certified"] else ""
    text = "%.6g%s" % (run["value"], mark)
    return "**%s**" % text if run.get("reported") else text


def pct(x):
    return "–" if x is None else "%.2f %%" % (100.0 * x)


def markdown(cases, meta):
    lines = ["# Non-associative friction: which state each test schedule certifies", "",
             "Written by `bench/report/non_associative_states.py` (%s, %s; load average %.2f at the start, "
             "%.2f at the end). One `rbla solve` per scene with `analysis.non_associative.trajectories = %d`: "
             "the scheme runs once per test schedule (when_close/at_most: test every when_close steps once "
             "a step's state dilates by less than 1 %% of its value, and at least every at_most steps). "
             "Values: α (seismic) or R in kN (settlement); * marks a certified state (fixed-point test passed "
             "at the default tolerance 10⁻³), † a certified state whose mechanism no state matches point by "
             "point (it matches in work only), bold the run reported (a pointwise certified state before a "
             "work-only one, then the most conservative); the most conservative certified state is the lowest "
             "α or the highest R." % (meta["date"], meta["rbla"], meta["load_start"], meta["load_end"], RUNS), ""]
    schedules = [r["test_schedule"] for r in cases[0]["runs"]]
    head = "| scene | load | formulation | " + " | ".join(
        "run %d (%d/%d)" % (k + 1, s["when_close"], s["at_most"]) for k, s in enumerate(schedules)) + \
        " | spread of certified | default short of best | best of runs 1–2 | best of runs 1–3 |"
    lines += [head, "|" + "---|" * (len(schedules) + 7)]
    for c in cases:
        cells = [cell(r) for r in c["runs"]]
        f = c["first_k_shortfall"]
        lines.append("| %s | %s | %s | %s | %s | %s | %s | %s |" % (
            c["scene"], c["load"], c["formulation"], " | ".join(cells), pct(c["spread"]), pct(f[0]), pct(f[1]),
            pct(f[2])))
    lines += ["", "Seconds of each run's conic solves:", "",
              "| scene | load | " + " | ".join("run %d" % (k + 1) for k in range(len(schedules))) + " |",
              "|" + "---|" * (len(schedules) + 2)]
    for c in cases:
        lines.append("| %s | %s | %s |" % (c["scene"], c["load"], " | ".join("%.2f" % r["seconds"] for r in c["runs"])))
    lines.append("")
    return "\n".join(lines)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--rbla", required=True)
    parser.add_argument("--out", required=True)
    parser.add_argument("--render", help="only rewrite the markdown from this run's JSON")
    args = parser.parse_args(argv)
    if args.render:
        with open(args.render) as f:
            data = json.load(f)
        with open(os.path.join(args.out, "non_associative_states.md"), "w") as f:
            f.write(markdown(data["cases"], data["meta"]))
        return
    rbla = os.path.abspath(args.rbla)
    meta = {"date": datetime.datetime.utcnow().strftime("%Y-%m-%d %H:%M UTC"), "load_start": float(load_average()),
            "rbla": subprocess.run([rbla, "--version"], capture_output=True, text=True).stdout.strip()}
    cases = []
    with tempfile.TemporaryDirectory() as work:
        for scene, load, gen_args, formulations in SCENES:
            path = os.path.join(work, "scene.json")
            generate(gen_args, path)
            formulation = (formulations or ["planar"])[0]
            c = summarise(scene, load, formulation, solve(rbla, path, formulation, work))
            print("%s %s %s: %s; spread %s, default short of best %s" % (
                scene, load, formulation, ", ".join("%.6g%s" % (r["value"], "*" if r["certified"] else "")
                                                    for r in c["runs"]), pct(c["spread"]),
                pct(c["first_k_shortfall"][0])), flush=True)
            cases.append(c)
    meta["load_end"] = float(load_average())
    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, "non_associative_states.json"), "w") as f:
        json.dump({"meta": meta, "cases": cases}, f, indent=1)
    with open(os.path.join(args.out, "non_associative_states.md"), "w") as f:
        f.write(markdown(cases, meta))


if __name__ == "__main__":
    main()
