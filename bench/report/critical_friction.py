#!/usr/bin/env python3
"""Cost of `rbla critical-friction` in single solves on generated scenes, in one session.

    python3 bench/report/critical_friction.py --rbla build/solver/rbla --out docs/benchmark

For each scene and question (stand under the own weight; carry a target alpha), one `rbla solve`
and one `rbla critical-friction` of the same model are timed in turn (--repeat pairs), so that
the search's cost in single solves is measured in the same minutes on a shared machine. Each
factor the search evaluates is an analysis with the dead-load check (a second, small solve).
Standard library only; writes critical_friction.md and critical_friction.json into --out.
"""
import json
import os
import sys

from search_runs import arguments, fmt, generate, report_failures, run_scenes, solve_against_search, write_report

# (scene, generator arguments, target alpha or None to stand)
SCENES = [
    ("facade, stand", ["facade", "--seismic", "x"], None),
    ("facade, alpha 0.2", ["facade", "--seismic", "x"], 0.2),
    ("church, stand", ["church", "--load", "seismic-x"], None),
    ("church, alpha 0.2", ["church", "--load", "seismic-x"], 0.2),
]


def measure(rbla, repeat, scene, work):
    name, args, target = scene
    model = os.path.join(work, "model.json")
    blocks = generate(args, model)
    search = [rbla, "critical-friction", model, "-q", "-o", os.path.join(work, "search.json")]
    if target is not None:
        search += ["--target-alpha", repr(target)]
    times = solve_against_search(rbla, model, search, repeat, work)
    with open(os.path.join(work, "search.json")) as f:
        c = json.load(f)["critical_friction"]
    return dict(times, scene=name, blocks=blocks, outcome=c["outcome"], factor=c.get("factor"),
                factor_lower=c.get("factor_lower"), friction=c.get("friction"), certified=c["certified"],
                evaluations=c["num_evaluations"], stop=c["stop"])


def markdown(rows, meta):
    lines = [
        "# Critical friction: cost in single solves", "",
        f"Written by `bench/report/critical_friction.py` ({meta['date']}, load average {meta['load_start']:.2f} at the "
        f"start, {meta['load_end']:.2f} at the end). Each scene's `rbla solve` and `rbla critical-friction` alternate "
        f"{meta['repeat']} times; times are medians, *cost* is the median of the per-pair ratios (search time over one "
        "solve's). The bracket is [factor lower, factor]; μ is the critical coefficient (every joint had 0.6).", "",
        "| scene | blocks | outcome | factor lower | factor | μ | certified | factors | one solve | search | cost (solves) |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        lines.append(
            f"| {r['scene']} | {r['blocks']} | {r['outcome']} | {fmt(r['factor_lower'], '.6g')} | {fmt(r['factor'], '.6g')} | "
            f"{fmt(r['friction'], '.6g')} | {'yes' if r['certified'] else 'no'} | {r['evaluations']} | "
            f"{r['single_solve_s']:.2f} s | {r['search_s']:.2f} s | {r['solves_equivalent']:.1f} |")
    lines += ["", "Why each search stopped:", ""]
    lines += [f"- {r['scene']}: {r['stop']}" for r in rows]
    return "\n".join(lines) + "\n"


def main():
    args = arguments(__doc__)
    rows, meta = run_scenes(args, SCENES, lambda scene, work: measure(args.rbla, args.repeat, scene, work),
                            lambda r: f"factor {r['factor']} ({r['outcome']}), {r['evaluations']} factors, "
                                      f"cost {r['solves_equivalent']:.1f} solves")
    write_report(args.out, "critical_friction", markdown(rows, meta), rows, meta)
    return report_failures([("search failed", [r["scene"] for r in rows if r["outcome"] == "failed"])])


if __name__ == "__main__":
    sys.exit(main())
