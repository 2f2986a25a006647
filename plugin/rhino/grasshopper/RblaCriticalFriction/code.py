#! python3
"""rbla Critical Friction: model JSON -> the smallest friction to stand or carry alpha (Esc cancels)."""
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
factor = None
friction = None
log = []
if model:
    try:
        result, res, log = gh.critical_friction(model, run=bool(run), exe=exe, timeout=timeout,
                                                target_alpha=target_alpha,
                                                interfaces=[i for i in (interfaces or []) if i],
                                                interfaces_of=[b for b in (interfaces_of or []) if b])
        if res is not None:
            search = res.data.get("critical_friction", {})
            verdict = search.get("verdict")
            factor = search.get("factor")
            friction = search.get("friction")
            ghenv.Component.Message = search.get("outcome", res.status)
    except runner.RblaError as e:
        log = gh.report_error(ghenv.Component, e)
