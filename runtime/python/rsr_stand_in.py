"""A stand-in for the names the 3-RSR wrist's generated module defines before the runtime sources it inlines
(runtime/python/rsr_legs.py, rsr_wrist_api.py): the tolerances and sizes templates/python/rsr_wrist.py.jinja prints
for the catalogue's wrist (catalogue/rsr_wrist.toml), the shared runtime's names, and what is derived or printed
per robot (kernels, Design) taken from that generated module, with no C extension (_C = None: the numpy path).
Never inlined: it lets the sources be imported, linted and tested as they are (tests/test_rsr_runtime.py)."""

from __future__ import annotations

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
    _rows,
    _stack,
    _vector,
    _wrap,
)
from wristkin.rsr_wrist import (  # noqa: F401  (derived or printed per robot, as the template prints them)
    Design,
    _design_values,
    _k_fk_plane,
    _k_fk_plane_cs,
    _k_fk_pose,
    _k_geometric_jacobian,
    _k_ik_coeffs,
    _k_jacobians,
)

SINGULAR_EPS = 1e-6
GIMBAL_EPS = 1e-10
TANGENT_TOL = 1e-12
DEGENERATE_EPS = 1e-12
IK_VERIFY_TOL = 1e-9
POSE_TOL = 1e-9
MAX_IK = 8
MAX_FK = 1
IK_AUX_NAMES = ("residual", "cond_inverse", "cond_direct")
FK_AUX_NAMES = ("r00", "r01", "r02", "px", "r10", "r11", "r12", "py", "r20", "r21", "r22", "pz", "cond_inverse",
                "cond_direct")

# the numpy path: no extension (the generated module binds these from wristkin._native when it is built)
_C = None
_C_IK = _C_FK = _C_IK_BATCH = _C_FK_BATCH = _C_JACOBIAN = None
_IK_RESULT = _FK_RESULT = None


def _c_design(vals):
    """No C design without the extension (the generated module's binds wristkin._native's)."""
    return None
