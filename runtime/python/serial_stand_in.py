"""A stand-in for the names a serial arm's generated module defines before the runtime sources it inlines
(runtime/python/serial_*.py): the constants templates/python/serial.py.jinja prints for the catalogue's PUMA-560
(catalogue/puma560.toml), the shared runtime's names, and what is derived or printed per robot (its kernels,
stage functions and Design) taken from that generated module, with no C extension (_C = None: the numpy path).
Never inlined: it lets the sources be imported, linted and tested as they are (tests/test_serial_runtime.py)."""

from __future__ import annotations

from _runtime import (  # noqa: F401  (re-exported: the runtime's names a generated module binds)
    FLAG_DOUBLE_ROOT,
    FLAG_INDETERMINATE,
    FLAG_PROJECTED,
    FLAG_SINGULAR_INVERSE,
    STATUS_INDETERMINATE,
    STATUS_OK,
    STATUS_UNREACHABLE,
    BatchSolutions,
    InvalidDesign,
    InvalidInput,
    Solutions,
    _array,
    _as_rotation,
    _projected_note,
    _rows,
    _stack,
    _vector,
    _wrap,
)
from wristkin.puma560 import (  # noqa: F401  (derived or printed per robot)
    _BASE,
    _STAGES,
    _TOOL,
    Design,
    _design_values,
    _k_fk,
    _k_fk_cs,
    _k_jacobian,
    _kv_fk,
)

NAME = "puma560"
JOINT_NAMES = ("q1", "q2", "q3", "q4", "q5", "q6", )
JOINT_KINDS = ("R", "R", "R", "R", "R", "R", )
DESIGN_NAMES = ("d1", "a2", "d3", "a3", "d4", "d6", )
N_JOINTS = 6
MAX_IK = 8
MAX_FK = 1
TANGENT_TOL = 1e-9
TANGENT_MAX = 1e-6
STAGE_NOISE = 3.552713678800501e-15
DOUBLE_ROOT_TOL = 1e-12
DOUBLE_ROOT_POLISH_TOL = 1e-12
ROOT_GAP_TOL = 5.684341886080802e-14
DEGENERATE_EPS = 1e-12
ON_AXIS_TOL = 1.4210854715202004e-14
IK_VERIFY_TOL = 1e-9
WRIST_EXACT_TOL = 1e-13
WRIST_FAMILY_TOL = 1.4210854715202004e-14
ROTATION_TOL = 1e-6
LENGTH_MAX = 1e6
DESIGN_SCALE_MIN = 1e-3
LENGTH_MIN = 1e-5
SINGULAR_EPS = 1e-6
LENGTHS_FLOOR = True  # DH lengths: each 0 or at least LENGTH_MIN
CALIBRATED = False  # the stages solve an ideal geometry, FK is the true chain's: every set polished on it
TANGENT_CALIBRATED = 0.0  # a calibrated robot's band on u past 1 (the PUMA: none)
POLISH_STEPS = 6  # Gauss-Newton steps at most per polish
N_LENGTHS = 6  # the design's first N_LENGTHS values are lengths (a held joint's angle follows them)
_HELD = -1  # a joint held at the design's last value (-1: none): Gauss-Newton steps leave it alone
DESIGN_CHECKS = ()
IMAGE_CHECKS = ()
_FK_IDEAL = None  # a calibrated robot's ideal table's FK (the stages' geometry), None otherwise
_DESIGN_CHECK = None  # the kernels of those conditions (a finite-screw chain's), None without any
_IMAGE_CHECK = None
_UNREACHABLE_NOTE = None  # what an unreachable pose's reason adds (a user's chain of fewer than six joints)
_FOLD_MASKS = (4, 2, )
_WRIST_JOINTS = (3, 5)
_WRIST_STAGE = 3
_WRIST_BEND = 4
_STAGE_SETS = 8  # the stages' sets (MAX_IK but for a calibrated arm's wrist family scan: twice this)
_FAMILY_SCAN = False  # a calibrated arm whose wrist is its last stage: its near-singular families scanned
_SHOULDER_FAMILY = None  # such an arm's (q1, its first stage's kernel) when that stage reads q1 from the wrist centre

# the numpy path: no extension (the generated module binds these from wristkin._native when it is built)
_C = None
_C_IK = _C_FK = _C_IK_BATCH = _C_FK_BATCH = _C_JACOBIAN = _C_FK_MATRIX = None
_IK_RESULT = _FK_RESULT = None


def _c_design(vals):
    """No C design without the extension (the generated module's binds wristkin._native's)."""
    return None


# an S-R-S arm's module (an arm_angle stage): the robot's size and its reader kernel (the PUMA has neither: stand-ins
# for the names serial_arm_angle.py reads)
SCALE = 1.0


def _k_arm_angle_parts(q, dp):
    """The first axis, the shoulder centre, the elbow point, the wrist centre and the elbow axis's direction the
    joints place (a derived kernel of an S-R-S arm's module)."""
    raise NotImplementedError("the PUMA-560 has no arm angle")
