"""A small JSON Schema (draft-07) validator: the subset rbla's two schemas use.

Keywords: type, enum, const, required, properties, additionalProperties, items (one schema),
minItems, maxItems, uniqueItems, minimum, maximum, exclusiveMinimum, exclusiveMaximum,
minLength, maxLength, pattern, $ref (local "#/..."), allOf, anyOf, oneOf, not, if/then/else.
Ignored: format, default, description, title, $schema, $id. Standard library only.

It is a convenience for the CAD side (an error before the solver starts, with the JSON pointer);
the solver's own validation (valijson + geometry checks, ``rbla validate``) is authoritative.
The schemas are bundled in ``rbla_cad/data/`` (copies of ``schema/*.schema.json``; a test
checks they are identical).
"""

import json
import os
import re

_DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data")
_cache = {}


def load_schema(name):
    """Load a bundled schema: "model" or "result" (or a path to a schema file)."""
    path = name if os.path.sep in name or name.endswith(".json") else \
        os.path.join(_DATA, "%s.schema.json" % name)
    if path not in _cache:
        with open(path, "r", encoding="utf-8") as f:
            _cache[path] = json.load(f)
    return _cache[path]


def _escape(token):
    return str(token).replace("~", "~0").replace("/", "~1")


def _is_type(value, t):
    if t == "object":
        return isinstance(value, dict)
    if t == "array":
        return isinstance(value, list)
    if t == "string":
        return isinstance(value, str)
    if t == "boolean":
        return isinstance(value, bool)
    if t == "null":
        return value is None
    if t == "integer":
        if isinstance(value, bool):
            return False
        return isinstance(value, int) or (isinstance(value, float) and value.is_integer())
    if t == "number":
        return isinstance(value, (int, float)) and not isinstance(value, bool)
    return True


def _resolve(root, ref):
    if not ref.startswith("#"):
        raise ValueError("only local $ref are supported: %r" % ref)
    node = root
    for part in ref[1:].split("/"):
        if not part:
            continue
        node = node[part.replace("~1", "/").replace("~0", "~")]
    return node


class _Validator(object):
    def __init__(self, root, limit):
        self.root = root
        self.limit = limit
        self.errors = []

    def full(self):
        return len(self.errors) >= self.limit

    def err(self, pointer, message):
        if len(self.errors) < self.limit:
            self.errors.append((pointer, message))

    def ok(self, schema, value):
        sub = _Validator(self.root, 1)
        sub.check(schema, value, "")
        return not sub.errors

    def check(self, schema, value, ptr):
        if self.full() or schema is True or not isinstance(schema, dict):
            return
        if "$ref" in schema:
            self.check(_resolve(self.root, schema["$ref"]), value, ptr)
            return
        t = schema.get("type")
        if t is not None:
            types = t if isinstance(t, list) else [t]
            if not any(_is_type(value, x) for x in types):
                self.err(ptr, "expected %s, got %s" % (" or ".join(types), _kind(value)))
                return
        if "enum" in schema and value not in schema["enum"]:
            self.err(ptr, "%s is not one of %s" % (json.dumps(value), json.dumps(schema["enum"])))
        if "const" in schema and value != schema["const"]:
            self.err(ptr, "must be %s" % json.dumps(schema["const"]))
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            if "minimum" in schema and value < schema["minimum"]:
                self.err(ptr, "%s is below the minimum %s" % (value, schema["minimum"]))
            if "maximum" in schema and value > schema["maximum"]:
                self.err(ptr, "%s is above the maximum %s" % (value, schema["maximum"]))
            if "exclusiveMinimum" in schema and value <= schema["exclusiveMinimum"]:
                self.err(ptr, "%s must be greater than %s" % (value, schema["exclusiveMinimum"]))
            if "exclusiveMaximum" in schema and value >= schema["exclusiveMaximum"]:
                self.err(ptr, "%s must be less than %s" % (value, schema["exclusiveMaximum"]))
        if isinstance(value, str):
            if "minLength" in schema and len(value) < schema["minLength"]:
                self.err(ptr, "string shorter than %d" % schema["minLength"])
            if "maxLength" in schema and len(value) > schema["maxLength"]:
                self.err(ptr, "string longer than %d" % schema["maxLength"])
            if "pattern" in schema and not re.search(schema["pattern"], value):
                self.err(ptr, "%s does not match %s" % (json.dumps(value), schema["pattern"]))
        if isinstance(value, list):
            if "minItems" in schema and len(value) < schema["minItems"]:
                self.err(ptr, "%d items, at least %d expected" % (len(value), schema["minItems"]))
            if "maxItems" in schema and len(value) > schema["maxItems"]:
                self.err(ptr, "%d items, at most %d expected" % (len(value), schema["maxItems"]))
            if schema.get("uniqueItems"):
                seen = set()
                for i, item in enumerate(value):
                    key = json.dumps(item, sort_keys=True)
                    if key in seen:
                        self.err("%s/%d" % (ptr, i), "duplicate item")
                    seen.add(key)
            items = schema.get("items")
            if isinstance(items, dict):
                for i, item in enumerate(value):
                    self.check(items, item, "%s/%d" % (ptr, i))
                    if self.full():
                        break
        if isinstance(value, dict):
            for key in schema.get("required", []):
                if key not in value:
                    self.err(ptr, "missing required property '%s'" % key)
            props = schema.get("properties", {})
            extra = schema.get("additionalProperties", True)
            for key, item in value.items():
                p = "%s/%s" % (ptr, _escape(key))
                if key in props:
                    self.check(props[key], item, p)
                elif extra is False:
                    self.err(p, "unknown property '%s'" % key)
                elif isinstance(extra, dict):
                    self.check(extra, item, p)
        for sub in schema.get("allOf", []):
            self.check(sub, value, ptr)
        if "anyOf" in schema and not any(self.ok(s, value) for s in schema["anyOf"]):
            self.err(ptr, "matches none of the allowed forms (anyOf)")
        if "oneOf" in schema and sum(1 for s in schema["oneOf"] if self.ok(s, value)) != 1:
            self.err(ptr, "must match exactly one allowed form (oneOf)")
        if "not" in schema and self.ok(schema["not"], value):
            self.err(ptr, "matches a forbidden form (not)")
        if "if" in schema:
            if self.ok(schema["if"], value):
                if "then" in schema:
                    self.check(schema["then"], value, ptr)
            elif "else" in schema:
                self.check(schema["else"], value, ptr)


def _kind(value):
    if value is None:
        return "null"
    if isinstance(value, bool):
        return "boolean"
    if isinstance(value, (int, float)):
        return "number"
    if isinstance(value, str):
        return "string"
    if isinstance(value, list):
        return "array"
    if isinstance(value, dict):
        return "object"
    return type(value).__name__


def validate(document, schema, limit=50):
    """Return a list of (JSON pointer, message); empty when the document is valid."""
    v = _Validator(schema, limit)
    v.check(schema, document, "")
    return v.errors


def validate_model(document, limit=50):
    return validate(document, load_schema("model"), limit)


def validate_result(document, limit=50):
    return validate(document, load_schema("result"), limit)
