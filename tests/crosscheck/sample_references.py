#!/usr/bin/env python3
"""Independent reference values for the bundled samples' headline numbers.

Every bundled sample is a planar scene, so rbla poses it as a linear program. This script asks
rbla only to *write* that LP (`rbla solve --dump-problem X.mps`) and solves it with Debian's CLP
(dual simplex, feasibility tolerances 1e-10): the objective is -alpha for a load-multiplier
analysis and R / F_s for settlement, where F_s (rbla's force scale) is the mean weight of the
free blocks, recomputed here from the sample's own volumes and unit weights.

For settlement samples it also gives the reaction before settlement that rbla reports
(solver/src/analysis/initial_reaction.hpp: the wall as one rigid body on uniformly elastic
ground), from Navier's linear base pressure in one dimension over the contact segments of the
bottom course on the two base blocks. This needs only the geometry, no solver; it is valid for a
flat base whose pressure stays compressive (checked), with self-weight only (no loads.dead) and
a wall of uniform depth in y (the depth cancels), i.e. the bundled wall_settlement scene.

Usage: sample_references.py RBLA_BINARY SAMPLES_DIR   (prints JSON to stdout)
"""
import json
import os
import re
import subprocess
import sys
import tempfile


def clp_objective(mps_path):
    out = subprocess.run(["clp", mps_path, "-primalT", "1e-10", "-dualT", "1e-10", "-dualsimplex"],
                         capture_output=True, text=True, check=True).stdout
    match = re.search(r"Optimal objective\s+([-+0-9.eE]+)", out)
    if not match:
        raise RuntimeError("CLP did not report an optimum for %s:\n%s" % (mps_path, out))
    return float(match.group(1))


def navier_initial_reaction(model):
    """R0 on the moving support: p(x) = N/A + N e (x - x_b)/I over the contact segments (unit depth)."""
    unit_weight = model.get("defaults", {}).get("unit_weight", 18.0)
    blocks = model["blocks"]
    supports = {b["id"]: b for b in blocks if b.get("role", "free") != "free"}
    top = {i: max(v[2] for v in b["vertices"]) for i, b in supports.items()}
    span = {i: (min(v[0] for v in b["vertices"]), max(v[0] for v in b["vertices"])) for i, b in supports.items()}
    weight = moment = 0.0
    segments = []  # (x0, x1, moving)
    for b in blocks:
        if b.get("role", "free") != "free":
            continue
        xs = [v[0] for v in b["vertices"]]
        zs = [v[2] for v in b["vertices"]]
        w = b["volume"] * b.get("unit_weight", unit_weight)
        weight += w
        moment += w * b["centroid"][0]
        for i, (x0, x1) in span.items():  # the bottom face on a support: the overlap in x
            if abs(min(zs) - top[i]) < 1e-9 and min(max(xs), x1) > max(min(xs), x0):
                segments.append((max(min(xs), x0), min(max(xs), x1), supports[i]["role"] == "moving_support"))
    x_g = moment / weight
    area = sum(b - a for a, b, _ in segments)
    x_b = sum((b * b - a * a) / 2 for a, b, _ in segments) / area
    inertia = sum(((b - x_b) ** 3 - (a - x_b) ** 3) / 3 for a, b, _ in segments)
    pressure = lambda x: weight / area + weight * (x_g - x_b) * (x - x_b) / inertia
    if min(pressure(a) for a, b, _ in segments) < 0 or min(pressure(b) for a, b, _ in segments) < 0:
        raise RuntimeError("the base lifts: the one-line Navier formula does not apply")
    return sum(weight * (b - a) / area + weight * (x_g - x_b) / inertia * ((b - x_b) ** 2 - (a - x_b) ** 2) / 2
               for a, b, moving in segments if moving)


def main():
    rbla, samples = sys.argv[1], sys.argv[2]
    references = {}
    with tempfile.TemporaryDirectory() as tmp:
        for name in sorted(os.listdir(samples)):
            if not name.endswith(".json"):
                continue
            model = json.load(open(os.path.join(samples, name)))
            mps = os.path.join(tmp, name + ".mps")
            subprocess.run([rbla, "solve", "-q", os.path.join(samples, name), "--dump-problem", mps],
                           check=True, capture_output=True)
            objective = clp_objective(mps)
            unit_weight = model.get("defaults", {}).get("unit_weight", 18.0)
            weights = [b["volume"] * b.get("unit_weight", unit_weight)
                       for b in model["blocks"] if b.get("role", "free") == "free"]
            if model.get("analysis", {}).get("type") == "settlement":
                references[name] = {"base_reaction": objective * sum(weights) / len(weights),
                                    "initial_base_reaction": navier_initial_reaction(model)}
            else:
                references[name] = {"load_multiplier": -objective}
    json.dump(references, sys.stdout, indent=1, sort_keys=True)
    print()


if __name__ == "__main__":
    main()
