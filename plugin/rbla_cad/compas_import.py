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

Other layouts (COMPAS 1 ``{"dtype", "value"}`` data, compas_assembly's ``{"assembly",
"blocks"}`` files, a single mesh or a list of meshes) are read by ``compas_formats``; anything
else is refused with a message saying what was found and what is expected.

Supports: the file's ``is_support`` nodes, ``--support KEY``, and, when the file marks none (or
with ``--ground always``), every block resting on the ground plane: the horizontal plane through
the model's lowest point, touched by a downward face whose corners are all within rbla's default
joint tolerance (3 % of that face's diameter, read from the bundled schema) of it and which comes
within rbla's clearance limit (30 mm) of it somewhere, the two tests rbla's interface detection
applies to a joint. compas_cra
files usually carry no supports (its example scripts call ``set_boundary_conditions([0])`` after
loading), so their lowest blocks become fixed.

Usage (from plugin/)::

    python3 -m rbla_cad.compas_import IN.json -o OUT.json [--support 0,1] [--ground auto|always|never]
                                     [--interfaces] [--unit-weight W] [--friction MU]

Exit status (one line on stderr says why): 0 converted; 1 a bad option (``--friction -1``,
``--unit-weight nan``: the ranges of the model schema) or a file that is not a convertible
assembly (a layout it does not know, or a value of the wrong kind inside a known one: the message
starts with that value's JSON pointer, ``/data/graph/data/node/3/block/data/vertex/2: expected a
point ...``; coordinates are numbers within the model schema's bound); 2 invalid input (not JSON,
nested too deeply) or a block failed its checks (the model is still written); 4 a file that cannot be read or written. Files are read and written as the
solver does (``safe_files``): the input must be a regular file, a pipe or ``-`` of at most
``--max-input-bytes`` (devices and folders are refused before reading); the output is never the
input, a folder, a block device or a socket, a pipe or character device is written into, and a
file is replaced atomically (temporary file in its folder, then renamed), a link's target in its
place.
"""

import argparse
import json
import math
import os
import sys

from .compas_formats import ConversionError, read_assembly, unwrap  # noqa: F401 (re-exported)
from .compas_formats import child, dtype_of, expect, kind_of, shown_pointer, shown_text, unwrap_at
# Geometry helpers are shared with the rest of the core (divergence-theorem volume, Newell normal).
from .geometry import dot as _dot, newell_normal, sub as _sub, volume_centroid
from .jsonschema_lite import load_schema
from .safe_files import MAX_INPUT_BYTES, FileError, check_not_input, read_input, resolve_output, write_output

SCHEMA_VERSION = "1.0.0"
# rbla's clearance limit at the default joint tolerance, in metres (docs/detection.md, "The
# rule"): a joint's faces must come this close somewhere. The solver writes the value it used as
# detection.tolerances.clearance_limit; tests/plugin/test_compas_import.py checks the two agree.
CLEARANCE_LIMIT_M = 0.03


def detection_defaults():
    """rbla's default joint tolerance (fraction of a face's diameter) and angle tolerance
    (degrees), from the bundled model schema: one place for those numbers."""
    props = load_schema("model")["properties"]["detection"]["properties"]
    return props["joint_tolerance"]["default"], props["angle_tolerance"]["default"]


def coordinate_limit():
    """The largest coordinate magnitude the model schema allows (its vec3 bound)."""
    return load_schema("model")["definitions"]["vec3"]["items"]["maximum"]


def model_defaults():
    """rbla's default unit weight (kN/m3) and friction coefficient, from the bundled model
    schema's `defaults`, so a converted model says what rbla would assume anyway."""
    props = load_schema("model")["properties"]["defaults"]["properties"]
    return props["unit_weight"]["default"], props["friction"]["default"]


def _closure_problems(vertices, faces):
    """Edges of a block not matched by an edge of opposite direction, after splitting edges at
    the vertices lying on them (T-junctions, as faces split into coplanar pieces leave them).
    Returns (number of unmatched edges, whether T-junctions were needed)."""
    def count(edge_list):
        edges = {}
        for e in edge_list:
            edges[e] = edges.get(e, 0) + 1
        return sum(1 for e, c in edges.items() if c != 1 or edges.get((e[1], e[0]), 0) != 1)
    plain = [(f[k], f[(k + 1) % len(f)]) for f in faces for k in range(len(f))]
    bad = count(plain)
    if not bad:
        return 0, False
    lo = [min(v[i] for v in vertices) for i in range(3)]
    hi = [max(v[i] for v in vertices) for i in range(3)]
    eps = 1e-9 * math.sqrt(sum((hi[i] - lo[i]) ** 2 for i in range(3)))
    split = []
    for a, b in plain:
        ab = _sub(vertices[b], vertices[a])
        L2 = _dot(ab, ab)
        inner = []
        for k, v in enumerate(vertices):
            if k in (a, b) or L2 == 0.0:
                continue
            t = _dot(_sub(v, vertices[a]), ab) / L2
            if 0.0 < t < 1.0:
                d = _sub(_sub(v, vertices[a]), tuple(t * c for c in ab))
                if math.sqrt(_dot(d, d)) <= eps:
                    inner.append((t, k))
        chain = [a] + [k for _, k in sorted(inner)] + [b]
        split.extend(zip(chain[:-1], chain[1:]))
    bad_split = count(split)
    return bad_split, bad_split == 0


def block_report(vertices, faces):
    """Checks of one block: closure/orientation of its edges (T-junctions accepted, as rbla
    accepts them), volume, largest face warp."""
    problems = []
    bad, t_junctions = _closure_problems(vertices, faces)
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
        mean = tuple(sum(p[i] for p in pts) / len(pts) for i in range(3))
        for p in pts:
            warp = max(warp, abs(_dot(_sub(p, mean), n)))
    return vol, cen, warp, problems, t_junctions


# --------------------------------------------------------------------------------------------
# Mesh data
# --------------------------------------------------------------------------------------------

def _coordinate(x, pointer):
    """A float from a JSON number within the model schema's bound (not a boolean, a string, or
    NaN/Infinity, which Python's json module reads); the bound also keeps volumes finite."""
    expect(x, (int, float), "a number", pointer)
    limit = coordinate_limit()
    try:
        x = float(x)
    except OverflowError:  # an integer of hundreds of digits
        x = math.inf
    if not abs(x) <= limit:  # also true for NaN
        raise ConversionError("expected a coordinate within +-%g (the model schema's bound), found %s"
                              % (limit, x), pointer)
    return x


def _point(p, pointer=""):
    """[x, y, z] of a point: COMPAS vertex attributes {"x", "y", "z"}, or [x, y, z] (a COMPAS
    Point's data, a polyhedron's vertex), wrapped or not."""
    p, at = unwrap_at(p, pointer)
    if isinstance(p, dict):
        for c in "xyz":
            if c not in p:
                raise ConversionError('expected a point {"x", "y", "z"}; "%s" is missing' % c, at)
        return [_coordinate(p[c], child(at, c)) for c in "xyz"]
    if isinstance(p, list) and len(p) == 3:
        return [_coordinate(c, child(at, i)) for i, c in enumerate(p)]
    raise ConversionError('expected a point ([x, y, z] or {"x", "y", "z"}), found %s'
                          % ("a list of %d items" % len(p) if isinstance(p, list) else kind_of(p)), at)


def _key_order(k):
    """Sort numeric keys numerically, others after them as text."""
    try:
        return (0, int(k), "")
    except (TypeError, ValueError):
        return (1, 0, str(k))


def _face_keys(face, pointer):
    """The vertex keys of a face, as the text of the keys of the vertex object (an index of a
    polyhedron's vertex list is looked up the same way)."""
    expect(face, list, "a face (a list of vertex keys)", pointer)
    return [str(expect(v, (int, str), "a vertex key (an integer or a string)", child(pointer, i)))
            for i, v in enumerate(face)]


def _mesh_parts(mesh, pointer):
    """({vertex key: (vertex, pointer)}, [(face key, vertex keys, pointer)], pointer of the
    vertices, pointer of the faces) of halfedge data or polyhedron data."""
    if "vertex" in mesh:
        v_at, f_at = child(pointer, "vertex"), child(pointer, "face")
        vertex = expect(mesh["vertex"], dict, "an object of vertices", v_at)
        face = expect(mesh["face"], dict, "an object of faces", f_at)
        vmap = {str(k): (v, child(v_at, k)) for k, v in vertex.items()}
        items = [(fk, face[fk], child(f_at, fk)) for fk in sorted(face, key=_key_order)]
    else:
        v_at, f_at = child(pointer, "vertices"), child(pointer, "faces")
        vertices = expect(mesh["vertices"], list, "a list of vertices", v_at)
        faces = expect(mesh["faces"], list, "a list of faces", f_at)
        vmap = {str(i): (v, child(v_at, i)) for i, v in enumerate(vertices)}
        items = [(i, f, child(f_at, i)) for i, f in enumerate(faces)]
    return vmap, [(fk, _face_keys(f, at), at) for fk, f, at in items], v_at, f_at


def mesh_geometry(mesh, key, info, pointer=""):
    """(vertices, faces) of a COMPAS mesh's data, vertices renumbered 0..n-1 in key order, unused
    ones dropped, repeated consecutive vertices and degenerate faces removed. pointer: where the
    mesh data is in the file, for messages; a value of the wrong kind, a face naming a vertex
    the mesh does not have, or a mesh without faces is a ConversionError naming its pointer."""
    vmap, polygons, v_at, f_at = _mesh_parts(mesh, pointer)
    for _, polygon, at in polygons:
        for i, v in enumerate(polygon):
            if v not in vmap:
                raise ConversionError("the face uses vertex %s, which %s does not have"
                                      % (shown_text(v), shown_pointer(v_at)), child(at, i))
    used = set(v for _, f, _ in polygons for v in f)
    vkeys = [k for k in sorted(vmap, key=_key_order) if k in used]
    info["dropped_vertices"] += len(vmap) - len(vkeys)
    index = {k: i for i, k in enumerate(vkeys)}
    vertices = [_point(*vmap[k]) for k in vkeys]
    faces = []
    for fk, polygon, _ in polygons:
        f = [index[v] for v in polygon]
        f = [v for i, v in enumerate(f) if v != f[i - 1]] if len(f) > 1 else f
        if len(set(f)) < 3:
            info["problems"].append("node %s: face %s degenerate, dropped" % (key, fk))
            continue
        faces.append(f)
    if not faces:  # nothing to make a block of (and no vertex to find the ground with)
        raise ConversionError("the mesh has no face with three distinct vertices or more", f_at)
    return vertices, faces


# --------------------------------------------------------------------------------------------
# Supports by contact with the ground
# --------------------------------------------------------------------------------------------

def ground_contacts(blocks, joint_tolerance, angle_tolerance, clearance=CLEARANCE_LIMIT_M):
    """Ids of the blocks that rest on the ground plane, the horizontal plane through the model's
    lowest point: blocks with a face that faces down (outward normal within angle_tolerance
    degrees of -z), whose every corner is within joint_tolerance times the face's diameter of
    that plane and whose lowest corner is within `clearance` (metres) of it: the tests rbla's
    interface detection would apply between the face and a slab on the ground. Feet that CAD
    left a few millimetres up, or warped, still count; a block that only touches the ground with
    an edge or a corner does not, nor does a large block standing on a thin plinth (its face is
    within 3 % of its diameter of the ground, but not within the clearance)."""
    z0 = min(v[2] for b in blocks for v in b["vertices"])
    cos_limit = math.cos(math.radians(angle_tolerance))
    resting = []
    for b in blocks:
        V = b["vertices"]
        for f in b["faces"]:
            pts = [V[i] for i in f]
            n = newell_normal(pts)
            ln = math.sqrt(_dot(n, n))
            if ln == 0.0 or -n[2] / ln < cos_limit:
                continue
            diameter = max(math.sqrt(_dot(_sub(p, q), _sub(p, q))) for p in pts for q in pts)
            heights = [p[2] - z0 for p in pts]
            if max(heights) <= joint_tolerance * diameter and min(heights) <= clearance * (1.0 + 1e-9):
                resting.append(b["id"])
                break
    return z0, resting


# --------------------------------------------------------------------------------------------
# Conversion
# --------------------------------------------------------------------------------------------

def _example_input_error(doc):
    courses = doc.get("courses") if isinstance(doc, dict) and "basecurve" in doc else None
    if isinstance(courses, list) and all(isinstance(c, list) for c in courses):
        dtypes = sorted({(dtype_of(x) or "?") if isinstance(x, dict) else type(x).__name__
                         for c in courses for x in c})
        raise ConversionError(
            "not an assembly: a compas_assembly example input (params, basecurve and %d courses "
            "of %s) that the example script turns into an assembly; its courses are not stacked "
            "(all at z = 0), so blocks would overlap. Convert the assembled result instead "
            "(wall_assembly.json for the running-bond wall)." % (len(courses), ", ".join(dtypes)))


def _make_block(key, mesh, attr, wrapper, pointer, default_support, fix_orientation, info):
    vertices, faces = mesh_geometry(mesh, key, info, pointer)
    vol, cen, warp, problems, t_junctions = block_report(vertices, faces)
    if vol <= 0.0:
        info["volume_negative"].append(key)
        if fix_orientation:
            faces = [list(reversed(f)) for f in faces]
            vol, cen, warp, problems, t_junctions = block_report(vertices, faces)
            info["reversed"].append(key)
    info["max_face_warp"] = max(info["max_face_warp"], warp)
    if t_junctions:
        info["t_junctions"].append(key)
    info["problems"].extend("node %s: %s" % (key, p) for p in problems)
    is_support = bool(attr.get("is_support", default_support))
    if is_support:
        info["supports_from_file"].append(key)
    b = {"id": key}
    attributes = mesh.get("attributes")
    label = (wrapper.get("name") if isinstance(wrapper, dict) else None) or mesh.get("name") or \
        (attributes.get("name") if isinstance(attributes, dict) else None)
    if isinstance(label, str) and label:
        b["label"] = label
    b["role"] = "fixed" if is_support else "free"
    b["vertices"] = vertices
    b["faces"] = faces
    b["centroid"] = [round(c, 12) + 0.0 for c in cen]
    if vol > 0.0:
        b["volume"] = vol
    return b


def _apply_supports(blocks, supports, ground, info):
    by_id = {b["id"]: b for b in blocks}
    for s in supports:
        if s not in by_id:
            raise ConversionError("--support %s: no such node (nodes: %s)"
                                  % (s, ", ".join(sorted(by_id, key=_key_order))))
        if by_id[s]["role"] != "fixed":
            by_id[s]["role"] = "fixed"
            info["supports_added"].append(s)
    use_ground = ground == "always" or (ground == "auto" and not any(b["role"] == "fixed" for b in blocks))
    if not use_ground:
        return
    joint_tolerance, angle_tolerance = detection_defaults()
    info["ground_level"], resting = ground_contacts(blocks, joint_tolerance, angle_tolerance)
    info["ground_contacts"] = resting
    if len(resting) == len(blocks):
        return
    for k in resting:
        if by_id[k]["role"] != "fixed":
            by_id[k]["role"] = "fixed"
            info["supports_added"].append(k)


def _stored_interfaces(asm, centroids, info):
    interfaces = []
    for u, v, polygons in sorted(asm.edges, key=lambda e: (_key_order(e[0]), _key_order(e[1]))):
        for k, (at, raw) in enumerate(polygons):
            pts = [_point(p, child(at, i)) for i, p in enumerate(expect(raw, list, "a list of points", at))]
            if len(pts) < 3:
                info["problems"].append("edge %s-%s: interface %d has %d points, skipped" % (u, v, k, len(pts)))
                continue
            if u not in centroids or v not in centroids:
                info["problems"].append("edge %s-%s: unknown node, skipped" % (u, v))
                continue
            # normal from blocks[0] into blocks[1]: orient the polygon so its right-hand normal
            # points from u's centroid side to v's
            if _dot(newell_normal(pts), _sub(centroids[v], centroids[u])) < 0.0:
                pts = list(reversed(pts))
            interfaces.append({"id": "I%s-%s-%d" % (u, v, k), "blocks": [u, v], "polygon": pts})
    return interfaces


def convert(doc, name="", supports=(), ground="auto", with_interfaces=False,
            unit_weight=None, friction=None, fix_orientation=False, fix_lowest=False):
    """Return (model dict, info dict) for a parsed COMPAS document.

    ground: "auto" finds supports by contact with the ground plane (ground_contacts) when the file
    marks none, "always" also when it does, "never" not at all. fix_lowest=True is the old name
    of ground="always". unit_weight and friction: the schema's defaults when None."""
    default_unit_weight, default_friction = model_defaults()
    unit_weight = default_unit_weight if unit_weight is None else unit_weight
    friction = default_friction if friction is None else friction
    if fix_lowest:
        ground = "always"
    _example_input_error(doc)
    asm = read_assembly(doc)
    info = {"dtype": asm.dtype, "layout": asm.layout, "blocks": 0, "supports_from_file": [],
            "supports_added": [], "ground_contacts": [], "ground_level": None, "volume_negative": [],
            "reversed": [], "t_junctions": [], "max_face_warp": 0.0, "problems": [], "interfaces": 0,
            "dropped_vertices": 0}
    blocks = [_make_block(key, mesh, attr, wrapper, pointer, asm.default_support, fix_orientation, info)
              for key, mesh, attr, wrapper, pointer in sorted(asm.nodes, key=lambda n: _key_order(n[0]))]
    _apply_supports(blocks, supports, ground, info)
    kind = (asm.dtype.split("/")[-1] if asm.dtype else "") or asm.layout
    model = {
        "schema_version": SCHEMA_VERSION,
        "title": ("%s (converted from COMPAS %s)" % (name, kind)).strip(),
        "units": {"length": "m", "force": "kN", "unit_weight": "kN/m3"},
        "gravity": "-z",
        "defaults": {"unit_weight": unit_weight, "friction": friction},
        "blocks": blocks,
    }
    if with_interfaces:
        centroids = {b["id"]: b["centroid"] for b in blocks}
        interfaces = _stored_interfaces(asm, centroids, info)
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


def _printable(text):
    """`text` with its control characters escaped (a newline as \\n, ESC as \\x1b): block ids come
    from the file, and a newline or a terminal escape in one must not forge or hide report lines."""
    return "".join(c if c.isprintable() else c.encode("unicode_escape").decode("ascii") for c in text)


def _id_list(ids, most=20):
    """At most `most` ids, comma-separated, and how many more there are."""
    shown = ",".join(ids[:most]) or "-"
    return shown + (" and %d more" % (len(ids) - most) if len(ids) > most else "")


def _report(path, model, info, with_interfaces):
    """The converter's messages on standard error; returns the exit status."""
    lines = []
    fixed = [b["id"] for b in model["blocks"] if b["role"] == "fixed"]
    msg = ("%s: %s, %d blocks (%d fixed: %s); max face warp %.2g m"
           % (path, info["layout"] + (" " + info["dtype"] if info["dtype"] else ""), info["blocks"],
              len(fixed), _id_list(fixed), info["max_face_warp"]))
    if with_interfaces:
        msg += "; %d interfaces written" % info["interfaces"]
    if info["dropped_vertices"]:
        msg += "; %d unused vertices dropped" % info["dropped_vertices"]
    lines.append(msg)
    if info["ground_level"] is not None:
        lines.append("%s: supports by contact with the ground plane z = %.6g m: %d blocks rest on it (%s)"
                     % (path, info["ground_level"], len(info["ground_contacts"]), _id_list(info["ground_contacts"])))
    if not fixed:
        why = ("every block rests on the ground plane, so none was made fixed by contact"
               if info["ground_contacts"] and len(info["ground_contacts"]) == info["blocks"]
               else "no is_support node and no block resting on the ground plane")
        lines.append("%s: warning: no support (%s); rbla will find that the structure cannot stand. "
                     "Use --support KEY." % (path, why))
    if info["t_junctions"]:
        lines.append("%s: note: blocks %s have vertices on other faces' edges (faces split into pieces); "
                     "accepted" % (path, _id_list(info["t_junctions"])))
    if info["volume_negative"]:
        lines.append("%s: warning: blocks %s have negative volume from their faces (inward faces)%s"
                     % (path, _id_list(info["volume_negative"]),
                        "; reversed" if info["reversed"] else "; use --fix-orientation"))
    for pr in info["problems"][:20]:
        lines.append("%s: warning: %s" % (path, pr))
    if len(info["problems"]) > 20:
        lines.append("%s: warning: and %d more problems" % (path, len(info["problems"]) - 20))
    for line in lines:
        sys.stderr.write(_printable(line) + "\n")
    bad = (info["volume_negative"] and not info["reversed"]) or any(
        "not shared" in pr or "zero area" in pr for pr in info["problems"])
    return 2 if bad else 0


class _Parser(argparse.ArgumentParser):
    """Bad options exit 1 with one line (the solver's usage error), not argparse's 2 and usage."""

    def error(self, message):
        self.exit(1, "%s: %s (see --help)\n" % (self.prog, message))


def _number(low, high):
    """An argparse type: a finite number in (low, high], the range the model schema allows."""
    def parse(text):
        try:
            x = float(text)
        except ValueError:
            x = float("nan")
        if not (low < x <= high):  # also false for nan
            raise argparse.ArgumentTypeError("must be a number in (%g, %g], got %r"
                                             % (low, high, text))
        return x
    return parse


def option_ranges():
    """(low, high) of the unit weight and the friction coefficient, from the bundled schema."""
    props = load_schema("model")["properties"]["defaults"]["properties"]
    return tuple((props[k].get("exclusiveMinimum", 0), props[k]["maximum"])
                 for k in ("unit_weight", "friction"))


def main(argv=None):
    p = _Parser(prog="python3 -m rbla_cad.compas_import",
                description="Convert a COMPAS assembly (or meshes) JSON file to an rbla model.")
    p.add_argument("input", help="COMPAS JSON file (COMPAS 1 or 2), a pipe, or - for standard input")
    p.add_argument("-o", "--output", default=None,
                   help="rbla model JSON (default stdout); never the input, a folder or a device "
                        "other than a pipe or character device")
    p.add_argument("--support", action="append", default=[],
                   help="node key(s) to make fixed, comma-separated; repeatable")
    p.add_argument("--ground", choices=["auto", "always", "never"], default="auto",
                   help="make fixed the blocks resting on the ground plane (the model's lowest level): "
                        "auto when the file marks no support, always, or never (default auto)")
    p.add_argument("--fix-lowest", action="store_true", help="the same as --ground always")
    p.add_argument("--interfaces", action="store_true",
                   help="write the interfaces stored on the graph edges (default: let rbla detect)")
    p.add_argument("--fix-orientation", action="store_true",
                   help="reverse the faces of blocks whose volume from the faces is negative")
    default_unit_weight, default_friction = model_defaults()
    unit_weight_range, friction_range = option_ranges()
    p.add_argument("--unit-weight", type=_number(*unit_weight_range),
                   default=default_unit_weight, help="kN/m3 (default %g)" % default_unit_weight)
    p.add_argument("--friction", type=_number(*friction_range),
                   default=default_friction, help="mu (default %g)" % default_friction)
    p.add_argument("--max-input-bytes", type=_number(0, float(1 << 62)),
                   default=MAX_INPUT_BYTES,
                   help="refuse a larger input (default %d, the solver's)" % MAX_INPUT_BYTES)
    p.add_argument("--compact", action="store_true", help="write the JSON on one line")
    args = p.parse_args(argv)

    name = os.path.splitext(os.path.basename(args.input))[0]
    # The output is examined before the conversion, so a wrong -o is never clobbered.
    output = "-" if args.output is None else args.output
    try:
        raw = read_input(args.input, int(args.max_input_bytes))
        d = os.path.dirname(output)
        if output != "-" and d and not os.path.lexists(d):
            os.makedirs(d)  # the converter has always created a missing output folder
        out = resolve_output(output)
        check_not_input(out, [args.input])
    except FileError as e:
        sys.stderr.write("%s\n" % e)
        return 4
    except OSError as e:
        sys.stderr.write("cannot create the folder of '%s': %s\n" % (output, e.strerror or e))
        return 4
    try:
        doc = json.loads(raw.decode("utf-8"))
    except RecursionError:
        sys.stderr.write("%s: cannot read JSON: too deeply nested\n" % args.input)
        return 2
    except ValueError as e:  # JSONDecodeError and UnicodeDecodeError
        sys.stderr.write("%s: cannot read JSON: %s\n" % (args.input, e))
        return 2
    supports = [s.strip() for arg in args.support for s in arg.split(",") if s.strip()]
    try:
        model, info = convert(doc, name=name, supports=supports,
                              ground="always" if args.fix_lowest else args.ground,
                              with_interfaces=args.interfaces, unit_weight=args.unit_weight,
                              friction=args.friction, fix_orientation=args.fix_orientation)
        text = dumps_model(model, args.compact)
    except ConversionError as e:
        sys.stderr.write("%s: cannot convert: %s\n" % (args.input, e))
        return 1
    except RecursionError:  # valid JSON nested deeper than the converter walks
        sys.stderr.write("%s: cannot convert: too deeply nested\n" % args.input)
        return 2
    try:
        write_output(out, text)
    except FileError as e:
        sys.stderr.write("%s\n" % e)
        return 4
    return _report(args.input, model, info, args.interfaces)


if __name__ == "__main__":
    sys.exit(main())
