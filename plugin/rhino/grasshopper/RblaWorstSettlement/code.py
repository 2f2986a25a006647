#! python3
"""rbla Worst Settlement: model JSON -> the most harmful settlement direction (Esc cancels)."""
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
ratio = None
tilt = None
azimuth = None
direction = None
upper_bound = None
ranking = []
log = []
if model:
    try:
        result, res, log = gh.worst_settlement(model, run=bool(run), exe=exe, timeout=timeout,
                                               tolerance=tolerance, cone_angle=cone_angle,
                                               candidate_groups=candidate_groups)
        if res is not None:
            search = res.data.get("worst_settlement", {})
            verdict = search.get("verdict")
            ratio = search.get("ratio")
            tilt = search.get("tilt_deg")
            azimuth = search.get("azimuth_deg")
            direction = search.get("direction")
            upper_bound = search.get("upper_bound")
            groups = search.get("candidate_groups")
            if groups:
                for g in groups["groups"]:
                    ranking.append("%s: R/R0 %s%s" % (
                        ", ".join(g["supports"]),
                        "%.4g" % g["ratio"] if "ratio" in g else g["status"],
                        " (most harmful)" if g["most_harmful"] else ""))
                ranking.append(groups["verdict"])
            ghenv.Component.Message = ("R/R0 %.4g at %.1f deg" % (ratio, tilt) if ratio is not None
                                       else res.status)
    except runner.RblaError as e:
        log = gh.report_error(ghenv.Component, e)
