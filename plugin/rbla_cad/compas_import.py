"""Convert COMPAS block-assembly JSON files to rbla model JSON (schema/model.schema.json 1.0.0).

Reads the COMPAS 2 JSON data format written by compas_assembly and compas_cra
(``compas.json_dump(assembly, ...)``)::

    {"dtype": "compas_assembly.datastructures/Assembly" | "compas_cra.datastructures/CRA_Assembly",
     "data": {"graph": {"dtype": "compas.datastructures/Graph",
                        "data": {"default_node_attributes": {"is_support": false, ...},
                                 "node": {KEY: {"block": {"dtype": ".../Block",
                                                          "data": {"vertex": {ID: {"x","y","z"}},
                                                                   "face": {ID: [vertex ids]}}},
                                                "is_support": bool}},
                                 "edge": {U: {V: {"interfaces": [{"dtype": ".../Interface",
                                                                  "data": {"points": [...],
                                                                           "frame": {...}}}]}}}}}}}

Each node's block mesh becomes an rbla block with id = the node key; ``is_support`` (or the node
default) makes it ``fixed``. Vertex ids are renumbered 0..n-1 in id order; unused vertices are
dropped. COMPAS meshes store faces counter-clockwise seen from outside, which is rbla's
convention: faces are kept as they are, and every block is checked (closed, consistently
oriented, positive volume from the faces). Centroid and volume are computed from the faces and
written. Interfaces stored on the graph edges are written only with ``--interfaces`` (by default
rbla detects them); their block order is chosen so the normal points from blocks[0] into blocks[1].

compas_cra files usually carry no supports (its example scripts call
``set_boundary_conditions([0])`` after loading): use ``--support 0`` or ``--fix-lowest``.

Usage (from plugin/)::

    python3 -m rbla_cad.compas_import IN.json -o OUT.json [--support 0,1] [--fix-lowest]
                                     [--interfaces] [--unit-weight 18] [--friction 0.6]

Exit status: 0 converted, 1 the file is not a convertible assembly (message on stderr),
2 a block failed its checks.
"""

import argparse
import json
import math
import os
import sys

SCHEMA_VERSION = "1.0.0"


class ConversionError(Exception):
    """The input is not an assembly this converter understands."""


# Geometry helpers are shared with the rest of the core (divergence-theorem volume, Newell normal).
from .geometry import cross as _cross, dot as _dot, newell_normal, sub as _sub, volume_centroid  # noqa: E402


def block_report(vertices, faces):
    """Checks of one block: closure/orientation of its edges, volume, largest face warp."""
    problems = []
    edges = {}
    for f in faces:
        for k in range(len(f)):
            e = (f[k], f[(k + 1) % len(f)])
            edges[e] = edges.get(e, 0) + 1
    bad = sum(1 for e, c in edges.items() if c != 1 or edges.get((e[1], e[0]), 0) != 1)
    if bad:
        problems.append("%d edges not shared by exactly two faces in opposite directions "
                        "(open mesh or inconsistent orientation)" % bad)
    vol, cen = volume_centroid(vertices, faces)
    warp = 0.0
    for f in faces:
        pts = [vertices[i] for i in f]
        n = newell_normal(pts)
        ln = math.sqrt(_dot(n, n))
        if ln == 0.0:
            problems.append("a face has zero area")
            continue
        n = (n[0] / ln, n[1] / ln, n[2] / ln)
        for p in pts:
            warp = max(warp, abs(_dot(_sub(p, pts[0]), n)))
    return vol, cen, warp, problems


# --------------------------------------------------------------------------------------------
# COMPAS data access
# --------------------------------------------------------------------------------------------

def unwrap(x):
    """Strip COMPAS {"dtype", "data", "guid"} wrappers."""
    while isinstance(x, dict) and "dtype" in x and "data" in x:
        x = x["data"]
    return x


def _point(p):
    p = unwrap(p)
    if isinstance(p, dict):
        return [float(p["x"]), float(p["y"]), float(p["z"])]
    return [float(p[0]), float(p[1]), float(p[2])]


def _key_order(k):
    """Sort numeric keys numerically, others after them as text."""
    try:
        return (0, int(k), "")
    except (TypeError, ValueError):
        return (1, 0, str(k))


def find_graph(doc):
    """The graph data dict ({"node": ..., "edge": ...}) of an assembly document."""
    if not isinstance(doc, dict):
        raise ConversionError("top level is a %s, not a COMPAS data object" % type(doc).__name__)
    if "courses" in doc and "basecurve" in doc:
        n = len(doc.get("courses", []))
        dtypes = sorted({unwrap_dtype(b) for c in doc["courses"] for b in c})
        raise ConversionError(
            "not an assembly: a compas_assembly example input (params, basecurve and %d courses "
            "of %s) that the example script turns into an assembly; its courses are not stacked "
            "(all at z = 0), so blocks would overlap. Convert the assembled result instead "
            "(wall_assembly.json for the running-bond wall)." % (n, ", ".join(dtypes)))
    dtype = doc.get("dtype", "")
    data = unwrap(doc)
    if isinstance(data, dict) and "graph" in data:
        g = unwrap(data["graph"])
    elif isinstance(data, dict) and "node" in data:
        g = data
    else:
        raise ConversionError("no assembly graph found (dtype %r, keys %s)"
                              % (dtype, sorted(data)[:10] if isinstance(data, dict) else "-"))
    if not isinstance(g, dict) or "node" not in g:
        raise ConversionError("the graph has no 'node' entries (dtype %r)" % dtype)
    return dtype, data, g


def unwrap_dtype(x):
    return x.get("dtype", "?") if isinstance(x, dict) else type(x).__name__


def mesh_of(node):
    """(vertex dict, face dict) of a node's block mesh."""
    blk = node.get("block")
    if blk is None:
        raise ConversionError("node has no 'block'")
    m = unwrap(blk)
    if not isinstance(m, dict) or "vertex" not in m or "face" not in m:
        raise ConversionError("block is not a COMPAS mesh (dtype %r)" % unwrap_dtype(blk))
    return m, m["vertex"], m["face"]


# --------------------------------------------------------------------------------------------
# Conversion
# --------------------------------------------------------------------------------------------

def convert(doc, name="", supports=(), fix_lowest=False, with_interfaces=False,
            unit_weight=18.0, friction=0.6, fix_orientation=False, log=None):
    """Return (model dict, info dict) for a parsed COMPAS assembly document."""
    if log is None:
        def log(msg):
            sys.stderr.write(msg + "\n")
    dtype, data, g = find_graph(doc)
    defaults = g.get("default_node_attributes") or {}
    default_support = bool(defaults.get("is_support", False))
    nodes = g["node"]
    if not nodes:
        raise ConversionError("the assembly has no nodes")
    info = {"dtype": dtype, "blocks": 0, "supports_from_file": [], "supports_added": [],
            "volume_negative": [], "reversed": [], "max_face_warp": 0.0, "problems": [],
            "interfaces": 0, "dropped_vertices": 0}
    blocks = []
    centroids = {}
    zmins = {}
    for key in sorted(nodes, key=_key_order):
        node = nodes[key] or {}
        try:
            mesh, vmap, fmap = mesh_of(node)
        except ConversionError as e:
            raise ConversionError("node %s: %s" % (key, e))
        fkeys = sorted(fmap, key=_key_order)
        used = set()
        for fk in fkeys:
            used.update(str(v) for v in fmap[fk])
        vkeys = [k for k in sorted(vmap, key=_key_order) if str(k) in used]
        missing = used - set(str(k) for k in vmap)
        if missing:
            raise ConversionError("node %s: faces use undefined vertices %s"
                                  % (key, sorted(missing)[:5]))
        info["dropped_vertices"] += len(vmap) - len(vkeys)
        index = {str(k): i for i, k in enumerate(vkeys)}
        vertices = [_point(vmap[k]) for k in vkeys]
        faces = []
        for fk in fkeys:
            f = [index[str(v)] for v in fmap[fk]]
            # drop repeated consecutive vertices (zero-length edges)
            f = [v for i, v in enumerate(f) if v != f[i - 1]] if len(f) > 1 else f
            if len(set(f)) < 3:
                info["problems"].append("node %s: face %s degenerate, dropped" % (key, fk))
                continue
            faces.append(f)
        vol, cen, warp, problems = block_report(vertices, faces)
        if vol <= 0.0:
            info["volume_negative"].append(str(key))
            if fix_orientation:
                faces = [list(reversed(f)) for f in faces]
                vol, cen, warp, problems = block_report(vertices, faces)
                info["reversed"].append(str(key))
        info["max_face_warp"] = max(info["max_face_warp"], warp)
        for p in problems:
            info["problems"].append("node %s: %s" % (key, p))
        is_support = bool(node.get("is_support", default_support))
        if is_support:
            info["supports_from_file"].append(str(key))
        b = {"id": str(key)}
        label = mesh.get("name") or (mesh.get("attributes") or {}).get("name")
        if isinstance(label, str) and label:
            b["label"] = label
        b["role"] = "fixed" if is_support else "free"
        b["vertices"] = vertices
        b["faces"] = faces
        b["centroid"] = [round(c, 12) + 0.0 for c in cen]
        if vol > 0.0:
            b["volume"] = vol
        blocks.append(b)
        centroids[str(key)] = cen
        zmins[str(key)] = min(v[2] for v in vertices)

    by_id = {b["id"]: b for b in blocks}
    for s in supports:
        if s not in by_id:
            raise ConversionError("--support %s: no such node (nodes: %s)"
                                  % (s, ", ".join(sorted(by_id, key=_key_order))))
        if by_id[s]["role"] != "fixed":
            by_id[s]["role"] = "fixed"
            info["supports_added"].append(s)
    if fix_lowest:
        lo = min(zmins.values())
        hi = max(max(v[2] for v in b["vertices"]) for b in blocks)
        tol = 1e-3 * max(hi - lo, 1e-9)
        for k, z in sorted(zmins.items(), key=lambda t: _key_order(t[0])):
            if z <= lo + tol and by_id[k]["role"] != "fixed":
                by_id[k]["role"] = "fixed"
                info["supports_added"].append(k)

    model = {
        "schema_version": SCHEMA_VERSION,
        "title": ("%s (converted from COMPAS %s)" % (name, dtype.split("/")[-1] or "assembly")).strip(),
        "units": {"length": "m", "force": "kN", "unit_weight": "kN/m3"},
        "gravity": "-z",
        "defaults": {"unit_weight": unit_weight, "friction": friction},
        "blocks": blocks,
    }

    if with_interfaces:
        interfaces = []
        for u, nbrs in sorted((g.get("edge") or {}).items(), key=lambda t: _key_order(t[0])):
            for v, attr in sorted((nbrs or {}).items(), key=lambda t: _key_order(t[0])):
                ifs = (attr or {}).get("interfaces") or []
                for k, itf in enumerate(ifs):
                    d = unwrap(itf)
                    pts = [_point(p) for p in d.get("points") or []]
                    if len(pts) < 3:
                        info["problems"].append("edge %s-%s: interface %d has %d points, skipped"
                                                % (u, v, k, len(pts)))
                        continue
                    n = newell_normal(pts)
                    a, b = str(u), str(v)
                    if a not in centroids or b not in centroids:
                        info["problems"].append("edge %s-%s: unknown node, skipped" % (u, v))
                        continue
                    # normal from blocks[0] into blocks[1]: orient the polygon so its
                    # right-hand normal points from a's centroid side to b's
                    if _dot(n, _sub(centroids[b], centroids[a])) < 0.0:
                        pts = list(reversed(pts))
                    interfaces.append({"id": "I%s-%s-%d" % (a, b, k), "blocks": [a, b],
                                       "polygon": pts})
        if interfaces:
            model["interfaces"] = interfaces
        info["interfaces"] = len(interfaces)
    info["blocks"] = len(blocks)
    return model, info


def dumps_model(model, compact=False):
    if compact:
        return json.dumps(model, separators=(",", ":")) + "\n"
    lines = ["{"]
    keys = list(model)
    for i, k in enumerate(keys):
        comma = "," if i + 1 < len(keys) else ""
        if k in ("blocks", "interfaces"):
            lines.append("  %s: [" % json.dumps(k))
            items = model[k]
            for j, it in enumerate(items):
                lines.append("    " + json.dumps(it, separators=(", ", ": "))
                             + ("," if j + 1 < len(items) else ""))
            lines.append("  ]" + comma)
        else:
            lines.append("  %s: %s%s" % (json.dumps(k), json.dumps(model[k], separators=(", ", ": ")),
                                         comma))
    lines.append("}")
    return "\n".join(lines) + "\n"


def main(argv=None):
    p = argparse.ArgumentParser(prog="python3 -m rbla_cad.compas_import",
                                description="Convert a COMPAS assembly JSON file to an rbla model.")
    p.add_argument("input", help="COMPAS assembly JSON file")
    p.add_argument("-o", "--output", default=None, help="rbla model JSON (default stdout)")
    p.add_argument("--support", action="append", default=[],
                   help="node key(s) to make fixed, comma-separated; repeatable")
    p.add_argument("--fix-lowest", action="store_true",
                   help="make fixed every block whose lowest point is at the model's lowest z")
    p.add_argument("--interfaces", action="store_true",
                   help="write the interfaces stored on the graph edges (default: let rbla detect)")
    p.add_argument("--fix-orientation", action="store_true",
                   help="reverse the faces of blocks whose volume from the faces is negative")
    p.add_argument("--unit-weight", type=float, default=18.0, help="kN/m3 (default 18)")
    p.add_argument("--friction", type=float, default=0.6, help="mu (default 0.6)")
    p.add_argument("--compact", action="store_true", help="write the JSON on one line")
    args = p.parse_args(argv)

    name = os.path.splitext(os.path.basename(args.input))[0]
    try:
        with open(args.input, encoding="utf-8") as fh:
            doc = json.load(fh)
    except (OSError, ValueError) as e:
        sys.stderr.write("%s: cannot read JSON: %s\n" % (args.input, e))
        return 1
    supports = [s.strip() for arg in args.support for s in arg.split(",") if s.strip()]
    try:
        model, info = convert(doc, name=name, supports=supports, fix_lowest=args.fix_lowest,
                              with_interfaces=args.interfaces, unit_weight=args.unit_weight,
                              friction=args.friction, fix_orientation=args.fix_orientation)
    except ConversionError as e:
        sys.stderr.write("%s: cannot convert: %s\n" % (args.input, e))
        return 1
    text = dumps_model(model, args.compact)
    if args.output in (None, "-"):
        sys.stdout.write(text)
    else:
        d = os.path.dirname(args.output)
        if d:
            os.makedirs(d, exist_ok=True)
        with open(args.output, "w", encoding="utf-8") as fh:
            fh.write(text)
    fixed = [b["id"] for b in model["blocks"] if b["role"] == "fixed"]
    msg = ("%s: %d blocks (%d fixed: %s), %s; max face warp %.2g m"
           % (args.input, info["blocks"], len(fixed), ",".join(fixed) or "-", info["dtype"],
              info["max_face_warp"]))
    if args.interfaces:
        msg += "; %d interfaces written" % info["interfaces"]
    if info["dropped_vertices"]:
        msg += "; %d unused vertices dropped" % info["dropped_vertices"]
    sys.stderr.write(msg + "\n")
    if not fixed:
        sys.stderr.write("%s: warning: no support (no is_support node); rbla will find that the "
                         "structure cannot stand. Use --support KEY or --fix-lowest.\n" % args.input)
    if info["volume_negative"]:
        sys.stderr.write("%s: warning: blocks %s have negative volume from their faces (inward "
                         "faces)%s\n" % (args.input, ",".join(info["volume_negative"]),
                                         "; reversed" if info["reversed"] else
                                         "; use --fix-orientation"))
    for pr in info["problems"][:20]:
        sys.stderr.write("%s: warning: %s\n" % (args.input, pr))
    bad = (info["volume_negative"] and not info["reversed"]) or any(
        "not shared" in pr or "zero area" in pr for pr in info["problems"])
    return 2 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
