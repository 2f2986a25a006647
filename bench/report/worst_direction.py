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
import argparse
import datetime
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
GENERATOR = os.path.join(ROOT, "samples", "generate_samples.py")
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


def timed(command):
    start = time.perf_counter()
    done = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if done.returncode != 0:
        raise RuntimeError(" ".join(command) + " failed: " + done.stderr[-2000:])
    return time.perf_counter() - start


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


def measure(rbla, name, args, dense, repeat, dense_step, work):
    model = os.path.join(work, "model.json")
    subprocess.run([sys.executable, GENERATOR] + args + ["-o", model], check=True, stdout=subprocess.DEVNULL)
    solve_times, search_times = [], []
    result = os.path.join(work, "search.json")
    for _ in range(repeat):
        solve_times.append(timed([rbla, "solve", model, "-q", "-o", os.path.join(work, "solve.json")]))
        search_times.append(timed([rbla, "worst-direction", model, "-q", "-o", result]))
    with open(result) as f:
        w = json.load(f)["worst_direction"]
    with open(os.path.join(work, "model.json")) as f:
        blocks = len(json.load(f)["blocks"])
    row = {
        "scene": name, "blocks": blocks, "alpha_min": w.get("load_multiplier"), "angle_deg": w.get("angle_deg"),
        "lower_bound": w.get("lower_bound"), "certified": w["certified"], "evaluations": w["num_evaluations"],
        "single_solve_s": statistics.median(solve_times), "search_s": statistics.median(search_times),
        "solves_equivalent": statistics.median([b / a for a, b in zip(solve_times, search_times)]),
        "stop": w["stop"],
        "alphas": [(e["angle_deg"], e.get("load_multiplier")) for e in w["evaluations"]],
    }
    if dense:
        best = dense_minimum(rbla, model, dense_step, work)
        row["dense_minimum"], row["dense_angle_deg"] = best if best else (None, None)
    return row


def fmt(value, spec):
    return "-" if value is None else format(value, spec)


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
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--rbla", default=os.path.join(ROOT, "build", "solver", "rbla"))
    parser.add_argument("--out", default=os.path.join(ROOT, "docs", "benchmark"))
    parser.add_argument("--repeat", type=int, default=2)
    parser.add_argument("--dense-step", type=float, default=5.0)
    parser.add_argument("--only", help="run only the scenes whose name contains this")
    args = parser.parse_args()
    meta = {"date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
            "load_start": os.getloadavg()[0], "repeat": args.repeat, "dense_step": args.dense_step}
    rows = []
    with tempfile.TemporaryDirectory() as work:
        for name, gen_args, dense in SCENES:
            if args.only and args.only not in name:
                continue
            row = measure(args.rbla, name, gen_args, dense, args.repeat, args.dense_step, work)
            print(f"{name}: alpha_min {row['alpha_min']} at {row['angle_deg']} deg, {row['evaluations']} directions, "
                  f"cost {row['solves_equivalent']:.1f} solves, dense {row.get('dense_minimum')}", flush=True)
            rows.append(row)
    meta["load_end"] = os.getloadavg()[0]
    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, "worst_direction.md"), "w") as f:
        f.write(markdown(rows, meta))
    with open(os.path.join(args.out, "worst_direction.json"), "w") as f:
        json.dump({"meta": meta, "rows": rows}, f, indent=1)
    # The certificate: the lower bound is below every alpha (the dense sampling's too), and a
    # certified minimum is within the tolerance of the dense sampling's.
    broken = [r["scene"] for r in rows if r.get("dense_minimum") is not None and r["lower_bound"] is not None
              and r["lower_bound"] > r["dense_minimum"] * (1 + 1e-9)]
    worse = [r["scene"] for r in rows if r.get("dense_minimum") is not None and r["certified"]
             and r["alpha_min"] > r["dense_minimum"] * (1 + TOLERANCE)]
    for what, scenes in (("lower bound above the dense sampling", broken), ("certified minimum above the dense sampling", worse)):
        if scenes:
            print(what + " on: " + ", ".join(scenes), file=sys.stderr)
    return 1 if broken or worse else 0


if __name__ == "__main__":
    sys.exit(main())
