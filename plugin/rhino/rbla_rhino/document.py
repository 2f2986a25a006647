"""RhinoDoc side: read the model from the document, put results on layers (RhinoCommon only).

Reading (``collect_model``): every selected object (or, with nothing selected, every visible
object outside the result layers) is classified by its User Text (keys in
``rbla_cad.usertext``): a load point (``rbla.load``), an interface surface
(``rbla.interface``), or a block (any closed Brep / Extrusion / closed Mesh / SubD, and any
Brep or mesh carrying rbla.* keys). Open surfaces and meshes without rbla.* keys are skipped as
construction geometry (and listed). Each bad block is reported by name; the export stops when
any is bad.

Results (``draw_result``) go on sub-layers of ``rbla results``: ``Displaced blocks``,
``Contacts`` (polygons coloured by state) and ``Labels`` (text dots with alpha or the base
reaction, and the support reactions); each drawing is one undo step (``BeginUndoRecord``), and
``clear_results`` deletes them (also undoable).
"""

import os
import tempfile

import Rhino
import Rhino.Geometry as rg
import scriptcontext as sc

from rbla_cad import usertext
from rbla_cad.model import ModelBuilder, ModelError
from rbla_cad import result as rres

from . import geometry as rgeo

RESULT_LAYER = "rbla results"
SUB_LAYERS = (("Displaced blocks", (220, 215, 205)), ("Contacts", (214, 39, 40)),
              ("Labels", (60, 60, 60)))
RUN_SECTION = "rbla_run"   # doc.Strings section holding the last run's file paths


# ----------------------------------------------------------------------------- user text

def object_user_text(obj):
    nvc = obj.Attributes.GetUserStrings()
    return dict((k, nvc[k]) for k in nvc.AllKeys)


def document_user_text(doc):
    out = {}
    for i in range(doc.Strings.Count):
        key = doc.Strings.GetKey(i)
        if key and key.lower().startswith(usertext.PREFIX):
            out[key] = doc.Strings.GetValue(i)
    return out


def document_units(doc):
    """Name of the document's length unit ("Millimeters", ...) for rbla_cad.host_length_unit."""
    return str(doc.ModelUnitSystem).split(".")[-1]


def _layer_path(doc, obj):
    try:
        return doc.Layers[obj.Attributes.LayerIndex].FullPath
    except Exception:
        return None


def _is_result_object(doc, obj):
    path = _layer_path(doc, obj) or ""
    return path == RESULT_LAYER or path.startswith(RESULT_LAYER + "::")


def candidate_objects(doc):
    """The selected objects, or every visible, unlocked-or-locked normal object when nothing
    is selected; result layers excluded."""
    selected = list(doc.Objects.GetSelectedObjects(False, False))
    if not selected:
        settings = Rhino.DocObjects.ObjectEnumeratorSettings()
        settings.HiddenObjects = False
        settings.DeletedObjects = False
        settings.IncludeLights = False
        settings.IncludeGrips = False
        selected = list(doc.Objects.GetObjectList(settings))
    return [o for o in selected if not _is_result_object(doc, o)]


# -------------------------------------------------------------------------------- export

class Collected(object):
    """What collect_model found: builder, {block id: object id}, issues, settings."""

    def __init__(self):
        self.builder = None
        self.block_objects = {}
        self.issues = []       # strings
        self.settings = None
        self.skipped = 0
        self.skipped_open = []  # names of open Breps/meshes without rbla keys (not blocks)


def collect_model(doc, objects=None, title=None):
    """Build the model from the document; returns a Collected (check ``issues``)."""
    out = Collected()
    tol = doc.ModelAbsoluteTolerance
    try:
        out.settings = usertext.document_settings(document_user_text(doc))
        mb = ModelBuilder(length=document_units(doc), force=out.settings["force_unit"],
                          unit_weight_unit=out.settings["unit_weight_unit"],
                          gravity=out.settings["gravity"],
                          title=title or (doc.Name or "Rhino model"),
                          default_unit_weight=out.settings["default_unit_weight"],
                          default_friction=out.settings["default_friction"])
    except ModelError as e:
        out.issues.append(str(e))
        return out
    out.builder = mb
    objs = candidate_objects(doc) if objects is None else list(objects)
    names = {}
    for o in objs:
        n = o.Attributes.Name
        if n:
            names[n] = names.get(n, 0) + 1
    used = set()
    geoms = {}
    interfaces = []
    loads = []
    for o in objs:
        ut = object_user_text(o)
        name = o.Attributes.Name or None
        who = "object %s" % (repr(name) if name else str(o.Id))
        g = o.Geometry
        try:
            if usertext.is_load(ut):
                if isinstance(g, rg.Point):
                    loads.append((o, usertext.load_attributes(ut, who), g.Location))
                else:
                    out.issues.append("%s: rbla.load is for point objects" % who)
                continue
            if usertext.is_interface(ut):
                interfaces.append((o, usertext.interface_attributes(ut, name, who)))
                continue
            if not (isinstance(g, (rg.Brep, rg.Extrusion, rg.Mesh)) or
                    (hasattr(rg, "SubD") and isinstance(g, rg.SubD))):
                out.skipped += 1
                continue
            if not usertext.normalise(ut) and not rgeo.is_solid(g):
                # an open surface or mesh without rbla keys: construction geometry, not a block
                out.skipped += 1
                out.skipped_open.append(name or str(o.Id))
                continue
            attrs = usertext.block_attributes(ut, name, _layer_path(doc, o), who)
            if attrs["ignore"]:
                out.skipped += 1
                continue
            bid = attrs["id"] or (name if name and names.get(name) == 1 else str(o.Id))
            if bid in used:
                raise ModelError("%s: block id %r is used twice" % (who, bid), bid)
            verts, faces, vol, cen = rgeo.block_polyhedron(g, tol, bid)
            mb.add_block(bid, verts, faces, role=attrs["role"], unit_weight=attrs["unit_weight"],
                         label=attrs["label"], centroid=cen, volume=vol,
                         friction=attrs["friction"])
            used.add(bid)
            out.block_objects[bid] = o.Id
            geoms[bid] = g
        except ModelError as e:
            out.issues.append(str(e))
    for o, a in interfaces:
        name = o.Attributes.Name or str(o.Id)
        poly = rgeo.planar_polygon(o.Geometry, tol)
        if poly is None:
            out.issues.append("interface %r: not a planar surface or closed planar polyline"
                              % name)
            continue
        ids = a["blocks"]
        if ids is None:
            c = rg.Point3d(sum(p[0] for p in poly) / len(poly), sum(p[1] for p in poly) / len(poly),
                           sum(p[2] for p in poly) / len(poly))
            near = sorted((rgeo.distance_to(g, c), bid) for bid, g in geoms.items())
            near = [bid for d, bid in near if d <= 10 * tol][:2]
            if len(near) != 2:
                out.issues.append("interface %r: cannot tell which two blocks it joins (set "
                                  "rbla.blocks = 'idA, idB')" % name)
                continue
            ids = near
        try:
            mb.add_interface(ids, poly, label=a["label"], friction=a["friction"])
        except ModelError as e:
            out.issues.append(str(e))
    for o, a, pt in loads:
        bid = a["block"]
        if bid is None:
            inside = [b for b, g in geoms.items() if rgeo.contains(g, pt, tol)]
            if len(inside) != 1:
                out.issues.append("load point %s: inside %d blocks; set rbla.block"
                                  % (o.Attributes.Name or o.Id, len(inside)))
                continue
            bid = inside[0]
        p = [pt.X, pt.Y, pt.Z]
        if a["kind"] == "live":
            mb.add_live_load(bid, a["force"], p, a["moment"])
        else:
            mb.add_dead_load(bid, a["force"], p, a["moment"])
    if not out.issues:
        try:
            usertext.apply_settings(mb, out.settings)
            if loads and any(a["kind"] == "live" for _, a, _ in loads) and \
                    out.settings["analysis"] == "seismic":
                out.issues.append("live loads given but rbla.analysis is 'seismic': set it to "
                                  "'live' in the Document User Text")
            mb.check()
        except ModelError as e:
            out.issues.append(str(e))
    return out


def run_folder(doc):
    """Folder for model/result files: next to the .3dm (NAME_rbla), else a temp folder."""
    if doc.Path:
        base = os.path.splitext(doc.Path)[0] + "_rbla"
    else:
        base = os.path.join(tempfile.gettempdir(), "rbla", "doc%d" % doc.RuntimeSerialNumber)
    if not os.path.isdir(base):
        os.makedirs(base)
    return base


def remember(doc, **paths):
    for k, v in paths.items():
        doc.Strings.SetString(RUN_SECTION, k, v or "")


def recall(doc, key):
    v = doc.Strings.GetValue(RUN_SECTION, key)
    return v or None


# ------------------------------------------------------------------------------- results

def _layer_index(doc, name, rgb, parent_id=None):
    full = name if parent_id is None else RESULT_LAYER + "::" + name
    idx = doc.Layers.FindByFullPath(full, -1)
    if idx >= 0:
        return idx
    layer = Rhino.DocObjects.Layer()
    layer.Name = name
    layer.Color = rgeo.colour(rgb)
    if parent_id is not None:
        layer.ParentLayerId = parent_id
    return doc.Layers.Add(layer)


def result_layers(doc):
    """{sub-layer name: index}, creating 'rbla results' and its sub-layers when missing."""
    parent = _layer_index(doc, RESULT_LAYER, (120, 120, 120))
    pid = doc.Layers[parent].Id
    return dict((n, _layer_index(doc, n, rgb, pid)) for n, rgb in SUB_LAYERS)


def _attributes(layer_index, rgb, name=None):
    a = Rhino.DocObjects.ObjectAttributes()
    a.LayerIndex = layer_index
    a.ColorSource = Rhino.DocObjects.ObjectColorSource.ColorFromObject
    a.ObjectColor = rgeo.colour(rgb)
    if name:
        a.Name = name
    return a


def clear_results(doc, undo=True):
    """Delete every object on the result layers; returns how many."""
    sn = doc.BeginUndoRecord("rbla clear results") if undo else 0
    try:
        count = 0
        for name, _ in SUB_LAYERS:
            idx = doc.Layers.FindByFullPath(RESULT_LAYER + "::" + name, -1)
            if idx < 0:
                continue
            for o in list(doc.Objects.FindByLayer(doc.Layers[idx]) or []):
                if doc.Objects.Delete(o, True):
                    count += 1
        return count
    finally:
        if undo:
            doc.EndUndoRecord(sn)
        doc.Views.Redraw()


def draw_result(doc, model, result, amplitude=None, screw=False, show_closed=False,
                hide_originals=False, block_objects=None):
    """Draw a result on the result layers (replacing the previous drawing), as one undo step.

    model: the model dict that was solved (its vertices are in the model unit; the drawing
    unit is the document's); result: rbla_cad.result.Result. Returns the amplitude used."""
    from rbla_cad.model import host_length_unit
    _, scale = host_length_unit(document_units(doc))
    if model.get("units", {}).get("length") != host_length_unit(document_units(doc))[0]:
        raise ModelError("the model's length unit (%s) is not the document's (%s): export and "
                         "solve again" % (model.get("units", {}).get("length"),
                                          document_units(doc)))
    s = result.displacement_scale if amplitude is None else float(amplitude)
    sn = doc.BeginUndoRecord("rbla show mechanism")
    try:
        clear_results(doc, undo=False)
        layers = result_layers(doc)
        for b in rres.displaced_blocks(model, result, s, scale, screw):
            mesh = rgeo.block_mesh(b["vertices"], b["faces"], b["rgb"])
            a = _attributes(layers["Displaced blocks"], b["rgb"], "rbla:" + b["id"])
            a.SetUserString("rbla.block", b["id"])
            doc.Objects.AddMesh(mesh, a)
        for c in rres.contact_polygons(result, show_closed, scale):
            a = _attributes(layers["Contacts"], c["rgb"], "rbla:%s %s" % (c["id"], c["state"]))
            a.SetUserString("rbla.interface_state", c["state"])
            if c["label"]:
                a.SetUserString("rbla.interface", c["label"])
            pts = c["polygon"]
            if len(pts) >= 3:
                doc.Objects.AddMesh(rgeo.polygon_mesh(pts), a)
            pl = rg.Polyline([rgeo.point3d(p) for p in pts] + [rgeo.point3d(pts[0])])
            doc.Objects.AddPolyline(pl, a)
        lab = layers["Labels"]
        bb = _model_box(model, scale)
        if bb is not None:
            top = rg.Point3d((bb[0][0] + bb[1][0]) / 2, (bb[0][1] + bb[1][1]) / 2,
                             bb[1][2] + 0.1 * (bb[1][2] - bb[0][2]))
            dot = rg.TextDot("\n".join(rres.summary_lines(result)), top)
            doc.Objects.AddTextDot(dot, _attributes(lab, (0, 0, 0), "rbla:summary"))
        for p, text in rres.reaction_labels(result, 3, scale):
            doc.Objects.AddTextDot(rg.TextDot(text, rgeo.point3d(p)),
                                   _attributes(lab, (60, 60, 60), "rbla:reaction"))
        if hide_originals and block_objects:
            for oid in block_objects.values():
                doc.Objects.Hide(oid, True)
    finally:
        doc.EndUndoRecord(sn)
    doc.Views.Redraw()
    return s


def _model_box(model, scale):
    pts = [p for b in model.get("blocks", []) for p in b["vertices"]]
    if not pts:
        return None
    k = 1.0 / scale
    lo = [min(p[i] for p in pts) * k for i in range(3)]
    hi = [max(p[i] for p in pts) * k for i in range(3)]
    return lo, hi


def active_doc():
    return sc.doc if isinstance(sc.doc, Rhino.RhinoDoc) else Rhino.RhinoDoc.ActiveDoc
