"""Make rbla_cad and rbla_rhino importable from a Rhino 8 script (command or component).

Order: already importable (installed into Rhino's Python, or a ScriptEditor project library)
-> $RBLA_PLUGIN_DIR (the repository's plugin/ folder) -> relative to this file
(plugin/rhino/commands/ -> plugin/ and plugin/rhino/).
"""

import os
import sys


def ensure_paths():
    try:
        import rbla_cad  # noqa: F401
        import rbla_rhino  # noqa: F401
        return
    except ImportError:
        pass
    roots = []
    env = os.environ.get("RBLA_PLUGIN_DIR")
    if env:
        roots.append(env)
    try:
        here = os.path.dirname(os.path.abspath(__file__))
        roots.append(os.path.dirname(os.path.dirname(here)))
    except NameError:
        pass
    for root in roots:
        for p in (root, os.path.join(root, "rhino")):
            if os.path.isdir(p) and p not in sys.path:
                sys.path.insert(0, p)


ensure_paths()
