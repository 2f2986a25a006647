#!/usr/bin/env python3
"""Cost and reliability of `rbla worst-direction` on generated scenes, in one session.

    python3 bench/report/worst_direction.py --rbla build/solver/rbla --out docs/benchmark

For each scene, one `rbla solve` along +x and one `rbla worst-direction` of the same model are
timed in turn (--repeat pairs), so that the search's cost in single solves is measured in the same
minutes on a shared machine. On the scenes marked `dense`, alpha is also evaluated along every
--dense-step degrees with `rbla solve`, and the search must not end above the smallest of them (the
search claims a global minimum; a dense sampling is the independent check). Standard library only;
writes worst_direction.md and worst_direction.json into --out.
"""
import json
import math
import os
import subprocess
import sys

from search_runs import arguments, fmt, generate, report_failures, run_scenes, solve_against_search, write_report

# The search's default tolerance (rbla worst-direction --tolerance).
TOLERANCE = 1e-3
IMPERFECT = ["--noise", "0.0005", "--warp", "0.002", "--joint-gap", "0.0005", "--split-faces", "0.3", "--rotate", "30"]
# (scene, generator arguments, check against a dense sampling)
SCENES = [
    ("facade", ["facade", "--seismic", "x"], False),
    ("church", ["church", "--load", "seismic-x"], False),
    ("arch", ["arch"], True),
    ("dome, imperfect", ["dome"] + IMPERFECT, True),
    ("vault, imperfect", ["vault"] + IMPERFECT, True),
]


def along(model_path, angle_deg, out_path):
    with open(model_path) as f:
        model = json.load(f)
    a = math.radians(angle_deg)
    model["analysis"].setdefault("seismic", {})["direction"] = [math.cos(a), math.sin(a), 0.0]
    with open(out_path, "w") as f:
        json.dump(model, f)


def dense_minimum(rbla, model_path, step, work):
    values = []
    for k in range(int(round(360 / step))):
        angle = k * step
        variant = os.path.join(work, "dense.json")
        result = os.path.join(work, "dense.result.json")
        along(model_path, angle, variant)
        subprocess.run([rbla, "solve", variant, "-q", "-o", result], check=True, stdout=subprocess.DEVNULL)
        with open(result) as f:
            r = json.load(f)
        if r.get("load_multiplier") is not None:
            values.append((r["load_multiplier"], angle))
    return min(values) if values else None


def measure(args, scene, work):
    name, gen_args, dense = scene
    model = os.path.join(work, "model.json")
    blocks = generate(gen_args, model)
    result = os.path.join(work, "search.json")
    times = solve_against_search(args.rbla, model, [args.rbla, "worst-direction", model, "-q", "-o", result],
                                 args.repeat, work)
    with open(result) as f:
        w = json.load(f)["worst_direction"]
    row = dict(times, scene=name, blocks=blocks, alpha_min=w.get("load_multiplier"), angle_deg=w.get("angle_deg"),
               lower_bound=w.get("lower_bound"), certified=w["certified"], evaluations=w["num_evaluations"],
               stop=w["stop"], alphas=[(e["angle_deg"], e.get("load_multiplier")) for e in w["evaluations"]])
    if dense:
        best = dense_minimum(args.rbla, model, args.dense_step, work)
        row["dense_minimum"], row["dense_angle_deg"] = best if best else (None, None)
    return row


def markdown(rows, meta):
    lines = [
        "# Weakest seismic direction: cost and reliability", "",
        f"Written by `bench/report/worst_direction.py` ({meta['date']}, load average {meta['load_start']:.2f} at the "
        f"start, {meta['load_end']:.2f} at the end). Each scene's `rbla solve` (along +x) and `rbla worst-direction` "
        f"alternate {meta['repeat']} times; times are medians, *cost* is the median of the per-pair ratios "
        f"(search time over one solve's). *Dense* is the smallest α of `rbla solve` every {meta['dense_step']:g}° "
        "(independent of the search). The certificate must hold: lower bound ≤ dense minimum, "
        "and a certified α min within the tolerance (1e-3) of it.", "",
        "| scene | blocks | α min | at | lower bound | certified | directions | one solve | search | cost (solves) | dense every "
        f"{meta['dense_step']:g}° |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        dense = "-" if r.get("dense_minimum") is None else f"{r['dense_minimum']:.6g} at {r['dense_angle_deg']:g}°"
        lines.append(
            f"| {r['scene']} | {r['blocks']} | {fmt(r['alpha_min'], '.6g')} | {fmt(r['angle_deg'], '.2f')}° | "
            f"{fmt(r['lower_bound'], '.6g')} | {'yes' if r['certified'] else 'no'} | {r['evaluations']} | {r['single_solve_s']:.2f} s | {r['search_s']:.2f} s | "
            f"{r['solves_equivalent']:.1f} | {dense} |")
    lines += ["", "Why each search stopped:", ""]
    lines += [f"- {r['scene']}: {r['stop']}" for r in rows]
    return "\n".join(lines) + "\n"


def main():
    args = arguments(__doc__, lambda parser: parser.add_argument("--dense-step", type=float, default=5.0))
    rows, meta = run_scenes(args, SCENES, lambda scene, work: measure(args, scene, work),
                            lambda r: f"alpha_min {r['alpha_min']} at {r['angle_deg']} deg, {r['evaluations']} "
                                      f"directions, cost {r['solves_equivalent']:.1f} solves, dense {r.get('dense_minimum')}")
    meta["dense_step"] = args.dense_step
    write_report(args.out, "worst_direction", markdown(rows, meta), rows, meta)
    # The certificate: the lower bound is below every alpha (the dense sampling's too), and a
    # certified minimum is within the tolerance of the dense sampling's.
    dense = [r for r in rows if r.get("dense_minimum") is not None]
    return report_failures([
        ("lower bound above the dense sampling",
         [r["scene"] for r in dense if r["lower_bound"] is not None and r["lower_bound"] > r["dense_minimum"] * (1 + 1e-9)]),
        ("certified minimum above the dense sampling",
         [r["scene"] for r in dense if r["certified"] and r["alpha_min"] > r["dense_minimum"] * (1 + TOLERANCE)]),
    ])


if __name__ == "__main__":
    sys.exit(main())
