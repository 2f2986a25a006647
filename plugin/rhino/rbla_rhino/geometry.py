"""Rhino geometry <-> the plain lists of rbla_cad (RhinoCommon only; runs inside Rhino 8).

Blocks: a closed Brep (or Extrusion) whose faces are all planar with a single polygonal outer
loop is written face by face, exactly (one polygon per face, vertices merged); anything else
(curved faces, holes, a closed Mesh, a SubD) goes through RhinoCommon meshing
(``Mesh.CreateFromBrep`` with ``SimplePlanes``), identical vertices combined, normals unified
and turned outward. Volume and centroid come from ``VolumeMassProperties`` and are written as
the CAD's values (the solver checks them against the faces).
"""

import Rhino.Geometry as rg
import System

from rbla_cad import geometry as geo
from rbla_cad import polygons
from rbla_cad.model import ModelError, check_block_geometry


def _pt(p):
    return [float(p.X), float(p.Y), float(p.Z)]


def to_brep(geometry):
    """Brep of a Brep, Extrusion or Surface (None for other geometry)."""
    if isinstance(geometry, rg.Brep):
        return geometry
    if isinstance(geometry, rg.Extrusion):
        return geometry.ToBrep(True)
    if isinstance(geometry, rg.Surface):
        return rg.Brep.CreateFromSurface(geometry)
    if hasattr(rg, "SubD") and isinstance(geometry, rg.SubD):
        return rg.Brep.CreateFromSubD(geometry)
    return None


def is_solid(geometry):
    if isinstance(geometry, rg.Mesh):
        return geometry.IsClosed
    b = to_brep(geometry)
    return b is not None and b.IsSolid


def _loop_polygon(loop, tolerance):
    """Points of a polygonal Brep loop (closing point dropped), or None."""
    crv = loop.To3dCurve()
    if crv is None:
        return None
    ok, pl = crv.TryGetPolyline()
    if not ok:
        if crv.IsPolyline():
            ok, pl = crv.TryGetPolyline()
        if not ok:
            return None
    pts = [_pt(pl[i]) for i in range(pl.Count)]
    if len(pts) > 1 and geo.norm(geo.sub(pts[0], pts[-1])) <= tolerance:
        pts.pop()
    # drop consecutive duplicates
    out = []
    for p in pts:
        if not out or geo.norm(geo.sub(p, out[-1])) > tolerance:
            out.append(p)
    if len(out) > 2 and geo.norm(geo.sub(out[0], out[-1])) <= tolerance:
        out.pop()
    return out if len(out) >= 3 else None


def _merge(points_lists, tolerance):
    """Shared vertex list and index faces from per-face point lists (merged within tol)."""
    verts = []
    index = {}
    faces = []
    q = max(tolerance, 1e-12)
    for pts in points_lists:
        f = []
        for p in pts:
            key = (int(round(p[0] / q)), int(round(p[1] / q)), int(round(p[2] / q)))
            if key not in index:
                index[key] = len(verts)
                verts.append(p)
            i = index[key]
            if not f or f[-1] != i:
                f.append(i)
        if len(f) > 1 and f[0] == f[-1]:
            f.pop()
        faces.append(f)
    return verts, faces


def polyhedron_from_planar_brep(brep, tolerance):
    """(vertices, faces) of a closed Brep with planar, single-loop, polygonal faces, each face
    counter-clockwise seen from outside; None when the Brep is not like that."""
    polys = []
    for face in brep.Faces:
        if face.Loops.Count != 1 or not face.IsPlanar(tolerance):
            return None
        pts = _loop_polygon(face.OuterLoop, tolerance)
        if pts is None:
            return None
        n = geo.newell_normal(pts)
        u = face.Domain(0).Mid
        v = face.Domain(1).Mid
        fn = face.NormalAt(u, v)  # the underlying surface's normal:
        if face.OrientationIsReversed:  # the face's outward normal is its reverse
            fn = -fn
        if geo.dot(n, (fn.X, fn.Y, fn.Z)) < 0:
            pts.reverse()
        polys.append(pts)
    verts, faces = _merge(polys, tolerance * 0.5)
    if any(len(f) < 3 for f in faces):
        return None
    vol, _ = geo.volume_centroid(verts, faces)
    if vol < 0:
        faces = [list(reversed(f)) for f in faces]
    return verts, faces


def mesh_of(geometry):
    """A closed, outward, vertex-combined mesh of a Brep/Extrusion/Mesh/SubD, or None."""
    if isinstance(geometry, rg.Mesh):
        mesh = geometry.DuplicateMesh()
    else:
        brep = to_brep(geometry)
        if brep is None:
            return None
        mp = rg.MeshingParameters.QualityRenderMesh
        mp.SimplePlanes = True
        mp.JaggedSeams = False
        parts = rg.Mesh.CreateFromBrep(brep, mp)
        if not parts:
            return None
        mesh = rg.Mesh()
        for m in parts:
            mesh.Append(m)
    mesh.Vertices.CombineIdentical(True, True)
    mesh.Vertices.CullUnused()
    mesh.Compact()
    mesh.UnifyNormals()
    if mesh.IsClosed and mesh.SolidOrientation() < 0:
        mesh.Flip(True, True, True)
    return mesh


def polyhedron_from_mesh(mesh):
    verts = [_pt(mesh.Vertices[i]) for i in range(mesh.Vertices.Count)]
    faces = []
    for i in range(mesh.Faces.Count):
        f = mesh.Faces[i]
        faces.append([f.A, f.B, f.C, f.D] if f.IsQuad else [f.A, f.B, f.C])
    return verts, faces


def block_polyhedron(geometry, tolerance, block_id="?"):
    """(vertices, faces, volume, centroid) of a closed block; raises ModelError (its message
    says what is wrong, the caller names the object).

    volume/centroid are RhinoCommon's VolumeMassProperties of what is written (the Brep when
    it is written exactly, else its mesh; None if it failed)."""
    brep = None if isinstance(geometry, rg.Mesh) else to_brep(geometry)
    if brep is not None:
        if not brep.IsSolid:
            raise ModelError("not a closed solid (open Brep: cap it or join it)", block_id)
        if brep.SolidOrientation == rg.BrepSolidOrientation.Inward:
            brep = brep.DuplicateBrep()
            brep.Flip()
    elif isinstance(geometry, rg.Mesh) and not geometry.IsClosed:
        raise ModelError("an open mesh (fill its holes first)", block_id)
    vf = None
    if brep is not None:
        vf = polyhedron_from_planar_brep(brep, tolerance)
        if vf is not None:
            try:
                check_block_geometry(block_id, vf[0], vf[1])
            except ModelError:
                vf = None  # fall back to meshing
    source = brep
    if vf is None:
        mesh = mesh_of(brep if brep is not None else geometry)
        if mesh is None or not mesh.IsClosed:
            raise ModelError("could not be meshed into a closed polyhedron", block_id)
        vf = polyhedron_from_mesh(mesh)
        source = mesh  # the faceted block's own values: no spurious disagreement warning
    vmp = rg.VolumeMassProperties.Compute(source)
    volume = centroid = None
    if vmp is not None and vmp.Volume > 0:
        volume = float(vmp.Volume)
        centroid = _pt(vmp.Centroid)
    return vf[0], vf[1], volume, centroid


def _face_polygons(brep, tolerance):
    """Outer loops of a Brep's faces (each planar and polygonal), or a reason why not."""
    polys = []
    for i, face in enumerate(brep.Faces):
        if not face.IsPlanar(tolerance):
            return None, "face %d is not planar" % i
        pts = _loop_polygon(face.OuterLoop, tolerance)
        if pts is None:
            return None, "face %d is not bounded by straight edges" % i
        polys.append(pts)
    return polys, None


def _mesh_polygons(mesh, tolerance):
    """An open mesh's faces (a warped quad as its two triangles)."""
    verts = [_pt(mesh.Vertices[i]) for i in range(mesh.Vertices.Count)]
    polys = []
    for i in range(mesh.Faces.Count):
        f = mesh.Faces[i]
        if not f.IsQuad:
            polys.append([verts[f.A], verts[f.B], verts[f.C]])
            continue
        quad = [verts[f.A], verts[f.B], verts[f.C], verts[f.D]]
        n, area = polygons.unit_normal(quad)
        if area > 0 and all(abs(geo.dot(geo.sub(p, quad[0]), n)) <= tolerance for p in quad):
            polys.append(quad)
        else:
            polys += [[quad[0], quad[1], quad[2]], [quad[0], quad[2], quad[3]]]
    return polys


def _curve_polygon(curve, tolerance):
    if not curve.IsClosed or not curve.IsPlanar(tolerance):
        return None, "a curve must be a closed planar polyline"
    ok, pl = curve.TryGetPolyline()
    if not ok:
        return None, "a curve must be a closed planar polyline"
    pts = [_pt(pl[i]) for i in range(pl.Count)]
    if len(pts) > 1 and geo.norm(geo.sub(pts[0], pts[-1])) <= tolerance:
        pts.pop()
    if len(pts) < 3:
        return None, "the polyline has fewer than 3 corners"
    return [pts], None


def shape_record(geometry, tolerance):
    """The shape part of an object's record for rbla_cad.cad_reader: a closed block as a
    polyhedron (shape 'solid'), open planar geometry as its pieces ('polygons'), a point, or
    'other'; what cannot be converted is given as 'error'."""
    if isinstance(geometry, rg.Point):
        return {"shape": "point", "point": _pt(geometry.Location)}
    if isinstance(geometry, rg.Curve):
        polys, why = _curve_polygon(geometry, tolerance)
        return {"shape": "polygons", "polygons": polys} if why is None else \
            {"shape": "polygons", "error": why}
    is_geom = isinstance(geometry, (rg.Brep, rg.Extrusion, rg.Surface, rg.Mesh)) or \
        (hasattr(rg, "SubD") and isinstance(geometry, rg.SubD))
    if not is_geom:
        return {"shape": "other"}
    if is_solid(geometry):
        try:
            v, f, vol, cen = block_polyhedron(geometry, tolerance)
        except ModelError as e:
            return {"shape": "solid", "error": str(e)}
        return {"shape": "solid", "vertices": v, "faces": f, "volume": vol, "centroid": cen}
    if isinstance(geometry, rg.Mesh):
        return {"shape": "polygons", "polygons": _mesh_polygons(geometry, tolerance)}
    brep = to_brep(geometry)
    polys, why = _face_polygons(brep, tolerance) if brep is not None else (None, "no surface")
    return {"shape": "polygons", "polygons": polys} if why is None else \
        {"shape": "polygons", "error": why}


# ------------------------------------------------------------------------------- output

def point3d(p):
    return rg.Point3d(float(p[0]), float(p[1]), float(p[2]))


def colour(rgb):
    return System.Drawing.Color.FromArgb(int(rgb[0]), int(rgb[1]), int(rgb[2]))


def polygon_mesh(points):
    """A mesh of one planar polygon (non-convex polygons handled by Rhino)."""
    pl = rg.Polyline([point3d(p) for p in points] + [point3d(points[0])])
    m = rg.Mesh.CreateFromClosedPolyline(pl)
    if m is None:  # fall back to a fan
        m = rg.Mesh()
        for p in points:
            m.Vertices.Add(float(p[0]), float(p[1]), float(p[2]))
        for k in range(1, len(points) - 1):
            m.Faces.AddFace(0, k, k + 1)
    return m


def block_mesh(vertices, faces, rgb=None):
    """A Rhino mesh of a polyhedron (triangles and quads kept, larger faces triangulated by
    Rhino), optionally with monotone vertex colours so Shaded and Rendered views show rgb."""
    m = rg.Mesh()
    for p in vertices:
        m.Vertices.Add(float(p[0]), float(p[1]), float(p[2]))
    extra = []
    for f in faces:
        if len(f) == 3:
            m.Faces.AddFace(f[0], f[1], f[2])
        elif len(f) == 4:
            m.Faces.AddFace(f[0], f[1], f[2], f[3])
        else:
            extra.append(polygon_mesh([vertices[i] for i in f]))
    for e in extra:
        m.Append(e)
    m.Vertices.CombineIdentical(True, True)
    m.Normals.ComputeNormals()
    m.Compact()
    if rgb is not None:
        m.VertexColors.CreateMonotoneMesh(colour(rgb))
    return m


def transform(matrix):
    """Rhino Transform of a 4x4 nested list."""
    t = rg.Transform(1.0)
    for i in range(4):
        for j in range(4):
            setattr(t, "M%d%d" % (i, j), float(matrix[i][j]))
    return t
