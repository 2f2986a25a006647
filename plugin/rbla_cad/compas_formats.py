"""Reading the block meshes of COMPAS files, in the layouts COMPAS 1 and COMPAS 2 write.

Standard library only. ``read_assembly(doc)`` returns the blocks (node key, mesh data, node
attributes), the node default for ``is_support``, the interfaces stored on the graph edges, and a
one-line name of the layout it found. Layouts understood:

- COMPAS 2 data (``compas.json_dump``): ``{"dtype", "data", "guid"}`` wrappers; an assembly
  (compas_assembly ``Assembly``, compas_cra ``CRA_Assembly``) holds a graph whose ``node``
  entries carry a ``block`` mesh and ``is_support``; interfaces are ``Interface`` objects with
  ``points`` in the edge attribute ``interfaces``.
- COMPAS 1 data: the same with ``{"dtype", "value"}`` wrappers; graphs may name their default
  node attributes ``dna`` and store interface polygons as the edge attribute
  ``interface_points``; compas_assembly's own ``to_json`` wrote ``{"assembly": graph, "blocks":
  {key: mesh}}``.
- A single mesh, or a list (or a name -> mesh object) of meshes, COMPAS 1 or 2: one block each.

Meshes are COMPAS halfedge data (``vertex``: key -> {x, y, z}, ``face``: key -> vertex keys) or
polyhedron data (``vertices``: [[x, y, z]], ``faces``: [[indices]]). Anything else is refused
with a ``ConversionError`` saying what was found and what is expected.
"""

EXPECTED = ("a COMPAS 2 assembly (compas_assembly Assembly or compas_cra CRA_Assembly written by "
            "compas.json_dump: {\"dtype\", \"data\"}), a COMPAS 1 assembly ({\"dtype\", \"value\"}, "
            "or compas_assembly's {\"assembly\", \"blocks\"}), or one or a list of COMPAS meshes "
            "(halfedge data with \"vertex\" and \"face\", or polyhedron data with \"vertices\" and "
            "\"faces\")")


class ConversionError(Exception):
    """The input is not an assembly this converter understands."""


def unwrap(x):
    """Strip COMPAS {"dtype", "data" (COMPAS 2) or "value" (COMPAS 1)} wrappers."""
    while isinstance(x, dict) and "dtype" in x and ("data" in x or "value" in x):
        x = x["data"] if "data" in x else x["value"]
    return x


def dtype_of(x):
    return x.get("dtype", "") if isinstance(x, dict) else ""


def generation(x):
    """'COMPAS 2' or 'COMPAS 1' from the wrapper of x, or '' when x has none."""
    if isinstance(x, dict) and "dtype" in x:
        return "COMPAS 2" if "data" in x else "COMPAS 1" if "value" in x else ""
    return ""


def is_mesh(x):
    m = unwrap(x)
    return isinstance(m, dict) and (("vertex" in m and "face" in m) or ("vertices" in m and "faces" in m))


def describe(doc):
    """A short description of what a document is, for error messages."""
    if isinstance(doc, list):
        kinds = sorted({dtype_of(x) or type(x).__name__ for x in doc[:50]})
        return "a list of %d items (%s)" % (len(doc), ", ".join(kinds) or "empty")
    if isinstance(doc, dict):
        keys = sorted(str(k) for k in doc)[:8]
        d = dtype_of(doc)
        return ("%s object of dtype %r" % (generation(doc) or "an", d) if d else "an object with keys %s" % keys)
    return "a JSON %s" % type(doc).__name__


class Assembly(object):
    """The blocks of a COMPAS file: nodes [(key, mesh data, attributes)], default is_support,
    edges [(u, v, [polygon points])], dtype and the name of the layout found."""

    def __init__(self, layout, dtype):
        self.layout = layout
        self.dtype = dtype
        self.nodes = []
        self.default_support = False
        self.edges = []


def _graph_of(data):
    """The graph data (with "node" or "vertex" entries) inside an assembly's data, or None."""
    if not isinstance(data, dict):
        return None
    if "graph" in data:
        g = unwrap(data["graph"])
        return g if isinstance(g, dict) else None
    if "node" in data or "vertex" in data:
        return data
    return None


def _interfaces_of(attr):
    """Polygons stored on an edge: COMPAS 2 Interface objects, or COMPAS 1 interface_points."""
    attr = attr or {}
    polygons = []
    for itf in attr.get("interfaces") or []:
        polygons.append(unwrap(itf).get("points") or [])
    if attr.get("interface_points"):
        polygons.append(attr["interface_points"])
    return polygons


def _from_graph(asm, g, blocks=None):
    nodes = g.get("node")
    if nodes is None:
        nodes = g.get("vertex")
    if not isinstance(nodes, dict) or not nodes:
        raise ConversionError("the assembly's graph has no nodes")
    defaults = g.get("default_node_attributes") or g.get("dna") or g.get("dva") or {}
    asm.default_support = bool(defaults.get("is_support", False))
    for key, attr in nodes.items():
        attr = attr or {}
        mesh = attr.get("block")
        if mesh is None and blocks is not None:
            mesh = blocks.get(str(key))
        if mesh is None:
            raise ConversionError("node %s has no block mesh" % key)
        if not is_mesh(mesh):
            raise ConversionError("node %s: the block is not a COMPAS mesh (dtype %r)" % (key, dtype_of(mesh)))
        asm.nodes.append((str(key), unwrap(mesh), attr, mesh))
    for u, nbrs in (g.get("edge") or {}).items():
        for v, attr in (nbrs or {}).items():
            asm.edges.append((str(u), str(v), _interfaces_of(attr)))
    return asm


def _from_meshes(items, layout):
    asm = Assembly(layout, "")
    for key, mesh in items:
        if not is_mesh(mesh):
            raise ConversionError("%s: item %s is not a COMPAS mesh (%s); expected %s"
                                  % (layout, key, describe(mesh), EXPECTED))
        asm.nodes.append((str(key), unwrap(mesh), {}, mesh))
    return asm


def read_assembly(doc):
    """The blocks of a parsed COMPAS document (see the module's docstring)."""
    if isinstance(doc, list):
        if not doc or not any(is_mesh(x) for x in doc):
            raise ConversionError("found %s; expected %s" % ("an empty list" if not doc else describe(doc), EXPECTED))
        gen = generation(doc[0]) or "plain"
        return _from_meshes(list(enumerate(doc)), "%s list of %d meshes" % (gen, len(doc)))
    if not isinstance(doc, dict):
        raise ConversionError("found %s; expected %s" % (describe(doc), EXPECTED))
    if "assembly" in doc and "blocks" in doc:  # compas_assembly's own to_json (COMPAS 1 era)
        g = _graph_of(unwrap(doc["assembly"]))
        if g is None:
            raise ConversionError("found an {\"assembly\", \"blocks\"} file whose assembly has no graph; expected %s"
                                  % EXPECTED)
        blocks = {str(k): v for k, v in (doc["blocks"] or {}).items()}
        return _from_graph(Assembly("compas_assembly {assembly, blocks} file", "Assembly"), g, blocks)
    data = unwrap(doc)
    g = _graph_of(data)
    if g is not None:
        gen = generation(doc) or "plain"
        return _from_graph(Assembly("%s assembly" % gen, dtype_of(doc)), g)
    if is_mesh(doc):
        return _from_meshes([("0", doc)], "%s mesh" % (generation(doc) or "plain"))
    if isinstance(data, dict) and data and all(is_mesh(v) for v in data.values()):
        gen = generation(next(iter(data.values()))) or "plain"
        return _from_meshes(sorted(data.items()), "%s object of %d meshes" % (gen, len(data)))
    raise ConversionError("found %s; expected %s" % (describe(doc), EXPECTED))
