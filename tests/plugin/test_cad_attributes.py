"""The CAD attribute convention is written once (plugin/rbla_cad/data/cad_attributes.json): the
doc page is generated from it, its values agree with the model schema, and the Python reader and
the JS reader (.3dm exchange) read no key and give no message code that the data does not list,
and use every one it lists. (The shared cases, test_cad_cases.py and tests/web/cad_cases.test.mjs,
check that both read them the same way.)"""

import json
import os
import re
import unittest

import _support
from rbla_cad import usertext as ut

DOC = os.path.join(_support.REPO, "docs", "cad-attributes.md")
PY_READERS = [os.path.join(_support.PLUGIN, *p) for p in (
    ("rbla_cad", "cad_reader.py"), ("rbla_cad", "usertext.py"),
    ("rhino", "rbla_rhino", "document.py"))]
JS_READERS = [os.path.join(_support.PLUGIN, "exchange", "lib", f) for f in (
    "cad-reader.mjs", "cad-attributes.mjs", "rhino-io.mjs", "rhino-records.mjs")]


def _read(path):
    with open(path, encoding="utf-8") as f:
        return f.read()


def _keys_in(paths):
    keys = set()
    for p in paths:
        keys |= set(re.findall(r"[\"'`](rbla\.[a-z_.]+)[\"'`]", _read(p)))
    return keys


def _codes_in(paths, pattern):
    codes = set()
    for p in paths:
        codes |= set(re.findall(pattern, _read(p)))
    return codes


def _schema_node(schema, pointer):
    """The schema of a model location ("/blocks/*/role"); None when it has no single one."""
    node = schema
    for seg in pointer.strip("/").split("/"):
        while "$ref" in node:
            node = schema["definitions"][node["$ref"].split("/")[-1]]
        if seg == "*":
            if "items" not in node:
                return None
            node = node["items"]
        elif seg in node.get("properties", {}):
            node = node["properties"][seg]
        else:
            return None
    while "$ref" in node:
        node = schema["definitions"][node["$ref"].split("/")[-1]]
    return node


class ConventionTest(unittest.TestCase):
    def test_doc_page_is_generated_from_the_data(self):
        self.assertEqual(_read(DOC), ut.markdown(),
                         "docs/cad-attributes.md is stale: run python3 "
                         "plugin/rbla_cad/usertext.py --markdown docs/cad-attributes.md")
        for kind in ut.KINDS:
            for key in ut.KEYS[kind]:
                self.assertIn("`%s`" % key, _read(DOC))

    def test_values_agree_with_the_model_schema(self):
        with open(os.path.join(_support.SCHEMA, "model.schema.json")) as f:
            schema = json.load(f)
        checked = 0
        for kind in ut.KINDS:
            for e in ut.KEYS[kind].values():
                node = _schema_node(schema, e["model"]) if "model" in e else None
                if node is None:
                    continue
                where = "%s %s (%s)" % (kind, e["key"], e["model"])
                if e["type"] in ("choice", "choice_or_json") and "enum" in node:
                    self.assertEqual(e["values"], node["enum"], where)
                    checked += 1
                if "default" in e and "default" in node:
                    self.assertEqual(e["default"], node["default"], where)
                    checked += 1
                for ours, theirs in (("minimum", "minimum"), ("maximum", "maximum"),
                                     ("exclusive_minimum", "exclusiveMinimum")):
                    if ours in e or theirs in node:
                        self.assertEqual(e.get(ours), node.get(theirs), where + " " + ours)
                        checked += 1
        self.assertGreater(checked, 30)

    def test_readers_use_exactly_the_listed_keys(self):
        listed = set()
        for kind in ut.KINDS:
            for e in ut.KEYS[kind].values():
                listed.add(e["key"])
                listed |= set(e.get("aliases", []))
        generic = set(k for kind in ut.KINDS for k, e in ut.KEYS[kind].items()
                      if e.get("ignored")) | set(a for kind in ut.KINDS for a in ut.ALIASES[kind])
        written = set(e["key"] for part in ("objects", "document")
                      for e in ut.DATA["results"][part])
        for name, paths, host in (("Python", PY_READERS, "rhino"), ("JS", JS_READERS, "exchange")):
            other_host = set(k for kind in ut.KINDS for k, e in ut.KEYS[kind].items()
                             if host not in e.get("hosts", [host]))
            used = _keys_in(paths)
            self.assertEqual(used - listed - written, set(),
                             "%s side reads or writes keys the data does not list" % name)
            self.assertEqual(listed - generic - other_host - used, set(),
                             "%s reader ignores keys the data lists" % name)

    def test_readers_give_exactly_the_listed_messages(self):
        listed = set(ut.MESSAGES)
        py = _codes_in(PY_READERS + [os.path.join(_support.PLUGIN, "rbla_cad", "usertext.py")],
                       r"(?:rep|report)\.add\(\s*\"(\w+)\"|Bad\(\"(\w+)\"")
        py = set(c for pair in py for c in (pair if isinstance(pair, tuple) else (pair,)) if c)
        js = _codes_in(JS_READERS, r"(?:rep|report)\.add\(\s*'(\w+)'|new Bad\('(\w+)'")
        js = set(c for pair in js for c in (pair if isinstance(pair, tuple) else (pair,)) if c)
        for name, used, unused in (("Python", py, set()), ("JS", js, {"model_schema"})):
            self.assertEqual(used - listed, set(), "%s gives unlisted codes" % name)
            self.assertEqual(listed - used, unused, "%s never gives some listed codes (JS: "
                                                    "all but model_schema)" % name)


if __name__ == "__main__":
    unittest.main()
