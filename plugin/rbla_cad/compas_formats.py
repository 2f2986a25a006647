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
with a ``ConversionError`` saying what was found and what is expected; a file of the right layout
with a value of the wrong kind inside (a number where an object belongs, a list that is not one)
is refused with the JSON pointer of that value, never with a Python exception.
"""

import json

EXPECTED = ("a COMPAS 2 assembly (compas_assembly Assembly or compas_cra CRA_Assembly written by "
            "compas.json_dump: {\"dtype\", \"data\"}), a COMPAS 1 assembly ({\"dtype\", \"value\"}, "
            "or compas_assembly's {\"assembly\", \"blocks\"}), or one or a list of COMPAS meshes "
            "(halfedge data with \"vertex\" and \"face\", or polyhedron data with \"vertices\" and "
            "\"faces\")")


class ConversionError(Exception):
    """The input is not an assembly this converter understands. With a pointer, the message
    starts with the JSON pointer of the value at fault, as the solver's messages do."""

    def __init__(self, message, pointer=None):
        if pointer is not None:
            message = "%s: %s" % (shown_pointer(pointer), message)
        Exception.__init__(self, message)
        self.pointer = pointer


# Longest pointer quoted in a message: keys come from the file, and one line must stay one line.
_MAX_SHOWN = 300


def child(pointer, key):
    """The JSON pointer (RFC 6901) of member or item key of the value at pointer."""
    return "%s/%s" % (pointer, str(key).replace("~", "~0").replace("/", "~1"))


def shown_pointer(pointer):
    """A pointer fit for a one-line message: control characters as \\uXXXX (no forged lines),
    cut to a few hundred characters, the root as (document)."""
    if not pointer:
        return "(document)"
    text = "".join(c if c >= " " and c != "\x7f" else "\\u%04x" % ord(c) for c in pointer)
    if len(text) > _MAX_SHOWN:
        text = "%s... (%d characters)" % (text[:_MAX_SHOWN], len(pointer))
    return text


def shown_text(text, limit=40):
    """Text from the file quoted for a one-line message (JSON escapes: no control characters)."""
    return json.dumps(text if len(text) <= limit else text[:limit] + "...")


def kind_of(x):
    """What a JSON value is, in words, for messages."""
    if x is None:
        return "null"
    if isinstance(x, bool):
        return "a boolean"
    if isinstance(x, (int, float)):
        return "a number"
    if isinstance(x, str):
        return "a string"
    if isinstance(x, list):
        return "a list"
    return "an object"


def expect(x, types, what, pointer):
    """x itself when it is one of types (bool is never a number here); else a ConversionError
    naming the pointer, what was expected and what was found."""
    if isinstance(x, types) and not (isinstance(x, bool) and bool not in _as_tuple(types)):
        return x
    raise ConversionError("expected %s, found %s" % (what, kind_of(x)), pointer)


def _as_tuple(types):
    return types if isinstance(types, tuple) else (types,)


def optional_object(x, pointer):
    """An object that may be absent (null): {} then."""
    return {} if x is None else expect(x, dict, "an object", pointer)


def unwrap_at(x, pointer=""):
    """(x without its COMPAS {"dtype", "data" (COMPAS 2) or "value" (COMPAS 1)} wrappers, the
    pointer of what is left)."""
    while isinstance(x, dict) and "dtype" in x and ("data" in x or "value" in x):
        key = "data" if "data" in x else "value"
        x, pointer = x[key], child(pointer, key)
    return x, pointer


def unwrap(x):
    """Strip COMPAS {"dtype", "data" (COMPAS 2) or "value" (COMPAS 1)} wrappers."""
    return unwrap_at(x)[0]


def dtype_of(x):
    """The dtype of a wrapper, or "" (also when the file gives something other than a string)."""
    d = x.get("dtype", "") if isinstance(x, dict) else ""
    return d if isinstance(d, str) else ""


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
    """The blocks of a COMPAS file: nodes [(key, mesh data, attributes, wrapper, pointer of the
    mesh data)], default is_support, edges [(u, v, [(pointer, polygon points)])], dtype and the
    name of the layout found."""

    def __init__(self, layout, dtype):
        self.layout = layout
        self.dtype = dtype
        self.nodes = []
        self.default_support = False
        self.edges = []


def _graph_of(data, pointer):
    """(graph data with "node" or "vertex" entries inside an assembly's data, its pointer), or
    (None, None)."""
    if not isinstance(data, dict):
        return None, None
    if "graph" in data:
        g, at = unwrap_at(data["graph"], child(pointer, "graph"))
        return (g, at) if isinstance(g, dict) else (None, None)
    if "node" in data or "vertex" in data:
        return data, pointer
    return None, None


def _support_flag(value, default, pointer):
    """is_support: a JSON boolean (null or absent: the default). Anything else is refused rather
    than read by Python's truth (the string "false" would make a support)."""
    if value is None:
        return default
    return expect(value, bool, "true or false", pointer)


def _interfaces_of(attr, pointer):
    """Polygons stored on an edge, as (pointer, points): COMPAS 2 Interface objects, or COMPAS 1
    interface_points."""
    attr = optional_object(attr, pointer)
    polygons = []
    at = child(pointer, "interfaces")
    for k, itf in enumerate(expect(attr.get("interfaces") or [], list, "a list of interfaces", at)):
        data, data_at = unwrap_at(itf, child(at, k))
        points = expect(data, dict, "an interface object", data_at).get("points") or []
        polygons.append((child(data_at, "points"), points))
    if attr.get("interface_points"):
        polygons.append((child(pointer, "interface_points"), attr["interface_points"]))
    return polygons


def _from_graph(asm, g, pointer, blocks=None, blocks_at=None):
    name = "node" if g.get("node") is not None else "vertex"
    nodes, nodes_at = g.get(name), child(pointer, name)
    if not nodes:
        raise ConversionError("the assembly's graph has no nodes", nodes_at)
    expect(nodes, dict, "the graph's nodes (an object)", nodes_at)
    for name in ("default_node_attributes", "dna", "dva"):
        if g.get(name):
            defaults_at = child(pointer, name)
            defaults = expect(g[name], dict, "an object", defaults_at)
            break
    else:
        defaults, defaults_at = {}, pointer
    asm.default_support = _support_flag(defaults.get("is_support"), False, child(defaults_at, "is_support"))
    for key, attr in nodes.items():
        node_at = child(nodes_at, key)
        attr = optional_object(attr, node_at)
        mesh, mesh_at = attr.get("block"), child(node_at, "block")
        if mesh is None and blocks is not None:
            mesh, mesh_at = blocks.get(str(key)), child(blocks_at, key)
        if mesh is None:
            raise ConversionError("the node has no block mesh", node_at)
        if not is_mesh(mesh):
            raise ConversionError("the block is not a COMPAS mesh (%s)" % describe(mesh), mesh_at)
        # resolved here, once: the node's own flag, else the graph's default
        attr = dict(attr, is_support=_support_flag(attr.get("is_support"), asm.default_support,
                                                   child(node_at, "is_support")))
        data, data_at = unwrap_at(mesh, mesh_at)
        asm.nodes.append((str(key), data, attr, mesh, data_at))
    edges_at = child(pointer, "edge")
    for u, nbrs in optional_object(g.get("edge"), edges_at).items():
        for v, attr in optional_object(nbrs, child(edges_at, u)).items():
            asm.edges.append((str(u), str(v), _interfaces_of(attr, child(child(edges_at, u), v))))
    return asm


def _from_meshes(items, layout):
    """items: (key, mesh, pointer of the mesh)."""
    asm = Assembly(layout, "")
    for key, mesh, pointer in items:
        if not is_mesh(mesh):
            raise ConversionError("%s: item %s is not a COMPAS mesh (%s); expected %s"
                                  % (layout, key, describe(mesh), EXPECTED))
        data, data_at = unwrap_at(mesh, pointer)
        asm.nodes.append((str(key), data, {}, mesh, data_at))
    return asm


def read_assembly(doc):
    """The blocks of a parsed COMPAS document (see the module's docstring)."""
    if isinstance(doc, list):
        if not doc or not any(is_mesh(x) for x in doc):
            raise ConversionError("found %s; expected %s" % ("an empty list" if not doc else describe(doc), EXPECTED))
        gen = generation(doc[0]) or "plain"
        return _from_meshes([(k, m, child("", k)) for k, m in enumerate(doc)],
                           "%s list of %d meshes" % (gen, len(doc)))
    if not isinstance(doc, dict):
        raise ConversionError("found %s; expected %s" % (describe(doc), EXPECTED))
    if "assembly" in doc and "blocks" in doc:  # compas_assembly's own to_json (COMPAS 1 era)
        g, g_at = _graph_of(*unwrap_at(doc["assembly"], "/assembly"))
        if g is None:
            raise ConversionError("found an {\"assembly\", \"blocks\"} file whose assembly has no graph; expected %s"
                                  % EXPECTED)
        blocks = {str(k): v for k, v in optional_object(doc["blocks"], "/blocks").items()}
        return _from_graph(Assembly("compas_assembly {assembly, blocks} file", "Assembly"), g, g_at,
                           blocks, "/blocks")
    data, data_at = unwrap_at(doc)
    g, g_at = _graph_of(data, data_at)
    if g is not None:
        gen = generation(doc) or "plain"
        return _from_graph(Assembly("%s assembly" % gen, dtype_of(doc)), g, g_at)
    if is_mesh(doc):
        return _from_meshes([("0", doc, "")], "%s mesh" % (generation(doc) or "plain"))
    if isinstance(data, dict) and data and all(is_mesh(v) for v in data.values()):
        gen = generation(next(iter(data.values()))) or "plain"
        return _from_meshes([(k, m, child(data_at, k)) for k, m in sorted(data.items())],
                           "%s object of %d meshes" % (gen, len(data)))
    raise ConversionError("found %s; expected %s" % (describe(doc), EXPECTED))
