#! python3
# Rhino 8 command RblaShowMechanism: Draw the last result at a chosen display amplitude.
# Install: see plugin/README.md (ScriptEditor project or Yak package). Thin: everything is in
# rbla_rhino.commands and the host-independent rbla_cad core.
import os
import sys

try:
    import _bootstrap  # noqa: F401  (adds plugin/ and plugin/rhino/ to sys.path if needed)
except ImportError:
    _here = os.path.dirname(os.path.abspath(__file__)) if "__file__" in globals() else ""
    if _here and _here not in sys.path:
        sys.path.insert(0, _here)
        import _bootstrap  # noqa: F401

from rbla_rhino import commands

commands.show_mechanism_command()
