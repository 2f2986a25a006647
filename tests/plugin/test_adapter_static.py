"""Static checks of the Rhino / Grasshopper adapter (it cannot run here): Python 3.9 syntax for
every plugin file, imports limited to the core + RhinoCommon + the standard library, and each
Grasshopper component's metadata agreeing with its code."""

import ast
import json
import os
import sys
import unittest

import _support

RHINO = os.path.join(_support.PLUGIN, "rhino")
ALLOWED_HOST = {"Rhino", "System", "scriptcontext", "Grasshopper", "rbla_cad", "rbla_rhino",
                "_bootstrap"}


def _py_files(root):
    for d, _, files in os.walk(root):
        if "__pycache__" in d:
            continue
        for f in files:
            if f.endswith(".py"):
                yield os.path.join(d, f)


def _read(path):
    with open(path, encoding="utf-8") as f:
        return f.read()


def _stdlib():
    names = getattr(sys, "stdlib_module_names", None)
    if names:
        return set(names)
    return {"os", "sys", "json", "math", "re", "tempfile", "hashlib", "collections",
            "threading", "subprocess", "shutil", "time", "queue", "argparse"}


class SyntaxTest(unittest.TestCase):
    def test_python39_syntax(self):
        files = list(_py_files(os.path.join(_support.PLUGIN, "rbla_cad"))) + \
            list(_py_files(RHINO))
        self.assertGreater(len(files), 15)
        for path in files:
            with open(path, encoding="utf-8") as f:
                src = f.read()
            try:
                ast.parse(src, path, feature_version=(3, 9))
            except SyntaxError as e:
                self.fail("%s is not Python 3.9 syntax: %s" % (path, e))
            self.assertNotIn(" match ", "".join(l for l in src.splitlines()
                                                if l.lstrip().startswith("match ")), path)

    def test_core_is_standard_library_only(self):
        std = _stdlib()
        for path in _py_files(os.path.join(_support.PLUGIN, "rbla_cad")):
            tree = ast.parse(_read(path))
            for node in ast.walk(tree):
                mods = []
                if isinstance(node, ast.Import):
                    mods = [a.name.split(".")[0] for a in node.names]
                elif isinstance(node, ast.ImportFrom) and node.level == 0:
                    mods = [node.module.split(".")[0]]
                for m in mods:
                    self.assertTrue(m in std or m == "Queue", "%s imports %s" % (path, m))

    def test_adapter_imports(self):
        std = _stdlib()
        for path in _py_files(RHINO):
            tree = ast.parse(_read(path))
            for node in ast.walk(tree):
                mods = []
                if isinstance(node, ast.Import):
                    mods = [a.name.split(".")[0] for a in node.names]
                elif isinstance(node, ast.ImportFrom) and node.level == 0:
                    mods = [node.module.split(".")[0]]
                for m in mods:
                    self.assertTrue(m in std or m in ALLOWED_HOST,
                                    "%s imports %s (only the core and RhinoCommon)" % (path, m))


class ComponentTest(unittest.TestCase):
    def test_metadata_matches_code(self):
        gh = os.path.join(RHINO, "grasshopper")
        comps = sorted(d for d in os.listdir(gh) if os.path.isdir(os.path.join(gh, d)))
        self.assertEqual(comps, ["RblaCriticalFriction", "RblaLegend", "RblaMechanism", "RblaModel", "RblaSolve",
                                 "RblaWorstDirection", "RblaWorstSettlement"])
        for c in comps:
            with open(os.path.join(gh, c, "metadata.json")) as f:
                meta = json.load(f)
            with open(os.path.join(gh, c, "code.py")) as f:
                tree = ast.parse(f.read())
            for key in ("name", "nickname", "category", "subcategory", "description"):
                self.assertTrue(meta.get(key), "%s: %s" % (c, key))
            used = set(n.id for n in ast.walk(tree)
                       if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load))
            assigned = set()
            for n in ast.walk(tree):
                if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Store):
                    assigned.add(n.id)
            ins = [p["name"] for p in meta["ghpython"]["inputParameters"]]
            outs = [p["name"] for p in meta["ghpython"]["outputParameters"]]
            self.assertFalse(set(ins) & set(outs), c)
            for p in meta["ghpython"]["inputParameters"]:
                self.assertIn(p["scriptParamAccess"], ("item", "list", "tree"))
                self.assertTrue(p["typeHintID"] and p["description"])
                self.assertIn(p["name"], used, "%s: input %s unused" % (c, p["name"]))
                self.assertNotIn(p["name"], assigned, "%s: input %s overwritten" % (c, p["name"]))
            for p in meta["ghpython"]["outputParameters"]:
                self.assertIn(p["name"], assigned, "%s: output %s never set" % (c, p["name"]))

    def test_commands_exist(self):
        cmds = os.path.join(RHINO, "commands")
        for name, fn in (("RblaExport", "export_command"), ("RblaSolve", "solve_command"),
                         ("RblaShowMechanism", "show_mechanism_command"),
                         ("RblaClear", "clear_command")):
            with open(os.path.join(cmds, name + ".py")) as f:
                self.assertIn("commands.%s()" % fn, f.read())
        src = _read(os.path.join(RHINO, "rbla_rhino", "commands.py"))
        for fn in ("export_command", "solve_command", "show_mechanism_command", "clear_command"):
            self.assertIn("def %s(" % fn, src)
        self.assertIn("BeginUndoRecord", _read(os.path.join(RHINO, "rbla_rhino", "document.py")))


if __name__ == "__main__":
    unittest.main()
