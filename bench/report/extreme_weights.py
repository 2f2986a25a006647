#!/usr/bin/env python3
"""Generated scenes with extreme per-block unit weights, associative and non-associative.

    python3 bench/report/extreme_weights.py --rbla build/solver/rbla --out docs/benchmark
    python3 bench/report/extreme_weights.py --rbla A/rbla --vs B/rbla --out /tmp/ab   # values of two builds

Each base scene (a town house under in-plane seismic load and under settlement, a church façade
under settlement and under out-of-plane seismic load, the town house again in millimetres with CAD
imperfections) is run in two variants the generators never make: unit weights spread over six
decades (each free block 18 kN/m3 times 10^u, u uniform in [-3, 3]) and 30 % of the free blocks
weightless. Every variant runs associative and non-associative, planar and 3-D (a scene that is not
planar is refused, which the report shows). What is checked, from outside rbla's own numbers: the
non-associative value on the safe side of the associative one (never above α, never below R), the
scheme's convergence, the work balance of the reported state and mechanism, and the warnings. With
--vs, a second build runs the same files and the relative difference of the values is reported.
Standard library only; writes extreme_weights.md and extreme_weights.json into --out.
"""

import argparse
import json
import os
import random
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
GENERATOR = os.path.join(ROOT, "samples", "generate_samples.py")

SCENES = [
    ("town house", "seismic", ["townhouse", "--bays", "2", "--storeys", "2", "--load", "seismic-x"]),
    ("town house", "settlement", ["townhouse", "--bays", "2", "--storeys", "2", "--load", "settlement"]),
    ("church", "settlement", ["church", "--blocks", "800", "--load", "settlement"]),
    ("church", "seismic out of plane", ["church", "--blocks", "800", "--load", "seismic-y"]),
    ("town house, mm, imperfect", "seismic",
     ["townhouse", "--bays", "2", "--storeys", "2", "--load", "seismic-x", "--units", "mm",
      "--noise", "0.0003", "--joint-gap", "0.0003"]),
]
WEIGHTS = {
    "six decades": lambda rnd, w: w * 10 ** rnd.uniform(-3, 3),
    "30 % weightless": lambda rnd, w: 0.0 if rnd.random() < 0.3 else w,
}


def write_variant(base, weights, friction, formulation, path):
    with open(base) as f:
        model = json.load(f)
    rnd = random.Random(7)
    unit_weight = model.get("defaults", {}).get("unit_weight", 18.0)
    for block in model["blocks"]:
        if block.get("role", "free") == "free":
            block["unit_weight"] = WEIGHTS[weights](rnd, unit_weight)
    model["analysis"]["friction_model"] = friction
    model["analysis"]["formulation"] = formulation
    with open(path, "w") as f:
        json.dump(model, f)


def solve(rbla, model, result):
    """(value, result JSON) or (None, first line of the error message)."""
    done = subprocess.run([rbla, "solve", model, "-o", result, "-q"], stdout=subprocess.DEVNULL,
                          stderr=subprocess.PIPE, text=True)
    if done.returncode != 0:
        lines = [l.strip() for l in done.stderr.splitlines() if l.strip()]
        return None, " ".join(lines[:2])[:160]
    with open(result) as f:
        r = json.load(f)
    value = r["load_multiplier"] if "load_multiplier" in r else r["base_reaction"]["at_collapse"]
    return value, r


def run_case(rbla, vs, work, scene, load, base, weights, formulation):
    values, rows = {}, {}
    for friction in ("associative", "non_associative"):
        path = os.path.join(work, "m_%s.json" % friction)
        write_variant(base, weights, friction, formulation, path)
        values[friction], rows[friction] = solve(rbla, path, path + ".result")
        if vs and values[friction] is not None:
            other, _ = solve(vs, path, path + ".vs")
            rows[friction + "_vs"] = other
    case = {"scene": scene, "load": load, "weights": weights, "formulation": formulation}
    a, n = values["associative"], values["non_associative"]
    if a is None or n is None:
        case["refused"] = rows["associative"] if a is None else rows["non_associative"]
        return case
    r = rows["non_associative"]
    conv = r["convergence"]
    settlement = "base_reaction" in r
    case.update({
        "associative": a, "non_associative": n,
        "safe_side": (n >= a * (1 - 1e-9)) if settlement else (n <= a * (1 + 1e-9)),
        "converged": conv.get("non_associative_converged"), "tests": conv.get("non_associative_checks"),
        "work_error": r["work_balance"]["relative_error"],
        "work_error_associative": rows["associative"]["work_balance"]["relative_error"],
        "warnings": sorted({w["code"] for w in r["warnings"] + rows["associative"]["warnings"]}),
        "verdict": r["verdict"],
    })
    if vs:
        case["vs"] = {k: rows.get(k + "_vs") for k in ("associative", "non_associative")}
    return case


def difference(c, friction):
    other = c.get("vs", {}).get(friction)
    return "–" if other is None else "%.1e" % (abs(other - c[friction]) / abs(c[friction]))


def markdown(cases, vs, meta):
    intro = ("Written by `bench/report/extreme_weights.py` (%s UTC; %s). Values: α (seismic) or R in kN "
             "(settlement). *Safe side*: the non-associative value is not above the associative α (not below "
             "the associative R). *Work*: |static − kinematic| / static of the reported state and mechanism "
             "(non-associative: to the scheme's tolerance, 1e-3 by default)." % (meta["date"], meta["rbla"]))
    if vs:
        intro += " *Δ vs*: relative difference of the value given by the second build: %s." % meta["vs"]
    out = ["# Extreme unit weights: generated scenes nobody tuned on", "", intro, "",
           "| scene | load | unit weights | formulation | associative | non-associative | safe side | "
           "converged (tests) | work assoc. / non-assoc. | warnings |" + (" Δ vs assoc. / non-assoc. |" if vs else ""),
           "|---|---|---|---|---|---|---|---|---|---|" + ("---|" if vs else "")]
    for c in cases:
        head = "| %s | %s | %s | %s |" % (c["scene"], c["load"], c["weights"], c["formulation"])
        if "refused" in c:
            out.append(head + " refused: %s |" % c["refused"] + " |" * (5 + (1 if vs else 0)))
            continue
        row = head + " %.9g | %.9g | %s | %s (%s) | %.0e / %.0e | %s |" % (
            c["associative"], c["non_associative"], "yes" if c["safe_side"] else "**no**",
            "yes" if c["converged"] else "**no**", c["tests"], c["work_error_associative"], c["work_error"],
            ", ".join(c["warnings"]) or "–")
        if vs:
            row += " %s / %s |" % (difference(c, "associative"), difference(c, "non_associative"))
        out.append(row)
    return "\n".join(out) + "\n"


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--rbla", required=True)
    parser.add_argument("--vs", help="a second rbla build: its values on the same files")
    parser.add_argument("--vs-label", help="what the second build is, for the report (default: its path)")
    parser.add_argument("--out", required=True)
    parser.add_argument("--report-only", action="store_true", help="rewrite the .md from OUT/extreme_weights.json")
    args = parser.parse_args(argv)
    json_path = os.path.join(args.out, "extreme_weights.json")
    if args.report_only:
        with open(json_path) as f:
            saved = json.load(f)
        with open(os.path.join(args.out, "extreme_weights.md"), "w") as f:
            f.write(markdown(saved["cases"], saved["meta"].get("vs"), saved["meta"]))
        return 0
    version = subprocess.run([args.rbla, "--version"], capture_output=True, text=True).stdout.strip()
    commit = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True).stdout.strip()
    meta = {"date": time.strftime("%Y-%m-%d %H:%M", time.gmtime()), "rbla": "%s, commit %s" % (version, commit),
            "vs": args.vs_label or args.vs}
    cases = []
    with tempfile.TemporaryDirectory() as work:
        for scene, load, gen_args in SCENES:
            base = os.path.join(work, "base.json")
            subprocess.run([sys.executable, GENERATOR] + gen_args + ["-o", base], check=True,
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            for weights in WEIGHTS:
                for formulation in ("planar", "3d"):
                    cases.append(run_case(args.rbla, args.vs, work, scene, load, base, weights, formulation))
                    print(json.dumps(cases[-1])[:200], file=sys.stderr)
    os.makedirs(args.out, exist_ok=True)
    with open(json_path, "w") as f:
        json.dump({"meta": meta, "cases": cases}, f, indent=1)
    with open(os.path.join(args.out, "extreme_weights.md"), "w") as f:
        f.write(markdown(cases, args.vs, meta))
    bad = [c for c in cases if "refused" not in c and not (c["safe_side"] and c["converged"])]
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
