"""What the search benchmarks (worst_direction.py, worst_settlement.py, critical_friction.py) share:
generating a scene, timing one `rbla solve` against one search in turn so that the cost in single
solves is measured in the same minutes, the session's conditions, and writing the report.
Standard library only.
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


def timed(command):
    start = time.perf_counter()
    done = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if done.returncode != 0:
        raise RuntimeError(" ".join(command) + " failed: " + done.stderr[-2000:])
    return time.perf_counter() - start


def generate(args, path):
    """A scene of samples/generate_samples.py; returns its number of blocks."""
    subprocess.run([sys.executable, GENERATOR] + args + ["-o", path], check=True, stdout=subprocess.DEVNULL)
    with open(path) as f:
        return len(json.load(f)["blocks"])


def solve_against_search(rbla, model, search, repeat, work):
    """`rbla solve` and the search command alternated `repeat` times: the median times and the
    median of the per-pair ratios (the search's cost in single solves)."""
    solve_times, search_times = [], []
    for _ in range(repeat):
        solve_times.append(timed([rbla, "solve", model, "-q", "-o", os.path.join(work, "solve.json")]))
        search_times.append(timed(search))
    return {"single_solve_s": statistics.median(solve_times), "search_s": statistics.median(search_times),
            "solves_equivalent": statistics.median([b / a for a, b in zip(solve_times, search_times)])}


def fmt(value, spec):
    return "-" if value is None else format(value, spec)


def arguments(doc, extra=None):
    """The common command line; `extra(parser)` adds a script's own options."""
    parser = argparse.ArgumentParser(description=doc.split("\n")[0])
    parser.add_argument("--rbla", default=os.path.join(ROOT, "build", "solver", "rbla"))
    parser.add_argument("--out", default=os.path.join(ROOT, "docs", "benchmark"))
    parser.add_argument("--repeat", type=int, default=2)
    parser.add_argument("--only", help="run only the scenes whose name contains this")
    if extra:
        extra(parser)
    return parser.parse_args()


def run_scenes(args, scenes, measure, summary):
    """measure(scene, work) -> row for every scene whose name matches --only, with the session's
    date and load before and after; prints summary(row) as each finishes."""
    meta = {"date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
            "load_start": os.getloadavg()[0], "repeat": args.repeat}
    rows = []
    with tempfile.TemporaryDirectory() as work:
        for scene in scenes:
            if args.only and args.only not in scene[0]:
                continue
            row = measure(scene, work)
            print(scene[0] + ": " + summary(row), flush=True)
            rows.append(row)
    meta["load_end"] = os.getloadavg()[0]
    return rows, meta


def write_report(out, name, text, rows, meta):
    """OUT/NAME.md and OUT/NAME.json (the rows and the session's conditions)."""
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, name + ".md"), "w") as f:
        f.write(text)
    with open(os.path.join(out, name + ".json"), "w") as f:
        json.dump({"meta": meta, "rows": rows}, f, indent=1)


def report_failures(checks):
    """checks: (what, scenes) pairs; prints the non-empty ones; 1 when any failed."""
    failed = False
    for what, scenes in checks:
        if scenes:
            print(what + " on: " + ", ".join(scenes), file=sys.stderr)
            failed = True
    return 1 if failed else 0
