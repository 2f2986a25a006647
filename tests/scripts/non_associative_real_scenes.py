#!/usr/bin/env python3
"""Non-associative friction at rbla's default settings on scenes not made for it: the COMPAS
assemblies (tests/data/compas, made by other tools) converted at default settings, and a
vault and a dome with CAD imperfections (vertex noise, warped and split faces, joint gaps and
overlaps, a rotated model) from samples/generate_samples.py. Each is solved associative and
non-associative, seismic along +x, -x and +y. Expectations that do not come from rbla's own output:

- the verdict (collapse, cannot stand, no mechanism) does not depend on the flow rule: the dead
  load check and the connectivity check do not involve it, and a mechanism under associative
  friction has a non-associative counterpart at some multiplier;
- the non-associative load multiplier is never above the associative one (the associative flow
  rule over-estimates strength; Drucker 1954, docs/method.md), to the solves' accuracy;
- at a collapse the scheme converges (its state passes the fixed-point test) and reports a value
  inside the range it gives.

Usage: non_associative_real_scenes.py SOURCE_DIR RBLA_BINARY
"""
import json
import os
import subprocess
import sys
import tempfile

EXTRA = {"concave-long": ["--support", "0"], "concave-short": ["--support", "0"]}
NOT_ASSEMBLIES = {"wall"}  # compas_assembly's example input, refused by the converter
DIRECTIONS = ([1, 0, 0], [-1, 0, 0], [0, 1, 0])
IMPERFECTIONS = ["--noise", "0.0005", "--warp", "0.002", "--joint-gap", "0.0005", "--split-faces", "0.3",
                 "--rotate", "30"]
SHELLS = {
    "vault 10 x 8, imperfect": ["vault", "--nu", "10", "--nv", "8"] + IMPERFECTIONS,
    "dome 6 x 24, imperfect": ["dome", "--rings", "6", "--segments", "24"] + IMPERFECTIONS,
}


def run(cmd, cwd=None):
    r = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError("%s failed (%d): %s" % (" ".join(cmd), r.returncode, r.stdout + r.stderr))
    return r


def solve(rbla, model, friction_model, direction, tmp):
    model = dict(model)
    model["analysis"] = {"type": "load_multiplier", "seismic": {"direction": direction},
                         "friction_model": friction_model}
    path, out = os.path.join(tmp, "model.json"), os.path.join(tmp, "result.json")
    with open(path, "w") as f:
        json.dump(model, f)
    run([rbla, "solve", "-q", path, "-o", out])
    with open(out) as f:
        return json.load(f)


def compare(name, a, n):
    """Problems of the non-associative result n against the associative a of the same scene."""
    if a["status"] != n["status"]:
        return ["%s: %s associative, %s non-associative" % (name, a["status"], n["status"])]
    if a["status"] != "collapse":
        return []
    c, av, nv = n["convergence"], a["load_multiplier"], n["load_multiplier"]
    problems = []
    if not c["non_associative_converged"]:
        problems.append("%s: not converged after %d steps (%s), gap %g"
                        % (name, len(c["non_associative"]), c["non_associative_stop"], c["non_associative_gap"]))
    if nv > av + 1e-7 * max(1.0, abs(av)):
        problems.append("%s: non-associative %.12g above associative %.12g" % (name, nv, av))
    bound = c["non_associative_bound"]
    if abs(bound - av) > 1e-7 * max(1.0, abs(av)):
        problems.append("%s: bound %.12g reported, associative run %.12g" % (name, bound, av))
    low, high = c["non_associative_range"]["low"], c["non_associative_range"]["high"]
    if not low - 1e-12 <= nv <= high + 1e-12:
        problems.append("%s: value %.12g outside its range [%.12g, %.12g]" % (name, nv, low, high))
    return problems


def check(rbla, name, model, tmp):
    problems = []
    for d in DIRECTIONS:
        label = "%s, seismic %s" % (name, d)
        a = solve(rbla, model, "associative", d, tmp)
        n = solve(rbla, model, "non_associative", d, tmp)
        problems += compare(label, a, n)
        steps = len(n.get("convergence", {}).get("non_associative", []))
        print("%s: %s; alpha %s associative, %s non-associative (%d steps)"
              % (label, n["status"], a.get("load_multiplier"), n.get("load_multiplier"), steps))
    return problems


def compas_models(source, tmp):
    data = os.path.join(source, "tests", "data", "compas")
    for d, _, files in sorted(os.walk(data)):
        for f in sorted(files):
            name = f[:-5]
            if not f.endswith(".json") or name in NOT_ASSEMBLIES:
                continue
            out = os.path.join(tmp, name + ".json")
            run([sys.executable, "-m", "rbla_cad.compas_import", os.path.join(d, f), "-o", out] + EXTRA.get(name, []),
                cwd=os.path.join(source, "plugin"))
            with open(out) as fh:
                yield name, json.load(fh)


def shell_models(source, tmp):
    for name, args in SHELLS.items():
        out = os.path.join(tmp, "shell.json")
        run([sys.executable, os.path.join(source, "samples", "generate_samples.py")] + args + ["-o", out])
        with open(out) as fh:
            yield name, json.load(fh)


def main():
    source, rbla = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    problems, scenes = [], 0
    with tempfile.TemporaryDirectory() as tmp:
        for source_models in (compas_models, shell_models):
            for name, model in source_models(source, tmp):
                scenes += 1
                problems += check(rbla, name, model, tmp)
    for p in problems:
        print("FAIL " + p)
    print("%d scenes, %d problems" % (scenes, len(problems)))
    return 1 if problems or scenes < 20 else 0


if __name__ == "__main__":
    sys.exit(main())
