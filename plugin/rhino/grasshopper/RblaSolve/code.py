#! python3
"""rbla Solve: model JSON -> result JSON by running the rbla executable (Esc cancels)."""
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

from rbla_cad import runner
from rbla_rhino import gh

result = None
verdict = None
alpha = None
reaction = None
log = []
if model:
    try:
        result, res, log = gh.solve(model, run=bool(run), exe=exe, timeout=timeout)
        if res is not None:
            verdict = res.verdict
            alpha = res.load_multiplier
            reaction = res.base_reaction
            ghenv.Component.Message = res.headline()
            for w in res.warnings:
                ghenv.Component.AddRuntimeMessage(
                    Grasshopper.Kernel.GH_RuntimeMessageLevel.Remark, w.get("message", ""))
    except runner.RblaError as e:
        log = gh.report_error(ghenv.Component, e)
