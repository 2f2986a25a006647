"""rbla_rhino: the thin Rhino 8 / Grasshopper adapter of rbla.

Imports only RhinoCommon (Rhino, System, scriptcontext, Grasshopper in the GH components) and
the host-independent core ``rbla_cad``; every rule that can be tested without Rhino (model
checks, User Text keys, transforms, colours) lives in the core.

  geometry   Rhino geometry <-> plain vertex / face lists, meshes from model blocks
  document   read blocks, interfaces, loads and settings from a RhinoDoc; results on layers
  commands   bodies of the RblaExport, RblaSolve, RblaShowMechanism and RblaClear commands
"""

__version__ = "0.1.0"
