"""The families: every kind of mechanism lives in one folder here. The core finds them by discovery (every
sub-package is a family, named by its folder) and reaches them only through the interface below, so adding a
family touches no core file (tests/test_architecture.py checks that the core names no mechanism).

A family package offers:
  from_spec(spec: derive.spec.Spec) -> mechanism   read and validate its spec fields (docs/specs.md), raising
                                                   derive.spec.SpecError naming the file and field
  SPEC_FIELDS                                      the fields it reads beside the common ones (documentation)

A mechanism (the object from_spec returns) offers:
  NAME                           its name: generated/python/wristkin/NAME.py, generated/c/NAME.{h,c}, ...
  derive() -> Derivation         every step with its rule, inputs and checks (derive/model.py)
  kernels(dv) -> [Kernel]        the expressions the solvers evaluate
  extra_context(kernels) -> dict what its templates need beyond the kernels and tolerances
  casadi_functions(dv, kernels)  {name: casadi.Function} for generated/casadi/NAME.casadi
  audit_numbers(dv, solver, audit_dir) -> dict   numeric findings for the audit (optional)
  TEMPLATES                      (python, C header, C source) templates
  VECTORISED_KERNELS             kernels also printed for numpy
  CASADI_DESIGN_NAMES, CASADI_DOCS   the CasADi index's design inputs and function texts (optional)
  DERIVE_SECONDS, DERIVE_AFTER   scheduling hints for parallel regeneration (optional)
"""

import importlib
import pkgutil

FAMILIES = {m.name: importlib.import_module(f"{__name__}.{m.name}")
            for m in sorted(pkgutil.iter_modules(__path__), key=lambda m: m.name) if m.ispkg}
