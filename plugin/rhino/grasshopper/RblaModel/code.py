#! python3
"""rbla Model: block geometry + attributes -> model JSON (see metadata.json for the ports)."""
# rbla_cad and rbla_rhino must be importable: install them as a ScriptEditor library, or set
# the environment variable RBLA_PLUGIN_DIR to the repository's plugin/ folder
# (see plugin/README.md).
import os
import sys
for _p in filter(None, [os.environ.get("RBLA_PLUGIN_DIR")]):
    for _q in (_p, os.path.join(_p, "rhino")):
        if _q not in sys.path:
            sys.path.insert(0, _q)

import Grasshopper

from rbla_cad.model import ModelError
from rbla_rhino import gh

model = None
ids = []
report = []
if blocks:
    try:
        model, ids, report = gh.build_model(
            blocks, ids=ids_in, roles=roles, unit_weights=unit_weights, labels=labels,
            frictions=frictions, interfaces=interfaces, interface_labels=interface_labels,
            interface_blocks=interface_blocks, analysis=analysis or "seismic",
            direction=direction, units=units, force=force or "kN", settings=settings)
        ghenv.Component.Message = "%d blocks" % len(ids)
    except ModelError as e:
        report = str(e).splitlines()
        ghenv.Component.AddRuntimeMessage(Grasshopper.Kernel.GH_RuntimeMessageLevel.Error, str(e))
    if model and path:
        with open(path, "w") as f:
            f.write(model)
