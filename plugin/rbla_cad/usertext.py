"""CAD attribute conventions (Rhino "User Text" key/value strings), parsed host-independently.

The Rhino adapter reads each object's User Text into a plain dict and calls these functions, so
the rules (and their error messages) are tested here without Rhino. Keys (case-insensitive):

Block objects (closed Breps, closed meshes, extrusions):
  rbla.role         free | fixed | moving_support            (default free)
  rbla.unit_weight  number, in the model's unit-weight unit (kN/m3 unless the document says
                    otherwise)                                (default: document default)
  rbla.friction     number > 0: friction of the user-labelled interfaces touching the block
  rbla.label        text kept in the model and results     (default: object name, else layer)
  rbla.id           explicit block id                       (default: object name when it is
                    set and unique, else the object's id (GUID))
  rbla.ignore       true: leave the object out

Interface surfaces (open planar surfaces or closed planar curves the user places on a contact):
  rbla.interface    marks the object as an interface; the value is its label (empty value:
                    the object name)
  rbla.blocks       "idA, idB": the two blocks (default: the two blocks nearest to it)
  rbla.friction     number > 0: friction of this interface

Load points (point objects):
  rbla.load         live | dead
  rbla.force        "fx, fy, fz" in the model's force unit
  rbla.moment       "mx, my, mz" (optional)
  rbla.block        block id the load acts on (default: the block containing the point)

Document User Text (analysis settings; all optional):
  rbla.analysis             seismic | live | settlement              (default seismic)
  rbla.seismic_direction    "x, y, z" horizontal                     (default 1, 0, 0)
  rbla.settlement_direction "x, y, z"                                (default gravity)
  rbla.gravity              -z | +z | -y | +y | -x | +x              (default -z)
  rbla.force_unit           N | kN | MN                              (default kN)
  rbla.unit_weight_unit     kN/m3 | N/m3 | N/mm3 | kN/mm3 | N/cm3 | kN/cm3 (default kN/m3)
  rbla.default_unit_weight  number                                   (default 18)
  rbla.default_friction     number                                   (default 0.6)
  rbla.friction_model       associative | non_associative
  rbla.cone                 exact | pyramid_inscribed | pyramid_circumscribed
  rbla.pyramid_faces        integer 3..256
  rbla.formulation          auto | 3d | planar
  rbla.time_limit           seconds (0 = none)
  rbla.exe                  path of the rbla executable (else $RBLA_EXE, else PATH)
"""

from .model import (CONES, FORMULATIONS, FRICTION_MODELS, GRAVITY_AXES, ROLES,
                    UNIT_WEIGHT_UNITS, ModelError, force_unit)

PREFIX = "rbla."
BLOCK_KEYS = ("rbla.role", "rbla.unit_weight", "rbla.friction", "rbla.label", "rbla.id",
              "rbla.ignore")
INTERFACE_KEYS = ("rbla.interface", "rbla.blocks", "rbla.friction")
LOAD_KEYS = ("rbla.load", "rbla.force", "rbla.moment", "rbla.block")
DOCUMENT_KEYS = ("rbla.analysis", "rbla.seismic_direction", "rbla.settlement_direction",
                 "rbla.gravity", "rbla.force_unit", "rbla.unit_weight_unit",
                 "rbla.default_unit_weight", "rbla.default_friction", "rbla.friction_model",
                 "rbla.cone", "rbla.pyramid_faces", "rbla.formulation", "rbla.time_limit",
                 "rbla.exe")
ANALYSES = ("seismic", "live", "settlement")
_TRUE = ("1", "true", "yes", "on", "y")


def normalise(user_text):
    """Lower-case the rbla.* keys, strip values; other keys are dropped."""
    out = {}
    for k, v in (user_text or {}).items():
        key = str(k).strip().lower()
        if key.startswith(PREFIX):
            out[key] = "" if v is None else str(v).strip()
    return out


def _num(text, key, who, positive=False, minimum=None):
    try:
        x = float(text.replace(",", ".") if text.count(",") == 1 and "." not in text else text)
    except ValueError:
        raise ModelError("%s: %s must be a number, got %r" % (who, key, text), pointer=key)
    if x != x or x in (float("inf"), float("-inf")):
        raise ModelError("%s: %s must be finite, got %r" % (who, key, text), pointer=key)
    if positive and x <= 0:
        raise ModelError("%s: %s must be > 0, got %r" % (who, key, text), pointer=key)
    if minimum is not None and x < minimum:
        raise ModelError("%s: %s must be >= %g, got %r" % (who, key, minimum, text), pointer=key)
    return x


def parse_vector(text, key="vector", who="document"):
    """'1, 0, 0' or '1 0 0' or '[1,0,0]' -> [1.0, 0.0, 0.0]."""
    t = str(text).strip().strip("[]()")
    parts = [p for p in t.replace(";", ",").replace(",", " ").split() if p]
    if len(parts) != 3:
        raise ModelError("%s: %s must be three numbers 'x, y, z', got %r" % (who, key, text),
                         pointer=key)
    return [_num(p, key, who) for p in parts]


def _choice(text, allowed, key, who):
    v = text.strip()
    low = dict((a.lower(), a) for a in allowed)
    if v.lower() not in low:
        raise ModelError("%s: %s must be one of %s, got %r" % (who, key, ", ".join(allowed), text),
                         pointer=key)
    return low[v.lower()]


def block_attributes(user_text, name=None, layer=None, who=None):
    """Block attributes from an object's User Text: dict with role, unit_weight, friction,
    label, id (None when not given), ignore. ``who`` names the object in errors."""
    ut = normalise(user_text)
    who = who or ("object %r" % name if name else "object")
    role = ut.get("rbla.role", "") or "free"
    role = role.lower().replace("-", "_").replace(" ", "_")
    if role in ("support", "fixed_support"):
        role = "fixed"
    if role in ("moving", "settling"):
        role = "moving_support"
    if role not in ROLES:
        raise ModelError("%s: rbla.role must be one of %s, got %r"
                         % (who, ", ".join(ROLES), ut.get("rbla.role")), pointer="rbla.role")
    out = {"role": role, "unit_weight": None, "friction": None, "label": None, "id": None,
           "ignore": ut.get("rbla.ignore", "").lower() in _TRUE}
    if ut.get("rbla.unit_weight"):
        out["unit_weight"] = _num(ut["rbla.unit_weight"], "rbla.unit_weight", who, minimum=0)
    if ut.get("rbla.friction"):
        out["friction"] = _num(ut["rbla.friction"], "rbla.friction", who, positive=True)
    out["label"] = ut.get("rbla.label") or name or layer or None
    if ut.get("rbla.id"):
        out["id"] = ut["rbla.id"]
    return out


def is_interface(user_text):
    return "rbla.interface" in normalise(user_text)


def interface_attributes(user_text, name=None, who=None):
    """Interface attributes: dict with label, blocks ([a, b] or None), friction."""
    ut = normalise(user_text)
    who = who or ("interface %r" % name if name else "interface")
    out = {"label": ut.get("rbla.interface") or name or None, "blocks": None, "friction": None}
    if ut.get("rbla.blocks"):
        ids = [s.strip() for s in ut["rbla.blocks"].replace(";", ",").split(",") if s.strip()]
        if len(ids) != 2 or ids[0] == ids[1]:
            raise ModelError("%s: rbla.blocks must name two different blocks 'idA, idB', got %r"
                             % (who, ut["rbla.blocks"]), pointer="rbla.blocks")
        out["blocks"] = ids
    if ut.get("rbla.friction"):
        out["friction"] = _num(ut["rbla.friction"], "rbla.friction", who, positive=True)
    return out


def is_load(user_text):
    return "rbla.load" in normalise(user_text)


def load_attributes(user_text, who="load point"):
    """Load attributes: dict with kind (live/dead), force, moment (or None), block (or None)."""
    ut = normalise(user_text)
    kind = _choice(ut.get("rbla.load", ""), ("live", "dead"), "rbla.load", who)
    if not ut.get("rbla.force") and not ut.get("rbla.moment"):
        raise ModelError("%s: give rbla.force 'fx, fy, fz' (and/or rbla.moment)" % who,
                         pointer="rbla.force")
    return {"kind": kind,
            "force": parse_vector(ut["rbla.force"], "rbla.force", who)
            if ut.get("rbla.force") else [0.0, 0.0, 0.0],
            "moment": parse_vector(ut["rbla.moment"], "rbla.moment", who)
            if ut.get("rbla.moment") else None,
            "block": ut.get("rbla.block") or None}


def document_settings(user_text):
    """Analysis settings from the document's User Text (see the module docs); defaults filled."""
    ut = normalise(user_text)
    who = "document"
    s = {
        "analysis": _choice(ut.get("rbla.analysis") or "seismic", ANALYSES, "rbla.analysis", who),
        "seismic_direction": parse_vector(ut.get("rbla.seismic_direction") or "1,0,0",
                                          "rbla.seismic_direction", who),
        "settlement_direction": parse_vector(ut["rbla.settlement_direction"],
                                             "rbla.settlement_direction", who)
        if ut.get("rbla.settlement_direction") else None,
        "gravity": _choice(ut.get("rbla.gravity") or "-z", GRAVITY_AXES, "rbla.gravity", who),
        "force_unit": force_unit(ut.get("rbla.force_unit") or "kN"),
        "unit_weight_unit": _choice(ut.get("rbla.unit_weight_unit") or "kN/m3",
                                    UNIT_WEIGHT_UNITS, "rbla.unit_weight_unit", who),
        "default_unit_weight": _num(ut["rbla.default_unit_weight"], "rbla.default_unit_weight",
                                    who, positive=True)
        if ut.get("rbla.default_unit_weight") else None,
        "default_friction": _num(ut["rbla.default_friction"], "rbla.default_friction", who,
                                 positive=True)
        if ut.get("rbla.default_friction") else None,
        "friction_model": _choice(ut["rbla.friction_model"], FRICTION_MODELS,
                                  "rbla.friction_model", who)
        if ut.get("rbla.friction_model") else None,
        "cone": _choice(ut["rbla.cone"], CONES, "rbla.cone", who) if ut.get("rbla.cone") else None,
        "pyramid_faces": int(_num(ut["rbla.pyramid_faces"], "rbla.pyramid_faces", who,
                                  minimum=3)) if ut.get("rbla.pyramid_faces") else None,
        "formulation": _choice(ut["rbla.formulation"], FORMULATIONS, "rbla.formulation", who)
        if ut.get("rbla.formulation") else None,
        "time_limit": _num(ut["rbla.time_limit"], "rbla.time_limit", who, minimum=0)
        if ut.get("rbla.time_limit") else None,
        "exe": ut.get("rbla.exe") or None,
    }
    return s


def apply_settings(builder, settings):
    """Set the analysis of a ModelBuilder from ``document_settings`` (blocks already added:
    a settlement analysis uses the blocks whose role is moving_support)."""
    a = settings["analysis"]
    if a == "seismic":
        builder.set_seismic(settings["seismic_direction"])
    elif a == "live":
        builder.set_load_multiplier()
    else:
        builder.set_settlement(direction=settings["settlement_direction"])
    builder.set_analysis(friction_model=settings["friction_model"], cone=settings["cone"],
                         pyramid_faces=settings["pyramid_faces"],
                         formulation=settings["formulation"], time_limit=settings["time_limit"])
