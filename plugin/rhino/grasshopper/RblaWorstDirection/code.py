#! python3
"""rbla Worst Direction: model JSON -> the weakest horizontal seismic direction (Esc cancels)."""
# rbla_cad and rbla_rhino must be importable: install them as a ScriptEditor library, or set
# the environment variable RBLA_PLUGIN_DIR to the repository's plugin/ folder
# (see plugin/README.md).
import os
import sys
for _p in filter(None, [os.environ.get("RBLA_PLUGIN_DIR")]):
    for _q in (_p, os.path.join(_p, "rhino")):
        if _q not in sys.path:
            sys.path.insert(0, _q)

from rbla_cad import runner
from rbla_rhino import gh

result = None
verdict = None
alpha = None
angle = None
direction = None
lower_bound = None
log = []
if model:
    try:
        result, res, log = gh.worst_direction(model, run=bool(run), exe=exe, timeout=timeout,
                                              tolerance=tolerance)
        if res is not None:
            search = res.data.get("worst_direction", {})
            verdict = search.get("verdict")
            alpha = search.get("load_multiplier")
            angle = search.get("angle_deg")
            direction = search.get("direction")
            lower_bound = search.get("lower_bound")
            ghenv.Component.Message = "alpha %.4g at %.1f deg" % (alpha, angle) if alpha is not None else res.status
    except runner.RblaError as e:
        log = gh.report_error(ghenv.Component, e)
