#!/usr/bin/env python3
"""Cost of `rbla critical-friction` in single solves on generated scenes, in one session.

    python3 bench/report/critical_friction.py --rbla build/solver/rbla --out docs/benchmark

For each scene and question (stand under the own weight; carry a target alpha), one `rbla solve`
and one `rbla critical-friction` of the same model are timed in turn (--repeat pairs), so that
the search's cost in single solves is measured in the same minutes on a shared machine. Each
factor the search evaluates is a solve with the dead-load check (a second, small solve), so the
cost is at least the number of factors. Standard library only; writes critical_friction.md and
critical_friction.json into --out.
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
# (scene, generator arguments, target alpha or None to stand)
SCENES = [
    ("facade, stand", ["facade", "--seismic", "x"], None),
    ("facade, alpha 0.2", ["facade", "--seismic", "x"], 0.2),
    ("church, stand", ["church", "--load", "seismic-x"], None),
    ("church, alpha 0.2", ["church", "--load", "seismic-x"], 0.2),
]


def timed(command):
    start = time.perf_counter()
    done = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if done.returncode != 0:
        raise RuntimeError(" ".join(command) + " failed: " + done.stderr[-2000:])
    return time.perf_counter() - start


def measure(rbla, name, args, target, repeat, work):
    model = os.path.join(work, "model.json")
    subprocess.run([sys.executable, GENERATOR] + args + ["-o", model], check=True, stdout=subprocess.DEVNULL)
    search = [rbla, "critical-friction", model, "-q", "-o", os.path.join(work, "search.json")]
    if target is not None:
        search += ["--target-alpha", repr(target)]
    solve_times, search_times = [], []
    for _ in range(repeat):
        solve_times.append(timed([rbla, "solve", model, "-q", "-o", os.path.join(work, "solve.json")]))
        search_times.append(timed(search))
    with open(os.path.join(work, "search.json")) as f:
        c = json.load(f)["critical_friction"]
    with open(model) as f:
        blocks = len(json.load(f)["blocks"])
    return {
        "scene": name, "blocks": blocks, "outcome": c["outcome"], "factor": c.get("factor"),
        "factor_lower": c.get("factor_lower"), "friction": c.get("friction"), "certified": c["certified"],
        "evaluations": c["num_evaluations"], "single_solve_s": statistics.median(solve_times),
        "search_s": statistics.median(search_times),
        "solves_equivalent": statistics.median([b / a for a, b in zip(solve_times, search_times)]),
        "stop": c["stop"],
    }


def fmt(value, spec):
    return "-" if value is None else format(value, spec)


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
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--rbla", default=os.path.join(ROOT, "build", "solver", "rbla"))
    parser.add_argument("--out", default=os.path.join(ROOT, "docs", "benchmark"))
    parser.add_argument("--repeat", type=int, default=2)
    parser.add_argument("--only", help="run only the scenes whose name contains this")
    args = parser.parse_args()
    meta = {"date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
            "load_start": os.getloadavg()[0], "repeat": args.repeat}
    rows = []
    with tempfile.TemporaryDirectory() as work:
        for name, gen_args, target in SCENES:
            if args.only and args.only not in name:
                continue
            row = measure(args.rbla, name, gen_args, target, args.repeat, work)
            print(f"{name}: factor {row['factor']} ({row['outcome']}), {row['evaluations']} factors, "
                  f"cost {row['solves_equivalent']:.1f} solves", flush=True)
            rows.append(row)
    meta["load_end"] = os.getloadavg()[0]
    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, "critical_friction.md"), "w") as f:
        f.write(markdown(rows, meta))
    with open(os.path.join(args.out, "critical_friction.json"), "w") as f:
        json.dump({"meta": meta, "rows": rows}, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
