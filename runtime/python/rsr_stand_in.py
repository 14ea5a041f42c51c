"""A stand-in for the names the 3-RSR wrist's generated module defines before the runtime source it inlines
(runtime/python/rsr_legs.py): the tolerances templates/python/rsr_wrist.py.jinja prints for the catalogue's wrist
(catalogue/rsr_wrist.toml), the shared runtime's names, and its derived kernels taken from that generated module.
Never inlined: it lets the source be imported, linted and tested as it is (tests/test_rsr_runtime.py)."""

from __future__ import annotations

from _runtime import (  # noqa: F401  (re-exported: the runtime's names a generated module binds)
    _TWO_PI,
    FLAG_DOUBLE_ROOT,
    FLAG_INDETERMINATE,
    FLAG_SINGULAR_INVERSE,
    InvalidInput,
    _vector,
)
from wristkin.rsr_wrist import (  # noqa: F401  (the derived kernels, as the template prints them)
    _k_fk_plane,
    _k_fk_plane_cs,
    _k_fk_pose,
    _k_ik_coeffs,
)

SINGULAR_EPS = 1e-6
GIMBAL_EPS = 1e-10
TANGENT_TOL = 1e-12
DEGENERATE_EPS = 1e-12
