"""Planar pieces of interface objects and points near blocks (host-independent, standard library).

The .3dm exchange has the same functions in plugin/exchange/lib/cad-geometry.mjs; both are run
on the shared cases of tests/plugin/cad_cases/ and must give the same polygons, so the two keep
the same steps in the same order (floating-point results then agree to the last bits).

``merge_coplanar(pieces, tol)``: a joint drawn as two triangles, a mesh or a polysurface is ONE
interface. Pieces are grouped by plane (every corner within ``tol`` of the plane of the group's
first piece), their corners are snapped together within ``tol``, edges are split where another
corner lies on them (T-junctions), and pieces sharing an edge are joined. The outline of a
group is what is left when every shared edge cancels against its reverse; when that is not one
simple loop (pieces that overlap or leave a hole) the convex hull of the corners is used: with
contact forces at the corners (no tension, Coulomb friction) any force system on points inside
the hull is a sum of forces at the hull's corners with the same resultant and moment, so the
statics are the same.
"""

import math

from . import geometry as geo


def unit_normal(points):
    """(unit normal, area) of a polygon by Newell's method; ((0, 0, 0), 0) when degenerate."""
    n = geo.newell_normal(points)
    a = geo.norm(n)
    if a == 0.0:
        return (0.0, 0.0, 0.0), 0.0
    return (n[0] / a, n[1] / a, n[2] / a), a


def _mean(points):
    # a plain running sum (not sum(), which compensates since Python 3.12): the JS side adds
    # the same way, and the interface polygons of both readers must agree to the last bits
    s = [0.0, 0.0, 0.0]
    for p in points:
        for c in range(3):
            s[c] += p[c]
    k = float(len(points))
    return (s[0] / k, s[1] / k, s[2] / k)


def plane_basis(n):
    """Two unit vectors u, v with (u, v, n) right-handed; the same choice as the JS side."""
    e = (1.0, 0.0, 0.0) if abs(n[0]) < 0.9 else (0.0, 1.0, 0.0)
    d = geo.dot(e, n)
    u = (e[0] - d * n[0], e[1] - d * n[1], e[2] - d * n[2])
    lu = geo.norm(u)
    u = (u[0] / lu, u[1] / lu, u[2] / lu)
    return u, geo.cross(n, u)


def _cluster_planes(pieces, tol):
    """Greedy plane groups in piece order: [[(piece index, oriented points)]]."""
    planes = []
    for i, pts in enumerate(pieces):
        n, area = unit_normal(pts)
        if area == 0.0:
            continue
        for plane in planes:
            pn, po, members = plane
            if all(abs(geo.dot(geo.sub(p, po), pn)) <= tol for p in pts):
                members.append((i, pts if geo.dot(n, pn) >= 0.0 else list(reversed(pts))))
                break
        else:
            planes.append((n, _mean(pts), [(i, list(pts))]))
    return [members for _, _, members in planes]


def _fitted_plane(members):
    """(unit normal, origin): the area-weighted normal and the mean corner of the pieces."""
    s = [0.0, 0.0, 0.0]
    corners = []
    for _, pts in members:
        a = geo.newell_normal(pts)
        for c in range(3):
            s[c] += a[c]
        corners.extend(pts)
    ln = geo.norm(s)
    return (s[0] / ln, s[1] / ln, s[2] / ln), _mean(corners)


def plane_tolerance(pieces, tol, relative):
    """max(tol, relative x the diagonal of the pieces' bounding box)."""
    lo, hi = geo.bounding_box([p for pts in pieces for p in pts])
    return max(tol, relative * geo.norm(geo.sub(hi, lo)))


def _snap(members, origin, u, v, tol):
    """Unique 2-D corners (within tol) and each piece's loop of corner indices."""
    pts2 = []
    loops = []
    for _, pts in members:
        loop = []
        for p in pts:
            d = geo.sub(p, origin)
            q = (geo.dot(d, u), geo.dot(d, v))
            k = -1
            for j, r in enumerate(pts2):
                dx, dy = q[0] - r[0], q[1] - r[1]
                if math.sqrt(dx * dx + dy * dy) <= tol:
                    k = j
                    break
            if k < 0:
                k = len(pts2)
                pts2.append(q)
            if not loop or loop[-1] != k:
                loop.append(k)
        while len(loop) > 1 and loop[0] == loop[-1]:
            loop.pop()
        loops.append(loop)
    return pts2, loops


def _segment_param(p, a, b):
    """(t, distance) of p's projection on segment ab."""
    dx, dy = b[0] - a[0], b[1] - a[1]
    ll = dx * dx + dy * dy
    t = ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / ll if ll > 0.0 else 0.0
    t = min(1.0, max(0.0, t))
    ex, ey = p[0] - (a[0] + t * dx), p[1] - (a[1] + t * dy)
    return t, math.sqrt(ex * ex + ey * ey)


def _split_t_junctions(pts2, loops, tol):
    out = []
    for loop in loops:
        new = []
        m = len(loop)
        for j in range(m):
            a, b = loop[j], loop[(j + 1) % m]
            new.append(a)
            inner = []
            for k, p in enumerate(pts2):
                if k == a or k == b:
                    continue
                t, dist = _segment_param(p, pts2[a], pts2[b])
                if 0.0 < t < 1.0 and dist <= tol:
                    inner.append((t, k))
            inner.sort()
            new.extend(k for _, k in inner)
        out.append(new)
    return out


def _area2(pts2, loop):
    s = 0.0
    m = len(loop)
    for j in range(m):
        a, b = pts2[loop[j]], pts2[loop[(j + 1) % m]]
        s += a[0] * b[1] - b[0] * a[1]
    return 0.5 * s


def _inside2(p, pts2, loop, tol):
    """p strictly inside the loop (even-odd rule), farther than tol from its edges."""
    m = len(loop)
    inside = False
    for j in range(m):
        a, b = pts2[loop[j]], pts2[loop[(j + 1) % m]]
        if _segment_param(p, a, b)[1] <= tol:
            return False
        if (a[1] > p[1]) != (b[1] > p[1]):
            x = a[0] + (p[1] - a[1]) * (b[0] - a[0]) / (b[1] - a[1])
            if p[0] < x:
                inside = not inside
    return inside


def _cross2(o, a, b):
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])


def _edges_cross(pts2, la, lb):
    """Two loops' edges cross properly (interiors of both segments)."""
    for j in range(len(la)):
        a, b = pts2[la[j]], pts2[la[(j + 1) % len(la)]]
        for k in range(len(lb)):
            c, d = pts2[lb[k]], pts2[lb[(k + 1) % len(lb)]]
            if len({la[j], la[(j + 1) % len(la)], lb[k], lb[(k + 1) % len(lb)]}) < 4:
                continue
            d1, d2 = _cross2(a, b, c), _cross2(a, b, d)
            d3, d4 = _cross2(c, d, a), _cross2(c, d, b)
            if ((d1 > 0) != (d2 > 0)) and ((d3 > 0) != (d4 > 0)) and \
                    d1 != 0 and d2 != 0 and d3 != 0 and d4 != 0:
                return True
    return False


def _overlap(pts2, la, lb, tol):
    if any(_inside2(pts2[k], pts2, lb, tol) for k in la if k not in lb):
        return True
    if any(_inside2(pts2[k], pts2, la, tol) for k in lb if k not in la):
        return True
    return _edges_cross(pts2, la, lb)


class _Union(object):
    def __init__(self, n):
        self.parent = list(range(n))

    def find(self, i):
        while self.parent[i] != i:
            self.parent[i] = self.parent[self.parent[i]]
            i = self.parent[i]
        return i

    def join(self, i, j):
        a, b = self.find(i), self.find(j)
        if a != b:
            self.parent[max(a, b)] = min(a, b)


def _components(pts2, loops, tol):
    """Groups of pieces that share an edge or overlap; overlapping groups are flagged."""
    n = len(loops)
    uf = _Union(n)
    seen = {}
    overlap = set()
    for i, loop in enumerate(loops):
        m = len(loop)
        for j in range(m):
            e = (loop[j], loop[(j + 1) % m])
            for (i2, e2) in seen.get((min(e), max(e)), []):
                uf.join(i, i2)
                if e2 == e:  # the same edge in the same direction: the pieces lie on one side
                    overlap.add(i)
            seen.setdefault((min(e), max(e)), []).append((i, e))
    for i in range(n):
        for k in range(i + 1, n):
            if uf.find(i) != uf.find(k) and _overlap(pts2, loops[i], loops[k], tol):
                uf.join(i, k)
                overlap.add(i)
    groups = {}
    for i in range(n):
        groups.setdefault(uf.find(i), []).append(i)
    out = []
    for root in sorted(groups):
        members = groups[root]
        out.append((members, any(i in overlap for i in members)))
    return out


def _trace(pts2, loops, members):
    """The single outline loop of the pieces, or None (several loops, a pinch, no edges)."""
    net = {}
    order = []
    for i in members:
        loop = loops[i]
        m = len(loop)
        for j in range(m):
            a, b = loop[j], loop[(j + 1) % m]
            key = (min(a, b), max(a, b))
            if key not in net:
                net[key] = 0
                order.append(key)
            net[key] += 1 if a < b else -1
    nxt = {}
    first = None
    for key in order:
        c = net[key]
        if c == 0:
            continue
        if abs(c) > 1:
            return None
        a, b = key if c > 0 else (key[1], key[0])
        if a in nxt:
            return None
        nxt[a] = b
        if first is None:
            first = a
    if first is None:
        return None
    loop = [first]
    while True:
        b = nxt.get(loop[-1])
        if b is None:
            return None
        if b == first:
            break
        if len(loop) > len(nxt):
            return None
        loop.append(b)
    return loop if len(loop) == len(nxt) else None


def _drop_collinear(pts2, loop, tol):
    changed = True
    while changed and len(loop) > 3:
        changed = False
        m = len(loop)
        for j in range(m):
            a, b, c = pts2[loop[j - 1]], pts2[loop[j]], pts2[loop[(j + 1) % m]]
            if _segment_param(b, a, c)[1] <= tol:
                del loop[j]
                changed = True
                break
    return loop


def _hull(pts2, members, loops):
    """Convex hull (Andrew's monotone chain), counter-clockwise, of the pieces' corners."""
    idx = sorted({k for i in members for k in loops[i]}, key=lambda k: (pts2[k][0], pts2[k][1]))
    if len(idx) < 3:
        return idx

    def half(seq):
        h = []
        for k in seq:
            while len(h) >= 2 and _cross2(pts2[h[-2]], pts2[h[-1]], pts2[k]) <= 0:
                h.pop()
            h.append(k)
        return h
    lower, upper = half(idx), half(list(reversed(idx)))
    return lower[:-1] + upper[:-1]


def merge_coplanar(pieces, tol, relative=0.0):
    """Merge planar pieces (lists of 3-D points) into interfaces.

    Returns a list of dicts {polygon: [3-D points], pieces: [piece indices], hull: bool}: one
    per group of coplanar pieces that touch (share an edge) or overlap. Pieces are coplanar
    within ``plane_tolerance(pieces, tol, relative)``, which also drops corners that lie on a
    straight outline; corners closer than ``tol`` are one corner. Degenerate pieces (zero area)
    are left out. ``hull`` says the outline could not be traced and the convex hull of the
    corners is used."""
    out = []
    if not pieces:
        return out
    ptol = plane_tolerance(pieces, tol, relative)
    for members in _cluster_planes(pieces, ptol):
        n, origin = _fitted_plane(members)
        u, v = plane_basis(n)
        pts2, loops = _snap(members, origin, u, v, tol)
        keep = [j for j, loop in enumerate(loops) if len(loop) >= 3 and
                abs(_area2(pts2, loop)) > tol * tol]
        members = [members[j] for j in keep]
        loops = _split_t_junctions(pts2, [loops[j] for j in keep], tol)
        for group, overlap in _components(pts2, loops, tol):
            loop = None if overlap else _trace(pts2, loops, group)
            if loop is not None:
                total = sum(abs(_area2(pts2, loops[i])) for i in group)
                if abs(abs(_area2(pts2, loop)) - total) > 1e-9 * total + tol * tol:
                    loop = None
            hull = loop is None
            loop = _hull(pts2, group, loops) if hull else _drop_collinear(pts2, loop, ptol)
            poly = [tuple(origin[c] + pts2[k][0] * u[c] + pts2[k][1] * v[c] for c in range(3))
                    for k in loop]
            out.append({"polygon": [list(p) for p in poly],
                        "pieces": [members[i][0] for i in group], "hull": hull})
    return out


# ------------------------------------------------------------------ points and block surfaces

def point_polygon_distance(p, polygon):
    """Distance from a 3-D point to a planar polygon (any simple polygon, convex or not)."""
    n, area = unit_normal(polygon)
    if area == 0.0:
        return min(geo.norm(geo.sub(p, q)) for q in polygon)
    o = polygon[0]
    u, v = plane_basis(n)
    h = geo.dot(geo.sub(p, o), n)
    pts2 = [(geo.dot(geo.sub(q, o), u), geo.dot(geo.sub(q, o), v)) for q in polygon]
    d = geo.sub(p, o)
    q = (geo.dot(d, u), geo.dot(d, v))
    loop = list(range(len(pts2)))
    edge = min(_segment_param(q, pts2[j], pts2[(j + 1) % len(pts2)])[1] for j in loop)
    if _inside2(q, pts2, loop, 0.0):
        return abs(h)
    return math.sqrt(h * h + edge * edge)


def surface_distance(p, vertices, faces):
    """Distance from a point to the surface of a polyhedron."""
    return min(point_polygon_distance(p, [vertices[i] for i in f]) for f in faces)


def winding_number(p, vertices, faces):
    """Generalised winding number of a closed, outward polyhedron about p (1 inside, 0
    outside), by the solid angles of its faces' fan triangles (van Oosterom & Strackee 1983)."""
    total = 0.0
    for f in faces:
        a = geo.sub(vertices[f[0]], p)
        for k in range(1, len(f) - 1):
            b = geo.sub(vertices[f[k]], p)
            c = geo.sub(vertices[f[k + 1]], p)
            la, lb, lc = geo.norm(a), geo.norm(b), geo.norm(c)
            num = geo.dot(a, geo.cross(b, c))
            den = la * lb * lc + geo.dot(a, b) * lc + geo.dot(a, c) * lb + geo.dot(b, c) * la
            total += 2.0 * math.atan2(num, den)
    return total / (4.0 * math.pi)


def contains(p, vertices, faces, tol):
    """p inside the polyhedron or within tol of its surface."""
    return surface_distance(p, vertices, faces) <= tol or winding_number(p, vertices, faces) > 0.5
