#!/usr/bin/env python3
"""Generate the parametric rbla sample models (schema/model.schema.json, version 1.0.0).

Standard library only; Python 3.9 or newer.

Every scene is a subcommand with its sizes as options; the model JSON goes to stdout or to
``--output FILE``. ``all --dir samples/`` regenerates every bundled sample with its defaults.

Conventions of the written models (see schema/model.schema.json):
  * units: metres, kilonewtons, kN/m3; gravity along -z;
  * every block has ``id``, ``role``, ``vertices``, ``faces`` (counter-clockwise seen from
    outside, i.e. outward normal by the right-hand rule), and ``centroid`` and ``volume``
    computed here from the faces by the divergence theorem, as a CAD would report them;
  * no ``interfaces``: the solver detects them from the geometry.

``--self-check`` verifies every block before writing: the faces close the polyhedron (each
directed edge appears once and its reverse once), every face is planar, the volume from the
faces is positive, every face normal points away from the centroid (all generated blocks are
convex), the written centroid/volume match, and the ids are unique.

Examples:
  python3 samples/generate_samples.py block --height 3 -o /tmp/block.json
  python3 samples/generate_samples.py facade --settling-fraction 0.3 -o /tmp/facade.json
  python3 samples/generate_samples.py church --load seismic-y --blocks 8000 -o /tmp/church.json
  python3 samples/generate_samples.py all --dir samples/ --self-check
"""

import argparse
import json
import math
import os
import sys
import time

import imperfections

# One polyhedron volume and centroid for all the Python code: the CAD core's (plugin/rbla_cad,
# standard library only), which tests/plugin/test_geometry_agreement.py holds equal to the solver's.
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "plugin"))
from rbla_cad.geometry import cross as _cross, dot as _dot, sub as _sub, volume_centroid  # noqa: E402

SCHEMA_VERSION = "1.0.0"
COORD_DECIMALS = 10    # vertex coordinates are rounded to 1e-10 length units
DERIVED_DECIMALS = 12  # centroid and volume are rounded to 1e-12
SNAP = 1e-9            # breakpoints of a course closer than this (m) are merged


# --------------------------------------------------------------------------------------------
# Geometry
# --------------------------------------------------------------------------------------------

def _r(x, nd=COORD_DECIMALS):
    """Round and drop the sign of zero, so -0.0 is never written."""
    return round(x, nd) + 0.0


def face_normal(vertices, face):
    """Newell's normal of a polygon (not normalised; its length is twice the area)."""
    nx = ny = nz = 0.0
    n = len(face)
    for i in range(n):
        p = vertices[face[i]]
        q = vertices[face[(i + 1) % n]]
        nx += (p[1] - q[1]) * (p[2] + q[2])
        ny += (p[2] - q[2]) * (p[0] + q[0])
        nz += (p[0] - q[0]) * (p[1] + q[1])
    return (nx, ny, nz)


def prism_xz(polygon_xz, y0, y1):
    """A prism: the polygon [(x, z), ...] in the x-z plane extruded along y from y0 to y1.

    Returns (vertices, faces), faces outward counter-clockwise seen from outside. The polygon
    is first made counter-clockwise in (x right, z up); then the face at y0 (outward normal -y)
    keeps that order, the face at y1 is reversed, and the side face of edge j -> j+1 is
    [j, n+j, n+j+1, j+1]. For a box, the bottom face comes out clockwise seen from above.
    """
    pts = list(polygon_xz)
    area2 = 0.0
    for i in range(len(pts)):
        x0, z0 = pts[i]
        x1, z1 = pts[(i + 1) % len(pts)]
        area2 += x0 * z1 - x1 * z0
    if area2 < 0.0:
        pts.reverse()
    n = len(pts)
    vertices = [[_r(x), _r(y0), _r(z)] for x, z in pts] + [[_r(x), _r(y1), _r(z)] for x, z in pts]
    faces = [list(range(n)), [n + j for j in reversed(range(n))]]
    for j in range(n):
        k = (j + 1) % n
        faces.append([j, n + j, n + k, k])
    return vertices, faces


def box(x0, x1, y0, y1, z0, z1):
    """Axis-aligned box as a prism along y (8 vertices, 6 faces)."""
    return prism_xz([(x0, z0), (x1, z0), (x1, z1), (x0, z1)], y0, y1)


def make_block(block_id, vertices, faces, role="free", label=None):
    vol, cen = volume_centroid(vertices, faces)
    b = {"id": block_id}
    if label:
        b["label"] = label
    b["role"] = role
    b["vertices"] = vertices
    b["faces"] = faces
    b["centroid"] = [_r(c, DERIVED_DECIMALS) for c in cen]
    b["volume"] = _r(vol, DERIVED_DECIMALS)
    return b


# --------------------------------------------------------------------------------------------
# Self-check
# --------------------------------------------------------------------------------------------

def check_block(b, planar=True):
    """Return a list of problems with one block (empty when it is sound). With planar=False
    (warped scenes) faces are not required to be planar."""
    problems = []
    V = b["vertices"]
    F = b["faces"]
    bid = b["id"]
    for f in F:
        for i in f:
            if i < 0 or i >= len(V):
                return ["block %s: face index %d out of range" % (bid, i)]
    # Closure: every directed edge once, and its reverse once.
    edges = {}
    for f in F:
        for k in range(len(f)):
            e = (f[k], f[(k + 1) % len(f)])
            edges[e] = edges.get(e, 0) + 1
    for (a, c), cnt in edges.items():
        if cnt != 1:
            problems.append("block %s: directed edge %d->%d used %d times" % (bid, a, c, cnt))
        if edges.get((c, a), 0) != 1:
            problems.append("block %s: edge %d->%d has no reverse (open or misoriented)" % (bid, a, c))
    vol, cen = volume_centroid(V, F)
    if not vol > 0.0:
        problems.append("block %s: volume from faces %.6g is not positive" % (bid, vol))
        return problems
    scale = vol ** (1.0 / 3.0)
    for fi, f in enumerate(F):
        n = face_normal(V, f)
        ln = math.sqrt(_dot(n, n))
        if ln == 0.0:
            problems.append("block %s: face %d is degenerate" % (bid, fi))
            continue
        n = (n[0] / ln, n[1] / ln, n[2] / ln)
        p0 = V[f[0]]
        for i in f:
            d = _dot(_sub(V[i], p0), n)
            if planar and abs(d) > 1e-9 * max(1.0, scale):
                problems.append("block %s: face %d not planar (%.3g)" % (bid, fi, d))
                break
        # convex blocks: the centroid lies on the inner side of every face plane
        if _dot(_sub(cen, p0), n) >= 0.0:
            problems.append("block %s: face %d normal does not point outward" % (bid, fi))
    if "volume" in b and abs(b["volume"] - vol) > 1e-9 * max(1.0, vol):
        problems.append("block %s: written volume %r != %r" % (bid, b["volume"], vol))
    if "centroid" in b:
        for k in range(3):
            if abs(b["centroid"][k] - cen[k]) > 1e-9 * max(1.0, scale):
                problems.append("block %s: written centroid %r != %r" % (bid, b["centroid"], cen))
                break
    return problems


def self_check(model, name, planar=True):
    problems = []
    ids = set()
    for b in model["blocks"]:
        if b["id"] in ids:
            problems.append("duplicate block id %s" % b["id"])
        ids.add(b["id"])
        problems.extend(check_block(b, planar))
    if problems:
        for p in problems[:50]:
            sys.stderr.write("self-check %s: %s\n" % (name, p))
        if len(problems) > 50:
            sys.stderr.write("self-check %s: ... %d more\n" % (name, len(problems) - 50))
        return False
    vol = sum(b["volume"] for b in model["blocks"])
    sys.stderr.write("self-check %s: OK, %d blocks, total volume %.6g\n"
                     % (name, len(model["blocks"]), vol))
    return True


# --------------------------------------------------------------------------------------------
# Model skeleton and output
# --------------------------------------------------------------------------------------------

def model_skeleton(title, args):
    return {
        "schema_version": SCHEMA_VERSION,
        "title": title,
        "units": {"length": "m", "force": "kN", "unit_weight": "kN/m3"},
        "gravity": "-z",
        "defaults": {"unit_weight": args.unit_weight, "friction": args.friction},
        "blocks": [],
    }


def seismic_analysis(direction):
    return {"type": "load_multiplier", "seismic": {"direction": list(direction)}}


def dumps_model(model, compact):
    """Compact: one line, no spaces. Otherwise readable: two-space indent, one block per line."""
    if compact:
        return json.dumps(model, separators=(",", ":")) + "\n"
    lines = ["{"]
    keys = list(model.keys())
    for i, k in enumerate(keys):
        comma = "," if i + 1 < len(keys) else ""
        if k == "blocks":
            lines.append('  "blocks": [')
            nb = len(model["blocks"])
            for j, b in enumerate(model["blocks"]):
                lines.append("    " + json.dumps(b, separators=(", ", ": "))
                             + ("," if j + 1 < nb else ""))
            lines.append("  ]" + comma)
        else:
            lines.append("  %s: %s%s" % (json.dumps(k), json.dumps(model[k], separators=(", ", ": ")),
                                         comma))
    lines.append("}")
    return "\n".join(lines) + "\n"


def write_model(model, path, compact):
    text = dumps_model(model, compact)
    if path is None or path == "-":
        sys.stdout.write(text)
    else:
        d = os.path.dirname(path)
        if d:
            os.makedirs(d, exist_ok=True)
        with open(path, "w", encoding="utf-8") as fh:
            fh.write(text)


# --------------------------------------------------------------------------------------------
# Running-bond courses
# --------------------------------------------------------------------------------------------

def _merge_sorted(xs):
    out = []
    for x in sorted(xs):
        if not out or x - out[-1] > SNAP:
            out.append(x)
    return out


def course_breakpoints(n_blocks, block_len, shifted):
    """Joint positions of one running-bond course of length n_blocks * block_len, from 0 to L.

    Unshifted courses have n_blocks whole blocks; shifted courses start and end with a half
    block (n_blocks - 1 whole blocks between), so both wall ends are straight.
    """
    L = n_blocks * block_len
    if not shifted:
        return [k * block_len for k in range(n_blocks + 1)]
    return [0.0] + [(k + 0.5) * block_len for k in range(n_blocks)] + [L]


def course_segments(breaks, cuts=(), holes=(), merged=()):
    """Segments [a, b] of a course.

    breaks: the course's regular joint positions; cuts: extra joint positions (opening jambs,
    lintel ends); holes: intervals left empty (openings); merged: intervals that become a single
    segment (a lintel), whose interior joints are dropped.
    """
    xs = list(breaks) + list(cuts)
    for a, b in list(holes) + list(merged):
        xs += [a, b]
    xs = _merge_sorted(xs)
    xs = [x for x in xs if not any(a + SNAP < x < b - SNAP for a, b in merged)]
    segs = []
    for a, b in zip(xs[:-1], xs[1:]):
        mid = 0.5 * (a + b)
        if any(h0 - SNAP <= mid <= h1 + SNAP for h0, h1 in holes):
            continue
        segs.append((a, b))
    return segs


def count_box_contacts(courses, base_segments, joint_tol=SNAP):
    """Interfaces a detector will find in a wall of box blocks (for the facade report).

    courses: per course a list of (x0, x1) in order; base_segments: the base blocks' x ranges.
    Counts head joints (neighbours in a course that touch), bed joints (overlapping x ranges of
    consecutive courses, base included). Every interface is a rectangle: 4 contact points.
    """
    def overlaps(lo, hi):
        n = 0
        i = j = 0
        while i < len(lo) and j < len(hi):
            a = max(lo[i][0], hi[j][0])
            b = min(lo[i][1], hi[j][1])
            if b - a > joint_tol:
                n += 1
            if lo[i][1] < hi[j][1]:
                i += 1
            else:
                j += 1
        return n
    n_if = 0
    for segs in courses:
        for (a0, a1), (b0, b1) in zip(segs[:-1], segs[1:]):
            if abs(b0 - a1) <= joint_tol:
                n_if += 1
    n_if += overlaps(sorted(base_segments), courses[0])
    for lo, hi in zip(courses[:-1], courses[1:]):
        n_if += overlaps(lo, hi)
    return n_if


# --------------------------------------------------------------------------------------------
# Scenes
# --------------------------------------------------------------------------------------------

def scene_block(args):
    b, d, h = args.width, args.depth, args.height
    m, t = args.base_margin, args.base_thickness
    model = model_skeleton("single block %g x %g x %g m on a fixed base, seismic +x; "
                           "closed form alpha = min(b/h, mu) = %g"
                           % (b, d, h, min(b / h, args.friction)), args)
    blocks = model["blocks"]
    blocks.append(make_block("base", *box(-b / 2 - m, b / 2 + m, -d / 2 - m, d / 2 + m, -t, 0.0),
                             role="fixed"))
    blocks.append(make_block("block", *box(-b / 2, b / 2, -d / 2, d / 2, 0.0, h)))
    model["analysis"] = seismic_analysis([1, 0, 0])
    return model


def scene_column(args):
    n, b, d, hb = args.count, args.width, args.depth, args.block_height
    m, t = args.base_margin, args.base_thickness
    H = n * hb
    model = model_skeleton("column of %d blocks %g x %g x %g m on a fixed base, seismic +x; "
                           "closed form alpha = min(b/H, mu) = %g"
                           % (n, b, d, hb, min(b / H, args.friction)), args)
    blocks = model["blocks"]
    blocks.append(make_block("base", *box(-b / 2 - m, b / 2 + m, -d / 2 - m, d / 2 + m, -t, 0.0),
                             role="fixed"))
    for i in range(n):
        blocks.append(make_block("c%02d" % i, *box(-b / 2, b / 2, -d / 2, d / 2, i * hb, (i + 1) * hb)))
    model["analysis"] = seismic_analysis([1, 0, 0])
    return model


def scene_arch(args):
    N, R, t, d = args.voussoirs, args.radius, args.thickness, args.depth
    if t >= 2 * R:
        raise SystemExit("arch: thickness must be smaller than the diameter")
    ri, re = R - t / 2.0, R + t / 2.0
    a, ha = args.abutment_margin, args.abutment_height
    y0, y1 = -d / 2.0, d / 2.0
    model = model_skeleton("semicircular arch, %d voussoirs, R = %g m, t = %g m (t/R = %.4g; "
                           "Couplet-Heyman minimum 0.1075), depth %g m, on fixed abutments; "
                           "seismic +x" % (N, R, t, t / R, d), args)
    blocks = model["blocks"]
    blocks.append(make_block("abutment_left", *box(-re - a, -ri + a, y0, y1, -ha, 0.0), role="fixed"))
    blocks.append(make_block("abutment_right", *box(ri - a, re + a, y0, y1, -ha, 0.0), role="fixed"))
    width = len(str(N - 1))
    for i in range(N):
        # voussoir i between the radial planes at phi0 and phi1, numbered from the left springing
        phi0 = math.pi * (1.0 - i / float(N))
        phi1 = math.pi * (1.0 - (i + 1) / float(N))
        c0, s0, c1, s1 = math.cos(phi0), math.sin(phi0), math.cos(phi1), math.sin(phi1)
        poly = [(ri * c0, ri * s0), (re * c0, re * s0), (re * c1, re * s1), (ri * c1, ri * s1)]
        blocks.append(make_block("v%0*d" % (width, i), *prism_xz(poly, y0, y1)))
    model["analysis"] = seismic_analysis([1, 0, 0])
    return model


def _wall_blocks(blocks, courses, bt, hb, prefix="c"):
    """Append box blocks for courses = [(z0, [(x0, x1, id_or_None), ...]), ...]."""
    for ci, (z0, segs) in enumerate(courses):
        k = 0
        for x0, x1, special in segs:
            bid = special if special else "%s%02d_%02d" % (prefix, ci, k)
            if not special:
                k += 1
            blocks.append(make_block(bid, *box(x0, x1, 0.0, bt, z0, z0 + hb)))


def scene_wall_opening(args):
    nc, nb = args.courses, args.blocks
    bl, bt, hb = args.block_length, args.block_thickness, args.block_height
    L = nb * bl
    ow = args.opening_width * bl
    oh = args.opening_height
    sill = args.sill_course if args.sill_course is not None else (nc - oh) // 2
    lintel_course = sill + oh
    if oh < 1 or sill < 0 or lintel_course >= nc:
        raise SystemExit("wall-opening: the opening (sill course %d, %d courses) and its lintel "
                         "must fit in %d courses" % (sill, oh, nc))
    ox0 = (L - ow) / 2.0
    ox1 = ox0 + ow
    lx0, lx1 = ox0 - args.lintel_bearing, ox1 + args.lintel_bearing
    if ox0 <= SNAP or lx0 < -SNAP or lx1 > L + SNAP:
        raise SystemExit("wall-opening: opening or lintel wider than the wall")
    lx0, lx1 = max(lx0, 0.0), min(lx1, L)
    m, t = args.base_margin, args.base_thickness
    model = model_skeleton("running-bond wall %d courses x %d blocks (%g x %g x %g m) with a "
                           "%g x %g m opening and a lintel, on a fixed base; seismic +x"
                           % (nc, nb, bl, bt, hb, ow, oh * hb, ), args)
    blocks = model["blocks"]
    blocks.append(make_block("base", *box(-m, L + m, -m, bt + m, -t, 0.0), role="fixed"))
    courses = []
    smallest = bl
    for c in range(nc):
        br = course_breakpoints(nb, bl, c % 2 == 1)
        if sill <= c < lintel_course:
            segs = [(a, b, None) for a, b in course_segments(br, holes=[(ox0, ox1)])]
        elif c == lintel_course:
            segs = [(a, b, "lintel" if abs(a - lx0) <= SNAP and abs(b - lx1) <= SNAP else None)
                    for a, b in course_segments(br, merged=[(lx0, lx1)])]
        else:
            segs = [(a, b, None) for a, b in course_segments(br)]
        smallest = min([smallest] + [b - a for a, b, _ in segs])
        courses.append((c * hb, segs))
    if smallest < 0.1 * bl:
        sys.stderr.write("wall-opening: warning: a block only %.3g m long (opening or lintel off "
                         "the half-block grid)\n" % smallest)
    _wall_blocks(blocks, courses, bt, hb)
    model["analysis"] = seismic_analysis([1, 0, 0])
    return model


def _base_split(L, m, fraction, gap):
    """x ranges of the fixed and the moving base blocks (the moving one is the right part)."""
    xs = L * (1.0 - fraction)
    return (-m, xs - gap / 2.0), (xs + gap / 2.0, L + m)


def _add_base(blocks, L, m, t, bt, fraction, gap, scene):
    """Base blocks under a wall of length L: one fixed block, or (fraction given) a fixed block
    and a moving support under the right part. Returns the x ranges of the base blocks."""
    if fraction is None:
        blocks.append(make_block("base", *box(-m, L + m, -m, bt + m, -t, 0.0), role="fixed"))
        return [(-m, L + m)]
    if not 0.0 < fraction < 1.0:
        raise SystemExit("%s: --settling-fraction must be in (0, 1)" % scene)
    (fa, fb), (ma, mb) = _base_split(L, m, fraction, gap)
    blocks.append(make_block("base_fixed", *box(fa, fb, -m, bt + m, -t, 0.0), role="fixed"))
    blocks.append(make_block("base_moving", *box(ma, mb, -m, bt + m, -t, 0.0),
                             role="moving_support"))
    return [(fa, fb), (ma, mb)]


def scene_wall_settlement(args):
    nc, nb = args.courses, args.blocks
    bl, bt, hb = args.block_length, args.block_thickness, args.block_height
    L = nb * bl
    f = args.settling_fraction
    if not 0.0 < f < 1.0:
        raise SystemExit("wall-settlement: --settling-fraction must be in (0, 1)")
    m, t = args.base_margin, args.base_thickness
    model = model_skeleton("running-bond wall %d courses x %d blocks (%g x %g x %g m) on a fixed "
                           "base (left) and a moving support under the right %g %% of its length; "
                           "settlement" % (nc, nb, bl, bt, hb, 100 * f), args)
    blocks = model["blocks"]
    (fa, fb), (ma, mb) = _base_split(L, m, f, args.support_gap)
    blocks.append(make_block("base_fixed", *box(fa, fb, -m, bt + m, -t, 0.0), role="fixed"))
    blocks.append(make_block("base_moving", *box(ma, mb, -m, bt + m, -t, 0.0), role="moving_support"))
    courses = []
    for c in range(nc):
        segs = course_segments(course_breakpoints(nb, bl, c % 2 == 1))
        courses.append((c * hb, [(a, b, None) for a, b in segs]))
    _wall_blocks(blocks, courses, bt, hb)
    model["analysis"] = {"type": "settlement"}
    return model


def scene_facade(args):
    nx, ny = args.nx, args.ny
    bl, bt, hb = args.block_length, args.block_thickness, args.block_height
    L = nx * bl
    m, t = args.base_margin, args.base_thickness
    what = "fixed base"
    model = model_skeleton("", args)
    blocks = model["blocks"]
    f = args.settling_fraction
    base_segs = _add_base(blocks, L, m, t, bt, f, args.support_gap, "facade")
    if f is not None:
        what = "fixed base and a moving support under the right %g %%; settlement" % (100 * f)
        model["analysis"] = {"type": "settlement"}
    else:
        direction = [0, 1, 0] if args.seismic == "y" else [1, 0, 0]
        what = "fixed base; seismic +%s" % (args.seismic or "x")
        model["analysis"] = seismic_analysis(direction)
    seg_courses = []
    courses = []
    for c in range(ny):
        segs = course_segments(course_breakpoints(nx, bl, c % 2 == 1))
        seg_courses.append(segs)
        courses.append((c * hb, [(a, b, None) for a, b in segs]))
    _wall_blocks(blocks, courses, bt, hb, prefix="r")
    n_if = count_box_contacts(seg_courses, base_segs)
    model["title"] = ("facade: running-bond wall %d x %d blocks (%g x %g x %g m), %d blocks, on a %s"
                      % (nx, ny, bl, bt, hb, len(blocks), what))
    sys.stderr.write("facade: %d blocks, %d interfaces expected from detection, %d contact points\n"
                     % (len(blocks), n_if, 4 * n_if))
    return model


# --------------------------------------------------------------------------------------------
# Town house: English bond, storeys of rectangular windows with flat lintels, a door
# --------------------------------------------------------------------------------------------
# A second façade family for the scale benchmark, built unlike the facade and church scenes
# (docs/benchmark/scale.md): courses alternate stretchers (one block length) and headers (half a
# block length, a quarter-length closer at each end), the openings are rectangular with one
# lintel block each, and their jambs cut the courses into closers. Lengths in quarter blocks q.

TOWNHOUSE_BAY_Q = 32            # bay width: 8 stretchers
TOWNHOUSE_STOREY_COURSES = 14   # 4 below the sill, 7 of window, the lintel, 2 above
TOWNHOUSE_WINDOW = (10, 22, 4, 7)   # window x0, x1 (q from the bay's left edge), sill course, courses
TOWNHOUSE_DOOR = (8, 24, 0, 9)      # the door of the middle bay on the ground floor, same units
TOWNHOUSE_BEARING_Q = 2         # lintel bearing on each side of the opening
TOWNHOUSE_PARAPET = 2           # courses above the top storey


def english_bond_breakpoints(n_stretchers, bl, header_course):
    """Joints of an English-bond course of length n_stretchers * bl: stretchers, or headers of
    half length between two quarter-length closers at the ends (joints at odd multiples of bl/4)."""
    L = n_stretchers * bl
    if not header_course:
        return [k * bl for k in range(n_stretchers + 1)]
    q = bl / 4.0
    return [0.0] + [q + 2.0 * q * k for k in range(2 * n_stretchers)] + [L]


def townhouse_openings(bays, storeys, q):
    """(x0, x1, first course, courses) of every opening: a window per bay and storey, the door
    in place of the middle bay's ground-floor window."""
    openings = []
    for st in range(storeys):
        for b in range(bays):
            x0, x1, sill, n = TOWNHOUSE_DOOR if (st == 0 and b == bays // 2) else TOWNHOUSE_WINDOW
            left = b * TOWNHOUSE_BAY_Q
            openings.append(((left + x0) * q, (left + x1) * q,
                             st * TOWNHOUSE_STOREY_COURSES + sill, n))
    return openings


def townhouse_course(c, br, openings, q):
    """Segments (x0, x1, id or None) of course c: holes where an opening passes, one lintel block
    over each opening whose top is this course."""
    holes = [(x0, x1) for x0, x1, first, n in openings if first <= c < first + n]
    lintels = [(x0 - TOWNHOUSE_BEARING_Q * q, x1 + TOWNHOUSE_BEARING_Q * q, k)
               for k, (x0, x1, first, n) in enumerate(openings) if c == first + n]
    segs = course_segments(br, holes=holes, merged=[(a, b) for a, b, _ in lintels])
    named = []
    for a, b in segs:
        lintel = [k for la, lb, k in lintels if abs(a - la) <= SNAP and abs(b - lb) <= SNAP]
        named.append((a, b, "lintel_%03d" % lintel[0] if lintel else None))
    return named


def scene_townhouse(args):
    bays, storeys = args.bays, args.storeys
    if bays < 1 or storeys < 1:
        raise SystemExit("townhouse: --bays and --storeys must be at least 1")
    bl, bt, hb = args.block_length, args.block_thickness, args.block_height
    q = bl / 4.0
    L = bays * TOWNHOUSE_BAY_Q * q
    n_stretchers = bays * TOWNHOUSE_BAY_Q // 4
    n_courses = storeys * TOWNHOUSE_STOREY_COURSES + TOWNHOUSE_PARAPET
    m, t = args.base_margin, args.base_thickness
    model = model_skeleton("", args)
    blocks = model["blocks"]
    settling = args.load == "settlement"
    _add_base(blocks, L, m, t, bt, args.settling_fraction if settling else None, args.support_gap,
              "townhouse")
    model["analysis"] = {"type": "settlement"} if settling else seismic_analysis([1, 0, 0])
    openings = townhouse_openings(bays, storeys, q)
    courses = []
    for c in range(n_courses):
        br = english_bond_breakpoints(n_stretchers, bl, c % 2 == 1)
        courses.append((c * hb, townhouse_course(c, br, openings, q)))
    _wall_blocks(blocks, courses, bt, hb, prefix="t")
    model["title"] = ("town house: English bond, %d bays x %d storeys (%.1f x %.1f m), %d windows "
                      "and a door with flat lintels, %d blocks; %s"
                      % (bays, storeys, L, n_courses * hb, len(openings) - 1, len(blocks),
                         "settlement of the right %g %% of the base" % (100 * args.settling_fraction)
                         if settling else "seismic +x"))
    return model


# --------------------------------------------------------------------------------------------
# Church façade: running bond with arched openings and a rose window
# --------------------------------------------------------------------------------------------

# Openings of the church façade as fractions of the wall width W and height H (22 m x 19 m at
# scale 1): (name, kind, centre x / W, sill z / H, springing (arch) or centre (rose) z / H,
# intrados radius / W). Doors have their sill at 0. Heights are snapped to course lines (the rose
# centre to mid-course), so every springing line and sill is a bed joint.
CHURCH_OPENINGS = [
    ("portal", "arch", 0.5, 0.0, 4.0 / 19, 1.32 / 22),
    ("rose", "rose", 0.5, None, 9.75 / 19, 1.6 / 22),
    ("portal_left", "arch", 0.2, 0.0, 3.0 / 19, 0.88 / 22),
    ("portal_right", "arch", 0.8, 0.0, 3.0 / 19, 0.88 / 22),
    ("window_left", "arch", 0.2, 7.0 / 19, 10.0 / 19, 0.66 / 22),
    ("window_right", "arch", 0.8, 7.0 / 19, 10.0 / 19, 0.66 / 22),
    ("lancet_left", "arch", 8.0 / 22, 13.0 / 19, 15.0 / 19, 0.44 / 22),
    ("lancet_right", "arch", 14.0 / 22, 13.0 / 19, 15.0 / 19, 0.44 / 22),
]
CHURCH_WIDTH, CHURCH_HEIGHT = 22.0, 19.0     # m, the wall at scale 1
CHURCH_BLOCKS_AT_SCALE_1 = 1674              # blocks (base included) written at scale 1, defaults


def _cross2(o, a, b):
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])


def _area2(poly):
    s = 0.0
    for i in range(len(poly)):
        x0, z0 = poly[i]
        x1, z1 = poly[(i + 1) % len(poly)]
        s += x0 * z1 - x1 * z0
    return 0.5 * s


def _clip(poly, a, b, keep_left):
    """Sutherland-Hodgman: the part of a convex polygon on the left (or right) of the line a->b."""
    sgn = 1.0 if keep_left else -1.0
    out = []
    n = len(poly)
    for i in range(n):
        p, q = poly[i], poly[(i + 1) % n]
        dp, dq = sgn * _cross2(a, b, p), sgn * _cross2(a, b, q)
        if dp >= 0.0:
            out.append(p)
        if (dp > 0.0 and dq < 0.0) or (dp < 0.0 and dq > 0.0):
            t = dp / (dp - dq)
            out.append((p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])))
    return out


def _clean(poly, tol=1e-9):
    """Drop repeated and collinear vertices (a collinear vertex would split one side face in two)."""
    pts = []
    for p in poly:
        if not pts or abs(p[0] - pts[-1][0]) > tol or abs(p[1] - pts[-1][1]) > tol:
            pts.append(p)
    while len(pts) > 1 and abs(pts[0][0] - pts[-1][0]) <= tol and abs(pts[0][1] - pts[-1][1]) <= tol:
        pts.pop()
    changed = True
    while changed and len(pts) >= 3:
        changed = False
        for i in range(len(pts)):
            a, p, b = pts[i - 1], pts[i], pts[(i + 1) % len(pts)]
            lab = math.hypot(b[0] - a[0], b[1] - a[1])
            if abs(_cross2(a, p, b)) <= tol * max(lab, 1.0):
                del pts[i]
                changed = True
                break
    return pts


def _segment_in_box(p, q, x0, x1, z0, z1):
    """Length fraction of segment p-q inside the open box (Liang-Barsky); 0 when it only touches."""
    t0, t1 = 0.0, 1.0
    dx, dz = q[0] - p[0], q[1] - p[1]
    for d, lo, hi, v in ((dx, x0, x1, p[0]), (dz, z0, z1, p[1])):
        if abs(d) < 1e-15:
            if not lo < v < hi:
                return 0.0
            continue
        ta, tb = (lo - v) / d, (hi - v) / d
        if ta > tb:
            ta, tb = tb, ta
        t0, t1 = max(t0, ta), min(t1, tb)
        if t1 <= t0:
            return 0.0
    return t1 - t0


def _circle_point(xc, zc, r, phi):
    """Point at angle phi on a circle; exact at the quarter angles, so springings stay on bed joints."""
    k = phi / (0.5 * math.pi)
    if abs(k - round(k)) < 1e-12:
        c, s = ((1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0))[int(round(k)) % 4]
    else:
        c, s = math.cos(phi), math.sin(phi)
    return (xc + r * c, zc + r * s)


class _Ring(object):
    """A ring of voussoirs: a round arch (half ring springing at zc) or a rose (full ring).

    The extrados is a polygon whose vertices are where the extrados circle crosses a bed joint
    (so each wall course meets one chord per side, and the wall pieces beside it stay convex
    without extra cuts), the springings, the crown and the bottom of a rose. Extra vertices
    between bed joints were tried: the vertical cuts they need left sliver triangles on the
    flanks. The intrados is the polygon of the voussoir joints. Voussoir j lies between the radial lines at two intrados angles, inside
    the extrados polygon and outside the intrados chord: a convex polygon whose outer faces are
    parts of extrados chords, so it shares planar faces with the wall pieces cut along them.
    """

    def __init__(self, name, xc, zc, ri, re, full, hb, voussoir_len):
        self.name, self.xc, self.zc, self.ri, self.re, self.full = name, xc, zc, ri, re, full
        two_pi = 2.0 * math.pi
        angles = {}  # angle -> exact point
        k_lo = int(math.floor((zc - re) / hb)) - 1
        k_hi = int(math.ceil((zc + re) / hb)) + 1
        for k in range(k_lo, k_hi + 1):
            z = k * hb
            if abs(z - zc) >= re - 1e-9 or (not full and z < zc - 1e-9):
                continue
            dx = math.sqrt(re * re - (z - zc) ** 2)
            phi = math.asin((z - zc) / re)
            angles[phi % two_pi] = (xc + dx, z)
            angles[(math.pi - phi) % two_pi] = (xc - dx, z)
        for phi in ((0.5 * math.pi, 1.5 * math.pi) if full else (0.0, 0.5 * math.pi, math.pi)):
            angles.setdefault(phi, _circle_point(xc, zc, re, phi))
        self.extrados = [(a, angles[a]) for a in sorted(angles)]  # (angle, point), increasing
        rm = 0.5 * (ri + re)
        span = two_pi if full else math.pi
        n = max(3, int(round(span * rm / voussoir_len)))
        if not full and n % 2 == 0:
            n += 1  # a keystone at the crown
        self.n_voussoirs = n
        offset = math.pi / n if full else 0.0
        self.joints = [offset + span * i / n for i in range(n + 1)]
        # the hole the ring and its void cut out of the wall (counter-clockwise)
        self.hole = [p for _, p in self.extrados]

    def _extrados_at(self, phi):
        """Where the ray from the centre at angle phi meets the extrados polygon."""
        ext = self.extrados
        two_pi = 2.0 * math.pi
        seq = ext + ([(ext[0][0] + two_pi, ext[0][1])] if self.full else [])
        if self.full:
            phi = phi % two_pi
            if phi < seq[0][0]:
                phi += two_pi
        for (a, pa), (b, pb) in zip(seq, seq[1:]):
            if abs(phi - a) < 1e-12:
                return pa
            if abs(phi - b) < 1e-12:
                return pb
            if a < phi < b:
                d = (math.cos(phi), math.sin(phi))
                ex, ez = pb[0] - pa[0], pb[1] - pa[1]
                # centre + t d = pa + s e
                det = d[0] * (-ez) - d[1] * (-ex)
                rx, rz = pa[0] - self.xc, pa[1] - self.zc
                s = (d[0] * rz - d[1] * rx) / det
                return (pa[0] + s * ex, pa[1] + s * ez)
        raise ValueError("%s: no extrados edge at angle %r" % (self.name, phi))

    def voussoirs(self):
        two_pi = 2.0 * math.pi
        ext = self.extrados
        if self.full:
            ext = ext + [(a + two_pi, p) for a, p in ext]
        for j in range(self.n_voussoirs):
            a, b = self.joints[j], self.joints[j + 1]
            poly = [_circle_point(self.xc, self.zc, self.ri, a),
                    _circle_point(self.xc, self.zc, self.ri, b),
                    self._extrados_at(b)]
            between = [p for phi, p in ext if a + 1e-12 < phi < b - 1e-12]
            poly += list(reversed(between))
            poly.append(self._extrados_at(a))
            yield _clean(poly)

    def bbox(self):
        z_lo = self.zc - self.re if self.full else self.zc
        return (self.xc - self.re, self.xc + self.re, z_lo, self.zc + self.re)


def church_layout(scale, bl, hb, ring_min, voussoir_len):
    """Wall size and openings at a scale: (nb blocks per course, nc courses, holes, rings, notes).

    Openings are placed in the order of CHURCH_OPENINGS (the most important first). Each keeps a
    block length from the wall's edges and a block length (a course height vertically) from the
    openings already placed; at small scales, where the rounded ring sizes make openings
    relatively larger, an opening that collides is moved up by up to 3 courses, and left out
    when that does not help. The notes say which.
    """
    nb = max(4, int(round(scale * CHURCH_WIDTH / 0.44)))
    nc = max(4, int(round(scale * CHURCH_HEIGHT / 0.50)))
    W, H = nb * bl, nc * hb
    holes, rings, boxes, notes = [], [], [], []

    def build(kind, name, xc, ri, fsill, fz, shift):
        ring_t = max(ring_min, 0.25 * ri)
        if kind == "arch":
            zs = (round(fz * H / hb) + shift) * hb
            sill = (round(fsill * H / hb) + (shift if fsill > 0.0 else 0)) * hb
            # extrados radius: the crown at mid-course, so no sliver course above it
            re = (math.ceil((ri + ring_t) / hb - 0.5) + 0.5) * hb
            if zs - sill < hb - SNAP:
                return None
            ring = _Ring(name, xc, zs, ri, re, False, hb, voussoir_len)
            rect = [(xc - ri, sill), (xc + ri, sill), (xc + ri, zs), (xc - ri, zs)]
            return ring, [rect, ring.hole], (xc - re, xc + re, sill, zs + re)
        zc = (math.floor(fz * H / hb) + 0.5 + shift) * hb
        re = math.ceil((ri + ring_t) / hb) * hb
        ring = _Ring(name, xc, zc, ri, re, True, hb, voussoir_len)
        return ring, [ring.hole], ring.bbox()

    def fits(a):
        if a[0] < bl - SNAP or a[1] > W - bl + SNAP or a[3] > H - hb + SNAP:
            return False
        return not any(a[0] < b[1] + bl and b[0] < a[1] + bl and a[2] < b[3] + hb
                       and b[2] < a[3] + hb for b in boxes)

    for name, kind, fx, fsill, fz, fr in CHURCH_OPENINGS:
        placed = None
        for shift in range(4):
            cand = build(kind, name, fx * W, fr * W, fsill, fz, shift)
            if cand is not None and fits(cand[2]):
                placed = cand
                if shift:
                    notes.append("%s moved up %d course%s" % (name, shift, "s" if shift > 1 else ""))
                break
        if placed is None:
            notes.append("%s left out (does not fit)" % name)
            continue
        ring, polys, box_ = placed
        holes.extend((name, poly) for poly in polys)
        rings.append(ring)
        boxes.append(box_)
    return nb, nc, holes, rings, notes


def church_course_pieces(c, nb, bl, hb, holes, min_joint_distance):
    """Convex pieces (x-z polygons) of course c of the running-bond wall with the holes cut out.

    Regular joints closer than min_joint_distance to where a hole's edge crosses the course are
    dropped (no slivers); the course is also cut below every hole vertex strictly inside it, so
    that in each cell at most one chord per side bounds the hole and the part outside the hole
    is an intersection of half-planes (convex); _convex_minus cuts each cell by each hole.
    """
    z0, z1 = c * hb, (c + 1) * hb
    L = nb * bl
    spans, cuts = [], []
    for _, poly in holes:
        n = len(poly)
        for i in range(n):
            p, q = poly[i], poly[(i + 1) % n]
            if z0 + SNAP < p[1] < z1 - SNAP:
                cuts.append(p[0])
            if _segment_in_box(p, q, -1e30, 1e30, z0, z1) <= 0.0:
                continue
            # x-range of the edge within the course
            xs = []
            for zz in (z0, z1):
                if (p[1] - zz) * (q[1] - zz) < 0.0:
                    xs.append(p[0] + (zz - p[1]) / (q[1] - p[1]) * (q[0] - p[0]))
            for r in (p, q):
                if z0 - SNAP <= r[1] <= z1 + SNAP:
                    xs.append(r[0])
            spans.append((min(xs), max(xs)))
    joints = [x for x in course_breakpoints(nb, bl, c % 2 == 1)
              if x <= SNAP or x >= L - SNAP
              or not any(a - min_joint_distance < x < b + min_joint_distance for a, b in spans)]
    xs = _merge_sorted(joints + cuts)
    pieces = []
    for xa, xb in zip(xs[:-1], xs[1:]):
        cell = [[(xa, z0), (xb, z0), (xb, z1), (xa, z1)]]
        for _, hole in holes:  # subtract the holes one after the other
            cell = [q for poly in cell for q in _convex_minus(poly, hole)]
        pieces.extend(cell)
    return pieces


def _convex_minus(poly, hole):
    """Convex pieces of convex poly minus convex hole (both counter-clockwise).

    With e_1..e_k the hole's edges that cross poly's interior, poly minus hole is the disjoint
    union of poly & out(e_i) & in(e_1) & ... & in(e_{i-1}): a point of poly outside the hole is
    on the outer side of an edge that crosses poly (the segment from it to a point of poly
    inside the hole crosses the hole's boundary inside poly).
    """
    n = len(hole)
    xs = [p[0] for p in poly]
    zs = [p[1] for p in poly]
    box_ = (min(xs), max(xs), min(zs), max(zs))
    edges = []
    for i in range(n):
        a, b = hole[i], hole[(i + 1) % n]
        if _segment_in_box(a, b, *box_) <= 1e-12:
            continue
        # the edge crosses poly's interior when poly has vertices strictly on both sides
        sides = [_cross2(a, b, p) for p in poly]
        if max(sides) > 1e-12 and min(sides) < -1e-12:
            edges.append((a, b))
    if not edges:
        mx = sum(xs) / len(xs)
        mz = sum(zs) / len(zs)
        inside = all(_cross2(hole[i], hole[(i + 1) % n], (mx, mz)) > 0.0 for i in range(n))
        return [] if inside else [poly]
    out = []
    for i, (a, b) in enumerate(edges):
        piece = poly
        for a2, b2 in edges[:i]:
            piece = _clip(piece, a2, b2, True)
        piece = _clip(piece, a, b, False)
        piece = _clean(piece) if len(piece) >= 3 else []
        if len(piece) >= 3 and abs(_area2(piece)) > 1e-9:
            out.append(piece)
    return out


def scene_church(args):
    bl, bt, hb = args.block_length, args.block_thickness, args.block_height
    if args.blocks is not None:
        scale = math.sqrt(args.blocks / float(CHURCH_BLOCKS_AT_SCALE_1))
    else:
        scale = args.scale
    nb, nc, holes, rings, notes = church_layout(scale, bl, hb, args.ring_thickness,
                                                args.voussoir_length)
    L = nb * bl
    m, t = args.base_margin, args.base_thickness
    model = model_skeleton("", args)
    blocks = model["blocks"]
    f = args.settling_fraction if args.load == "settlement" else None
    _add_base(blocks, L, m, t, bt, f, args.support_gap, "church")
    if f is not None:
        what = "a fixed base and a moving support under the right %g %%; settlement" % (100 * f)
        model["analysis"] = {"type": "settlement"}
    else:
        axis = args.load[-1]
        what = "a fixed base; seismic +%s (%s)" % (axis, "in plane" if axis == "x" else "out of plane")
        model["analysis"] = seismic_analysis([1, 0, 0] if axis == "x" else [0, 1, 0])
    wc = len(str(nc - 1))
    n_wall = 0
    min_area = float("inf")
    for c in range(nc):
        pieces = church_course_pieces(c, nb, bl, hb, holes, args.joint_clearance * bl)
        wk = len(str(max(len(pieces) - 1, 1)))
        for k, poly in enumerate(pieces):
            min_area = min(min_area, abs(_area2(poly)))
            blocks.append(make_block("r%0*d_%0*d" % (wc, c, wk, k), *prism_xz(poly, 0.0, bt)))
        n_wall += len(pieces)
    n_vous = 0
    for ring in rings:
        wv = len(str(ring.n_voussoirs - 1))
        for j, poly in enumerate(ring.voussoirs()):
            min_area = min(min_area, abs(_area2(poly)))
            blocks.append(make_block("%s_v%0*d" % (ring.name, wv, j), *prism_xz(poly, 0.0, bt)))
            n_vous += 1
    model["title"] = ("church facade %g x %g m (scale %.4g): running bond of %g x %g x %g m blocks "
                      "(length x course height x thickness) with arched openings (%s)%s; "
                      "%d blocks on %s"
                      % (L, nc * hb, scale, bl, hb, bt, ", ".join(r.name for r in rings),
                         "; " + "; ".join(notes) if notes else "", len(blocks), what))
    sys.stderr.write("church: scale %.4g, wall %g x %g m (%d courses of %d blocks), %d wall pieces, "
                     "%d voussoirs in %d rings, %d blocks in all; smallest block face %.3g m2%s\n"
                     % (scale, L, nc * hb, nc, nb, n_wall, n_vous, len(rings), len(blocks), min_area,
                        "".join("; " + n for n in notes)))
    return model


# --------------------------------------------------------------------------------------------
# Shells of voussoirs in the style of COMPAS exports: a dome and a freeform vault
# --------------------------------------------------------------------------------------------

def hexahedron(bottom, top):
    """A block from two quads of corresponding corners (bottom[i] joined to top[i]).

    Faces: the two quads and four side quads, oriented outward (reversed together when the
    corners come in the other order). The faces need not be planar: offset surfaces give warped
    quads, exactly as CAD voussoirs made from a mesh do.
    """
    vertices = [[_r(c) for c in p] for p in list(bottom) + list(top)]
    faces = [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]]
    vol, _ = volume_centroid(vertices, faces)
    if vol < 0.0:
        faces = [list(reversed(f)) for f in faces]
    return vertices, faces


def staggered_voussoir(bottom, top):
    """A dome voussoir whose bed faces carry a vertex at their middle, where the neighbouring
    courses' joints fall. bottom and top are rings [inner 0, inner mid, inner 1, outer 1, outer mid,
    outer 0]; bottom[i] is joined to top[i].

    A bed face lies on a cone through the dome's centre, so a chord face across a whole voussoir
    would cut the neighbouring course's chords: with 16 voussoirs per course the staggered beds
    overlapped by 3 cm and gaped by 6 cm on a 10 m dome. Split at the middle, each half is a quad
    between two rays from the centre (planar) and is exactly the neighbour's half. The inner and
    outer halves are isosceles trapezoids of a sphere (planar)."""
    vertices = [[_r(c) for c in p] for p in list(bottom) + list(top)]
    faces = [[5, 4, 1, 0], [4, 3, 2, 1], [6, 7, 10, 11], [7, 8, 9, 10]]
    faces += [[j, (j + 1) % 6, 6 + (j + 1) % 6, 6 + j] for j in range(6)]
    vol, _ = volume_centroid(vertices, faces)
    if vol < 0.0:
        faces = [list(reversed(f)) for f in faces]
    return vertices, faces


def scene_dome(args):
    """Hemispherical dome of voussoirs between meridian and parallel planes, courses staggered
    by half a voussoir (so every bed face carries two voussoirs above), an oculus at the top,
    springing at z = 0 on a fixed square slab. Clean faces are planar: a quad between two
    meridians and two parallels of a sphere is an isosceles trapezoid, and a staggered voussoir's
    bed faces are split where the neighbouring joints fall (staggered_voussoir)."""
    R, t, nr, ns = args.radius, args.thickness, args.rings, args.segments
    top = math.radians(args.oculus)
    if not 0.0 < top < math.pi / 2 or t >= R:
        raise SystemExit("dome: the oculus must be in (0, 90) degrees and the thickness below R")
    ri, re = R - t / 2.0, R + t / 2.0
    m, tb = args.base_margin, args.base_thickness
    model = model_skeleton("hemispherical dome of %d voussoirs (%d courses x %d), R = %g m, "
                           "t = %g m, oculus at %g deg, on a fixed slab; seismic +x"
                           % (nr * ns, nr, ns, R, t, args.oculus), args)
    blocks = model["blocks"]
    blocks.append(make_block("base", *box(-re - m, re + m, -re - m, re + m, -tb, 0.0), role="fixed"))

    def point(r, theta, phi):
        # theta from the vertical axis; the springing course starts at theta = 90 deg (z = 0)
        z = 0.0 if abs(theta - math.pi / 2) < 1e-15 else r * math.cos(theta)
        return (r * math.sin(theta) * math.cos(phi), r * math.sin(theta) * math.sin(phi), z)

    def ring(theta, phis):
        return [point(ri, theta, p) for p in phis] + [point(re, theta, p) for p in reversed(phis)]
    split_beds = args.stagger and nr > 1 and not args.crossing_beds
    wr, ws = len(str(nr - 1)), len(str(ns - 1))
    for k in range(nr):
        th0 = math.pi / 2 - (math.pi / 2 - top) * k / nr
        th1 = math.pi / 2 - (math.pi / 2 - top) * (k + 1) / nr
        shift = 0.5 if (args.stagger and k % 2) else 0.0
        for j in range(ns):
            name = "d%0*d_%0*d" % (wr, k, ws, j)
            ph0 = 2.0 * math.pi * (j + shift) / ns
            ph1 = 2.0 * math.pi * (j + 1 + shift) / ns
            if split_beds:
                phis = [ph0, 0.5 * (ph0 + ph1), ph1]
                blocks.append(make_block(name, *staggered_voussoir(ring(th0, phis), ring(th1, phis))))
            else:
                blocks.append(make_block(name, *hexahedron(ring(th0, [ph0, ph1]), ring(th1, [ph0, ph1]))))
    model["analysis"] = seismic_analysis([1, 0, 0])
    return model


def scene_vault(args):
    """Freeform barrel vault: the mid-surface z = H (1 - (x/a)^2) (1 + c sin(pi y / L)) over
    [-a, a] x [0, L], cut into an nu x nv quad mesh and offset by +-t/2 along the vertex normals
    (as COMPAS materialises a form-found mesh). Neighbouring voussoirs share their joint faces
    exactly, but those faces, like the intrados and extrados, are warped (the surface is doubly
    curved). The two long edges stand on a fixed slab: their offsets are horizontal there, so
    every foot is a horizontal face at z = 0 (2 nv feet)."""
    a, L, H, t, c = args.half_span, args.length, args.rise, args.thickness, args.wave
    nu, nv = args.nu, args.nv
    m, tb = args.base_margin, args.base_thickness
    model = model_skeleton("freeform barrel vault of %d voussoirs (%d x %d), span %g m, length %g m, "
                           "rise %g m (x (1 + %g sin)), t = %g m, warped faces, %d feet on a fixed "
                           "slab; seismic +x" % (nu * nv, nu, nv, 2 * a, L, H, c, t, 2 * nv), args)
    blocks = model["blocks"]
    blocks.append(make_block("base", *box(-a - t - m, a + t + m, -m, L + m, -tb, 0.0), role="fixed"))

    def mid(i, j):
        x, y = -a + 2.0 * a * i / nu, L * j / float(nv)
        g = 1.0 + c * math.sin(math.pi * y / L)
        z = H * (1.0 - (x / a) ** 2) * g
        fx = -2.0 * H * x / a ** 2 * g
        fy = H * (1.0 - (x / a) ** 2) * c * math.pi / L * math.cos(math.pi * y / L)
        if i in (0, nu):  # a foot: offset horizontally, the foot face lies on the ground
            n = (-fx, -fy, 0.0)
            z = 0.0
        else:
            n = (-fx, -fy, 1.0)
        ln = math.sqrt(_dot(n, n))
        return (x, y, z), (n[0] / ln, n[1] / ln, n[2] / ln)

    def offset(i, j, side):
        p, n = mid(i, j)
        return tuple(p[k] + side * 0.5 * t * n[k] for k in range(3))
    wu, wv = len(str(nu - 1)), len(str(nv - 1))
    for i in range(nu):
        for j in range(nv):
            corners = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)]
            intrados = [offset(p, q, -1.0) for p, q in corners]
            extrados = [offset(p, q, 1.0) for p, q in corners]
            blocks.append(make_block("v%0*d_%0*d" % (wu, i, wv, j), *hexahedron(intrados, extrados)))
    model["analysis"] = seismic_analysis([1, 0, 0])
    return model


# --------------------------------------------------------------------------------------------
# CLI
# --------------------------------------------------------------------------------------------

BUNDLED = [
    ("block.json", "block"),
    ("column.json", "column"),
    ("arch.json", "arch"),
    ("wall_opening.json", "wall-opening"),
    ("wall_settlement.json", "wall-settlement"),
]

SCENES = {
    "block": scene_block,
    "column": scene_column,
    "arch": scene_arch,
    "wall-opening": scene_wall_opening,
    "wall-settlement": scene_wall_settlement,
    "facade": scene_facade,
    "church": scene_church,
    "townhouse": scene_townhouse,
    "dome": scene_dome,
    "vault": scene_vault,
}


def build_parser():
    common = argparse.ArgumentParser(add_help=False)
    common.add_argument("--unit-weight", type=float, default=18.0,
                        help="unit weight of the blocks, kN/m3 (default 18)")
    common.add_argument("--friction", type=float, default=0.6,
                        help="friction coefficient mu (default 0.6)")
    common.add_argument("--self-check", action="store_true",
                        help="check every block's closure, orientation, volume and centroid")
    out = argparse.ArgumentParser(add_help=False)
    out.add_argument("-o", "--output", default=None, help="output file (default stdout)")
    fmt = out.add_mutually_exclusive_group()
    fmt.add_argument("--compact", dest="compact", action="store_true", default=None,
                     help="write the JSON on one line")
    fmt.add_argument("--pretty", dest="compact", action="store_false",
                     help="write the JSON one block per line")
    base = argparse.ArgumentParser(add_help=False)
    base.add_argument("--base-margin", type=float, default=0.5,
                      help="how far the base slab extends beyond the structure, m (default 0.5)")
    base.add_argument("--base-thickness", type=float, default=0.5,
                      help="base slab thickness, m (default 0.5)")

    imperf = argparse.ArgumentParser(add_help=False)
    imperfections.add_arguments(imperf)

    p = argparse.ArgumentParser(description=__doc__.split("\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter,
                                epilog="Run '<subcommand> -h' for a scene's options.")
    sub = p.add_subparsers(dest="scene", metavar="SCENE")
    sub.required = True
    D = argparse.ArgumentDefaultsHelpFormatter

    s = sub.add_parser("block", parents=[common, out, base, imperf], formatter_class=D,
                       help="a single block on a fixed base, seismic +x (alpha = min(b/h, mu))")
    s.add_argument("--width", type=float, default=1.0, help="b, along x, m")
    s.add_argument("--depth", type=float, default=1.0, help="d, along y, m")
    s.add_argument("--height", type=float, default=2.0, help="h, along z, m")

    s = sub.add_parser("column", parents=[common, out, base, imperf], formatter_class=D,
                       help="n stacked blocks on a fixed base, seismic +x (alpha = min(b/H, mu))")
    s.add_argument("--count", type=int, default=4, help="number of blocks")
    s.add_argument("--width", type=float, default=0.5, help="b, along x, m")
    s.add_argument("--depth", type=float, default=0.5, help="along y, m")
    s.add_argument("--block-height", type=float, default=0.5, help="height of one block, m")

    s = sub.add_parser("arch", parents=[common, out, imperf], formatter_class=D,
                       help="semicircular arch of radial voussoirs on fixed abutments, seismic +x")
    s.add_argument("--voussoirs", type=int, default=16, help="N")
    s.add_argument("--radius", type=float, default=5.0, help="centreline radius R, m")
    s.add_argument("--thickness", type=float, default=0.8, help="radial thickness t, m")
    s.add_argument("--depth", type=float, default=1.0, help="depth along y, m")
    s.add_argument("--abutment-margin", type=float, default=0.5,
                   help="how far each abutment extends beyond the springing joint, m")
    s.add_argument("--abutment-height", type=float, default=1.0, help="abutment height, m")

    wall = argparse.ArgumentParser(add_help=False)
    wall.add_argument("--block-length", type=float, default=0.44, help="along x, m")
    wall.add_argument("--block-thickness", type=float, default=0.38, help="along y, m")
    wall.add_argument("--block-height", type=float, default=0.25, help="along z, m")

    s = sub.add_parser("wall-opening", parents=[common, out, base, wall, imperf], formatter_class=D,
                       help="running-bond wall with a window and a lintel, seismic +x")
    s.add_argument("--courses", type=int, default=12, help="number of courses")
    s.add_argument("--blocks", type=int, default=10, help="whole blocks per course")
    s.add_argument("--opening-width", type=int, default=2, help="opening width in blocks (centred)")
    s.add_argument("--opening-height", type=int, default=4, help="opening height in courses")
    s.add_argument("--sill-course", type=int, default=None,
                   help="first course of the opening (default: centred)")
    s.add_argument("--lintel-bearing", type=float, default=0.44,
                   help="how far the lintel runs past each jamb, m")

    gap_help = ("gap between the fixed and the moving base blocks, m: two supports that touch "
                "would form an interface that can hold the moving one")
    s = sub.add_parser("wall-settlement", parents=[common, out, base, wall, imperf], formatter_class=D,
                       help="running-bond wall on a fixed and a moving base block, settlement")
    s.add_argument("--courses", type=int, default=10, help="number of courses")
    s.add_argument("--blocks", type=int, default=12, help="whole blocks per course")
    s.add_argument("--settling-fraction", type=float, default=0.4,
                   help="fraction of the wall length (right end) over the moving support")
    s.add_argument("--support-gap", type=float, default=0.01, help=gap_help)

    s = sub.add_parser("facade", parents=[common, out, base, imperf], formatter_class=D,
                       help="façade-scale running-bond wall (default 50 x 38, ~1900 blocks)")
    s.add_argument("--nx", type=int, default=50, help="whole blocks per course")
    s.add_argument("--ny", type=int, default=38, help="number of courses")
    s.add_argument("--block-length", type=float, default=0.44, help="along x, m")
    s.add_argument("--block-thickness", type=float, default=0.38, help="along y, m")
    s.add_argument("--block-height", type=float, default=0.50, help="along z, m")
    g = s.add_mutually_exclusive_group()
    g.add_argument("--settling-fraction", type=float, default=None,
                   help="make the right F of the base a moving support; settlement analysis")
    g.add_argument("--seismic", choices=["x", "y"], default=None,
                   help="seismic analysis along +x or +y (the default is +x)")
    s.add_argument("--support-gap", type=float, default=0.01, help=gap_help)

    s = sub.add_parser("church", parents=[common, out, base, imperf], formatter_class=D,
                       help="church facade with arched doors and windows and a rose window "
                            "(~1900 blocks; --scale or --blocks from ~200 to ~50000)")
    g = s.add_mutually_exclusive_group()
    g.add_argument("--scale", type=float, default=1.0,
                   help="linear scale of the 22 x 19 m wall and of its openings; the blocks keep "
                        "their size, so the block count grows as scale^2")
    g.add_argument("--blocks", type=int, default=None,
                   help="approximate number of blocks: sets scale = sqrt(N / %d)"
                        % CHURCH_BLOCKS_AT_SCALE_1)
    s.add_argument("--load", choices=["settlement", "seismic-x", "seismic-y"], default="settlement",
                   help="settlement of the right part of the base, or seismic along +x (in plane, "
                        "planar LP) or +y (out of plane, 3-D)")
    s.add_argument("--settling-fraction", type=float, default=0.5,
                   help="fraction of the wall length (right end) over the moving support")
    s.add_argument("--support-gap", type=float, default=0.01, help=gap_help)
    s.add_argument("--block-length", type=float, default=0.44, help="along x, m")
    s.add_argument("--block-height", type=float, default=0.50, help="course height, along z, m")
    s.add_argument("--block-thickness", type=float, default=0.38, help="along y, m")
    s.add_argument("--ring-thickness", type=float, default=0.30,
                   help="smallest voussoir ring thickness, m (also at least a quarter of the "
                        "opening's radius; rounded up so the crown is at mid-course)")
    s.add_argument("--voussoir-length", type=float, default=0.45,
                   help="target length of a voussoir along the ring's mid-line, m")
    s.add_argument("--joint-clearance", type=float, default=0.35,
                   help="running-bond joints closer than this many block lengths to an opening's "
                        "edge are dropped, so no sliver is cut")

    s = sub.add_parser("townhouse", parents=[common, out, base, imperf], formatter_class=D,
                       help="town-house facade in English bond with storeys of windows, flat "
                            "lintels and a door (5 x 3 bays x storeys: ~2000 blocks)")
    s.add_argument("--bays", type=int, default=5, help="window bays along the facade (3.5 m each "
                   "at the default block length)")
    s.add_argument("--storeys", type=int, default=3, help="storeys of %d courses"
                   % TOWNHOUSE_STOREY_COURSES)
    s.add_argument("--load", choices=["settlement", "seismic-x"], default="seismic-x",
                   help="settlement of the right part of the base, or seismic along +x (in plane)")
    s.add_argument("--settling-fraction", type=float, default=0.5,
                   help="fraction of the wall length (right end) over the moving support")
    s.add_argument("--support-gap", type=float, default=0.01, help=gap_help)
    s.add_argument("--block-length", type=float, default=0.44, help="stretcher length along x, m")
    s.add_argument("--block-height", type=float, default=0.25, help="course height, along z, m")
    s.add_argument("--block-thickness", type=float, default=0.45, help="along y, m")

    s = sub.add_parser("dome", parents=[common, out, base, imperf], formatter_class=D,
                       help="hemispherical dome of staggered voussoirs with an oculus, on a fixed "
                            "slab, seismic +x (3-D)")
    s.add_argument("--radius", type=float, default=7.5, help="mid-surface radius R, m")
    s.add_argument("--thickness", type=float, default=0.5, help="shell thickness t, m")
    s.add_argument("--rings", type=int, default=12, help="courses from the springing to the oculus")
    s.add_argument("--segments", type=int, default=40, help="voussoirs per course")
    s.add_argument("--oculus", type=float, default=15.0,
                   help="half-angle of the oculus seen from the centre, degrees")
    s.add_argument("--no-stagger", dest="stagger", action="store_false",
                   help="align the meridian joints of all courses")
    s.add_argument("--crossing-beds", action="store_true",
                   help="one chord face per bed, as faceted CAD domes are drawn: the staggered "
                        "courses' beds then cross at a few degrees (overlaps and gaps of "
                        "centimetres when a course has few voussoirs)")

    s = sub.add_parser("vault", parents=[common, out, base, imperf], formatter_class=D,
                       help="freeform barrel vault of voussoirs with warped faces (an offset quad "
                            "mesh), feet on a fixed slab, seismic +x (3-D)")
    s.add_argument("--half-span", type=float, default=4.0, help="a: the feet are at x = +-a, m")
    s.add_argument("--length", type=float, default=10.0, help="L, along y, m")
    s.add_argument("--rise", type=float, default=3.0, help="H at the ends, m")
    s.add_argument("--wave", type=float, default=0.3,
                   help="c: the crown rises to H (1 + c) at mid-length (double curvature)")
    s.add_argument("--thickness", type=float, default=0.4, help="t, m")
    s.add_argument("--nu", type=int, default=20, help="voussoirs across the span")
    s.add_argument("--nv", type=int, default=30, help="voussoirs along the length")

    s = sub.add_parser("all", parents=[common], formatter_class=D,
                       help="regenerate every bundled sample with its default sizes")
    s.add_argument("--dir", default=os.path.dirname(os.path.abspath(__file__)),
                   help="output directory")
    return p


def _planar_faces(args):
    """Whether the scene's faces are planar: not for the vault (offset surfaces) nor after
    imperfections that move vertices."""
    return args.scene != "vault" and not (args.noise or args.warp)


def main(argv=None):
    p = build_parser()
    args = p.parse_args(argv)
    t0 = time.time()
    if args.scene == "all":
        ok = True
        for fname, scene in BUNDLED:
            # defaults of that scene, with the common options of this call
            sargs = p.parse_args([scene, "--unit-weight", repr(args.unit_weight),
                                  "--friction", repr(args.friction)])
            model = SCENES[scene](sargs)
            if args.self_check and not self_check(model, fname):
                ok = False
                continue
            path = os.path.join(args.dir, fname)
            write_model(model, path, compact=False)
            sys.stderr.write("wrote %s (%d blocks)\n" % (path, len(model["blocks"])))
        return 0 if ok else 1
    model = SCENES[args.scene](args)
    imperfections.apply(model, args, make_block)
    if args.self_check and not self_check(model, args.scene, planar=_planar_faces(args)):
        return 1
    compact = args.compact
    if compact is None:
        compact = len(model["blocks"]) > 200
    write_model(model, args.output, compact)
    if args.output not in (None, "-"):
        sys.stderr.write("wrote %s (%d blocks, %.2f s)\n"
                         % (args.output, len(model["blocks"]), time.time() - t0))
    return 0


if __name__ == "__main__":
    sys.exit(main())
