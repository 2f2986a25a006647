"""CAD attributes (Rhino "User Text" key/value strings), read by the convention in
``data/cad_attributes.json``.

That file is the single source of the convention: the keys of each kind of object (block,
interface, load point, document), their types, accepted values and synonyms, bounds, defaults,
old key names, and every message a reader gives, with its code and severity. It is loaded here
at import; the .3dm exchange (plugin/exchange/lib/cad-attributes.mjs) loads the same file, and
docs/cad-attributes.md is generated from it (``python3 usertext.py --markdown FILE``). Nothing
about the keys is written in this module: it implements the value *types* (number, vector,
choice, ...) and the message formatting, identically to the JS reader (tests/plugin/cad_cases
run both on the same cases).

A value that cannot be read is an error naming the object and the key; an unknown key, a key
on the wrong kind of object, an empty value and an old key name are warnings that say what was
used instead. Nothing is dropped silently.
"""

import json
import math
import os
import re

DATA_PATH = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data",
                         "cad_attributes.json")


def _load():
    with open(DATA_PATH, encoding="utf-8") as f:
        return json.load(f)


DATA = _load()
PREFIX = DATA["prefix"]
KINDS = tuple(DATA["objects"].keys())
KEYS = dict((kind, dict((e["key"], e) for e in DATA["objects"][kind]["keys"])) for kind in KINDS)
ALIASES = dict((kind, dict((a, e["key"]) for e in DATA["objects"][kind]["keys"]
                           for a in e.get("aliases", []))) for kind in KINDS)
MESSAGES = dict((k, v) for k, v in DATA["messages"].items() if not k.startswith("$"))
TRUE = tuple(DATA["booleans"]["true"])
FALSE = tuple(DATA["booleans"]["false"])

_NUMBER = re.compile(r"^[+-]?([0-9]+(\.[0-9]*)?|\.[0-9]+)([eE][+-]?[0-9]+)?$")


# ----------------------------------------------------------------------------------- messages

def q(text):
    """A value quoted as in every message of both readers (a JSON string)."""
    return json.dumps(str(text), ensure_ascii=False)


def fmt(x):
    """A number as both readers print it: C's %.12g."""
    return "%.12g" % x


def who_object(name, guid):
    """How messages name an object: object "Stone 7", or unnamed object <guid>."""
    return "object %s" % q(name) if name else "unnamed object %s" % guid


class Message(object):
    __slots__ = ("code", "severity", "text", "object", "key")

    def __init__(self, code, severity, text, obj=None, key=None):
        self.code, self.severity, self.text, self.object, self.key = \
            code, severity, text, obj, key

    def as_dict(self):
        return {"code": self.code, "severity": self.severity, "text": self.text,
                "object": self.object, "key": self.key}

    def __repr__(self):
        return "%s %s: %s" % (self.severity, self.code, self.text)


class Report(object):
    """Errors and warnings in the order they were found."""

    def __init__(self):
        self.messages = []

    def add(self, code, obj=None, key=None, **fields):
        spec = MESSAGES[code]
        if key is not None and "key" not in fields:
            fields["key"] = key
        text = re.sub(r"\{(\w+)\}", lambda m: str(fields[m.group(1)]), spec["text"])
        msg = Message(code, spec["severity"], text, obj, key)
        self.messages.append(msg)
        return msg

    @property
    def errors(self):
        return [m for m in self.messages if m.severity == "error"]

    @property
    def warnings(self):
        return [m for m in self.messages if m.severity == "warning"]

    def codes(self, severity=None):
        return [m.code for m in self.messages if severity is None or m.severity == severity]


# ------------------------------------------------------------------------------------ values

class Bad(Exception):
    """A value that cannot be read: the message code and its fields."""

    def __init__(self, code, **fields):
        Exception.__init__(self, code)
        self.code, self.fields = code, fields


def normalise(user_text):
    """{lower-cased rbla.* key: stripped value}; other keys are dropped."""
    out = {}
    for k, v in (user_text or {}).items():
        key = str(k).strip().lower()
        if key.startswith(PREFIX):
            out[key] = "" if v is None else str(v).strip()
    return out


def _choice_key(text):
    t = re.sub(r"\s+", "_", text.strip().lower())
    return re.sub(r"(?<=\w)-(?=\w)", "_", t)


def parse_number(text, decimal_comma=True):
    t = text.strip()
    if decimal_comma and t.count(",") == 1 and "." not in t:
        t = t.replace(",", ".")
    if not _NUMBER.match(t):
        raise Bad("bad_number")
    x = float(t)
    if math.isinf(x):
        raise Bad("bad_number")
    return x


def range_text(entry):
    parts = []
    if "minimum" in entry:
        parts.append(">= " + fmt(entry["minimum"]))
    if "exclusive_minimum" in entry:
        parts.append("> " + fmt(entry["exclusive_minimum"]))
    if "maximum" in entry:
        parts.append("<= " + fmt(entry["maximum"]))
    return " and ".join(parts)


def _in_range(x, entry):
    return not (("minimum" in entry and x < entry["minimum"]) or
                ("exclusive_minimum" in entry and x <= entry["exclusive_minimum"]) or
                ("maximum" in entry and x > entry["maximum"]))


def parse_vector(text):
    t = text.strip()
    if len(t) >= 2 and (t[0], t[-1]) in (("[", "]"), ("(", ")")):
        t = t[1:-1]
    if ";" in t:
        parts = [p.strip() for p in t.split(";")]
        comma = True
    else:
        parts = [p for p in re.split(r"[,\s]+", t.strip()) if p]
        comma = False
    if len(parts) != 3:
        raise Bad("bad_vector")
    try:
        return [parse_number(p, comma) for p in parts]
    except Bad:
        raise Bad("bad_vector")


def _parse_choice(entry, text):
    k = _choice_key(text)
    for v in entry["values"]:
        if _choice_key(v) == k:
            return v
    for s, v in entry.get("synonyms", {}).items():
        if _choice_key(s) == k:
            return v
    raise Bad("bad_choice", allowed=", ".join(entry["values"]))


def _parse_json(entry, text):
    shape = entry["json"]

    def bad(_):
        raise ValueError("not JSON")
    try:
        v = json.loads(text, parse_constant=bad)
    except ValueError:
        v = None
    if not isinstance(v, dict if shape == "object" else list):
        raise Bad("bad_json", expected=_json_expected(entry))
    return v


def _json_expected(entry):
    what = "a JSON %s (model schema %s)" % (entry["json"], entry["model"])
    if entry["type"] == "choice_or_json":
        return "one of %s, or %s" % (", ".join(entry["values"]), what)
    return what


def parse_value(entry, text):
    """The value of one key from its (non-empty) text; raises Bad."""
    t = entry["type"]
    if t == "number" or t == "integer":
        x = parse_number(text)
        if t == "integer" and x != math.floor(x):
            raise Bad("bad_integer")
        if not _in_range(x, entry):
            raise Bad("out_of_range", range=range_text(entry))
        return int(x) if t == "integer" else x
    if t == "vector":
        v = parse_vector(text)
        if entry.get("nonzero") and not any(v):
            raise Bad("zero_vector")
        return v
    if t == "choice":
        return _parse_choice(entry, text)
    if t == "choice_or_json":
        if text.lstrip()[:1] in ("{", "["):
            return _parse_json(entry, text)
        try:
            return _parse_choice(entry, text)
        except Bad:
            raise Bad("bad_json", expected=_json_expected(entry))
    if t == "json":
        return _parse_json(entry, text)
    if t == "boolean":
        low = text.strip().lower()
        if low in TRUE:
            return True
        if low in FALSE:
            return False
        raise Bad("bad_boolean")
    if t == "pair":
        sep = ";" if ";" in text else ","
        ids = [s.strip() for s in text.split(sep)]
        if len(ids) != 2 or not ids[0] or not ids[1] or ids[0] == ids[1]:
            raise Bad("bad_pair")
        return ids
    if t in ("text", "id"):
        limit = entry.get("maximum_length", 1000000)
        if len(text) > limit or (t == "id" and not text):
            raise Bad("bad_text", maximum=limit, length=len(text))
        return text
    raise ValueError("cad_attributes.json: unknown type %r of %s" % (t, entry["key"]))


def default_text(entry):
    """What a reader uses when the key is absent (for messages and the doc page)."""
    if "default_text" in entry:
        return entry["default_text"]
    if "default" not in entry:
        return "none"
    d = entry["default"]
    if isinstance(d, bool):
        return "true" if d else "false"
    if isinstance(d, list):
        return ", ".join(fmt(x) for x in d)
    if isinstance(d, (int, float)):
        return fmt(d)
    return str(d)


# ------------------------------------------------------------------------------- key reading

def _edit_distance(a, b):
    prev = list(range(len(b) + 1))
    for i, ca in enumerate(a, 1):
        cur = [i]
        for j, cb in enumerate(b, 1):
            cur.append(min(prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (ca != cb)))
        prev = cur
    return prev[-1]


def _hint(key, kind):
    """'; did you mean rbla.x?' for the closest known key at most 2 edits away (keys of this
    kind of object first, then of the others)."""
    for kinds in ((kind,), tuple(k for k in KINDS if k != kind)):
        best, dist = None, 3
        for k in kinds:
            for name in list(KEYS[k]) + list(ALIASES[k]):
                d = _edit_distance(key, name)
                if d < dist:
                    best, dist = ALIASES[k].get(name, name), d
        if best:
            return "; did you mean %s?" % best
    return ""


def _kind_of_key(key):
    for kind in KINDS:
        if key in KEYS[kind] or key in ALIASES[kind]:
            return kind
    return None


def read_keys(kind, user_text, who, report, obj=None, host=None):
    """Parse an object's (or the document's) rbla.* keys of ``kind``.

    Returns {key: value} for the keys given with a readable value. Messages go to ``report``:
    errors for unreadable values, warnings for unknown keys, keys of another kind of object,
    empty values (the default is used) and old key names."""
    ut = normalise(user_text)
    out = {}
    for key in sorted(ut):
        text = ut[key]
        name = key
        if key in ALIASES[kind]:
            name = ALIASES[kind][key]
            if name in ut:
                report.add("conflict", obj, key, who=who, other=name)
                continue
            report.add("old_key", obj, key, who=who, new=name)
        entry = KEYS[kind].get(name)
        if entry is None:
            other = _kind_of_key(key)
            if other is not None:
                report.add("misplaced_key", obj, key, who=who, kind=kind)
            else:
                report.add("unknown_key", obj, key, who=who, hint=_hint(key, kind))
            continue
        if host is not None and host not in entry.get("hosts", [host]):
            continue
        if entry.get("ignored"):
            continue
        if text == "" and not entry.get("empty_allowed"):
            if entry.get("marker"):
                report.add("bad_choice", obj, name, who=who, value=q(text),
                           allowed=", ".join(entry["values"]))
            else:
                report.add("empty_value", obj, name, who=who, used=default_text(entry))
            continue
        try:
            out[name] = parse_value(entry, text) if text or not entry.get("empty_allowed") \
                else ""
        except Bad as e:
            report.add(e.code, obj, name, who=who, value=q(text), **e.fields)
    return out


def read_value(kind, key, text, who):
    """One key's value from its text, or a ModelError with the convention's message (for
    inputs that are not User Text but take the same values, e.g. Grasshopper ports)."""
    from .model import ModelError
    try:
        return parse_value(KEYS[kind][key], str(text))
    except Bad as e:
        msg = Report().add(e.code, None, key, who=who, value=q(text), **e.fields)
        raise ModelError(msg.text, pointer=key)


# -------------------------------------------------------------------------------------- docs

def markdown():
    """The doc page docs/cad-attributes.md, generated from the data file."""
    L = ["# CAD attributes (User Text) read by rbla", "",
         "<!-- generated from plugin/rbla_cad/data/cad_attributes.json by "
         "`python3 plugin/rbla_cad/usertext.py --markdown docs/cad-attributes.md`; "
         "do not edit -->", "",
         "The Rhino plugin (`plugin/rhino` over `plugin/rbla_cad`) and the .3dm exchange "
         "(`plugin/exchange`) read these keys the same way: both load the data file named "
         "above, and the tests run both readers on the same cases "
         "(`tests/plugin/cad_cases/`). Keys are case-insensitive. A value that cannot be read "
         "is an **error** naming the object and the key (the export stops and lists every "
         "error); anything else the readers do not take as given is a **warning** that says "
         "what was used instead.", ""]
    L += ["## Syntax of values", ""]
    for k, v in DATA["syntax"].items():
        L.append("- **%s**: %s." % (k, v))
    L.append("")
    for kind in KINDS:
        L += ["## %s" % {"block": "Blocks", "interface": "Interface objects",
                         "load": "Load points", "document": "Document User Text"}[kind], "",
              DATA["objects"][kind]["what"], "",
              "| key | value | default | meaning |", "|---|---|---|---|"]
        for e in DATA["objects"][kind]["keys"]:
            L.append("| `%s`%s | %s | %s | %s%s |" % (
                e["key"], "".join(" (old name `%s`)" % a for a in e.get("aliases", [])),
                _value_text(e), default_text(e), e["text"],
                " (model: `%s`)" % e["model"] if "model" in e else ""))
        L.append("")
        if kind == "interface":
            L += [DATA["interface_merge"]["$comment"].replace(
                "relative x", "%s x" % fmt(DATA["interface_merge"]["relative"])),
                "", DATA["interface_search"]["$comment"].replace(
                    "factor x", "%s x" % fmt(DATA["interface_search"]["factor"])).replace(
                    "interface_merge.relative x", "%s x" % fmt(DATA["interface_merge"]["relative"])),
                ""]
    L += ["## Units", "",
          "The document's unit system gives `units.length`; other units are converted "
          "(warning `units_converted`):", "", "| document unit | model unit | factor |",
          "|---|---|---|"]
    for name, v in DATA["length_units"].items():
        if not name.startswith("$"):
            L.append("| %s | %s | %s |" % (name, v[0], fmt(v[1])))
    L += ["", DATA["length_units"]["$comment"], "",
          "Objects on the layers %s (and layers whose path starts with %s) are results drawn "
          "by rbla and are never read." % (
              ", ".join("`%s`" % x for x in DATA["result_layers"]["exact"]),
              ", ".join("`%s`" % x for x in DATA["result_layers"]["prefix"])), "",
          "## Keys rbla writes on results", "", DATA["results"]["$comment"], "",
          "| on | key | meaning |", "|---|---|---|"]
    for part, where in (("objects", "result objects"), ("document", "result document")):
        for e in DATA["results"][part]:
            L.append("| %s | `%s` | %s |" % (where, e["key"], e["text"]))
    L += ["", "## Messages", "", "| code | severity | text |", "|---|---|---|"]
    for code, m in MESSAGES.items():
        L.append("| `%s` | %s | %s |" % (code, m["severity"], m["text"].replace("|", "\\|")))
    L.append("")
    return "\n".join(L)


def _value_text(e):
    t = e["type"]
    if t in ("choice", "choice_or_json"):
        s = " \\| ".join("`%s`" % v for v in e["values"])
        if e.get("synonyms"):
            s += " (also %s)" % ", ".join("`%s` = `%s`" % kv for kv in e["synonyms"].items())
        if t == "choice_or_json":
            s += ", or a JSON %s" % e["json"]
        return s
    if t in ("number", "integer"):
        r = range_text(e)
        return ("%s%s%s" % ("whole number" if t == "integer" else "number",
                            " " + r if r else "",
                            " (%s)" % e["unit"].replace("_", " ") if e.get("unit") else ""))
    if t == "vector":
        return "vector x, y, z%s%s" % (" (not zero)" if e.get("nonzero") else "",
                                       ", perpendicular to gravity" if e.get("horizontal")
                                       else "")
    if t == "json":
        return "JSON %s" % e["json"]
    return {"pair": "two block ids", "id": "text (id)", "boolean": "boolean",
            "text": "text"}[t]


if __name__ == "__main__":
    import sys
    if len(sys.argv) == 3 and sys.argv[1] == "--markdown":
        with open(sys.argv[2], "w", encoding="utf-8") as f:
            f.write(markdown())
    else:
        sys.stdout.write("usage: usertext.py --markdown FILE\n")
        sys.exit(2)
