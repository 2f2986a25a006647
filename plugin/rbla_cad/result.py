"""Read an rbla result (schema/result.schema.json 1.1.0) and turn it into things to draw.

    from rbla_cad.result import load_result, block_transform, apply_transform
    res = load_result("result.json")
    res.status, res.verdict, res.load_multiplier, res.base_reaction
    T = res.transforms(centroids, amplitude=res.displacement_scale)   # {block id: 4x4}
    apply_transform(T["B1"], (x, y, z))

Block motion. Each block has a virtual translation u of its centroid g and a rotation vector
theta (axis x angle, radians) about g. Drawn at display amplitude s, a point p of the block goes
to  p' = g + R(s theta)(p - g) + s u,  R by Rodrigues' formula (an exact rotation, so the block
stays rigid however large s is; for small s theta it matches the virtual velocity
u + theta x (p - g) to first order; ``screw=True`` gives the finite screw motion instead,
which keeps a rocking block's hinge exactly in place). The stored values are not pre-multiplied:
``mechanism.displacement_scale`` (``Result.displacement_scale``) is the solver's suggested s.
Centroids are not in the result: take them from the model (``model.block_centroids``).

Colours (RGB 0-255) are the solver's SVG colours (solver/src/io/svg_writer.cpp): opening red,
sliding blue, opening + sliding purple, hinge orange; closed contacts (not drawn by the SVG)
light grey; blocks moving / at rest / support as in the SVG legend.
"""

import collections
import json
import math

from . import geometry as geo

STATE_COLOURS = collections.OrderedDict([
    ("closed", (180, 180, 180)),           # kGhostColour #b4b4b4
    ("opening", (214, 39, 40)),            # kOpeningColour #d62728
    ("sliding", (31, 119, 180)),           # kSlidingColour #1f77b4
    ("opening_sliding", (148, 103, 189)),  # kOpeningSlidingColour #9467bd
    ("hinge", (255, 127, 14)),             # kHingeColour #ff7f0e
])
STATE_LABELS = {"closed": "closed", "opening": "opening", "sliding": "sliding",
                "opening_sliding": "opening + sliding", "hinge": "hinge"}
BLOCK_COLOURS = collections.OrderedDict([
    ("moving", (244, 177, 131)),    # kMovingRgb 0xf4b183
    ("resting", (220, 215, 205)),   # kRestingRgb 0xdcd7cd
    ("support", (90, 90, 90)),      # kSupportRgb 0x5a5a5a
])
BLOCK_LABELS = {"moving": "moving block", "resting": "block at rest", "support": "support"}


def rgb_hex(rgb):
    return "#%02x%02x%02x" % tuple(int(c) for c in rgb)


def state_colour(state):
    """RGB of a contact state (closed, opening, sliding, opening_sliding, hinge)."""
    try:
        return STATE_COLOURS[state]
    except KeyError:
        raise ValueError("unknown contact state %r" % (state,))


def legend(include_closed=True, include_blocks=True):
    """Legend entries in display order: dicts with key, label, rgb, hex, kind
    ("contact" or "block")."""
    out = []
    for key, rgb in STATE_COLOURS.items():
        if key == "closed" and not include_closed:
            continue
        out.append({"key": key, "label": STATE_LABELS[key], "rgb": rgb, "hex": rgb_hex(rgb),
                    "kind": "contact"})
    if include_blocks:
        for key, rgb in BLOCK_COLOURS.items():
            out.append({"key": key, "label": BLOCK_LABELS[key], "rgb": rgb, "hex": rgb_hex(rgb),
                        "kind": "block"})
    return out


# ------------------------------------------------------------------------------ rigid motion

def rotation_matrix(theta):
    """3x3 rotation matrix (nested lists) of the rotation vector theta (axis x angle, radians),
    by Rodrigues: R = I + a [k]x + b [k]x^2 with a = sin(t)/t, b = (1 - cos t)/t^2 on the
    unnormalised cross-product matrix (series for small t, so no cancellation)."""
    x, y, z = float(theta[0]), float(theta[1]), float(theta[2])
    t2 = x * x + y * y + z * z
    t = math.sqrt(t2)
    if t < 1e-4:
        a = 1.0 - t2 / 6.0 + t2 * t2 / 120.0
        b = 0.5 - t2 / 24.0 + t2 * t2 / 720.0
    else:
        a = math.sin(t) / t
        b = (1.0 - math.cos(t)) / t2
    return [
        [1.0 - b * (y * y + z * z), -a * z + b * x * y, a * y + b * x * z],
        [a * z + b * x * y, 1.0 - b * (x * x + z * z), -a * x + b * y * z],
        [-a * y + b * x * z, a * x + b * y * z, 1.0 - b * (x * x + y * y)],
    ]


def block_transform(centroid, translation, rotation, amplitude=1.0, length_scale=1.0,
                    screw=False):
    """4x4 matrix (nested lists, row-major, acting on column vectors [x, y, z, 1]) of
    p -> g + R(s theta)(p - g) + s u  with s = amplitude.

    centroid g in the drawing's coordinates; translation u in the model's length unit;
    length_scale = model units per drawing unit (ModelBuilder.length_scale), so the drawn
    translation is s u / length_scale (1 when the drawing and the model share units).

    screw=True draws instead the exponential of the twist (the finite screw motion whose
    velocity field is s (u + theta x (p - g))): same rotation R(s theta), but points whose
    virtual velocity is zero (a rocking block's hinge line) stay exactly where they are,
    where the default moves them by O(s^2). Both agree to first order in s."""
    s = float(amplitude)
    w = [s * float(c) for c in rotation]
    R = rotation_matrix(w)
    g = [float(c) for c in centroid]
    k = 1.0 / float(length_scale)
    su = [s * float(translation[i]) * k for i in range(3)]
    if not screw:
        t = [g[i] + su[i] - sum(R[i][j] * g[j] for j in range(3)) for i in range(3)]
    else:
        # velocity field v(p) = v0 + w x p with v0 = s u - w x g; p' = R p + A v0,
        # A = I + b [w]x + c [w]x^2, b = (1 - cos t)/t^2, c = (t - sin t)/t^3
        v0 = geo.sub(su, geo.cross(w, g))
        t2 = w[0] * w[0] + w[1] * w[1] + w[2] * w[2]
        tt = math.sqrt(t2)
        if tt < 1e-4:
            b = 0.5 - t2 / 24.0 + t2 * t2 / 720.0
            c = 1.0 / 6.0 - t2 / 120.0 + t2 * t2 / 5040.0
        else:
            b = (1.0 - math.cos(tt)) / t2
            c = (tt - math.sin(tt)) / (t2 * tt)
        wv = geo.cross(w, v0)
        wwv = geo.cross(w, wv)
        t = [v0[i] + b * wv[i] + c * wwv[i] for i in range(3)]
    return [R[0] + [t[0]], R[1] + [t[1]], R[2] + [t[2]], [0.0, 0.0, 0.0, 1.0]]


def apply_transform(matrix, point):
    """Apply a 4x4 (affine) matrix to a 3-D point; returns a tuple."""
    x, y, z = float(point[0]), float(point[1]), float(point[2])
    m = matrix
    return (m[0][0] * x + m[0][1] * y + m[0][2] * z + m[0][3],
            m[1][0] * x + m[1][1] * y + m[1][2] * z + m[1][3],
            m[2][0] * x + m[2][1] * y + m[2][2] * z + m[2][3])


def identity():
    return [[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0],
            [0.0, 0.0, 0.0, 1.0]]


# ------------------------------------------------------------------------------------ result

BlockMotion = collections.namedtuple("BlockMotion", "id role translation rotation falling")


class Interface(object):
    """One interface of the result: ids, frame, state, contact polygon, forces."""

    def __init__(self, data):
        self.data = data
        self.id = data["id"]
        self.label = data.get("label", "")
        self.blocks = tuple(data["blocks"])
        self.normal = tuple(data["normal"])
        self.tangents = tuple(tuple(t) for t in data["tangents"])
        self.area = data["area"]
        self.state = data.get("state", "closed")
        self.cracked = bool(data.get("cracked", False))
        self.points = data.get("points", [])
        self.polygon = [tuple(p["position"]) for p in self.points]
        self.point_states = [p.get("state", "closed") for p in self.points]
        self.resultant = data.get("resultant")

    @property
    def colour(self):
        return state_colour(self.state)

    def centroid(self):
        return geo.polygon_centroid(self.polygon) if self.polygon else None

    def force(self):
        """Resultant force vector acting on blocks[1] (global frame, model force unit), or
        None when the result has no forces."""
        if not self.points or "normal_force" not in self.points[0]:
            return None
        n, (t1, t2) = self.normal, self.tangents
        f = [0.0, 0.0, 0.0]
        for p in self.points:
            nf = p.get("normal_force", 0.0)
            sf = p.get("shear_force", [0.0, 0.0])
            for i in range(3):
                f[i] += nf * n[i] + sf[0] * t1[i] + sf[1] * t2[i]
        return tuple(f)

    def centre_of_pressure(self):
        """Point of the contact polygon where the resultant normal force acts: the
        resultant's eccentricity when the result gives it, else the normal-force-weighted mean
        of the contact points; the polygon centroid when there is no normal force."""
        c = self.centroid()
        if c is None:
            return None
        e = (self.resultant or {}).get("eccentricity")
        if e is not None and any(e):
            return geo.add(c, e)
        total = sum(p.get("normal_force", 0.0) for p in self.points)
        if total <= 0.0:
            return c
        return tuple(sum(p.get("normal_force", 0.0) * p["position"][i] for p in self.points)
                     / total for i in range(3))


class Result(object):
    """A parsed result document (``data`` keeps the raw dict)."""

    def __init__(self, data):
        if not isinstance(data, dict) or "status" not in data:
            raise ValueError("not an rbla result: no 'status'")
        self.data = data
        self.status = data["status"]
        self.verdict = data.get("verdict", "")
        self.units = data.get("units", {})
        self.length_unit = self.units.get("length", "m")
        self.force_unit = self.units.get("force", "kN")
        self.analysis = data.get("analysis", {})
        self.analysis_type = self.analysis.get("type")
        self.load_multiplier = data.get("load_multiplier")
        br = data.get("base_reaction")
        self.base_reaction = br.get("at_collapse") if br else None
        self.base_reaction_info = br
        mech = data.get("mechanism") or {}
        self.displacement_scale = mech.get("displacement_scale", 1.0)
        self.normalisation = mech.get("normalisation")
        self.blocks = collections.OrderedDict()
        for b in data.get("blocks", []):
            self.blocks[b["id"]] = BlockMotion(b["id"], b["role"], tuple(b["translation"]),
                                               tuple(b["rotation"]), bool(b.get("falling")))
        self.interfaces = [Interface(i) for i in data.get("interfaces", [])]
        self.cracked_interfaces = list(data.get("cracked_interfaces", []))
        self.warnings = list(data.get("warnings", []))
        self.sensitivities = data.get("sensitivities")

    @property
    def is_collapse(self):
        return self.status == "collapse"

    def headline(self, digits=4):
        """Short text for a label: 'alpha = 0.5000', 'R = 11.76 kN', or the status."""
        if self.status == "collapse" and self.load_multiplier is not None:
            return "alpha = %.*f" % (digits, self.load_multiplier)
        if self.status == "collapse" and self.base_reaction is not None:
            return "R = %.*g %s" % (digits, self.base_reaction, self.force_unit)
        return self.status.replace("_", " ")

    def moving_blocks(self, tolerance=1e-9):
        """Ids of the blocks whose translation or rotation is non-zero."""
        out = []
        for b in self.blocks.values():
            if max(abs(c) for c in b.translation + b.rotation) > tolerance:
                out.append(b.id)
        return out

    def transform(self, block_id, centroid, amplitude=None, length_scale=1.0, screw=False):
        """4x4 matrix of one block's displayed motion (identity for a block without motion);
        amplitude None = the solver's displacement_scale. See :func:`block_transform`."""
        s = self.displacement_scale if amplitude is None else amplitude
        b = self.blocks.get(block_id)
        if b is None:
            return identity()
        return block_transform(centroid, b.translation, b.rotation, s, length_scale, screw)

    def transforms(self, centroids, amplitude=None, length_scale=1.0, screw=False):
        """{block id: 4x4} for every block in ``centroids`` ({id: (x, y, z)})."""
        return dict((bid, self.transform(bid, g, amplitude, length_scale, screw))
                    for bid, g in centroids.items())

    def state_counts(self):
        counts = collections.OrderedDict((k, 0) for k in STATE_COLOURS)
        for i in self.interfaces:
            counts[i.state] = counts.get(i.state, 0) + 1
        return counts

    def influential_joints(self, count=5):
        """The joints whose friction coefficient changes the result most, from the result's
        ``sensitivities`` (largest magnitude first, as the solver lists them): list of
        (interface id, derivative, symbol) with symbol 'dalpha/dmu' or 'dR/dmu' (R in the
        model's force unit). Empty when the result has no sensitivities."""
        s = self.sensitivities or {}
        out = []
        for entry in s.get("interfaces", [])[:count]:
            if "d_base_reaction_d_friction" in entry:
                out.append((entry["id"], entry["d_base_reaction_d_friction"], "dR/dmu"))
            elif "d_load_multiplier_d_friction" in entry:
                out.append((entry["id"], entry["d_load_multiplier_d_friction"], "dalpha/dmu"))
        return out

    def support_reactions(self):
        """Forces the supports (fixed or moving blocks) exert on the structure, per interface:
        list of dicts {interface, support, block, force (x, y, z), point (centre of
        pressure)}, in the model's units. Empty when the result has no forces, or no contact
        points (a result written with --detail interfaces or blocks)."""
        roles = dict((b.id, b.role) for b in self.blocks.values())
        out = []
        for itf in self.interfaces:
            f = itf.force()
            if f is None:
                continue
            r0 = roles.get(itf.blocks[0], "free")
            r1 = roles.get(itf.blocks[1], "free")
            if r0 != "free" and r1 == "free":
                out.append({"interface": itf.id, "support": itf.blocks[0],
                            "block": itf.blocks[1], "force": f,
                            "point": itf.centre_of_pressure()})
            elif r1 != "free" and r0 == "free":
                out.append({"interface": itf.id, "support": itf.blocks[1],
                            "block": itf.blocks[0], "force": geo.scale(f, -1.0),
                            "point": itf.centre_of_pressure()})
        return out


def load_result(path):
    with open(path, "r", encoding="utf-8") as f:
        return Result(json.load(f))


# ------------------------------------------------------------------------ drawing helpers

def block_colour_key(role, moving):
    """'support', 'moving' or 'resting' (the SVG's block colours)."""
    if role in ("fixed", "moving_support") and not moving:
        return "support"
    return "moving" if moving else "resting"


def displaced_blocks(model, result, amplitude=None, length_scale=1.0, screw=False,
                     tolerance=1e-9):
    """The model's blocks moved by the mechanism at display amplitude s (None: the solver's
    suggestion): list of dicts {id, role, moving, vertices (moved, drawing units), faces,
    transform (4x4), colour_key, rgb}. ``model`` is the model dict (vertices in model units
    divided by ``length_scale`` give drawing units)."""
    from .model import block_centroids
    if not isinstance(result, Result):
        result = Result(result)
    k = 1.0 / float(length_scale)
    centroids = block_centroids(model)
    moving = set(result.moving_blocks(tolerance))
    out = []
    for b in model.get("blocks", []):
        bid = b["id"]
        g = tuple(c * k for c in centroids[bid])
        T = result.transform(bid, g, amplitude, length_scale, screw)
        verts = [apply_transform(T, [c * k for c in p]) for p in b["vertices"]]
        role = b.get("role", "free")
        key = block_colour_key(role, bid in moving)
        out.append({"id": bid, "role": role, "moving": bid in moving, "vertices": verts,
                    "faces": [list(f) for f in b["faces"]], "transform": T,
                    "colour_key": key, "rgb": BLOCK_COLOURS[key]})
    return out


def contact_polygons(result, include_closed=False, length_scale=1.0):
    """Contact polygons to draw: list of dicts {id, label, blocks, state, rgb, polygon
    (drawing units), cracked}; closed interfaces only when include_closed."""
    if not isinstance(result, Result):
        result = Result(result)
    k = 1.0 / float(length_scale)
    out = []
    for itf in result.interfaces:
        if itf.state == "closed" and not include_closed:
            continue
        if len(itf.polygon) < 2:
            continue
        out.append({"id": itf.id, "label": itf.label, "blocks": itf.blocks, "state": itf.state,
                    "rgb": state_colour(itf.state), "cracked": itf.cracked,
                    "polygon": [tuple(c * k for c in p) for p in itf.polygon]})
    return out


def reaction_labels(result, digits=3, length_scale=1.0):
    """(point, text) pairs for the support reactions: the force the support exerts on the
    structure at the centre of pressure, e.g. 'base: N 36 | T 18 kN' (normal and tangential
    parts with respect to the interface)."""
    if not isinstance(result, Result):
        result = Result(result)
    k = 1.0 / float(length_scale)
    itfs = dict((i.id, i) for i in result.interfaces)
    out = []
    for r in result.support_reactions():
        itf = itfs[r["interface"]]
        f = r["force"]
        n = abs(geo.dot(f, itf.normal))
        t = geo.norm(geo.sub(f, geo.scale(itf.normal, geo.dot(f, itf.normal))))
        text = "%s: N %.*g | T %.*g %s" % (r["support"], digits, n, digits, t, result.force_unit)
        out.append((tuple(c * k for c in r["point"]), text))
    return out


def influence_labels(result, count=5, digits=3, length_scale=1.0):
    """(point, text) pairs marking the most influential joints at their contact polygons'
    centroids, numbered as the mechanism SVG numbers them: '#1 I33: dR/dmu = -1.09 kN'."""
    if not isinstance(result, Result):
        result = Result(result)
    k = 1.0 / float(length_scale)
    itfs = dict((i.id, i) for i in result.interfaces)
    out = []
    for rank, (iid, value, symbol) in enumerate(result.influential_joints(count), 1):
        itf = itfs.get(iid)
        c = itf.centroid() if itf is not None else None
        if c is None:
            continue
        unit = " " + result.force_unit if symbol == "dR/dmu" else ""
        text = "#%d %s: %s = %.*g%s" % (rank, iid, symbol, digits, value, unit)
        out.append((tuple(x * k for x in c), text))
    return out


def summary_lines(result):
    """A few lines for a text dot or a panel: verdict, alpha or R, state counts, warnings."""
    if not isinstance(result, Result):
        result = Result(result)
    lines = [result.verdict or result.status]
    if result.load_multiplier is not None:
        lines.append("alpha = %.6g" % result.load_multiplier)
    if result.base_reaction is not None:
        lines.append("R = %.6g %s at collapse" % (result.base_reaction, result.force_unit))
    counts = ", ".join("%s %d" % (STATE_LABELS[k], v) for k, v in result.state_counts().items()
                       if v and k != "closed")
    if counts:
        lines.append("contacts: " + counts)
    if result.warnings:
        lines.append("%d warning(s): %s" % (len(result.warnings),
                                            result.warnings[0].get("message", "")))
    return lines
