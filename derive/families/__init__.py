"""The families: every kind of mechanism lives in one folder here, and the core reaches it only through this
registry and the interface below (tests/test_architecture.py checks that the core names no mechanism).

A mechanism (a module or an object) offers:
  NAME                           its name: generated/python/wristkin/NAME.py, generated/c/NAME.{h,c}, ...
  derive() -> Derivation         every step with its rule, inputs and checks (derive/model.py)
  kernels(dv) -> [Kernel]        the expressions the solvers evaluate
  extra_context(kernels) -> dict what its templates need beyond the kernels and tolerances
  casadi_functions(dv, kernels)  {name: casadi.Function} for generated/casadi/NAME.casadi
  audit_numbers(dv, solver, audit_dir) -> dict   numeric findings for the audit (optional)
  TEMPLATES                      (python, C header, C source) templates (default python/NAME.py.jinja, ...)
  VECTORISED_KERNELS             kernels also printed for numpy
  CASADI_DESIGN_NAMES, CASADI_DOCS   the CasADi index's design inputs and function texts (optional)
  DERIVE_SECONDS, DERIVE_AFTER   scheduling hints for parallel regeneration (optional)
"""

from . import rsr, screw, serial, spherical_parallel

FAMILIES = {"spherical_parallel": spherical_parallel, "rsr": rsr, "serial": serial, "screw": screw}

REGISTRY = {name: mech for family in FAMILIES.values() for name, mech in family.MECHANISMS.items()}
