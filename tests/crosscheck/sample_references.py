#!/usr/bin/env python3
"""Independent reference values for the bundled samples' headline numbers.

Every bundled sample is a planar scene, so rbla poses it as a linear program. This script asks
rbla only to *write* that LP (`rbla solve --dump-problem X.mps`) and solves it with Debian's CLP
(dual simplex, feasibility tolerances 1e-10): the objective is -alpha for a load-multiplier
analysis and R / F_s for settlement, where F_s (rbla's force scale) is the mean weight of the
free blocks, recomputed here from the sample's own volumes and unit weights.

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
                references[name] = {"base_reaction": objective * sum(weights) / len(weights)}
            else:
                references[name] = {"load_multiplier": -objective}
    json.dump(references, sys.stdout, indent=1, sort_keys=True)
    print()


if __name__ == "__main__":
    main()
