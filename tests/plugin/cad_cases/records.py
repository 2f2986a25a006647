"""The shared CAD cases (cases.json) as document records for rbla_cad.cad_reader, and the
Python reader's output for each (``python3 records.py`` prints it as JSON: the web test
compares it with the .3dm exchange's, model and messages)."""

import json
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
PLUGIN = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(HERE))), "plugin")
if PLUGIN not in sys.path:
    sys.path.insert(0, PLUGIN)

from rbla_cad import cad_reader  # noqa: E402
from rbla_cad.model import box  # noqa: E402


def load_cases():
    with open(os.path.join(HERE, "cases.json"), encoding="utf-8") as f:
        return json.load(f)["cases"]


def object_record(i, o):
    """The record of case object i (its guid is guid-i)."""
    rec = {"guid": "guid-%d" % i, "name": o.get("name"), "layer": o.get("layer", "Default"),
           "hidden": bool(o.get("hidden")), "user_text": dict(o.get("user_text", {}))}
    if "box" in o or "solid" in o:
        v, f = box(*o["box"]) if "box" in o else (o["solid"]["vertices"], o["solid"]["faces"])
        rec.update({"type": "Brep" if o.get("as") == "brep" else "Mesh",
                    "shape": "solid", "vertices": v, "faces": f})
    elif "pieces" in o:
        rec.update({"type": {"mesh": "Mesh", "brep": "Brep", "curve": "PolylineCurve"}[o["as"]],
                    "shape": "polygons", "polygons": o["pieces"]})
    else:
        rec.update({"type": "Point", "shape": "point", "point": o["point"]})
    return rec


def document_record(case):
    d = case["document"]
    return {"name": d.get("name"), "units": d["units"], "tolerance": d["tolerance"],
            "user_text": dict(d.get("user_text", {})),
            "objects": [object_record(i, o) for i, o in enumerate(case["objects"])]}


def run(case):
    r = cad_reader.read_document(document_record(case))
    return {"name": case["name"], "model": r.model,
            "messages": [m.as_dict() for m in r.report.messages]}


if __name__ == "__main__":
    json.dump([run(c) for c in load_cases()], sys.stdout)
