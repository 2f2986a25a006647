"""rbla_cad: the host-independent CAD side of rbla (model export, solver runs, results).

Standard library only, Python 3.9+, so it runs inside CAD hosts' Python too (Rhino 8 CPython).

Modules:
  model           ModelBuilder: blocks, interfaces, loads, analysis -> model JSON, with checks
  runner          Runner: runs the rbla executable (progress, timeout, cancel, exit codes)
  result          Result: verdict, alpha / base reaction, block transforms, colours, legend
  geometry        vector and polyhedron helpers (divergence-theorem volume and centroid)
  jsonschema_lite small draft-07 validator for the bundled schemas (data/)
  compas_import   COMPAS assembly JSON -> model JSON
  safe_files      reading inputs and writing outputs by the solver's rules (atomic, never the input)
"""

__version__ = "0.1.0"

__all__ = ["compas_import", "geometry", "jsonschema_lite", "model", "result", "runner", "safe_files"]
