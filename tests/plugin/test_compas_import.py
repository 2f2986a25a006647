"""The COMPAS converter: COMPAS 1 and 2 layouts, lists of meshes, a message naming the format for
anything else, supports by contact with the ground plane, and split faces accepted.

Inputs: the COMPAS assemblies in tests/data/compas (made by other tools), the same data re-encoded
as COMPAS 1 writes it ({"dtype", "value"} wrappers, compas_assembly's {"assembly", "blocks"}
files), and the generator's vault written as COMPAS meshes with its feet moved as CAD leaves them.
"""

import copy
import json
import os
import random
import subprocess
import sys
import tempfile
import unittest

import _support  # noqa: F401
from rbla_cad import compas_import
from rbla_cad.compas_formats import ConversionError

DATA = os.path.join(_support.REPO, "tests", "data", "compas")


def load(name):
    with open(os.path.join(DATA, name), encoding="utf-8") as fh:
        return json.load(fh)


def as_compas1(x):
    """The same data as COMPAS 1's encoder writes it: {"dtype", "value"} instead of "data"."""
    if isinstance(x, list):
        return [as_compas1(v) for v in x]
    if not isinstance(x, dict):
        return x
    out = {}
    for k, v in x.items():
        if k == "guid":
            continue
        out["value" if k == "data" and "dtype" in x else k] = as_compas1(v)
    return out


def mesh_data(block):
    """A COMPAS 2 mesh (halfedge data) of an rbla block."""
    vertex = {str(i): {"x": v[0], "y": v[1], "z": v[2]} for i, v in enumerate(block["vertices"])}
    face = {str(i): list(f) for i, f in enumerate(block["faces"])}
    return {"dtype": "compas.datastructures/Mesh", "data": {"vertex": vertex, "face": face}}


def generated_vault(nu=6, nv=8):
    script = os.path.join(_support.SAMPLES, "generate_samples.py")
    text = subprocess.run([sys.executable, script, "vault", "--nu", str(nu), "--nv", str(nv)],
                          capture_output=True, text=True, check=True).stdout
    return json.loads(text)


def box(name, low, high):
    """An rbla block: the axis-aligned box from `low` to `high`, faces counter-clockwise from
    outside."""
    (x0, y0, z0), (x1, y1, z1) = low, high
    vertices = [[x0, y0, z0], [x1, y0, z0], [x1, y1, z0], [x0, y1, z0],
                [x0, y0, z1], [x1, y0, z1], [x1, y1, z1], [x0, y1, z1]]
    faces = [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]]
    return {"id": name, "vertices": vertices, "faces": faces}


def roles(model):
    return {b["id"]: b["role"] for b in model["blocks"]}


class Compas2Test(unittest.TestCase):
    def test_arch_keeps_its_supports_and_stored_interfaces(self):
        model, info = compas_import.convert(load("compas_assembly/arch_assembly.json"), with_interfaces=True)
        self.assertEqual(info["layout"], "COMPAS 2 assembly")
        self.assertEqual(len(model["blocks"]), 30)
        self.assertEqual(sorted(info["supports_from_file"]), ["0", "29"])
        self.assertIsNone(info["ground_level"])  # the file marks supports: no ground rule
        self.assertEqual(len(model["interfaces"]), 29)


class Compas1Test(unittest.TestCase):
    def test_value_wrappers_give_the_same_model(self):
        doc = load("compas_assembly/arch_assembly.json")
        two, _ = compas_import.convert(doc, with_interfaces=True)
        one, info = compas_import.convert(as_compas1(doc), with_interfaces=True)
        self.assertEqual(info["layout"], "COMPAS 1 assembly")
        self.assertEqual(one["blocks"], two["blocks"])
        self.assertEqual(one["interfaces"], two["interfaces"])

    def test_compas_assembly_to_json_layout(self):
        # compas_assembly's own to_json: {"assembly": graph data, "blocks": {key: mesh}} with the
        # graph's default node attributes named "dna" and interfaces as "interface_points".
        doc = load("compas_assembly/arch_assembly.json")
        graph = copy.deepcopy(doc["data"]["graph"]["data"])
        blocks = {k: as_compas1(n.pop("block")) for k, n in graph["node"].items()}
        graph["dna"] = graph.pop("default_node_attributes")
        for u, nbrs in graph["edge"].items():
            for v, attr in nbrs.items():
                attr["interface_points"] = attr.pop("interfaces")[0]["data"]["points"]
        model, info = compas_import.convert({"assembly": graph, "blocks": blocks}, with_interfaces=True)
        reference, _ = compas_import.convert(doc, with_interfaces=True)
        self.assertIn("assembly, blocks", info["layout"])
        self.assertEqual(model["blocks"], reference["blocks"])
        self.assertEqual(model["interfaces"], reference["interfaces"])

    def test_a_list_of_meshes_becomes_blocks(self):
        vault = generated_vault()
        free = [b for b in vault["blocks"] if b["id"] != "base"]
        for encode, layout in ((lambda d: d, "COMPAS 2 list"), (as_compas1, "COMPAS 1 list")):
            model, info = compas_import.convert(encode([mesh_data(b) for b in free]))
            self.assertTrue(info["layout"].startswith(layout), info["layout"])
            self.assertEqual(len(model["blocks"]), len(free))
            for converted, original in zip(model["blocks"], free):
                self.assertEqual(converted["vertices"], original["vertices"])


class FormatMessageTest(unittest.TestCase):
    def check(self, doc, found):
        with self.assertRaises(ConversionError) as ctx:
            compas_import.convert(doc)
        message = str(ctx.exception)
        self.assertIn(found, message)
        self.assertIn("expected a COMPAS 2 assembly", message)
        self.assertIn("COMPAS 1 assembly", message)
        self.assertIn("list of COMPAS meshes", message)

    def test_other_compas_objects_are_named(self):
        box = {"dtype": "compas.geometry/Box", "data": {"xsize": 1, "ysize": 1, "zsize": 1}}
        self.check(box, "found COMPAS 2 object of dtype 'compas.geometry/Box'")
        self.check(as_compas1(box), "found COMPAS 1 object of dtype 'compas.geometry/Box'")
        self.check([[0, 0, 0], [1, 0, 0]], "found a list of 2 items (list)")
        self.check(42, "found a JSON int")

    def test_a_list_with_something_else_names_the_item(self):
        doc = [mesh_data(generated_vault(2, 2)["blocks"][1]), {"dtype": "compas.geometry/Point", "data": [0, 0, 0]}]
        with self.assertRaises(ConversionError) as ctx:
            compas_import.convert(doc)
        self.assertIn("item 1 is not a COMPAS mesh", str(ctx.exception))

    def test_the_example_input_of_the_wall_is_refused_with_its_reason(self):
        with self.assertRaises(ConversionError) as ctx:
            compas_import.convert(load("compas_assembly/wall.json"))
        self.assertIn("not an assembly", str(ctx.exception))


def _set(doc, path, value):
    """doc with the value at path (a list of keys) replaced, or removed when value is _DELETE."""
    doc = copy.deepcopy(doc)
    parent = doc
    for k in path[:-1]:
        parent = parent[k]
    if value is _DELETE:
        del parent[path[-1]]
    else:
        parent[path[-1]] = value
    return doc


_DELETE = object()
TWO = "compas_assembly/two-blocks_assembly.json"
NODE0 = ["data", "graph", "data", "node", "0"]
MESH0 = NODE0 + ["block", "data"]
EDGE01 = ["data", "graph", "data", "edge", "0", "1"]


def polyhedra():
    """The two blocks of two-blocks_assembly.json as a list of COMPAS polyhedron meshes."""
    out = []
    for node in load(TWO)["data"]["graph"]["data"]["node"].values():
        m = node["block"]["data"]
        keys = sorted(m["vertex"], key=int)
        out.append({"dtype": "compas.datastructures/Mesh",
                    "data": {"vertices": [[m["vertex"][k][c] for c in "xyz"] for k in keys],
                             "faces": list(m["face"].values())}})
    return out


# Well-nested JSON of the right layout with a wrong value inside, made from the real files: each
# is refused with the JSON pointer of that value (before: KeyError, TypeError, AttributeError,
# ValueError or IndexError from deep inside the converter). (path, new value, pointer, words)
MALFORMED_ASSEMBLY = [
    (["data", "graph", "data", "node"], 5, "/data/graph/data/node", "found a number"),
    (NODE0, [1, 2], "/data/graph/data/node/0", "found a list"),
    (NODE0 + ["is_support"], "false", "/data/graph/data/node/0/is_support", "true or false"),
    (["data", "graph", "data", "default_node_attributes"], -1,
     "/data/graph/data/default_node_attributes", "expected an object"),
    (MESH0 + ["vertex"], None, "/data/graph/data/node/0/block/data/vertex", "object of vertices"),
    (MESH0 + ["vertex", "3"], "0.5 0.5 0.5", "/data/graph/data/node/0/block/data/vertex/3", "expected a point"),
    (MESH0 + ["vertex", "3", "y"], _DELETE, "/data/graph/data/node/0/block/data/vertex/3", '"y" is missing'),
    (MESH0 + ["vertex", "3", "x"], "0.5", "/data/graph/data/node/0/block/data/vertex/3/x", "expected a number"),
    (MESH0 + ["vertex", "3", "x"], True, "/data/graph/data/node/0/block/data/vertex/3/x", "found a boolean"),
    (MESH0 + ["vertex", "3", "x"], float("nan"), "/data/graph/data/node/0/block/data/vertex/3/x", "nan"),
    (MESH0 + ["vertex", "3", "x"], 1e300, "/data/graph/data/node/0/block/data/vertex/3/x", "schema's bound"),
    (MESH0 + ["face"], "0 1 2 3", "/data/graph/data/node/0/block/data/face", "object of faces"),
    (MESH0 + ["face"], {}, "/data/graph/data/node/0/block/data/face", "no face"),
    (MESH0 + ["face", "2"], 7, "/data/graph/data/node/0/block/data/face/2", "a face"),
    (MESH0 + ["face", "2", 1], 99, "/data/graph/data/node/0/block/data/face/2/1", "vertex \"99\""),
    (MESH0 + ["face", "2", 1], {"key": 2}, "/data/graph/data/node/0/block/data/face/2/1", "vertex key"),
    (MESH0 + ["attributes"], 5, None, None),  # a name not given as an object is no label: accepted
    (["data", "graph", "data", "edge"], [], "/data/graph/data/edge", "expected an object"),
    (EDGE01 + ["interfaces"], "none", "/data/graph/data/edge/0/1/interfaces", "list of interfaces"),
    (EDGE01 + ["interfaces", 0, "data"], 3, "/data/graph/data/edge/0/1/interfaces/0/data", "interface object"),
    (EDGE01 + ["interfaces", 0, "data", "points"], 4, "/data/graph/data/edge/0/1/interfaces/0/data/points",
     "list of points"),
    (EDGE01 + ["interfaces", 0, "data", "points", 2, "data"], [0.5, 0.5],
     "/data/graph/data/edge/0/1/interfaces/0/data/points/2/data", "a list of 2 items"),
]


class MalformedInputTest(unittest.TestCase):
    """Every malformed value is a ConversionError whose message starts with its JSON pointer."""

    def refused(self, doc, pointer, words, **options):
        with self.assertRaises(ConversionError) as ctx:
            compas_import.convert(doc, with_interfaces=True, **options)
        message = str(ctx.exception)
        self.assertTrue(message.startswith(pointer + ": "), message)
        if words:
            self.assertIn(words, message)
        self.assertNotIn("\n", message)
        return message

    def test_wrong_values_in_an_assembly_name_their_pointer(self):
        doc = load(TWO)
        for path, value, pointer, words in MALFORMED_ASSEMBLY:
            with self.subTest(path="/".join(map(str, path)), value=value):
                bad = _set(doc, path, value)
                if pointer is None:
                    compas_import.convert(bad, with_interfaces=True)
                else:
                    self.refused(bad, pointer, words)

    def test_a_dtype_that_is_not_text_is_no_dtype(self):
        model, info = compas_import.convert(_set(load(TWO), ["dtype"], 7))
        self.assertEqual(len(model["blocks"]), 2)
        self.assertEqual(info["dtype"], "")

    def test_wrong_values_in_polyhedra_name_their_pointer(self):
        doc = polyhedra()
        for path, value, pointer, words in [
                ([0, "data", "vertices"], {"0": [0, 0, 0]}, "/0/data/vertices", "list of vertices"),
                ([1, "data", "vertices", 2], "x", "/1/data/vertices/2", "expected a point"),
                ([1, "data", "vertices", 2], [0, 0], "/1/data/vertices/2", "a list of 2 items"),
                ([1, "data", "faces"], None, "/1/data/faces", "list of faces"),
                ([1, "data", "faces", 0], "0123", "/1/data/faces/0", "a face"),
                ([1, "data", "faces", 0, 2], 8, "/1/data/faces/0/2", "vertex \"8\""),
                ([1, "data", "faces", 0, 2], -1, "/1/data/faces/0/2", "vertex \"-1\""),
                ([1, "data", "faces", 0, 2], 2.0, "/1/data/faces/0/2", "vertex key")]:
            with self.subTest(path="/".join(map(str, path)), value=value):
                self.refused(_set(doc, path, value), pointer, words)

    def test_compas1_blocks_file_names_its_pointer(self):
        graph = copy.deepcopy(load(TWO)["data"]["graph"]["data"])
        blocks = {k: as_compas1(n.pop("block")) for k, n in graph["node"].items()}
        graph["dna"] = graph.pop("default_node_attributes")
        self.refused({"assembly": graph, "blocks": []}, "/blocks", "expected an object")
        blocks["1"]["value"]["vertex"]["4"]["z"] = None
        self.refused({"assembly": graph, "blocks": blocks}, "/blocks/1/value/vertex/4/z", "found null")
        graph["dna"] = "none"
        self.refused({"assembly": graph, "blocks": blocks}, "/assembly/dna", "expected an object")

    def test_keys_with_control_characters_stay_on_one_line(self):
        doc = load(TWO)
        mesh = doc["data"]["graph"]["data"]["node"]["0"]["block"]["data"]
        mesh["face"]["2"][1] = "x\ny"
        message = self.refused(doc, "/data/graph/data/node/0/block/data/face/2/1", "x\\ny")
        doc = load(TWO)
        doc["data"]["graph"]["data"]["node"]["a\nb"] = 3
        message = self.refused(doc, "/data/graph/data/node/a\\u000ab", "expected an object")
        self.assertNotIn("\n", message)

    def test_the_example_input_with_wrong_courses_is_described_not_crashed(self):
        doc = load("compas_assembly/wall.json")
        for courses in (None, [1, 2], [[{"dtype": 3}]]):
            with self.subTest(courses=courses):
                with self.assertRaises(ConversionError):
                    compas_import.convert(dict(doc, courses=courses))


class GroundContactTest(unittest.TestCase):
    def test_every_foot_of_an_imperfect_vault_is_fixed(self):
        # The generator's vault without its slab, as meshes: 2 nv feet at z = 0 (by construction:
        # the blocks v00_* and v05_*). CAD leaves the feet at slightly different heights and
        # warped: each foot raised by 0 to 8 mm and one of its corners by up to 4 mm more. A band
        # of 1e-3 of the height (3 mm) fixes only some; contact with the ground plane fixes all,
        # and nothing else (the next row starts about 0.5 m up).
        vault = generated_vault(6, 8)
        rng = random.Random(7)
        meshes = []
        for b in vault["blocks"]:
            if b["id"] == "base":
                continue
            if b["id"].startswith(("v0_", "v5_")):
                lift = rng.uniform(0.0, 0.008)
                b = copy.deepcopy(b)
                low = [i for i, v in enumerate(b["vertices"]) if v[2] == 0.0]
                for i in low:
                    b["vertices"][i][2] += lift
                b["vertices"][low[0]][2] += rng.uniform(0.0, 0.004)
            meshes.append((b["id"], mesh_data(b)))
        doc = {"dtype": "compas_assembly.datastructures/Assembly",
               "data": {"graph": {"dtype": "compas.datastructures/Graph",
                                  "data": {"node": {k: {"block": m} for k, m in meshes}, "edge": {}}}}}
        model, info = compas_import.convert(doc)
        feet = {b["id"] for b in model["blocks"] if b["id"].startswith(("v0_", "v5_"))}
        self.assertEqual(len(feet), 16)
        self.assertEqual({k for k, r in roles(model).items() if r == "fixed"}, feet)
        self.assertEqual(set(info["ground_contacts"]), feet)

    def test_legs_standing_on_an_edge_do_not_rest_on_the_ground(self):
        # compas_cra's A: two leaning legs touch the ground along an edge only.
        model, info = compas_import.convert(load("compas_cra/A.json"))
        self.assertEqual(info["ground_contacts"], [])
        self.assertNotIn("fixed", roles(model).values())

    def test_a_pier_on_a_plinth_is_not_fixed_to_the_ground(self):
        # A 1 x 1 m pier on a 1.2 x 1.2 m plinth 40 mm thick: the pier's foot is within 3 % of its
        # diameter (42 mm) of the ground plane, but 40 mm clear of it everywhere: it stands on the
        # plinth, not on the ground, as rbla's detection (clearance limit 30 mm) sees it.
        plinth = box("plinth", (-0.6, -0.6, 0.0), (0.6, 0.6, 0.04))
        pier = box("pier", (-0.5, -0.5, 0.04), (0.5, 0.5, 2.04))
        doc = [mesh_data(plinth), mesh_data(pier)]
        model, info = compas_import.convert(doc)
        self.assertEqual(info["ground_contacts"], ["0"])
        self.assertEqual(roles(model), {"0": "fixed", "1": "free"})
        # The same foot 20 mm up is a foot CAD left off the ground: it counts.
        model, info = compas_import.convert([mesh_data(box("pier", (-0.5, -0.5, 0.02), (0.5, 0.5, 2.02))),
                                             mesh_data(box("x", (3.0, 0.0, 0.0), (3.2, 0.2, 0.2)))])
        self.assertEqual(sorted(info["ground_contacts"]), ["0", "1"])

    @unittest.skipUnless(_support.solver_executable(), "rbla not built")
    def test_the_clearance_limit_is_the_solvers(self):
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "result.json")
            subprocess.run([_support.solver_executable(), "solve", _support.sample("block.json"), "-o", out, "-q"],
                           check=True, capture_output=True)
            with open(out, encoding="utf-8") as fh:
                tolerances = json.load(fh)["detection"]["tolerances"]
        self.assertEqual(tolerances["clearance_limit"], compas_import.CLEARANCE_LIMIT_M)

    def test_files_with_supports_keep_theirs_unless_asked(self):
        doc = load("compas_assembly/wall_assembly.json")
        model, info = compas_import.convert(doc)
        self.assertEqual(len(info["supports_from_file"]), 10)
        self.assertIsNone(info["ground_level"])
        model, info = compas_import.convert(doc, ground="always")
        self.assertIsNotNone(info["ground_level"])


class SplitFacesTest(unittest.TestCase):
    def test_a_cap_split_with_a_vertex_on_an_edge_is_accepted(self):
        # A box whose top is split into two quads by a line between the midpoints of two edges:
        # the side faces do not carry the midpoints (T-junctions), as rbla accepts.
        v = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1],
             [0.5, 0, 1], [0.5, 1, 1]]
        f = [[0, 3, 2, 1], [4, 8, 9, 7], [8, 5, 6, 9], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]]
        doc = [{"dtype": "compas.datastructures/Mesh",
                "data": {"vertex": {str(i): {"x": p[0], "y": p[1], "z": p[2]} for i, p in enumerate(v)},
                         "face": {str(i): x for i, x in enumerate(f)}}}]
        model, info = compas_import.convert(doc, ground="never")
        self.assertEqual(info["t_junctions"], ["0"])
        self.assertFalse([p for p in info["problems"] if "not shared" in p], info["problems"])
        self.assertAlmostEqual(model["blocks"][0]["volume"], 1.0)


if __name__ == "__main__":
    unittest.main()
