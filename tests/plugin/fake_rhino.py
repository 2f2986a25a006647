"""A tiny stand-in for the parts of RhinoCommon the adapter uses, so its code paths (collect a
document of mesh blocks, draw a result on layers, Grasshopper helpers) run in the tests.

It checks our control flow and bookkeeping, not RhinoCommon itself: the stubs only mimic the
signatures the adapter calls. ``install()`` puts the modules into sys.modules; ``uninstall()``
removes them (and the adapter modules imported meanwhile).
"""

import sys
import types

import _support  # noqa: F401
from rbla_cad import geometry as geo


class Color(object):
    def __init__(self, r, g, b):
        self.R, self.G, self.B = r, g, b

    @staticmethod
    def FromArgb(r, g, b):
        return Color(r, g, b)


class Point3d(object):
    def __init__(self, x, y, z):
        self.X, self.Y, self.Z = float(x), float(y), float(z)

    def DistanceTo(self, o):
        return geo.norm((self.X - o.X, self.Y - o.Y, self.Z - o.Z))


class Vector3d(Point3d):
    pass


class Polyline(list):
    def __init__(self, pts):
        list.__init__(self, pts)

    @property
    def Count(self):
        return len(self)


class _Faces(list):
    def AddFace(self, *idx):
        self.append(_Face(*idx))

    @property
    def Count(self):
        return len(self)


class _Face(object):
    def __init__(self, a, b, c, d=None):
        self.A, self.B, self.C = a, b, c
        self.D = c if d is None else d
        self.IsQuad = d is not None and d != c


class _Verts(list):
    def Add(self, x, y, z):
        self.append(Point3d(x, y, z))

    @property
    def Count(self):
        return len(self)

    def CombineIdentical(self, a, b):
        return True

    def CullUnused(self):
        return 0


class _Colours(object):
    def __init__(self):
        self.colour = None

    def CreateMonotoneMesh(self, c):
        self.colour = c


class _Normals(object):
    def ComputeNormals(self):
        return True


class Mesh(object):
    def __init__(self):
        self.Vertices = _Verts()
        self.Faces = _Faces()
        self.VertexColors = _Colours()
        self.Normals = _Normals()

    def Append(self, other):
        n = len(self.Vertices)
        self.Vertices.extend(other.Vertices)
        for f in other.Faces:
            self.Faces.append(_Face(f.A + n, f.B + n, f.C + n, f.D + n if f.IsQuad else None))

    def DuplicateMesh(self):
        m = Mesh()
        m.Append(self)
        return m

    def Compact(self):
        return True

    def UnifyNormals(self):
        return 0

    def _vf(self):
        verts = [(p.X, p.Y, p.Z) for p in self.Vertices]
        faces = [[f.A, f.B, f.C, f.D] if f.IsQuad else [f.A, f.B, f.C] for f in self.Faces]
        return verts, faces

    @property
    def IsClosed(self):
        """Every edge (between coordinates) is used by exactly two faces."""
        v, f = self._vf()
        count = {}
        for face in f:
            for j in range(len(face)):
                e = tuple(sorted((tuple(v[face[j]]), tuple(v[face[(j + 1) % len(face)]]))))
                count[e] = count.get(e, 0) + 1
        return bool(count) and all(c == 2 for c in count.values())

    def SolidOrientation(self):
        v, f = self._vf()
        return 1 if geo.volume_centroid(v, f)[0] > 0 else -1

    def Flip(self, a, b, c):
        for f in self.Faces:
            if f.IsQuad:
                f.B, f.D = f.D, f.B
            else:
                f.B, f.C = f.C, f.B

    @staticmethod
    def CreateFromClosedPolyline(pl):
        m = Mesh()
        pts = list(pl)[:-1]
        for p in pts:
            m.Vertices.Add(p.X, p.Y, p.Z)
        for k in range(1, len(pts) - 1):
            m.Faces.AddFace(0, k, k + 1)
        return m

    def ClosestPoint(self, p):
        v, _ = self._vf()
        lo, hi = geo.bounding_box(v)
        return Point3d(*[min(max(c, lo[i]), hi[i]) for i, c in enumerate((p.X, p.Y, p.Z))])

    def IsPointInside(self, p, tol, strict):
        v, _ = self._vf()
        lo, hi = geo.bounding_box(v)
        return all(lo[i] - tol <= c <= hi[i] + tol for i, c in enumerate((p.X, p.Y, p.Z)))


class Point(object):
    """A point object's geometry."""

    def __init__(self, x, y, z):
        self.Location = Point3d(x, y, z)


class Curve(object):
    pass


class PolylineCurve(Curve):
    """A polyline curve; closed when its last point repeats the first."""

    def __init__(self, pts):
        self.pts = [Point3d(*p) for p in pts]

    @property
    def IsClosed(self):
        return len(self.pts) > 3 and self.pts[0].DistanceTo(self.pts[-1]) == 0.0

    def IsPlanar(self, tol):
        from rbla_cad import polygons
        pts = [(p.X, p.Y, p.Z) for p in self.pts]
        n, area = polygons.unit_normal(pts)
        return area > 0 and all(abs(geo.dot(geo.sub(p, pts[0]), n)) <= tol for p in pts)

    def TryGetPolyline(self):
        return True, Polyline(self.pts)


class VolumeMassProperties(object):
    @staticmethod
    def Compute(g):
        vol, cen = geo.volume_centroid(*g._vf())
        out = VolumeMassProperties()
        out.Volume = vol
        out.Centroid = Point3d(*cen)
        return out


class TextDot(object):
    def __init__(self, text, point):
        self.Text, self.Point = text, point


class Transform(object):
    def __init__(self, diagonal):
        for i in range(4):
            for j in range(4):
                setattr(self, "M%d%d" % (i, j), diagonal if i == j else 0.0)


class _Unused(object):
    pass


class ObjectAttributes(object):
    def __init__(self):
        self.LayerIndex = 0
        self.Name = None
        self.ColorSource = None
        self.ObjectColor = None
        self._user = {}

    def SetUserString(self, k, v):
        self._user[k] = v

    def GetUserStrings(self):
        return _NVC(self._user)


class _NVC(dict):
    @property
    def AllKeys(self):
        return list(self.keys())


class Layer(object):
    def __init__(self):
        self.Name = ""
        self.Color = None
        self.ParentLayerId = None
        self.Id = object()
        self.FullPath = ""
        self.IsVisible = True


class _Layers(list):
    def FindByFullPath(self, path, missing):
        for i, layer in enumerate(self):
            if layer.FullPath == path:
                return i
        return missing

    def Add(self, layer):
        parent = [x for x in self if x.Id is layer.ParentLayerId]
        layer.FullPath = (parent[0].FullPath + "::" if parent else "") + layer.Name
        self.append(layer)
        return len(self) - 1


class RhinoObject(object):
    _n = 0

    def __init__(self, geometry, attributes, guid=None):
        RhinoObject._n += 1
        self.Id = guid or "guid-%d" % RhinoObject._n
        self.Geometry = geometry
        self.Attributes = attributes
        self.IsHidden = False


class _Objects(list):
    def _add(self, g, a, guid=None):
        o = RhinoObject(g, a or ObjectAttributes(), guid)
        self.append(o)
        return o.Id

    AddMesh = AddPolyline = AddTextDot = _add

    def FindByLayer(self, layer):
        return [o for o in self if o.Attributes.LayerIndex is not None and
                self.doc.Layers[o.Attributes.LayerIndex] is layer]

    def Delete(self, o, quiet):
        self.remove(o)
        return True

    def Hide(self, oid, ignore):
        return True

    def GetSelectedObjects(self, a, b):
        return []

    def GetObjectList(self, settings):
        return list(self)


class _Strings(object):
    def __init__(self):
        self.d = {}

    @property
    def Count(self):
        return len(self.d)

    def GetKey(self, i):
        return list(self.d.keys())[i]

    def GetValue(self, *args):
        if len(args) == 1 and isinstance(args[0], int):
            return list(self.d.values())[args[0]]
        return self.d.get("\\".join(args))

    def SetString(self, *args):
        self.d["\\".join(args[:-1])] = args[-1]


class _Views(object):
    def Redraw(self):
        pass


class Doc(object):
    def __init__(self, unit="Meters"):
        self.ModelUnitSystem = "UnitSystem." + unit
        self.ModelAbsoluteTolerance = 0.001
        self.Name = "test"
        self.Path = None
        self.RuntimeSerialNumber = 1
        self.Layers = _Layers()
        default = Layer()
        default.Name = default.FullPath = "Default"
        self.Layers.append(default)
        self.Objects = _Objects()
        self.Objects.doc = self
        self.Strings = _Strings()
        self.Views = _Views()
        self.undo = []

    def BeginUndoRecord(self, name):
        self.undo.append(name)
        return len(self.undo)

    def EndUndoRecord(self, sn):
        return True


def mesh_box(x0, x1, y0, y1, z0, z1):
    from rbla_cad.model import box
    v, f = box(x0, x1, y0, y1, z0, z1)
    m = Mesh()
    for p in v:
        m.Vertices.Add(*p)
    for face in f:
        m.Faces.AddFace(*face)
    return m


def install():
    rhino = types.ModuleType("Rhino")
    rg = types.ModuleType("Rhino.Geometry")
    for cls in (Point3d, Vector3d, Polyline, Mesh, VolumeMassProperties, TextDot, Transform,
                Point, Curve, PolylineCurve):
        setattr(rg, cls.__name__, cls)
    for name in ("Brep", "Extrusion", "Surface", "SubD"):
        setattr(rg, name, type(name, (_Unused,), {}))
    rg.BrepSolidOrientation = types.SimpleNamespace(Inward=-1, Outward=1)
    rg.MeshingParameters = types.SimpleNamespace(QualityRenderMesh=None)
    dobj = types.ModuleType("Rhino.DocObjects")
    dobj.Layer = Layer
    dobj.ObjectAttributes = ObjectAttributes
    dobj.ObjectColorSource = types.SimpleNamespace(ColorFromObject=1)
    dobj.ObjectEnumeratorSettings = lambda: types.SimpleNamespace()
    rhino.Geometry = rg
    rhino.DocObjects = dobj
    rhino.RhinoDoc = types.SimpleNamespace(ActiveDoc=None)
    rhino.RhinoApp = types.SimpleNamespace(WriteLine=lambda *a: None)
    rhino.Commands = types.SimpleNamespace(Result=types.SimpleNamespace(
        Success=0, Cancel=1, Nothing=2, Failure=3))
    system = types.ModuleType("System")
    system.Drawing = types.SimpleNamespace(Color=Color)
    sc = types.ModuleType("scriptcontext")
    sc.doc = None
    sys.modules.update({"Rhino": rhino, "Rhino.Geometry": rg, "Rhino.DocObjects": dobj,
                        "System": system, "scriptcontext": sc})
    rhino_dir = _support.PLUGIN + "/rhino"
    if rhino_dir not in sys.path:
        sys.path.insert(0, rhino_dir)
    return rhino


def uninstall():
    for name in list(sys.modules):
        if name in ("Rhino", "Rhino.Geometry", "Rhino.DocObjects", "System", "scriptcontext") \
                or name == "rbla_rhino" or name.startswith("rbla_rhino."):
            del sys.modules[name]

def mesh_of(vertices, faces):
    """A mesh of a polyhedron or of open pieces: triangles and quads as they are, larger
    faces as fans of triangles (the cases use convex ones)."""
    m = Mesh()
    for p in vertices:
        m.Vertices.Add(*p)
    for face in faces:
        if len(face) <= 4:
            m.Faces.AddFace(*face)
        else:
            for k in range(1, len(face) - 1):
                m.Faces.AddFace(face[0], face[k], face[k + 1])
    return m
