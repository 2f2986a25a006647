#!/usr/bin/env python3
"""COMPAS assemblies (tests/data/compas, made by other tools) converted and solved at rbla's
default settings agree with the same assemblies solved with the interfaces stored in the files,
which COMPAS detected: the same verdict, and the load multiplier within 3 %. (That the stored
interfaces are found, polygon by polygon, is tests/regression/test_compas_interfaces.cpp.)
Files without stored interfaces are converted and solved, and say so.

Usage: compas_agreement.py SOURCE_DIR RBLA_BINARY
"""
import json
import os
import subprocess
import sys
import tempfile

# compas_cra's example scripts fix node 0 of the interlocking pieces, which both lie on the
# ground (so the ground-contact rule fixes neither).
EXTRA = {"concave-long": ["--support", "0"], "concave-short": ["--support", "0"]}
NOT_ASSEMBLIES = {"wall"}  # compas_assembly's example input, refused with a message


def run(cmd, cwd=None):
    return subprocess.run(cmd, cwd=cwd, capture_output=True, text=True)


def convert(source, path, out, extra):
    r = run([sys.executable, "-m", "rbla_cad.compas_import", path, "-o", out] + extra, cwd=os.path.join(source, "plugin"))
    return r.returncode, r.stderr


def solve(rbla, model, result):
    r = run([rbla, "solve", "-q", model, "-o", result])
    if r.returncode != 0:
        raise RuntimeError("rbla solve %s failed (%d): %s" % (model, r.returncode, r.stdout + r.stderr))
    return json.load(open(result))


def check(source, rbla, path, tmp):
    name = os.path.splitext(os.path.basename(path))[0]
    extra = EXTRA.get(name, [])
    detected_model, stored_model = os.path.join(tmp, name + ".json"), os.path.join(tmp, name + "_stored.json")
    code, err = convert(source, path, detected_model, extra)
    if name in NOT_ASSEMBLIES:
        return [] if code == 1 and "not an assembly" in err else ["%s: expected a refusal, got %d: %s" % (name, code, err)]
    if code != 0:
        return ["%s: conversion failed (%d): %s" % (name, code, err)]
    detected = solve(rbla, detected_model, os.path.join(tmp, name + "_r.json"))
    convert(source, path, stored_model, extra + ["--interfaces"])
    if "interfaces" not in json.load(open(stored_model)):
        print("%s: no stored interfaces; %s with %d detected (%s)"
              % (name, detected["status"], detected["model_summary"]["num_interfaces"], detected["verdict"]))
        return []
    stored = solve(rbla, stored_model, os.path.join(tmp, name + "_rs.json"))
    problems = []
    a, b = detected.get("load_multiplier"), stored.get("load_multiplier")
    if detected["status"] != stored["status"]:
        problems.append("%s: verdicts differ: %s (detected) and %s (stored)" % (name, detected["verdict"], stored["verdict"]))
    elif a is not None and abs(a - b) > 0.03 * abs(b):
        problems.append("%s: alpha %.6g (detected) and %.6g (stored) differ by more than 3 %%" % (name, a, b))
    print("%s: %d interfaces detected, %d stored; %s; alpha %s (detected) and %s (stored)"
          % (name, detected["model_summary"]["num_interfaces"], stored["model_summary"]["num_interfaces"],
             detected["status"], a, b))
    return problems


def main():
    source, rbla = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    data = os.path.join(source, "tests", "data", "compas")
    files = sorted(os.path.join(d, f) for d, _, fs in os.walk(data) for f in fs if f.endswith(".json"))
    problems = []
    with tempfile.TemporaryDirectory() as tmp:
        for path in files:
            problems += check(source, rbla, path, tmp)
    for p in problems:
        print("FAIL " + p)
    print("%d files, %d problems" % (len(files), len(problems)))
    return 1 if problems or len(files) < 20 else 0


if __name__ == "__main__":
    sys.exit(main())
