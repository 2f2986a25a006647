"""RhinoDoc side: read the model from the document, put results on layers (RhinoCommon only).

Reading (``collect_model``): every selected object (or, with nothing selected, every object
outside the result layers) becomes a plain record (its geometry as a polyhedron, planar pieces
or a point; its name, layer and User Text) and the host-independent reader
``rbla_cad.cad_reader`` builds the model from the records by the CAD attribute convention
(``rbla_cad/data/cad_attributes.json``, docs/cad-attributes.md), exactly as the .3dm exchange
does. Every unreadable attribute is an error naming the object and the key; anything taken
differently from what was written is a warning saying what was used instead.

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

from rbla_cad import cad_reader, usertext
from rbla_cad.model import ModelError
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
    """The selected objects, or every normal object (hidden ones too: the reader leaves them
    out with a warning) when nothing is selected; result layers excluded."""
    selected = list(doc.Objects.GetSelectedObjects(False, False))
    if not selected:
        settings = Rhino.DocObjects.ObjectEnumeratorSettings()
        settings.HiddenObjects = True
        settings.DeletedObjects = False
        settings.IncludeLights = False
        settings.IncludeGrips = False
        selected = list(doc.Objects.GetObjectList(settings))
    return [o for o in selected if not _is_result_object(doc, o)]


# -------------------------------------------------------------------------------- export

class Collected(object):
    """What collect_model found: the model (None when there are errors), the builder,
    {block id: object id}, the reader's errors and warnings (texts and Message objects), the
    document settings (``exe``: rbla.exe)."""

    def __init__(self, reading, object_ids):
        self.reading = reading
        self.model = reading.model
        self.builder = reading.builder
        self.block_objects = dict((bid, object_ids[g]) for bid, g in
                                  reading.block_objects.items() if g in object_ids)
        self.messages = reading.report.messages
        self.issues = [m.text for m in reading.report.errors]
        self.warnings = [m.text for m in reading.report.warnings]
        self.settings = {"exe": reading.settings.get("rbla.exe")}


def _is_hidden(doc, obj):
    try:
        layer = doc.Layers[obj.Attributes.LayerIndex]
        return bool(obj.IsHidden) or not layer.IsVisible
    except Exception:
        return bool(getattr(obj, "IsHidden", False))


def object_record(doc, obj, tolerance):
    """The plain record of one Rhino object (see rbla_cad.cad_reader)."""
    g = obj.Geometry
    rec = {"guid": str(obj.Id), "name": obj.Attributes.Name or None,
           "layer": _layer_path(doc, obj), "hidden": _is_hidden(doc, obj),
           "type": type(g).__name__, "user_text": object_user_text(obj)}
    rec.update(rgeo.shape_record(g, tolerance))
    return rec


def document_record(doc, objects=None, title=None):
    """The plain record of the document (its objects: ``objects``, else candidate_objects)."""
    tol = doc.ModelAbsoluteTolerance
    objs = candidate_objects(doc) if objects is None else list(objects)
    name = title or (os.path.splitext(doc.Name)[0] if doc.Name else None)
    return objs, {"name": name, "units": document_units(doc), "tolerance": tol,
                  "user_text": document_user_text(doc),
                  "objects": [object_record(doc, o, tol) for o in objs]}


def collect_model(doc, objects=None, title=None):
    """Read the model from the document by the CAD attribute convention; returns a
    Collected (``issues`` lists the errors; ``model`` is None when there is one)."""
    objs, record = document_record(doc, objects, title)
    reading = cad_reader.read_document(record, host="rhino")
    return Collected(reading, dict((str(o.Id), o.Id) for o in objs))


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
            a.SetUserString("rbla.state", c["state"])
            a.SetUserString("rbla.blocks", ", ".join(c["blocks"]))
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
        for p, text in rres.influence_labels(result, 5, 3, scale):
            doc.Objects.AddTextDot(rg.TextDot(text, rgeo.point3d(p)),
                                   _attributes(lab, (17, 17, 17), "rbla:influential_joint"))
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
