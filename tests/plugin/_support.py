"""Shared helpers of the plugin tests: puts plugin/ on sys.path, finds the solver and samples.

The solver is found through $RBLA_EXE (or rbla on PATH); tests that need it are skipped when
neither is set.
"""

import os
import sys

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PLUGIN = os.path.join(REPO, "plugin")
SAMPLES = os.path.join(REPO, "samples")
SCHEMA = os.path.join(REPO, "schema")
if PLUGIN not in sys.path:
    sys.path.insert(0, PLUGIN)

from rbla_cad import runner as _runner  # noqa: E402


def solver_executable():
    """Path of rbla from $RBLA_EXE / PATH, or None."""
    try:
        return _runner.find_executable()
    except _runner.SolverNotFoundError:
        if os.environ.get(_runner.ENV_VAR):
            raise  # set but wrong: fail loudly rather than skip
        return None


def sample(name):
    return os.path.join(SAMPLES, name)
