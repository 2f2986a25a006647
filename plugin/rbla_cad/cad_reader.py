"""A CAD document read into an rbla model by the attribute convention (data/cad_attributes.json).

Host-independent: the Rhino adapter (plugin/rhino/rbla_rhino/document.py) turns each Rhino
object into a plain record and calls ``read_document``; the .3dm exchange does the same with
rhino3dm objects in plugin/exchange/lib/cad-reader.mjs, step for step, and tests/plugin/cad_cases
runs both on the same records. A document record::

    {"name": "vault.3dm", "units": "Meters", "tolerance": 0.001,
     "user_text": {"rbla.analysis": "seismic", ...},
     "objects": [{"guid": "...", "name": "B1", "layer": "Walls::South", "hidden": False,
                  "type": "Brep", "user_text": {...},
                  "shape": "solid", "vertices": [...], "faces": [...],  # closed, outward
                  "volume": 1.0, "centroid": [...]},                    # optional CAD values
                 {"shape": "polygons", "polygons": [[[x, y, z], ...], ...]},  # open planar
                 {"shape": "point", "point": [x, y, z]},
                 {"shape": "other"}, ...]}

``shape`` may come with ``error`` (what the host could not convert). Coordinates and the
tolerance are in the document's unit. ``read_document`` returns a :class:`Reading`: the model
dict (None when there is an error), the :class:`usertext.Report` of errors and warnings, the
builder and {block id: object guid}.
"""

from . import geometry as geo
from . import polygons
from . import usertext as ut
from .model import ModelBuilder, ModelError

DATA = ut.DATA
SEARCH_FACTOR = DATA["interface_search"]["factor"]
MERGE_RELATIVE = DATA["interface_merge"]["relative"]


class Reading(object):
    def __init__(self):
        self.report = ut.Report()
        self.model = None
        self.builder = None
        self.block_objects = {}   # block id -> object guid
        self.settings = {}        # the document keys read (key -> value)


def read_document(doc, host="rhino"):
    """Read a document record (see the module docs) into a Reading."""
    r = Reading()
    rep = r.report
    units = _units(doc.get("units"), rep)
    if units is None:
        return r
    length, scale = units
    tol = float(doc.get("tolerance") or 0.001)
    r.settings = ds = ut.read_keys("document", doc.get("user_text"), "document", rep, host=host)
    mb = _builder(doc, ds, length, scale)
    r.builder = mb
    kinds = _classify(doc.get("objects") or [], rep)
    solids = _blocks(kinds["block"], mb, rep, r.block_objects)
    if not kinds["block"]:
        rep.add("no_blocks")
    _interfaces(kinds["interface"], solids, mb, tol, rep)
    live = _loads(kinds["load"], solids, mb, tol, rep)
    live += _legacy_json(ds, mb)
    _analysis(doc.get("user_text"), ds, mb, live, rep)
    _detection(ds, mb, rep)
    _model_checks(mb, rep, bool(kinds["block"]))
    _friction_warning(mb, rep)
    if not rep.errors:
        try:
            r.model = mb.to_dict()
        except ModelError as e:
            rep.add("model_schema", who="model", detail=str(e))
    return r


# ------------------------------------------------------------------------------ document level

def _units(name, rep):
    """(model length unit, factor) of the document's unit system, or None (error reported)."""
    table = dict((k.lower(), v) for k, v in DATA["length_units"].items() if not k.startswith("$"))
    key = str(name or "None").strip()
    if key.lower().startswith("unitsystem."):
        key = key[len("unitsystem."):]
    if key.lower() not in table:
        rep.add("unsupported_units", unit=ut.q(key))
        return None
    length, scale = table[key.lower()]
    if key.lower() == "none":
        rep.add("units_assumed")
    elif scale != 1:
        rep.add("units_converted", unit=ut.q(key), scale=ut.fmt(scale), length=length)
    return length, float(scale)


def _builder(doc, ds, length, scale):
    mb = ModelBuilder(length=length, force=ds.get("rbla.force_unit", "kN"),
                      unit_weight_unit=ds.get("rbla.unit_weight_unit", "kN/m3"),
                      gravity=ds.get("rbla.gravity", "-z"),
                      title=ds.get("rbla.title") or doc.get("name") or "",
                      default_unit_weight=ds.get("rbla.default_unit_weight"),
                      default_friction=ds.get("rbla.default_friction"))
    mb.length_scale = scale
    return mb


def _on_result_layer(layer):
    layer = layer or ""
    rl = DATA["result_layers"]
    return any(layer == x or layer.startswith(x + "::") for x in rl["exact"]) or \
        any(layer.startswith(x) for x in rl["prefix"])


def _who(rec):
    return ut.who_object(rec.get("name"), rec.get("guid"))


def _ignored(rec, user_text, rep):
    """True when rbla.ignore says so, or when it cannot be read (an error, reported)."""
    text = user_text.get("rbla.ignore", "")
    if not text:
        return False
    try:
        return ut.parse_value(ut.KEYS["block"]["rbla.ignore"], text)
    except ut.Bad as e:
        rep.add(e.code, rec.get("guid"), "rbla.ignore", who=_who(rec), value=ut.q(text))
        return True


def _classify(objects, rep):
    """Objects sorted into blocks, interfaces and loads (skipped ones reported)."""
    kinds = {"block": [], "interface": [], "load": []}
    hidden = []
    for rec in objects:
        if _on_result_layer(rec.get("layer")):
            continue
        keys = ut.normalise(rec.get("user_text"))
        if _ignored(rec, keys, rep):
            continue
        if rec.get("hidden"):
            hidden.append(ut.q(rec["name"]) if rec.get("name") else rec.get("guid"))
            continue
        shape = rec.get("shape")
        if "rbla.load" in keys or (keys and shape == "point"):
            kinds["load"].append(rec)
        elif "rbla.interface" in keys:
            kinds["interface"].append(rec)
        elif shape == "solid":
            kinds["block"].append(rec)
        elif keys:
            rep.add("not_a_solid", rec.get("guid"), who=_who(rec), type=rec.get("type", shape))
        elif shape == "polygons":
            rep.add("not_a_block", rec.get("guid"), who=_who(rec), type=rec.get("type", shape))
    if hidden:
        rep.add("hidden_skipped", count=len(hidden),
                names=", ".join(hidden[:10]) + (", ..." if len(hidden) > 10 else ""))
    return kinds


# ------------------------------------------------------------------------------------ blocks

def _block_ids(recs, attrs, rep):
    """Each block object's id: rbla.id, else its name when unique, else its guid."""
    count = {}
    for rec, a in zip(recs, attrs):
        if "rbla.id" not in a and rec.get("name"):
            count[rec["name"]] = count.get(rec["name"], 0) + 1
    warned = set()
    ids = []
    for rec, a in zip(recs, attrs):
        name = rec.get("name")
        if "rbla.id" in a:
            ids.append(a["rbla.id"])
        elif name and count[name] == 1:
            ids.append(name)
        else:
            if name and name not in warned:
                warned.add(name)
                rep.add("duplicate_name", rec.get("guid"), count=count[name], name=ut.q(name))
            ids.append(rec.get("guid"))
    return ids


def _blocks(recs, mb, rep, block_objects):
    """Add the block objects to the builder; returns {id: (vertices, faces, role, box low,
    box high)} in the document's units (for interface and load searches), in document order."""
    attrs = [ut.read_keys("block", rec.get("user_text"), _who(rec), rep, rec.get("guid"))
             for rec in recs]
    ids = _block_ids(recs, attrs, rep)
    solids = {}
    first = {}
    for rec, a, bid in zip(recs, attrs, ids):
        who = _who(rec)
        if bid in first:
            rep.add("duplicate_id", rec.get("guid"), "rbla.id", who=who, what="block",
                    id=ut.q(bid), other=first[bid])
            continue
        first[bid] = who
        if rec.get("error"):
            rep.add("block_geometry", rec.get("guid"), who=who, detail=rec["error"])
            continue
        name = rec.get("name")
        label = a.get("rbla.label") or (name if name and name != bid else None) or \
            rec.get("layer") or None
        role = a.get("rbla.role", "free")
        try:
            mb.add_block(bid, rec["vertices"], rec["faces"], role=role,
                         unit_weight=a.get("rbla.unit_weight"), label=label,
                         centroid=rec.get("centroid"), volume=rec.get("volume"),
                         friction=a.get("rbla.friction"))
        except ModelError as e:
            rep.add("block_geometry", rec.get("guid"), who=who, detail=str(e))
            continue
        lo, hi = geo.bounding_box(rec["vertices"])
        solids[bid] = (rec["vertices"], rec["faces"], role, lo, hi)
        block_objects[bid] = rec.get("guid")
    return solids


# -------------------------------------------------------------------------------- interfaces

def _found_text(ids):
    if not ids:
        return "no block"
    return "%d blocks: %s" % (len(ids), ", ".join(ut.q(b) for b in ids[:5])) + \
        (", ..." if len(ids) > 5 else "")


def _in_box(p, lo, hi, margin):
    """p within margin of the box (a cheap test before the exact ones)."""
    return all(lo[c] - margin <= p[c] <= hi[c] + margin for c in range(3))


def _interface_pair(rec, a, polys, solids, tol, rep):
    """The two block ids of an interface object, or None (error reported)."""
    who = _who(rec)
    if "rbla.blocks" in a:
        missing = [b for b in a["rbla.blocks"] if b not in solids]
        for b in missing:
            rep.add("unknown_block", rec.get("guid"), "rbla.blocks", who=who, id=ut.q(b))
        return None if missing else list(a["rbla.blocks"])
    near = polygons.plane_tolerance(polys, SEARCH_FACTOR * tol, MERGE_RELATIVE)
    corners = [p for poly in polys for p in poly]
    found = [bid for bid, (v, f, _, lo, hi) in solids.items()
             if all(_in_box(p, lo, hi, near) for p in corners) and
             all(polygons.surface_distance(p, v, f) <= near for p in corners)]
    if len(found) != 2:
        rep.add("interface_blocks", rec.get("guid"), who=who, found=_found_text(found))
        return None
    return found


def _interface_label(value, name):
    """The value of rbla.interface, or the object name when the value says only 'yes'."""
    if not value or value.strip().lower() in ut.TRUE:
        return name or None
    return value


def _interface_items(recs, solids, tol, rep):
    items = []
    for rec in recs:
        who = _who(rec)
        a = ut.read_keys("interface", rec.get("user_text"), who, rep, rec.get("guid"))
        if rec.get("shape") != "polygons" or rec.get("error"):
            detail = rec.get("error") or "got %s" % (
                "a closed solid" if rec.get("shape") == "solid" else rec.get("type", "?"))
            rep.add("interface_geometry", rec.get("guid"), who=who, detail=detail)
            continue
        polys = rec["polygons"]
        pair = _interface_pair(rec, a, polys, solids, tol, rep)
        if pair is None or "rbla.interface" not in a:
            continue
        label = _interface_label(a["rbla.interface"], rec.get("name"))
        items.append({"rec": rec, "who": who, "pair": pair, "label": label,
                      "friction": a.get("rbla.friction"), "id": a.get("rbla.id"),
                      "polygons": polys})
    return items


def _interfaces(recs, solids, mb, tol, rep):
    """Interface objects -> interfaces: coplanar touching pieces of one object, or of objects
    with the same blocks, label and friction (and no id), become one."""
    buckets = []
    index = {}
    for n, it in enumerate(_interface_items(recs, solids, tol, rep)):
        key = (tuple(sorted(it["pair"])), it["label"], it["friction"],
               n if it["id"] is not None else None)
        if key not in index:
            index[key] = len(buckets)
            buckets.append([])
        buckets[index[key]].append(it)
    ids = {}
    for bucket in buckets:
        pieces, owner = [], []
        for it in bucket:
            pieces.extend(it["polygons"])
            owner.extend([it] * len(it["polygons"]))
        groups = polygons.merge_coplanar(pieces, tol, MERGE_RELATIVE)
        head = bucket[0]
        if not groups:
            rep.add("interface_geometry", head["rec"].get("guid"), who=head["who"],
                    detail="its pieces have no area")
            continue
        if head["id"] is not None:
            if len(groups) > 1:
                rep.add("interface_split", head["rec"].get("guid"), "rbla.id", who=head["who"],
                        count=len(groups))
                continue
            if head["id"] in ids:
                rep.add("duplicate_id", head["rec"].get("guid"), "rbla.id", who=head["who"],
                        what="interface", id=ut.q(head["id"]), other=ids[head["id"]])
                continue
            ids[head["id"]] = head["who"]
        for g in groups:
            it = owner[g["pieces"][0]]
            if g["hull"]:
                rep.add("interface_hull", it["rec"].get("guid"), who=it["who"])
            try:
                mb.add_interface(it["pair"], g["polygon"], id=it["id"], label=it["label"],
                                 friction=it["friction"])
            except ModelError as e:
                rep.add("interface_geometry", it["rec"].get("guid"), who=it["who"],
                        detail=str(e))


# ------------------------------------------------------------------------------------- loads

def _load_block(rec, a, point, solids, tol, rep):
    who = _who(rec)
    if "rbla.block" in a:
        bid = a["rbla.block"]
        if bid not in solids:
            rep.add("unknown_block", rec.get("guid"), "rbla.block", who=who, id=ut.q(bid))
            return None
    else:
        found = [b for b, (v, f, _, lo, hi) in solids.items()
                 if _in_box(point, lo, hi, tol) and polygons.contains(point, v, f, tol)]
        if len(found) != 1:
            rep.add("load_block", rec.get("guid"), who=who, found=_found_text(found))
            return None
        bid = found[0]
    if solids[bid][2] != "free":
        rep.add("load_on_support", rec.get("guid"), who=who, id=ut.q(bid))
        return None
    return bid


def _loads(recs, solids, mb, tol, rep):
    """Load points -> loads; returns the number of live loads (also those with errors)."""
    live = 0
    for rec in recs:
        who = _who(rec)
        a = ut.read_keys("load", rec.get("user_text"), who, rep, rec.get("guid"))
        if rec.get("shape") != "point":
            rep.add("load_not_point", rec.get("guid"), who=who,
                    type=rec.get("type", rec.get("shape")))
            continue
        if "rbla.load" not in a:
            if "rbla.load" not in ut.normalise(rec.get("user_text")):
                rep.add("load_no_kind", rec.get("guid"), who=who)
            continue
        live += a["rbla.load"] == "live"
        if "rbla.force" not in a and "rbla.moment" not in a:
            rep.add("load_no_force", rec.get("guid"), who=who)
            continue
        bid = _load_block(rec, a, rec["point"], solids, tol, rep)
        if bid is None:
            continue
        add = mb.add_live_load if a["rbla.load"] == "live" else mb.add_dead_load
        add(bid, a.get("rbla.force", [0.0, 0.0, 0.0]), rec["point"], a.get("rbla.moment"))
    return live


def _legacy_json(ds, mb):
    """rbla.loads / rbla.interfaces (model JSON, in the model's units) added as they are."""
    loads = ds.get("rbla.loads") or {}
    mb.dead_loads.extend(loads.get("dead", []) if isinstance(loads.get("dead"), list) else [])
    live = loads.get("live", []) if isinstance(loads.get("live"), list) else []
    mb.live_loads.extend(live)
    mb.interfaces.extend(ds.get("rbla.interfaces") or [])
    return len(live)


# ---------------------------------------------------------------------------------- analysis

def _excluded(ds, name, rep):
    """A JSON-valued key given with the keys it replaces: conflict errors; True if any."""
    bad = [k for k in ut.KEYS["document"][name]["json_excludes"] if k in ds]
    for k in bad:
        rep.add("conflict", None, name, who="document", other=k)
    return bool(bad)


def _seismic_direction(user_text, ds, gravity, rep):
    axis = "xyz".index(gravity[1])
    d = ds.get("rbla.seismic_direction")
    if d is None:
        d = [0.0, 1.0, 0.0] if axis == 0 else \
            [float(x) for x in ut.KEYS["document"]["rbla.seismic_direction"]["default"]]
    if abs(d[axis]) > 1e-9 * geo.norm(d):
        text = ut.normalise(user_text).get("rbla.seismic_direction", "")
        rep.add("not_horizontal", None, "rbla.seismic_direction", who="document",
                gravity=gravity, value=ut.q(text))
        return None
    return d


def _analysis(user_text, ds, mb, live, rep):
    an = ds.get("rbla.analysis")
    if isinstance(an, dict):
        if not _excluded(ds, "rbla.analysis", rep):
            mb.analysis = dict(an)
        kind = "settlement" if an.get("type") == "settlement" else an.get("type",
                                                                            "load_multiplier")
        if live and kind == "settlement":
            rep.add("live_loads_not_used", count=live, analysis=kind)
    else:
        kind = an or ("live" if live else "seismic")
        if kind == "seismic":
            d = _seismic_direction(user_text, ds, mb.gravity, rep)
            if d is not None:
                mb.set_seismic(d)
        elif kind == "live":
            mb.set_load_multiplier()
            if not live:
                rep.add("no_live_loads")
        else:
            mb.set_settlement(direction=ds.get("rbla.settlement_direction"))
        if live and kind != "live":
            rep.add("live_loads_not_used", count=live, analysis=kind)
        mb.set_analysis(friction_model=ds.get("rbla.friction_model"), cone=ds.get("rbla.cone"),
                        pyramid_faces=ds.get("rbla.pyramid_faces"),
                        formulation=ds.get("rbla.formulation"),
                        time_limit=ds.get("rbla.time_limit"))
    roles = [b["role"] for b in mb.blocks]
    if kind == "settlement" and "moving_support" not in roles:
        rep.add("no_moving_support")
    held = [b["id"] for b in mb.blocks if b["role"] == "moving_support"]
    if held and kind != "settlement":
        rep.add("moving_support_held", count=len(held), analysis=kind,
                ids=", ".join(ut.q(b) for b in held[:5]) + (", ..." if len(held) > 5 else ""))


def _detection(ds, mb, rep):
    det = ds.get("rbla.detection")
    if isinstance(det, dict):
        if not _excluded(ds, "rbla.detection", rep):
            mb.detection = dict(det)
        return
    mb.set_detection(mode=det, distance_tolerance=ds.get("rbla.distance_tolerance"),
                     angle_tolerance=ds.get("rbla.angle_tolerance"))


def _model_checks(mb, rep, any_block_object):
    """No support, no free block: only asked when nothing else is wrong (a block whose
    rbla.role could not be read would otherwise also count as 'no support')."""
    if not any_block_object or rep.errors:
        return
    roles = [b["role"] for b in mb.blocks]
    if mb.blocks and "fixed" not in roles and "moving_support" not in roles:
        rep.add("no_support")
    if mb.blocks and "free" not in roles:
        rep.add("no_free_block")


def _friction_warning(mb, rep):
    mu, base = mb.detected_friction()
    frictions = mb._block_friction
    if not frictions or not mb.detects():
        return
    why = ("the smallest block value, below rbla.default_friction = %s" % ut.fmt(base)
           if mu < base else "rbla.default_friction; no block value is smaller")
    rep.add("block_friction", count=len(frictions), mu=ut.fmt(mu), why=why,
            values=", ".join(ut.fmt(v) for v in sorted(set(frictions.values()))))
