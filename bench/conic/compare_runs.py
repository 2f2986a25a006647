#!/usr/bin/env python3
"""Solve the same CBF problems with two builds of rbla_conic_cbf_solve and compare the outcomes.

A refactoring of the interior-point method must not change its path: this prints, per problem,
the iterations of both builds, the relative difference of their primal objectives and whether
the statuses agree, and exits with status 1 when a problem takes more iterations, ends in
another status, or moves its objective by more than --tol (relative).

    # once: dump a set of real problems (samples, façade settlement and seismic, planar and 3-D)
    python3 bench/conic/compare_runs.py --generate /tmp/conic-problems --rbla build/solver/rbla \
        --wall-bench build-conic-bench/rbla_conic_wall_bench
    # then after each change:
    python3 bench/conic/compare_runs.py --base /tmp/conic-base/rbla_conic_cbf_solve \
        --new build-conic-bench/rbla_conic_cbf_solve /tmp/conic-problems

The problems stay out of git (they are megabytes each); --generate rebuilds them from the
bundled samples and samples/generate_samples.py.
"""

import argparse
import json
import pathlib
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
SAMPLES = ROOT / "samples"

# name → (how to make the model, formulation or None for the model's own).
FACADE = ["facade", "--compact"]
MODELS = {
    "block": (["file", "block.json"], None),
    "column": (["file", "column.json"], None),
    "arch": (["file", "arch.json"], None),
    "wall_opening_planar": (["file", "wall_opening.json"], "planar"),
    "wall_opening_3d": (["file", "wall_opening.json"], "3d"),
    "wall_settlement_planar": (["file", "wall_settlement.json"], "planar"),
    "wall_settlement_3d": (["file", "wall_settlement.json"], "3d"),
    "facade_seismic_planar": (FACADE + ["--seismic", "x"], "planar"),
    "facade_seismic_3d": (FACADE + ["--seismic", "x"], "3d"),
    "facade_settlement_planar": (FACADE + ["--settling-fraction", "0.3"], "planar"),
    "facade_settlement_3d": (FACADE + ["--settling-fraction", "0.3"], "3d"),
    "dome_3d": (["dome", "--compact"], None),
}


def make_model(recipe):
    if recipe[0] == "file":
        return json.loads((SAMPLES / recipe[1]).read_text())
    out = subprocess.run([sys.executable, str(SAMPLES / "generate_samples.py"), *recipe],
                         check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def generate(directory, rbla, wall_bench):
    directory.mkdir(parents=True, exist_ok=True)
    if wall_bench:
        # The synthetic wall with one dense column (alpha times the loads), 20 x 15 blocks: its
        # bordered solve loses accuracy late and the dense column moves into the sparse factor.
        problem = directory / "synthetic_wall_dense_column.cbf"
        subprocess.run([wall_bench, "20", "15", "--dump", str(problem)], check=True, capture_output=True)
        print(f"wrote {problem}")
    for name, (recipe, formulation) in MODELS.items():
        model = make_model(recipe)
        if formulation:
            model.setdefault("analysis", {})["formulation"] = formulation
        model_path = directory / f"{name}.json"
        model_path.write_text(json.dumps(model))
        problem = directory / f"{name}.cbf"
        subprocess.run([rbla, "solve", "-q", str(model_path), "-o", str(directory / f"{name}.result.json"),
                        "--dump-problem", str(problem)], check=True)
        print(f"wrote {problem}")


def run(binary, problem, extra):
    result = subprocess.run([binary, str(problem), *extra], capture_output=True, text=True)
    if result.returncode != 0:
        return {"status": f"exit {result.returncode}", "iterations": -1, "primal_objective": float("nan")}
    return json.loads(result.stdout.strip().splitlines()[-1])


def relative_difference(a, b):
    """|a − b| / |a| (|b| when a is 0); nan when either is not a number."""
    if a != a or b != b:
        return float("nan")
    return abs(a - b) / abs(a) if a != 0 else abs(b)


def compare(base, new, problems, extra, tol):
    header = f"{'problem':28s} {'iter base/new':>13s} {'obj rel diff':>12s}  {'status base':16s} same"
    print(header)
    print("-" * len(header))
    ok = True
    worst, iterations = 0.0, [0, 0]
    for problem in problems:
        a, b = run(base, problem, extra), run(new, problem, extra)
        pa, pb = a["primal_objective"], b["primal_objective"]
        rel = relative_difference(pa, pb)
        both_nan = pa != pa and pb != pb  # e.g. an infeasible problem's primal objective
        same_status = a["status"] == b["status"]
        good = same_status and b["iterations"] <= a["iterations"] and (rel <= tol or both_nan)
        ok &= good
        worst = max(worst, rel) if rel == rel else worst
        iterations[0] += a["iterations"]
        iterations[1] += b["iterations"]
        iters = f"{a['iterations']}/{b['iterations']}"
        print(f"{problem.stem:28s} {iters:>13s} {rel:12.2e}  {a['status']:16s} {'yes' if same_status else 'NO'}"
              f"{'' if good else '   <-- differs'}")
    print(f"{len(problems)} problems, iterations {iterations[0]}/{iterations[1]}, largest objective "
          f"difference {worst:.2e} (relative): {'same path' if ok else 'DIFFERENT'}")
    return ok


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("problems", nargs="?", type=pathlib.Path, help="folder of .cbf files")
    parser.add_argument("--base", help="the reference rbla_conic_cbf_solve")
    parser.add_argument("--new", help="the rbla_conic_cbf_solve under test")
    parser.add_argument("--tol", type=float, default=1e-9, help="largest relative objective difference")
    parser.add_argument("--generate", type=pathlib.Path, help="write the problem set into this folder")
    parser.add_argument("--rbla", help="the rbla command-line program (with --generate)")
    parser.add_argument("--wall-bench", help="rbla_conic_wall_bench, for the synthetic wall with a dense "
                        "column (with --generate; optional)")
    parser.add_argument("--solver-args", default="",
                        help="extra arguments for both solvers, one string ('--solver-args=--threads 1')")
    args = parser.parse_args()
    if args.generate:
        if not args.rbla:
            parser.error("--generate needs --rbla")
        generate(args.generate, args.rbla, args.wall_bench)
        return 0
    if not (args.problems and args.base and args.new):
        parser.error("give the problem folder, --base and --new")
    problems = sorted(args.problems.glob("*.cbf"), key=lambda p: (p.stat().st_size, p.name))
    return 0 if compare(args.base, args.new, problems, args.solver_args.split(), args.tol) else 1


if __name__ == "__main__":
    sys.exit(main())
