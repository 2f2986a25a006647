"""Build and check rbla model JSON (schema/model.schema.json 1.x) from plain block geometry.

Host-independent (standard library only, Python 3.9+): the Rhino/Grasshopper adapter gives it
vertex lists and face index lists it read from Breps or meshes, plus each object's attributes.

    from rbla_cad.model import ModelBuilder
    mb = ModelBuilder(length="m", force="kN")
    mb.add_block("base", base_vertices, base_faces, role="fixed")
    mb.add_block("B1", vertices, faces, unit_weight=18.0, label="Layer::Wall")
    mb.set_seismic([1, 0, 0])
    mb.write("model.json")

Checks. ``add_block`` checks the block at once and raises :class:`ModelError` naming it (id
empty or already used, role unknown, too few vertices or faces, a face index out of range, a
face with fewer than 3 distinct vertices or zero area, faces that do not close the surface,
faces used twice in the same direction along an edge (inconsistent orientation), and a volume by
the divergence theorem that is not positive: inverted (inward faces) or flat). Duplicated
vertices and T-junctions, as mesh exports make them, are accepted, as the solver accepts them.
``check()`` (called by ``to_dict()`` and ``write()``) checks what involves several parts: at
least one support and one free block, interfaces and loads referring to known blocks, a
settlement analysis having a moving support (moving supports in a load-multiplier analysis are
held fixed, as the solver does, with a warning in ``builder.warnings``). Finally ``to_dict()``
validates the document against the bundled copy of ``schema/model.schema.json`` with the
small draft-07 validator in :mod:`rbla_cad.jsonschema_lite`; the solver's own ``rbla validate`` (``Runner.validate``) runs
the same schema plus its geometric checks and is the final word.

Interfaces. ``add_interface`` gives a user-labelled contact (its polygon and the two block
ids). When interfaces are given the builder writes ``detection.mode = "merge"`` unless told
otherwise, so the solver still detects the contacts the user did not label.

Friction. The schema has friction on interfaces and a model default only. ``add_block(...,
friction=mu)`` is accepted for CAD convenience: a given interface without its own friction takes
the smaller of its two blocks' values; the interfaces the solver detects share one friction,
``defaults.friction``, which is then the smallest of the model default and every block value
(``detected_friction``; a warning in ``builder.warnings`` says so).
"""

import json
import math
import os

from . import geometry as geo
from . import safe_files
from . import usertext

SCHEMA_VERSION = "1.0.0"

LENGTH_UNITS = ("mm", "cm", "m")
FORCE_UNITS = ("N", "kN", "MN")
UNIT_WEIGHT_UNITS = ("kN/m3", "N/m3", "N/mm3", "kN/mm3", "N/cm3", "kN/cm3")
ROLES = ("free", "fixed", "moving_support")
GRAVITY_AXES = ("-z", "+z", "-y", "+y", "-x", "+x")
FRICTION_MODELS = ("associative", "non_associative")
CONES = ("exact", "pyramid_inscribed", "pyramid_circumscribed")
FORMULATIONS = ("auto", "3d", "planar")
DETECTION_MODES = ("auto", "off", "merge")
DEFAULT_FRICTION = usertext.KEYS["document"]["rbla.default_friction"]["default"]

# Host length-unit names -> the Rhino UnitSystem name whose model unit and factor the CAD
# attribute convention gives (data/cad_attributes.json, "length_units": the one table of them).
_HOST_LENGTH_NAMES = {
    "mm": "Millimeters", "millimeter": "Millimeters", "millimetre": "Millimeters",
    "millimetres": "Millimeters",
    "cm": "Centimeters", "centimeter": "Centimeters", "centimetre": "Centimeters",
    "centimetres": "Centimeters",
    "m": "Meters", "meter": "Meters", "metre": "Meters", "metres": "Meters",
    "dm": "Decimeters", "decimeter": "Decimeters",
    "km": "Kilometers", "kilometer": "Kilometers",
    "um": "Microns", "micron": "Microns", "micrometer": "Microns",
    "in": "Inches", "inch": "Inches",
    "ft": "Feet", "foot": "Feet",
    "yd": "Yards", "yard": "Yards",
}
_LENGTH_UNITS = dict((k.lower(), (v[0], float(v[1])))
                     for k, v in usertext.DATA["length_units"].items()
                     if not k.startswith("$") and k != "None")

_FORCE_ALIASES = {"n": "N", "newton": "N", "newtons": "N", "kn": "kN", "kilonewton": "kN",
                  "kilonewtons": "kN", "mn": "MN", "meganewton": "MN", "meganewtons": "MN"}


class ModelError(ValueError):
    """A model that rbla would reject. ``issues`` is a list of (block_id or None, JSON pointer,
    message); ``block_id`` and ``pointer`` are those of the first issue."""

    def __init__(self, message, block_id=None, pointer="", issues=None):
        self.issues = list(issues) if issues else [(block_id, pointer, message)]
        self.block_id = self.issues[0][0]
        self.pointer = self.issues[0][1]
        if len(self.issues) > 1:
            lines = [message] + ["  %s%s" % ("" if p is None else (p + ": ") if p else "", m)
                                 for (_, p, m) in self.issues]
            message = "\n".join(lines)
        ValueError.__init__(self, message)


def host_length_unit(name):
    """Map a host unit name ("Millimeters", "m", "Inches", ...) to (schema unit, scale).

    ``scale`` multiplies host coordinates to get schema coordinates (1 for mm, cm and m; inches
    and feet are written in mm, kilometres in m; the table is the CAD attribute convention's).
    Raises ModelError for unknown or unitless systems (Rhino "None", "Parsecs", ...)."""
    key = str(name).strip().lower()
    if key.startswith("unitsystem."):
        key = key[len("unitsystem."):]
    key = _HOST_LENGTH_NAMES.get(key, _HOST_LENGTH_NAMES.get(key.rstrip("s"), key)).lower()
    if key not in _LENGTH_UNITS:
        raise ModelError("unsupported length unit %r: use millimetres, centimetres or metres "
                         "(microns, decimetres, kilometres, inches, feet and yards are "
                         "converted)" % (name,), pointer="/units/length")
    return _LENGTH_UNITS[key]


def force_unit(name):
    """Normalise a force unit name ("kN", "newtons", ...) to the schema's N / kN / MN."""
    key = str(name).strip()
    if key in FORCE_UNITS:
        return key
    low = key.lower()
    if low in _FORCE_ALIASES:
        return _FORCE_ALIASES[low]
    raise ModelError("unsupported force unit %r: use N, kN or MN" % (name,), pointer="/units/force")


def _vec3(value, what, block_id=None, pointer=""):
    try:
        v = [float(value[0]), float(value[1]), float(value[2])]
        if len(value) != 3:
            raise ValueError
    except (TypeError, ValueError, IndexError):
        raise ModelError("%s must be three numbers, got %r" % (what, value), block_id, pointer)
    for c in v:
        if math.isnan(c) or math.isinf(c) or abs(c) > 1e15:
            raise ModelError("%s has a non-finite or huge component: %r" % (what, value),
                             block_id, pointer)
    return v


def _number(value, what, pointer, minimum=None, exclusive_minimum=None, maximum=None):
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise ModelError("%s must be a number, got %r" % (what, value), pointer=pointer)
    if math.isnan(x) or math.isinf(x):
        raise ModelError("%s must be finite, got %r" % (what, value), pointer=pointer)
    if minimum is not None and x < minimum:
        raise ModelError("%s must be >= %g, got %g" % (what, minimum, x), pointer=pointer)
    if exclusive_minimum is not None and x <= exclusive_minimum:
        raise ModelError("%s must be > %g, got %g" % (what, exclusive_minimum, x), pointer=pointer)
    if maximum is not None and x > maximum:
        raise ModelError("%s must be <= %g, got %g" % (what, maximum, x), pointer=pointer)
    return x


def _choice(value, allowed, what, pointer):
    if value not in allowed:
        raise ModelError("%s must be one of %s, got %r" % (what, ", ".join(allowed), value),
                         pointer=pointer)
    return value


def check_block_geometry(block_id, vertices, faces, pointer=""):
    """Check one block's polyhedron; return (volume, centroid). Raises ModelError naming it.

    Closed: the face area vectors sum to zero (robust to T-junctions and duplicated vertices).
    Consistently oriented: no edge (after merging coincident vertices) is used twice in the same
    direction. Outward: the volume by the divergence theorem is positive.
    """
    label = "block %r" % (block_id,)
    if len(vertices) < 4:
        raise ModelError("%s has %d vertices; a polyhedron needs at least 4"
                         % (label, len(vertices)), block_id, pointer + "/vertices")
    if len(faces) < 4:
        raise ModelError("%s has %d faces; a closed polyhedron needs at least 4"
                         % (label, len(faces)), block_id, pointer + "/faces")
    nv = len(vertices)
    lo, hi = geo.bounding_box(vertices)
    size = geo.norm(geo.sub(hi, lo))
    if size == 0.0:
        raise ModelError("%s is a single point" % label, block_id, pointer + "/vertices")
    for k, f in enumerate(faces):
        fp = "%s/faces/%d" % (pointer, k)
        if len(f) < 3:
            raise ModelError("%s: face %d has %d vertices (at least 3)" % (label, k, len(f)),
                             block_id, fp)
        for j, i in enumerate(f):
            if isinstance(i, bool) or not isinstance(i, int) or i < 0 or i >= nv:
                raise ModelError("%s: face %d refers to vertex %r, but the block has %d "
                                 "vertices (0-based indices 0..%d)" % (label, k, i, nv, nv - 1),
                                 block_id, "%s/%d" % (fp, j))
        if len(set(f)) < 3:
            raise ModelError("%s: face %d has fewer than 3 distinct vertices" % (label, k),
                             block_id, fp)
    # merge coincident vertices (mesh exports duplicate them) for the edge checks
    tol = 1e-9 * size
    key_of = {}
    canon = []
    for p in vertices:
        key = (round(p[0] / tol), round(p[1] / tol), round(p[2] / tol)) if tol > 0 else tuple(p)
        canon.append(key_of.setdefault(key, len(key_of)))
    area_sum = [0.0, 0.0, 0.0]
    area_abs = 0.0
    for k, f in enumerate(faces):
        a = geo.newell_normal([vertices[i] for i in f])
        la = geo.norm(a)
        if la <= 1e-14 * size * size:
            raise ModelError("%s: face %d has zero area (degenerate face)" % (label, k),
                             block_id, "%s/faces/%d" % (pointer, k))
        area_abs += la
        for i in range(3):
            area_sum[i] += a[i]
    if geo.norm(area_sum) > 1e-6 * area_abs:
        raise ModelError("%s is not closed: its faces leave a hole (open mesh) or some faces are "
                         "flipped (the face area vectors sum to %.3g of the total area)"
                         % (label, geo.norm(area_sum) / area_abs), block_id, pointer + "/faces")
    used = {}
    for k, f in enumerate(faces):
        m = len(f)
        for j in range(m):
            e = (canon[f[j]], canon[f[(j + 1) % m]])
            if e[0] == e[1]:
                continue
            if e in used:
                raise ModelError("%s has inconsistently oriented faces: faces %d and %d run along "
                                 "the same edge (vertices %d -> %d) in the same direction; faces "
                                 "must be counter-clockwise seen from outside"
                                 % (label, used[e], k, f[j], f[(j + 1) % m]),
                                 block_id, "%s/faces/%d" % (pointer, k))
            used[e] = k
    vol, cen = geo.volume_centroid(vertices, faces)
    if abs(vol) <= 1e-9 * size ** 3:
        raise ModelError("%s has zero volume (flat or degenerate)" % label, block_id,
                         pointer + "/faces")
    if vol < 0:
        raise ModelError("%s is inverted: its faces point inward (volume %.6g from the faces); "
                         "reverse every face" % (label, vol), block_id, pointer + "/faces")
    return vol, cen


class ModelBuilder(object):
    """Collects blocks, interfaces, loads and analysis settings; writes the model JSON.

    length: "mm" | "cm" | "m" (or a host name: see :func:`host_length_unit`; a non-native unit
    such as inches sets ``length_scale`` and every coordinate given is multiplied by it).
    force: "N" | "kN" | "MN". unit_weight_unit: default "kN/m3" whatever the length unit.
    """

    def __init__(self, length="m", force="kN", unit_weight_unit="kN/m3", gravity="-z",
                 title="", default_unit_weight=None, default_friction=None):
        self.length, self.length_scale = host_length_unit(length)
        self.force = force_unit(force)
        self.unit_weight_unit = _choice(unit_weight_unit, UNIT_WEIGHT_UNITS, "unit weight unit",
                                        "/units/unit_weight")
        self.gravity = _choice(gravity, GRAVITY_AXES, "gravity", "/gravity")
        self.title = str(title or "")
        self.default_unit_weight = None
        self.default_friction = None
        if default_unit_weight is not None:
            self.default_unit_weight = _number(default_unit_weight, "default unit weight",
                                               "/defaults/unit_weight", exclusive_minimum=0,
                                               maximum=1e12)
        if default_friction is not None:
            self.default_friction = _number(default_friction, "default friction",
                                            "/defaults/friction", exclusive_minimum=0,
                                            maximum=100)
        self.blocks = []          # block dicts in schema form
        self._block_index = {}    # id -> index
        self._block_friction = {}
        self.interfaces = []
        self.dead_loads = []
        self.live_loads = []
        self.analysis = {}
        self.detection = {}
        self.warnings = []

    # ---------------------------------------------------------------------------------- blocks
    def _p(self, p):
        s = self.length_scale
        v = _vec3(p, "point", None, "")
        return [v[0] * s, v[1] * s, v[2] * s] if s != 1.0 else v

    def add_block(self, id, vertices, faces, role="free", unit_weight=None, label=None,
                  centroid=None, volume=None, friction=None):
        """Add a closed polyhedral block; check it and raise ModelError naming it if bad.

        vertices: [[x, y, z], ...] in the builder's (host) length unit; faces: lists of 0-based
        vertex indices, counter-clockwise seen from outside. unit_weight in
        ``unit_weight_unit`` (None: the model default). centroid/volume: the CAD's values
        (computed from the faces when not given; the solver checks given ones). Returns the
        block dict as it will be written.
        """
        index = len(self.blocks)
        pointer = "/blocks/%d" % index
        if not isinstance(id, str) or not id or len(id) > 200:
            raise ModelError("block %d: id must be a non-empty string of at most 200 characters, "
                             "got %r" % (index, id), None, pointer + "/id")
        if id in self._block_index:
            raise ModelError("block id %r is used twice (blocks %d and %d); ids must be unique"
                             % (id, self._block_index[id], index), id, pointer + "/id")
        if role not in ROLES:
            raise ModelError("block %r: role must be one of %s, got %r"
                             % (id, ", ".join(ROLES), role), id, pointer + "/role")
        try:
            verts = [self._p(v) for v in vertices]
        except ModelError:
            raise ModelError("block %r: vertices must be [x, y, z] number triples" % (id,), id,
                             pointer + "/vertices")
        try:
            fcs = [list(f) for f in faces]
        except TypeError:
            raise ModelError("block %r: faces must be lists of vertex indices" % (id,), id,
                             pointer + "/faces")
        fcs = [[int(i) if isinstance(i, float) and i == int(i) else i for i in f] for f in fcs]
        vol, cen = check_block_geometry(id, verts, fcs, pointer)
        block = {"id": id}
        if label:
            block["label"] = str(label)[:1000]
        block["role"] = role
        block["vertices"] = verts
        block["faces"] = fcs
        if centroid is not None:
            block["centroid"] = self._p(centroid)
        else:
            block["centroid"] = [float(c) for c in cen]
        if volume is not None:
            v = _number(volume, "block %r volume" % (id,), pointer + "/volume",
                        exclusive_minimum=0)
            block["volume"] = v * self.length_scale ** 3
        else:
            block["volume"] = vol
        if unit_weight is not None:
            try:
                block["unit_weight"] = _number(unit_weight, "block %r unit weight" % (id,),
                                               pointer + "/unit_weight", minimum=0, maximum=1e12)
            except ModelError as e:
                raise ModelError(str(e), id, pointer + "/unit_weight")
        if friction is not None:
            try:
                self._block_friction[id] = _number(friction, "block %r friction" % (id,),
                                                   pointer, exclusive_minimum=0, maximum=100)
            except ModelError as e:
                raise ModelError(str(e), id, pointer)
        self._block_index[id] = index
        self.blocks.append(block)
        return block

    def block(self, id):
        return self.blocks[self._block_index[id]]

    # ------------------------------------------------------------------------------ interfaces
    def add_interface(self, blocks, polygon, id=None, label=None, friction=None):
        """Add a contact interface between two blocks (ids), with its planar contact polygon
        (corners in order). The normal points from blocks[0] into blocks[1]. Block ids are
        checked in ``check()`` so interfaces may be added before their blocks."""
        index = len(self.interfaces)
        pointer = "/interfaces/%d" % index
        name = id or label or ("#%d" % index)
        if len(blocks) != 2 or blocks[0] == blocks[1]:
            raise ModelError("interface %s: needs two different block ids, got %r"
                             % (name, blocks), None, pointer + "/blocks")
        pts = [self._p(p) for p in polygon]
        if len(pts) < 3:
            raise ModelError("interface %s: polygon needs at least 3 corners, got %d"
                             % (name, len(pts)), None, pointer + "/polygon")
        a = geo.norm(geo.newell_normal(pts))
        lo, hi = geo.bounding_box(pts)
        d = geo.norm(geo.sub(hi, lo))
        if a <= 1e-12 * d * d or d == 0:
            raise ModelError("interface %s: polygon has zero area" % name, None,
                             pointer + "/polygon")
        itf = {}
        if id is not None:
            if any(i.get("id") == id for i in self.interfaces):
                raise ModelError("interface id %r is used twice" % (id,), None, pointer + "/id")
            itf["id"] = str(id)
        if label:
            itf["label"] = str(label)[:1000]
        itf["blocks"] = [str(blocks[0]), str(blocks[1])]
        itf["polygon"] = pts
        if friction is not None:
            itf["friction"] = _number(friction, "interface %s friction" % name,
                                      pointer + "/friction", exclusive_minimum=0, maximum=100)
        self.interfaces.append(itf)
        return itf

    def set_detection(self, mode=None, relative_tolerance=None, distance_tolerance=None,
                      angle_tolerance=None, min_area_fraction=None):
        if mode is not None:
            self.detection["mode"] = _choice(mode, DETECTION_MODES, "detection mode",
                                             "/detection/mode")
        if relative_tolerance is not None:
            self.detection["relative_tolerance"] = _number(
                relative_tolerance, "relative tolerance", "/detection/relative_tolerance",
                exclusive_minimum=0, maximum=0.1)
        if distance_tolerance is not None:
            self.detection["distance_tolerance"] = _number(
                distance_tolerance, "distance tolerance", "/detection/distance_tolerance",
                exclusive_minimum=0) * self.length_scale
        if angle_tolerance is not None:
            self.detection["angle_tolerance"] = _number(
                angle_tolerance, "angle tolerance", "/detection/angle_tolerance",
                exclusive_minimum=0, maximum=45)
        if min_area_fraction is not None:
            self.detection["min_area_fraction"] = _number(
                min_area_fraction, "min area fraction", "/detection/min_area_fraction",
                minimum=0, maximum=1)

    # ----------------------------------------------------------------------------------- loads
    def _load(self, block, force, point, moment):
        load = {"block": str(block)}
        load["force"] = _vec3(force if force is not None else [0, 0, 0], "load force")
        if point is not None:
            load["point"] = self._p(point)
        if moment is not None:
            m = _vec3(moment, "load moment")
            load["moment"] = [c * self.length_scale for c in m]
        return load

    def add_dead_load(self, block, force=None, point=None, moment=None):
        """Constant load on a free block, in the force unit (point default: its centroid)."""
        self.dead_loads.append(self._load(block, force, point, moment))

    def add_live_load(self, block, force=None, point=None, moment=None):
        """Load scaled by the load multiplier alpha (a load_multiplier analysis)."""
        self.live_loads.append(self._load(block, force, point, moment))
        self.analysis["type"] = "load_multiplier"

    # -------------------------------------------------------------------------------- analysis
    def set_seismic(self, direction=(1.0, 0.0, 0.0)):
        """Load-multiplier analysis with seismic forces alpha x W_i along a horizontal direction."""
        d = _vec3(direction, "seismic direction", None, "/analysis/seismic/direction")
        if geo.norm(d) == 0:
            raise ModelError("seismic direction must not be zero",
                             pointer="/analysis/seismic/direction")
        self.analysis["type"] = "load_multiplier"
        self.analysis["seismic"] = {"direction": d}
        self.analysis.pop("settlement", None)

    def set_load_multiplier(self):
        """Load-multiplier analysis of the live loads (add them with add_live_load)."""
        self.analysis["type"] = "load_multiplier"
        self.analysis.pop("settlement", None)

    def set_settlement(self, moving=None, direction=None):
        """Settlement analysis: the blocks in ``moving`` (ids; optional if their role is already
        moving_support) settle along ``direction`` (default: gravity)."""
        for bid in moving or []:
            if bid not in self._block_index:
                raise ModelError("settlement: unknown block %r" % (bid,), bid,
                                 "/analysis/settlement")
            self.block(bid)["role"] = "moving_support"
        self.analysis["type"] = "settlement"
        self.analysis.pop("seismic", None)
        st = {}
        if direction is not None:
            d = _vec3(direction, "settlement direction", None, "/analysis/settlement/direction")
            if geo.norm(d) == 0:
                raise ModelError("settlement direction must not be zero",
                                 pointer="/analysis/settlement/direction")
            st["direction"] = d
        if st:
            self.analysis["settlement"] = st
        else:
            self.analysis.pop("settlement", None)

    def set_analysis(self, friction_model=None, cone=None, pyramid_faces=None, formulation=None,
                     time_limit=None, relative_gap=None, feasibility=None,
                     non_associative=None):
        """Solver settings (see the schema's ``analysis``); None leaves a setting at its default.
        non_associative: dict with max_iterations, tolerance, damping, trajectories."""
        a = self.analysis
        if friction_model is not None:
            a["friction_model"] = _choice(friction_model, FRICTION_MODELS, "friction model",
                                          "/analysis/friction_model")
        if cone is not None:
            a["cone"] = _choice(cone, CONES, "cone", "/analysis/cone")
        if pyramid_faces is not None:
            n = int(_number(pyramid_faces, "pyramid faces", "/analysis/pyramid_faces",
                            minimum=3, maximum=256))
            a["pyramid_faces"] = n
        if formulation is not None:
            a["formulation"] = _choice(formulation, FORMULATIONS, "formulation",
                                       "/analysis/formulation")
        if time_limit is not None:
            a["time_limit"] = _number(time_limit, "time limit", "/analysis/time_limit",
                                      minimum=0, maximum=1e7)
        tol = {}
        if relative_gap is not None:
            tol["relative_gap"] = _number(relative_gap, "relative gap",
                                          "/analysis/tolerances/relative_gap",
                                          minimum=1e-14, maximum=0.1)
        if feasibility is not None:
            tol["feasibility"] = _number(feasibility, "feasibility",
                                         "/analysis/tolerances/feasibility",
                                         minimum=1e-14, maximum=0.1)
        if tol:
            a.setdefault("tolerances", {}).update(tol)
        if non_associative:
            na = {}
            for key, val in dict(non_associative).items():
                if key == "max_iterations":
                    na[key] = int(_number(val, key, "/analysis/non_associative/" + key,
                                          minimum=1, maximum=1000))
                elif key == "tolerance":
                    na[key] = _number(val, key, "/analysis/non_associative/" + key,
                                      exclusive_minimum=0, maximum=0.5)
                elif key == "damping":
                    na[key] = _number(val, key, "/analysis/non_associative/" + key,
                                      exclusive_minimum=0, maximum=1)
                elif key == "pointwise_retry":
                    if not isinstance(val, bool):
                        raise ModelError("non-associative setting pointwise_retry must be true or false",
                                         pointer="/analysis/non_associative/" + key)
                    na[key] = val
                elif key == "trajectories":
                    na[key] = int(_number(val, key, "/analysis/non_associative/" + key,
                                          minimum=1, maximum=6))
                else:
                    raise ModelError("unknown non-associative setting %r" % (key,),
                                     pointer="/analysis/non_associative")
            a["non_associative"] = na

    # -------------------------------------------------------------------------------- checking
    def problems(self):
        """Model-level issues as a list of (block_id or None, pointer, message)."""
        out = []
        if not self.blocks:
            out.append((None, "/blocks", "the model has no blocks"))
            return out
        roles = [b["role"] for b in self.blocks]
        if "fixed" not in roles and "moving_support" not in roles:
            out.append((None, "/blocks", "no support: give at least one block the role 'fixed' "
                                         "(or 'moving_support' for a settlement analysis)"))
        if "free" not in roles:
            out.append((None, "/blocks", "no free block: every block is a support"))
        settlement = self.analysis.get("type") == "settlement"
        if settlement and "moving_support" not in roles:
            out.append((None, "/analysis/settlement",
                        "settlement analysis without any block of role 'moving_support'"))
        for i, itf in enumerate(self.interfaces):
            for j, bid in enumerate(itf["blocks"]):
                if bid not in self._block_index:
                    out.append((bid, "/interfaces/%d/blocks/%d" % (i, j),
                                "interface %s refers to unknown block %r"
                                % (itf.get("id") or itf.get("label") or i, bid)))
        for kind, loads in (("dead", self.dead_loads), ("live", self.live_loads)):
            for i, load in enumerate(loads):
                bid = load["block"]
                p = "/loads/%s/%d/block" % (kind, i)
                if bid not in self._block_index:
                    out.append((bid, p, "%s load %d refers to unknown block %r" % (kind, i, bid)))
                elif self.block(bid)["role"] != "free":
                    out.append((bid, p, "%s load %d acts on support block %r; loads act on free "
                                        "blocks" % (kind, i, bid)))
        return out

    def check(self):
        """Raise ModelError listing every model-level issue (blocks were checked when added)."""
        issues = self.problems()
        if issues:
            raise ModelError("the model is not valid (%d issue%s)"
                             % (len(issues), "" if len(issues) == 1 else "s")
                             if len(issues) > 1 else issues[0][2], issues=issues)

    # ---------------------------------------------------------------------------------- output
    def detects(self):
        """Whether the solver will detect interfaces (detection mode, given interfaces)."""
        mode = self.detection.get("mode") or ("merge" if self.interfaces else "auto")
        return mode == "merge" or (mode == "auto" and not self.interfaces)

    def detected_friction(self):
        """(mu, base): the friction of the interfaces the solver detects, and the model default.

        The model has one friction for detected interfaces. Blocks given a friction of their own
        (CAD convenience) cannot pass it on to them, so detected interfaces take the smallest of
        the default and every block value: a lower friction never raises the collapse
        multiplier of an associative analysis, so the answer errs on the safe side."""
        base = self.default_friction if self.default_friction is not None else DEFAULT_FRICTION
        if not self._block_friction or not self.detects():
            return base, base
        return min([base] + list(self._block_friction.values())), base

    def _interface_out(self, itf, lowered, base):
        """An interface as written: without a friction of its own it takes the smaller of its
        blocks' values, else the model default as it was before detected_friction lowered it."""
        itf = dict(itf)
        if "friction" not in itf:
            mus = [self._block_friction[b] for b in itf.get("blocks", [])
                   if b in self._block_friction]
            if mus:
                itf["friction"] = min(mus)
            elif lowered:
                itf["friction"] = base
        return itf

    def to_dict(self, check=True, validate_schema=True):
        """The model document (a dict ready for json.dump). Runs ``check()`` and the schema
        validation unless told not to."""
        if check:
            self.check()
        doc = {"schema_version": SCHEMA_VERSION}
        if self.title:
            doc["title"] = self.title[:1000]
        doc["units"] = {"length": self.length, "force": self.force,
                        "unit_weight": self.unit_weight_unit}
        doc["gravity"] = self.gravity
        mu, base = self.detected_friction()
        defaults = {}
        if self.default_unit_weight is not None:
            defaults["unit_weight"] = self.default_unit_weight
        if mu < base or self.default_friction is not None:
            defaults["friction"] = mu
        if defaults:
            doc["defaults"] = defaults
        doc["blocks"] = [dict(b) for b in self.blocks]
        self.warnings = [w for w in self.warnings
                         if not w.startswith("friction:") and not w.startswith("role:")]
        if self.analysis.get("type") != "settlement":
            held = [b["id"] for b in self.blocks if b["role"] == "moving_support"]
            if held:
                self.warnings.append("role: moving supports %s are held fixed: the analysis is "
                                     "not a settlement analysis" % ", ".join(held[:5]))
        if self.interfaces:
            doc["interfaces"] = [self._interface_out(itf, mu < base, base)
                                 for itf in self.interfaces]
        detection = dict(self.detection)
        if self.interfaces and "mode" not in detection:
            detection["mode"] = "merge"
        if detection:
            doc["detection"] = detection
        if self._block_friction and self.detects():
            self.warnings.append(
                "friction: block friction values (%s) apply to the given interfaces touching "
                "those blocks; the interfaces the solver detects all use %s"
                % (", ".join(usertext.fmt(v) for v in sorted(set(self._block_friction.values()))),
                   usertext.fmt(mu)))
        loads = {}
        if self.dead_loads:
            loads["dead"] = [dict(x) for x in self.dead_loads]
        if self.live_loads:
            loads["live"] = [dict(x) for x in self.live_loads]
        if loads:
            doc["loads"] = loads
        if self.analysis:
            doc["analysis"] = json.loads(json.dumps(self.analysis))
        if validate_schema:
            from . import jsonschema_lite
            errors = jsonschema_lite.validate_model(doc)
            if errors:
                issues = [(None, p, m) for (p, m) in errors]
                raise ModelError("the model does not match the schema (%d issue%s)"
                                 % (len(issues), "" if len(issues) == 1 else "s")
                                 if len(issues) > 1 else "%s: %s" % errors[0], issues=issues)
        return doc

    def to_json(self, indent=1, **kw):
        return json.dumps(self.to_dict(**kw), indent=indent)

    def write(self, path, indent=1, **kw):
        """Check, then write the model JSON by the solver's rules (:mod:`rbla_cad.safe_files`:
        a file is replaced atomically, keeping its permissions, a link's target written, a pipe
        written into, "-" standard output). Returns the absolute path ("-" as given); raises
        ModelError before anything is written, or safe_files.FileError (an OSError) naming the
        path."""
        text = self.to_json(indent=indent, **kw) + "\n"
        safe_files.write_output(path, text)
        return path if path == "-" else os.path.abspath(path)


def box(x0, x1, y0, y1, z0, z1):
    """Vertices and outward faces of an axis-aligned box (handy for tests and scripts)."""
    v = [[x0, y0, z0], [x1, y0, z0], [x1, y1, z0], [x0, y1, z0],
         [x0, y0, z1], [x1, y0, z1], [x1, y1, z1], [x0, y1, z1]]
    f = [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]]
    return v, f


def block_centroids(model):
    """{block id: centroid} of a model dict, always from the faces (divergence theorem): the
    solver uses the geometric centroid, and the result's block motions refer to it."""
    out = {}
    for b in model.get("blocks", []):
        out[b["id"]] = geo.volume_centroid(b["vertices"], b["faces"])[1]
    return out


def load_model(path):
    with open(path, "r", encoding="utf-8") as f:
        return json.load(f)
