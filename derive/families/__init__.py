"""The families: every kind of mechanism lives in one folder here. The core finds them by discovery (every
sub-package is a family, named by its folder) and reaches them only through the interface below, so adding a
family touches no core file (tests/test_architecture.py checks that the core names no mechanism).

A family package is a `derive.mechanism.Family` (from_spec, SPEC_FIELDS, SOURCE_SUFFIXES); the object its
from_spec returns is a `derive.mechanism.Mechanism` (NAME, TEMPLATES, derive, kernels, extra_context,
casadi_functions, audit_numbers and the scheduling / CasADi members), built on `MechanismDefaults` for the optional
ones. tests/test_architecture.py checks every family and catalogue mechanism against these types.
"""

import importlib
import pkgutil

FAMILIES = {m.name: importlib.import_module(f"{__name__}.{m.name}")
            for m in sorted(pkgutil.iter_modules(__path__), key=lambda m: m.name) if m.ispkg}
