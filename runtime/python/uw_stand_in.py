"""A stand-in for the names the underactuated wrist's generated module defines before the runtime sources it
inlines (runtime/python/uw_*.py): the constants templates/python/underactuated_wrist.py.jinja prints for the
catalogue's wrist (catalogue/underactuated_wrist.toml), the shared runtime's names, and the derived kernels taken
from that generated module (they are SymPy's output, not hand-written), with no C extension (_C = None: the
numpy path). Never inlined: it lets the sources be imported, linted and tested as they are
(tests/test_uw_runtime.py)."""

from __future__ import annotations

import poly_real_roots as _poly
from _runtime import (  # noqa: F401  (re-exported: the runtime's names a generated module binds)
    _TWO_PI,
    FLAG_DOUBLE_ROOT,
    FLAG_GIMBAL,
    FLAG_INDETERMINATE,
    FLAG_SINGULAR_DIRECT,
    FLAG_SINGULAR_INVERSE,
    STATUS_INDETERMINATE,
    STATUS_NO_ASSEMBLY,
    STATUS_OK,
    STATUS_UNREACHABLE,
    BatchSolutions,
    InvalidDesign,
    InvalidInput,
    Solutions,
    WristkinError,
    _vector,
    _wrap,
    _wrap_all,
)
from wristkin.underactuated_wrist import (  # noqa: F401  (the derived kernels, as the template prints them)
    _k_base_axes,
    _k_design_constants,
    _k_euler_rate_matrix,
    _k_fk_def,
    _k_fk_rotation,
    _k_ik_abc,
    _k_jacobian_rates,
    _k_jacobians,
    _k_middle_axes,
    _k_platform_axes,
    _kv_fk_def,
    _kv_fk_rotation,
    _kv_ik_abc,
    _kv_middle_axes,
    _kv_platform_axes,
)

_poly_real_roots = _poly._poly_real_roots
_POLY_FLAG_DOUBLE = _poly._POLY_FLAG_DOUBLE
_POLY_STATUS_ZERO = _poly._POLY_STATUS_ZERO

NAME = "underactuated_wrist"
DESIGN_NAMES = ("alpha1", "alpha2", "beta1", "beta2")
DESIGN_DEFAULT = (1.0471975511965976, 1.0471975511965976, 0.5235987755982988, 0.7660250087003112)
MAX_IK = 8
MAX_FK = 8
NO_ASSEMBLY_REASON = "no real assembly mode for these joint angles"  # fk's reason where no mode is real
IK_AUX_NAMES = ("Phi1", "Phi2", "Phi3", "cond_inverse", "cond_direct")
FK_AUX_NAMES = ("r00", "r01", "r02", "r10", "r11", "r12", "r20", "r21", "r22", "zeta", "eta",
                "cond_inverse", "cond_direct")
SINGULAR_EPS = 1e-6
GIMBAL_EPS = 1e-10
TANGENT_TOL = 1e-12
FK_RESIDUAL_TOL = 1e-10
FK_DUPLICATE_TOL = 1e-7
FK_FOLD_TOL = 1e-8
TOUCH_TOL = 1e-8
DESIGN_MARGIN = 1e-3
POLISH_ITERS = 40
RATE_MAX = 1e6

# the numpy path: no extension (the generated module binds these from wristkin._native when it is built)
_C = None
_C_IK = _C_FK = _C_IK_BATCH = _C_FK_BATCH = _C_DESIGN = None
_IK_RESULT = _FK_RESULT = None
