"""A stand-in for the names the SCARA + 3-RSR hybrid's generated module defines before the runtime source it
inlines (runtime/python/scara_rsr_api.py): the sizes and tolerances templates/python/scara_rsr.py.jinja prints for
the catalogue's hybrid (catalogue/scara_rsr.toml), the shared runtime's names, and what is derived or printed per
robot (kernels, Design) taken from that generated module, with no C extension (_C = None: the numpy path). The
3-RSR core's names come from rsr_legs.py, as the generated module inlines it. Never inlined: it lets the source be
imported, linted and tested as it is (tests/test_rsr_runtime.py)."""

from __future__ import annotations

from _runtime import (  # noqa: F401  (re-exported: the runtime's names a generated module binds)
    FLAG_DOUBLE_ROOT,
    FLAG_GIMBAL,
    FLAG_INDETERMINATE,
    FLAG_PROJECTED,
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
    _as_rotation,
    _projected_note,
    _rows,
    _stack,
    _vector,
    _wrap,
)
from wristkin.scara_rsr import (  # noqa: F401  (derived or printed per robot, as the template prints them)
    Design,
    _design_values,
    _k_fk_compose,
    _k_jacobian,
    _k_wrist_offset,
)

JOINT_KINDS = ("R", "R", "P", "R", "R", "R", "R")
N_JOINTS = 7
MAX_IK = 16
MAX_FK = 1
IK_AUX_NAMES = ("residual", "alpha1", "beta", "gamma", "cond_inverse", "cond_direct")
FK_AUX_NAMES = ("alpha", "beta", "gamma", "alpha1", "cond_inverse", "cond_direct")
SINGULAR_EPS = 1e-6
GIMBAL_EPS = 1e-10
TANGENT_TOL = 1e-12
DEGENERATE_EPS = 1e-12
IK_VERIFY_TOL = 1e-9
DESIGN_SCALE_MIN = 1e-3
LINK_RATIO_MIN = 1e-3
ROTATION_TOL = 1e-6

# the numpy path: no extension (the generated module binds these from wristkin._native when it is built)
_C = None
_C_IK = _C_FK = _C_IK_BATCH = _C_FK_BATCH = _C_JACOBIAN = _C_FK_MATRIX = None


def _c_design(vals):
    """No C design without the extension (the generated module's binds wristkin._native's)."""
    return None
