"""Small vector and polyhedron helpers shared by the rbla_cad modules.

Standard library only (Python 3.9+). Vectors are tuples or lists of three floats.
"""

import math


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def add(a, b):
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def scale(a, s):
    return (a[0] * s, a[1] * s, a[2] * s)


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def norm(a):
    return math.sqrt(dot(a, a))


def newell_normal(points):
    """Area vector of a planar (or nearly planar) polygon by Newell's method: its direction is
    the normal by the right-hand rule, its length the polygon's area."""
    n = [0.0, 0.0, 0.0]
    m = len(points)
    for i in range(m):
        p, q = points[i], points[(i + 1) % m]
        n[0] += (p[1] - q[1]) * (p[2] + q[2])
        n[1] += (p[2] - q[2]) * (p[0] + q[0])
        n[2] += (p[0] - q[0]) * (p[1] + q[1])
    return (0.5 * n[0], 0.5 * n[1], 0.5 * n[2])


def polygon_centroid(points):
    """Area centroid of a planar polygon (falls back to the vertex mean when degenerate)."""
    if not points:
        raise ValueError("empty polygon")
    o = points[0]
    nrm = newell_normal(points)
    ln = norm(nrm)
    if ln == 0.0:
        k = float(len(points))
        return tuple(sum(p[i] for p in points) / k for i in range(3))
    u = scale(nrm, 1.0 / ln)
    total = 0.0
    c = [0.0, 0.0, 0.0]
    for k in range(1, len(points) - 1):
        a, b = sub(points[k], o), sub(points[k + 1], o)
        w = dot(cross(a, b), u) * 0.5
        total += w
        for i in range(3):
            c[i] += w * (a[i] + b[i]) / 3.0
    if total == 0.0:
        k = float(len(points))
        return tuple(sum(p[i] for p in points) / k for i in range(3))
    return (o[0] + c[0] / total, o[1] + c[1] / total, o[2] + c[2] / total)


def volume_centroid(vertices, faces):
    """Signed volume and centroid of a closed polyhedron by the divergence theorem.

    Faces are fanned into triangles from the mean of their corners (so that a warped face gives
    the same surface whichever corner its list starts at, as the solver's
    geometry::mass_properties does); each triangle and a reference point (the first vertex) form
    a tetrahedron. Positive volume means the faces are oriented outward (counter-clockwise seen
    from outside). Returns (volume, (x, y, z)); the centroid is the first vertex when the volume
    is zero.
    """
    o = vertices[0]
    vol6 = 0.0
    s = [0.0, 0.0, 0.0]
    for f in faces:
        n = len(f)
        a = sub([sum(vertices[i][k] for i in f) / n for k in range(3)], o)
        for k in range(n):
            b = sub(vertices[f[k]], o)
            c = sub(vertices[f[(k + 1) % n]], o)
            v = dot(a, cross(b, c))
            vol6 += v
            for i in range(3):
                s[i] += v * (a[i] + b[i] + c[i])
    if vol6 == 0.0:
        return 0.0, (float(o[0]), float(o[1]), float(o[2]))
    return vol6 / 6.0, tuple(o[i] + s[i] / (4.0 * vol6) for i in range(3))


def bounding_box(points):
    lo = [min(p[i] for p in points) for i in range(3)]
    hi = [max(p[i] for p in points) for i in range(3)]
    return lo, hi
