#! python3
"""rbla Legend: labels and colours of the contact states and block kinds (the solver's SVG
colours)."""
# rbla_cad and rbla_rhino must be importable: install them as a ScriptEditor library, or set
# the environment variable RBLA_PLUGIN_DIR to the repository's plugin/ folder
# (see plugin/README.md).
import os
import sys
for _p in filter(None, [os.environ.get("RBLA_PLUGIN_DIR")]):
    for _q in (_p, os.path.join(_p, "rhino")):
        if _q not in sys.path:
            sys.path.insert(0, _q)

from rbla_rhino import gh

labels, colours, hex_colours, keys = gh.legend(
    include_closed=True if include_closed is None else bool(include_closed),
    include_blocks=True if include_blocks is None else bool(include_blocks))
