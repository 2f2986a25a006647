#!/usr/bin/env python3
"""Cost and reliability of `rbla worst-settlement` on generated scenes, in one session.

    python3 bench/report/worst_settlement.py --rbla build/solver/rbla --out docs/benchmark

For each scene, one `rbla solve` (vertical settlement) and one `rbla worst-settlement` of the same
model are timed in turn (--repeat pairs), so that the search's cost in single solves is measured in
the same minutes on a shared machine. On the scenes marked `dense`, R / R0 is also evaluated with
`rbla solve` over a grid of the cone (every --dense-tilt degrees of tilt, --dense-azimuth degrees
of azimuth), and the search must not end below the largest of them by more than its tolerance, nor
its certified upper bound below it. Standard library only; writes worst_settlement.md and
worst_settlement.json into --out.
"""
import json
import math
import os
import subprocess
import sys

from search_runs import arguments, fmt, generate, report_failures, run_scenes, solve_against_search, write_report

# The search's defaults (rbla worst-settlement --tolerance, --cone-angle).
TOLERANCE = 1e-3
CONE = 30.0
IMPERFECT = ["--noise", "0.0005", "--warp", "0.002", "--joint-gap", "0.0005", "--split-faces", "0.3", "--rotate", "30"]
# (scene, generator arguments, check against a dense sampling)
SCENES = [
    ("wall", ["wall-settlement"], True),
    ("wall, imperfect", ["wall-settlement"] + IMPERFECT, True),
    ("facade", ["facade", "--settling-fraction", "0.5"], False),
    ("church", ["church", "--load", "settlement"], False),
]


def unit(v):
    n = math.sqrt(sum(c * c for c in v))
    return [c / n for c in v]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def dense_maximum(rbla, model_path, w, tilt_step, azimuth_step, work):
    """Largest R / R0 over a grid of the cone, with R0 = w . d from the search's own w (checked
    against each solve's own R0)."""
    with open(model_path) as f:
        model = json.load(f)
    down = [0.0, 0.0, -1.0]  # the generator's gravity
    # rbla's azimuth axes: +x, and up cross +x (counter-clockwise seen from above).
    e1 = [1.0, 0.0, 0.0]
    e2 = cross([-c for c in down], e1)
    best = None
    tilt = 0.0
    while tilt <= CONE + 1e-9:
        azimuths = [0.0] if tilt == 0.0 else [k * azimuth_step for k in range(int(round(360 / azimuth_step)))]
        for azimuth in azimuths:
            t, p = math.radians(tilt), math.radians(azimuth)
            d = unit([math.cos(t) * down[i] + math.sin(t) * (math.cos(p) * e1[i] + math.sin(p) * e2[i])
                      for i in range(3)])
            model["analysis"]["settlement"] = {"direction": d}
            variant, result = os.path.join(work, "dense.json"), os.path.join(work, "dense.result.json")
            with open(variant, "w") as f:
                json.dump(model, f)
            subprocess.run([rbla, "solve", variant, "-q", "-o", result], check=True, stdout=subprocess.DEVNULL)
            with open(result) as f:
                r = json.load(f)
            reaction = r.get("base_reaction", {})
            if reaction.get("at_collapse") is None:
                continue
            r0 = sum(wi * di for wi, di in zip(w, d))
            if reaction.get("initial") is not None and abs(reaction["initial"] - r0) > 1e-6 * abs(r0):
                raise RuntimeError("R0 along %s: solve %g, w . d %g" % (d, reaction["initial"], r0))
            ratio = reaction["at_collapse"] / r0
            if best is None or ratio > best[0]:
                best = (ratio, tilt, azimuth)
        tilt += tilt_step
    return best


def measure(args, scene, work):
    name, gen_args, dense = scene
    model = os.path.join(work, "model.json")
    blocks = generate(gen_args, model)
    result = os.path.join(work, "search.json")
    times = solve_against_search(args.rbla, model, [args.rbla, "worst-settlement", model, "-q", "-o", result],
                                 args.repeat, work)
    with open(result) as f:
        w = json.load(f)["worst_settlement"]
    row = dict(times, scene=name, blocks=blocks, ratio=w.get("ratio"), tilt_deg=w.get("tilt_deg"),
               azimuth_deg=w.get("azimuth_deg"), upper_bound=w.get("upper_bound"), certified=w["certified"],
               evaluations=w["num_evaluations"], stop=w["stop"], vertical_ratio=w["evaluations"][0].get("ratio"))
    if dense:
        best = dense_maximum(args.rbla, model, w["initial_reaction_vector"], args.dense_tilt, args.dense_azimuth, work)
        row["dense_maximum"], row["dense_tilt_deg"], row["dense_azimuth_deg"] = best if best else (None, None, None)
    return row


def markdown(rows, meta):
    lines = [
        "# Most harmful settlement direction: cost and reliability", "",
        f"Written by `bench/report/worst_settlement.py` ({meta['date']}, load average {meta['load_start']:.2f} at the "
        f"start, {meta['load_end']:.2f} at the end). Cone of {CONE:g}° around gravity. Each scene's `rbla solve` "
        f"(vertical settlement) and `rbla worst-settlement` alternate {meta['repeat']} times; times are medians, *cost* "
        "is the median of the per-pair ratios (search time over one solve's). *Vertical* is R/R0 of the vertical "
        f"settlement. *Dense* is the largest R/R0 of `rbla solve` every {meta['dense_tilt']:g}° of tilt and "
        f"{meta['dense_azimuth']:g}° of azimuth (independent of the search). The certificate must hold: upper bound ≥ "
        "dense maximum, and a certified ratio within the tolerance (1e-3) of it.", "",
        "| scene | blocks | R/R0 max | tilt | azimuth | upper bound | certified | vertical | directions | one solve "
        "| search | cost (solves) | dense |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        dense = "-" if r.get("dense_maximum") is None else (
            f"{r['dense_maximum']:.6g} at {r['dense_tilt_deg']:g}°, {r['dense_azimuth_deg']:g}°")
        lines.append(
            f"| {r['scene']} | {r['blocks']} | {fmt(r['ratio'], '.6g')} | {fmt(r['tilt_deg'], '.2f')}° | "
            f"{fmt(r['azimuth_deg'], '.2f')}° | {fmt(r['upper_bound'], '.6g')} | {'yes' if r['certified'] else 'no'} | "
            f"{fmt(r['vertical_ratio'], '.6g')} | {r['evaluations']} | {r['single_solve_s']:.2f} s | "
            f"{r['search_s']:.2f} s | {r['solves_equivalent']:.1f} | {dense} |")
    lines += ["", "Why each search stopped:", ""]
    lines += [f"- {r['scene']}: {r['stop']}" for r in rows]
    return "\n".join(lines) + "\n"


def main():
    def extra(parser):
        parser.add_argument("--dense-tilt", type=float, default=5.0)
        parser.add_argument("--dense-azimuth", type=float, default=10.0)
    args = arguments(__doc__, extra)
    rows, meta = run_scenes(args, SCENES, lambda scene, work: measure(args, scene, work),
                            lambda r: f"R/R0 {r['ratio']} at tilt {r['tilt_deg']}, azimuth {r['azimuth_deg']}, "
                                      f"{r['evaluations']} directions, cost {r['solves_equivalent']:.1f} solves, "
                                      f"dense {r.get('dense_maximum')}")
    meta.update(dense_tilt=args.dense_tilt, dense_azimuth=args.dense_azimuth)
    write_report(args.out, "worst_settlement", markdown(rows, meta), rows, meta)
    dense = [r for r in rows if r.get("dense_maximum") is not None]
    return report_failures([
        ("upper bound below the dense sampling",
         [r["scene"] for r in dense if r["upper_bound"] is not None and r["upper_bound"] < r["dense_maximum"] * (1 - 1e-9)]),
        ("certified maximum below the dense sampling",
         [r["scene"] for r in dense if r["certified"] and r["ratio"] < r["dense_maximum"] * (1 - TOLERANCE)]),
    ])


if __name__ == "__main__":
    sys.exit(main())
