"""Functions behind the Grasshopper components (plugin/rhino/grasshopper/*/code.py).

Plain inputs in, plain outputs out, so each component's code is a few lines. Models and
results travel between components as JSON text (a GH string), which also makes them easy to
internalise or write to a file.
"""

import hashlib
import json

import Rhino
import Rhino.Geometry as rg

from rbla_cad import polygons, usertext
from rbla_cad import runner as rrun
from rbla_cad import result as rres
from rbla_cad.model import ModelBuilder, ModelError, host_length_unit

from . import geometry as rgeo

_cache = {}


def _item(values, i, default=None):
    """values[i], or the single value for all, or default (GH list-matching made simple)."""
    if not values:
        return default
    if len(values) == 1:
        return values[0] if values[0] is not None else default
    if i < len(values) and values[i] is not None:
        return values[i]
    return default


def build_model(blocks, ids=None, roles=None, unit_weights=None, labels=None, frictions=None,
                interfaces=None, interface_labels=None, interface_blocks=None,
                analysis="seismic", direction=None, units=None, force="kN",
                settings=None, tolerance=None):
    """Model JSON text from block geometry (Breps / Meshes) and per-block lists.

    roles: free / fixed / moving_support (one per block, or one for all; read like User Text
    rbla.role, so `support` is fixed); analysis: seismic (direction = the horizontal load
    direction, default +x), live or settlement (direction = the settlement direction, default
    gravity), read like rbla.analysis. Interface geometry: planar pieces, merged like interface
    objects (coplanar pieces that touch are one interface). settings: JSON text of extra analysis settings
    (friction_model, cone, pyramid_faces, formulation, time_limit). units: the document's when
    empty. Returns (json text, ids, report lines); raises ModelError listing every bad block."""
    doc = Rhino.RhinoDoc.ActiveDoc
    tol = tolerance or (doc.ModelAbsoluteTolerance if doc else 0.001)
    unit = units or (str(doc.ModelUnitSystem).split(".")[-1] if doc else "m")
    mb = ModelBuilder(length=unit, force=force or "kN")
    issues = []
    out_ids = []
    for i, g in enumerate(blocks or []):
        if g is None:
            continue
        bid = str(ids[i]) if ids and i < len(ids) and ids[i] else "B%d" % i
        try:
            v, f, vol, cen = rgeo.block_polyhedron(g, tol, bid)
        except ModelError as e:
            issues.append("block %r: %s" % (bid, e))
            continue
        try:
            role = usertext.read_value("block", "rbla.role", _item(roles, i, "free"),
                                       "block %s" % usertext.q(bid))
            mb.add_block(bid, v, f, role=role, unit_weight=_item(unit_weights, i),
                         label=_item(labels, i), centroid=cen, volume=vol,
                         friction=_item(frictions, i))
            out_ids.append(bid)
        except ModelError as e:
            issues.append(str(e))
    for i, s in enumerate(interfaces or []):
        _add_interface(mb, i, s, _item(interface_blocks, i), _item(interface_labels, i), tol,
                       issues)
    if issues:
        raise ModelError("%d problem(s):\n%s" % (len(issues), "\n".join(issues)))
    d = None
    if direction is not None:
        d = [direction.X, direction.Y, direction.Z]
    kind = usertext.read_value("document", "rbla.analysis", analysis or "seismic",
                               "analysis input")
    if kind == "settlement":
        mb.set_settlement(direction=d)
    elif kind == "live":
        mb.set_load_multiplier()
    else:
        mb.set_seismic(d or [1, 0, 0])
    if settings:
        mb.set_analysis(**json.loads(settings))
    doc_json = mb.to_dict()
    report = ["%d blocks, units %s/%s" % (len(doc_json["blocks"]), mb.length, mb.force)]
    report += ["warning: " + w for w in mb.warnings]
    return json.dumps(doc_json), out_ids, report


def _add_interface(mb, i, geometry, pair, label, tol, issues):
    """One interface input: its planar pieces merged (coplanar pieces that touch are one
    interface, as in the User Text convention) between the two given blocks."""
    shape = rgeo.shape_record(geometry, tol) if geometry is not None else {}
    if shape.get("shape") != "polygons" or shape.get("error") or not pair:
        issues.append("interface %d: needs planar surfaces, an open mesh or a closed planar "
                      "polyline, and its two block ids ('idA, idB')%s"
                      % (i, "; " + shape["error"] if shape.get("error") else ""))
        return
    try:
        ids = usertext.read_value("interface", "rbla.blocks", pair, "interface %d" % i)
        for g in polygons.merge_coplanar(shape["polygons"], tol,
                                         usertext.DATA["interface_merge"]["relative"]):
            mb.add_interface(ids, g["polygon"], label=label)
    except ModelError as e:
        issues.append(str(e))


def solve(model_text, run=True, exe=None, timeout=None):
    """(result JSON text, Result, log lines). Cached by model text so toggling 'run' or
    re-solving an unchanged model does not start the solver again. Esc cancels."""
    return _run("solve", model_text, run, exe, timeout, {})


def worst_direction(model_text, run=True, exe=None, timeout=None, tolerance=None):
    """As solve(), with ``rbla worst-direction``: the result is the analysis along the weakest
    horizontal direction; result.data["worst_direction"] holds the search."""
    return _run("worst_direction", model_text, run, exe, timeout, {"tolerance": tolerance or None})


def worst_settlement(model_text, run=True, exe=None, timeout=None, tolerance=None, cone_angle=None,
                     candidate_groups=None):
    """As solve(), with ``rbla worst-settlement``: the result is the settlement analysis along
    the most harmful direction; result.data["worst_settlement"] holds the search.
    ``candidate_groups``: comma-separated support ids or labels, one text per group: the groups
    are ranked and the most harmful one's analysis returned."""
    groups = [g for g in (candidate_groups or []) if g and g.strip()]
    return _run("worst_settlement", model_text, run, exe, timeout,
                {"tolerance": tolerance or None, "cone_angle": cone_angle or None,
                 "candidate_groups": groups or None})


def critical_friction(model_text, run=True, exe=None, timeout=None, target_alpha=None,
                      interfaces=None, interfaces_of=None):
    """As solve(), with ``rbla critical-friction``: the result is the analysis at the critical
    friction; result.data["critical_friction"] holds the search. ``interfaces`` (ids or labels)
    and ``interfaces_of`` (block ids or labels) choose the joints scaled; empty: all."""
    return _run("critical_friction", model_text, run, exe, timeout,
                {"target_alpha": target_alpha, "interfaces": list(interfaces or []) or None,
                 "interfaces_of": list(interfaces_of or []) or None})


def _run(command, model_text, run, exe, timeout, options):
    key = hashlib.sha1(json.dumps([command, model_text or "", options], sort_keys=True)
                       .encode("utf-8")).hexdigest()
    if key in _cache:
        return _cache[key]
    if not run:
        return None, None, ["set run to True to solve"]
    log = []
    try:
        import Grasshopper
        cancel = Grasshopper.Kernel.GH_Document.IsEscapeKeyDown
    except Exception:
        cancel = None

    def progress(ev):
        if ev.kind in ("stage", "warning"):
            log.append(ev.text)
    runner = rrun.Runner(exe or None, timeout=timeout or None)
    outcome = getattr(runner, command)(json.loads(model_text), progress=progress, cancel=cancel,
                                       verbose=False, **options)
    text = json.dumps(outcome.result.data)
    _cache.clear()
    _cache[key] = (text, outcome.result, log)
    return _cache[key]


def report_error(component, error):
    """Show a solver error on a component (a warning when cancelled, an error otherwise) and
    return its lines for the component's log output."""
    import Grasshopper
    level = Grasshopper.Kernel.GH_RuntimeMessageLevel
    component.AddRuntimeMessage(
        level.Warning if isinstance(error, rrun.CancelledError) else level.Error, str(error))
    return str(error).splitlines()


def mechanism(model_text, result_text, amplitude=None, screw=False, show_closed=False):
    """Display geometry: dict of lists (blocks, block_colours, contacts, contact_colours,
    outlines, states, transforms, dot_points, dot_texts) and the amplitude used."""
    model = json.loads(model_text)
    res = rres.Result(json.loads(result_text))
    doc = Rhino.RhinoDoc.ActiveDoc
    scale = 1.0
    if doc is not None:
        unit, scale = host_length_unit(str(doc.ModelUnitSystem).split(".")[-1])
        if unit != model["units"]["length"]:
            scale = 1.0  # drawing in model units
    s = res.displacement_scale if amplitude is None else float(amplitude)
    out = dict((k, []) for k in ("ids", "blocks", "block_colours", "transforms", "contacts",
                                 "contact_colours", "outlines", "states", "dot_points",
                                 "dot_texts"))
    for b in rres.displaced_blocks(model, res, s, scale, screw):
        out["ids"].append(b["id"])
        out["blocks"].append(rgeo.block_mesh(b["vertices"], b["faces"], b["rgb"]))
        out["block_colours"].append(rgeo.colour(b["rgb"]))
        out["transforms"].append(rgeo.transform(b["transform"]))
    for c in rres.contact_polygons(res, show_closed, scale):
        pts = c["polygon"]
        out["states"].append(c["state"])
        out["contact_colours"].append(rgeo.colour(c["rgb"]))
        out["contacts"].append(rgeo.polygon_mesh(pts) if len(pts) >= 3 else None)
        out["outlines"].append(rg.Polyline([rgeo.point3d(p) for p in pts] +
                                           [rgeo.point3d(pts[0])]))
    for p, text in rres.reaction_labels(res, 3, scale) + rres.influence_labels(res, 5, 3, scale):
        out["dot_points"].append(rgeo.point3d(p))
        out["dot_texts"].append(text)
    return out, s


def legend(include_closed=True, include_blocks=True):
    items = rres.legend(include_closed, include_blocks)
    return ([i["label"] for i in items], [rgeo.colour(i["rgb"]) for i in items],
            [i["hex"] for i in items], [i["key"] for i in items])
