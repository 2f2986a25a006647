#!/usr/bin/env python3
"""Writes the fuzz seed inputs into OUT_DIR: the samples and schema examples as they are and
minified, variants of the single-block sample that switch on every schema feature (given
interfaces, loads, units, gravity axes, detection modes, settlement, cones), and small hostile
inputs. tests/fuzz/corpus is these seeds plus what the fuzzer found, minimised with
`fuzz_model -merge=1` (docs/fuzzing.md). Standard library only."""
import copy
import json
import pathlib
import sys

root = pathlib.Path(__file__).resolve().parents[2]
out = pathlib.Path(sys.argv[1])
out.mkdir(parents=True, exist_ok=True)
count = 0


def put(name, text):
    global count
    data = text.encode() if isinstance(text, str) else text
    (out / name).write_bytes(data)
    count += 1


def dump(doc):
    return json.dumps(doc, separators=(",", ":"))


for path in sorted((root / "samples").glob("*.json")) + sorted((root / "schema" / "examples").glob("*.json")):
    put("file_" + path.stem + ".json", path.read_bytes())
    put("min_" + path.stem + ".json", dump(json.loads(path.read_text())))

block = json.loads((root / "samples" / "block.json").read_text())
base, top = block["blocks"]


def variant(name, edit):
    doc = copy.deepcopy(block)
    edit(doc)
    put("var_" + name + ".json", dump(doc))


def given_interface(d):
    d["interfaces"] = [{"id": "I0", "label": "bed", "blocks": ["base", "block"], "friction": 0.5,
                        "polygon": [[-0.5, -0.5, 0], [0.5, -0.5, 0], [0.5, 0.5, 0], [-0.5, 0.5, 0]]}]
    d["detection"] = {"mode": "off"}


variant("given_interface", given_interface)
variant("merge", lambda d: d.update(detection={"mode": "merge", "distance_tolerance": 1e-3,
                                               "angle_tolerance": 2, "min_area_fraction": 0.01}))
variant("relative_tol", lambda d: d.update(detection={"mode": "auto", "relative_tolerance": 0.1}))
variant("loads", lambda d: d.update(loads={
    "dead": [{"block": "block", "force": [0, 0, -10], "point": [0, 0, 2], "moment": [0, 1, 0]}],
    "live": [{"block": "block", "force": [1, 0, 0]}]}, analysis={"cone": "pyramid_inscribed",
                                                                  "pyramid_faces": 3}))
variant("units_mm", lambda d: (d.update(units={"length": "mm", "force": "N", "unit_weight": "N/mm3"}),
                               [b.update(vertices=[[1000 * c for c in v] for v in b["vertices"]],
                                         centroid=[1000 * c for c in b["centroid"]],
                                         volume=b["volume"] * 1e9) for b in d["blocks"]]))
variant("gravity_y", lambda d: d.update(gravity="+y", analysis={"seismic": {"direction": [0, 0, 1]}}))
variant("settlement", lambda d: (d["blocks"][0].update(role="moving_support"), d.update(analysis={
    "type": "settlement", "settlement": {"direction": [0, 0, -1]}, "friction_model": "non_associative",
    "non_associative": {"max_iterations": 5, "tolerance": 0.01, "damping": 1},
    "tolerances": {"relative_gap": 1e-6, "feasibility": 1e-6}, "formulation": "3d", "time_limit": 10})))
variant("no_analysis", lambda d: d.pop("analysis"))
variant("weightless", lambda d: d["blocks"][1].update(unit_weight=0, label="x"))
variant("bad_cad", lambda d: d["blocks"][1].update(volume=3.0, centroid=[1, 1, 1]))
variant("inverted", lambda d: d["blocks"][1].update(faces=[f[::-1] for f in top["faces"]]))
variant("flat", lambda d: d["blocks"][1].update(vertices=[[v[0], v[1], 0] for v in top["vertices"]]))
variant("bad_index", lambda d: d["blocks"][1].update(faces=top["faces"][:-1] + [[3, 7, 4, 99]]))
variant("duplicate_id", lambda d: d["blocks"][1].update(id="base"))
variant("overlap", lambda d: d["blocks"][1].update(vertices=[[v[0], v[1], v[2] - 0.25] for v in top["vertices"]]))

hostile = {
    "empty": "", "null": "null", "array": "[]", "object": "{}", "string": '"x"',
    "bom": "\ufeff{}", "nul": "{\u0000}", "deep_array": "[" * 20000 + "]" * 20000,
    "deep_object": '{"a":' * 8000 + "1" + "}" * 8000,
    "deep_in_model": dump(block)[:-1] + ',"title":' + "[" * 5000 + "]" * 5000 + "}",
    "huge_number": '{"schema_version":"1.0.0","units":{"length":"m"},"blocks":[{"id":"a","vertices":'
                   '[[1e999,0,0],[0,1,0],[0,0,1],[0,0,0]],"faces":[[0,1,2],[0,2,3],[0,3,1],[1,3,2]]}]}',
    "tetra": '{"schema_version":"1.0.0","units":{"length":"m"},"blocks":[{"id":"a","vertices":'
             '[[1,0,0],[0,1,0],[0,0,1],[0,0,0]],"faces":[[0,1,2],[0,2,3],[0,3,1],[1,3,2]]}]}',
    "bad_utf8": b'{"title":"\xff\xfe","schema_version":"1.0.0"}',
    "surrogate": '{"title":"\\ud800","schema_version":"1.0.0","units":{"length":"m"},"blocks":[]}',
    "dup_keys": '{"units":{"length":"m"},"units":{"length":"mm"},"schema_version":"1.0.0","blocks":[]}',
}
for name, text in hostile.items():
    put("hostile_" + name + ".json", text)
print(f"make_seeds: {count} inputs in {out}")
