"""rbla_cad: the host-independent CAD side of rbla (model import and export).

Standard library only, Python 3.9+, so it runs inside CAD hosts' Python too.
"""

__all__ = ["compas_import"]
