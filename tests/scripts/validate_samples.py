#!/usr/bin/env python3
"""Validate model JSON files against the rbla model schema (JSON Schema draft-07).

Usage: validate_samples.py SCHEMA FILE [FILE ...]

Prints every error as `FILE: /json/pointer: message` and exits 1 when any file fails (2 on a
usage error or when the schema itself is invalid). Needs the `jsonschema` package.
"""

import json
import sys

try:
    import jsonschema
except ImportError:  # pragma: no cover
    sys.stderr.write("validate_samples.py: the 'jsonschema' package is required\n")
    sys.exit(2)


def json_pointer(path):
    """RFC 6901 pointer of a jsonschema error path ('' is the document root)."""
    parts = []
    for p in path:
        parts.append(str(p).replace("~", "~0").replace("/", "~1"))
    return "/" + "/".join(parts) if parts else "/"


def main(argv):
    if len(argv) < 3:
        sys.stderr.write(__doc__)
        return 2
    with open(argv[1], encoding="utf-8") as fh:
        schema = json.load(fh)
    cls = jsonschema.validators.validator_for(schema, default=jsonschema.Draft7Validator)
    try:
        cls.check_schema(schema)
    except jsonschema.exceptions.SchemaError as e:
        sys.stderr.write("%s: invalid schema: %s\n" % (argv[1], e.message))
        return 2
    validator = cls(schema)
    failed = 0
    for path in argv[2:]:
        try:
            with open(path, encoding="utf-8") as fh:
                doc = json.load(fh)
        except (OSError, ValueError) as e:
            print("%s: cannot read JSON: %s" % (path, e))
            failed += 1
            continue
        errors = sorted(validator.iter_errors(doc), key=lambda e: list(map(str, e.absolute_path)))
        if errors:
            failed += 1
            for e in errors[:100]:
                print("%s: %s: %s" % (path, json_pointer(e.absolute_path), e.message[:300]))
            if len(errors) > 100:
                print("%s: ... %d more errors" % (path, len(errors) - 100))
        else:
            print("%s: valid" % path)
    print("%d of %d files valid" % (len(argv) - 2 - failed, len(argv) - 2))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
