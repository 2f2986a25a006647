#! python3
"""rbla Mechanism: displaced blocks and contact polygons coloured by state."""
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

blocks = []
block_colours = []
transforms = []
contacts = []
contact_colours = []
outlines = []
states = []
dot_points = []
dot_texts = []
used_amplitude = None
if model and result:
    out, used_amplitude = gh.mechanism(model, result, amplitude=amplitude, screw=bool(hinge_exact),
                                       show_closed=bool(show_closed))
    blocks = out["blocks"]
    block_colours = out["block_colours"]
    transforms = out["transforms"]
    contacts = out["contacts"]
    contact_colours = out["contact_colours"]
    outlines = out["outlines"]
    states = out["states"]
    dot_points = out["dot_points"]
    dot_texts = out["dot_texts"]
    ghenv.Component.Message = "x %g" % used_amplitude
