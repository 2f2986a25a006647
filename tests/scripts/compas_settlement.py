#!/usr/bin/env python3
"""The most harmful settlement direction on an assembly made by another tool.

COMPAS's arch (tests/data/compas/compas_assembly/arch_assembly.json: 30 voussoirs, the two
springing blocks fixed) is converted with the plugin's importer, one springing block is made a
settling support, and `rbla worst-settlement` searches a 30-degree cone. Expectations that do not
come from rbla's own output:
  - the arch is symmetric about its own plane, so directions mirrored about that plane give the
    same base reaction and the same initial reaction;
  - the most harmful direction leans outwards, away from the other springing (an abutment that
    spreads is the classical worst case for an arch);
  - a sampling of the cone with `rbla solve` (every 10 degrees of tilt, 15 of azimuth: 73
    directions, few enough for the sanitizer run) finds no ratio above the search's certified
    upper bound, nor more than the tolerance above its best;
  - ranked as candidate groups (`--candidate-group`), the two springings are mirror images, so
    their largest R/R0 agree to the tolerance and the ranking must not claim to be certain.

Usage: compas_settlement.py SOURCE_DIR RBLA_BINARY
"""
import json
import math
import os
import subprocess
import sys
import tempfile

TOLERANCE = 1e-3


def run(cmd, cwd=None):
    r = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError("%s failed (%d): %s" % (" ".join(cmd), r.returncode, r.stdout + r.stderr))
    return r


def settling_arch(source, tmp):
    converted = os.path.join(tmp, "arch.json")
    arch = os.path.join(source, "tests", "data", "compas", "compas_assembly", "arch_assembly.json")
    run([sys.executable, "-m", "rbla_cad.compas_import", arch, "-o", converted], cwd=os.path.join(source, "plugin"))
    with open(converted) as f:
        model = json.load(f)
    fixed = [b for b in model["blocks"] if b.get("role") == "fixed"]
    assert len(fixed) == 2, "the arch should have its two springing blocks fixed"
    # The springing on the -x side settles; the other stays.
    centre_x = [sum(v[0] for v in b["vertices"]) / len(b["vertices"]) for b in fixed]
    moving = fixed[0] if centre_x[0] < centre_x[1] else fixed[1]
    moving["role"] = "moving_support"
    model["analysis"] = {"type": "settlement"}
    path = os.path.join(tmp, "arch_settling.json")
    with open(path, "w") as f:
        json.dump(model, f)
    return path, model


def direction(tilt, azimuth):
    t, p = math.radians(tilt), math.radians(azimuth)
    return [math.sin(t) * math.cos(p), math.sin(t) * math.sin(p), -math.cos(t)]


def dense_maximum(rbla, model, w, tmp):
    best = None
    for tilt in range(0, 31, 10):
        for azimuth in ([0] if tilt == 0 else range(0, 360, 15)):
            model["analysis"]["settlement"] = {"direction": direction(tilt, azimuth)}
            path, result = os.path.join(tmp, "dense.json"), os.path.join(tmp, "dense_r.json")
            with open(path, "w") as f:
                json.dump(model, f)
            run([rbla, "solve", "-q", path, "-o", result])
            with open(result) as f:
                r = json.load(f)
            d = model["analysis"]["settlement"]["direction"]
            ratio = r["base_reaction"]["at_collapse"] / sum(a * b for a, b in zip(w, d))
            best = max(best, ratio) if best is not None else ratio
    return best


def mirrored_springings(rbla, model, tmp):
    """Both springing blocks as candidate groups: equal harm, a ranking that says it is unsure."""
    springings = [b["id"] for b in model["blocks"] if b.get("role") in ("fixed", "moving_support")]
    model["analysis"].pop("settlement", None)
    path, out = os.path.join(tmp, "groups.json"), os.path.join(tmp, "groups_r.json")
    with open(path, "w") as f:
        json.dump(model, f)
    run([rbla, "worst-settlement", "-q", path, "--candidate-group", springings[0],
         "--candidate-group", springings[1], "-o", out])
    with open(out) as f:
        w = json.load(f)["worst_settlement"]
    ranking = w["candidate_groups"]
    ratios = [g.get("ratio") for g in ranking["groups"]]
    print("springings as candidate groups: R/R0 %s, certain %s" % (ratios, ranking["certain"]))
    problems = []
    if None in ratios:
        return ["a springing's search did not collapse: " + ranking["verdict"]]
    if abs(ratios[0] - ratios[1]) > TOLERANCE * max(ratios):
        problems.append("the mirrored springings' R/R0 differ: %s" % ratios)
    if ranking["certain"]:
        problems.append("the ranking of mirror images claims to be certain: " + ranking["verdict"])
    top = [g for g in ranking["groups"] if g["most_harmful"]]
    if len(top) != 1 or top[0]["ratio"] != w["ratio"]:
        problems.append("the file is not the most harmful group's search")
    return problems


def main():
    source, rbla = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    problems = []
    with tempfile.TemporaryDirectory() as tmp:
        path, model = settling_arch(source, tmp)
        out = os.path.join(tmp, "worst.json")
        run([rbla, "worst-settlement", "-q", path, "-o", out])
        with open(out) as f:
            w = json.load(f)["worst_settlement"]
        by_angle = {(round(e["tilt_deg"], 6), round(e["azimuth_deg"], 6)): e for e in w["evaluations"]}
        for (tilt, azimuth), e in by_angle.items():
            mirror = by_angle.get((tilt, round((360.0 - azimuth) % 360.0, 6)))
            if mirror and abs(mirror["base_reaction"] - e["base_reaction"]) > 1e-6 * abs(e["base_reaction"]):
                problems.append("R at azimuth %g and %g differ: %g, %g" % (azimuth, 360 - azimuth, e["base_reaction"],
                                                                           mirror["base_reaction"]))
        outward = w["direction"][0]
        print("arch: R/R0 %.6g at tilt %.2f, azimuth %.2f (certified %s, bound %s), %d directions"
              % (w["ratio"], w["tilt_deg"], w["azimuth_deg"], w["certified"], w.get("upper_bound"),
                 w["num_evaluations"]))
        if not outward < 0.0:
            problems.append("the most harmful direction does not lean outwards: %s" % w["direction"])
        if not w["certified"]:
            problems.append("not certified: " + w["stop"])
        dense = dense_maximum(rbla, model, w["initial_reaction_vector"], tmp)
        print("sampling of the cone: largest R/R0 %.6g" % dense)
        if w.get("upper_bound") is not None and w["upper_bound"] < dense * (1 - 1e-9):
            problems.append("upper bound %.9g below the dense sampling's %.9g" % (w["upper_bound"], dense))
        if w["ratio"] < dense * (1 - TOLERANCE):
            problems.append("best %.9g below the dense sampling's %.9g by more than the tolerance" % (w["ratio"], dense))
        problems += mirrored_springings(rbla, model, tmp)
    for p in problems:
        print("FAIL " + p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
