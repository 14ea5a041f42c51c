"""A stand-in for the names a user robot's generated module defines before the runtime sources it inlines
(runtime/python/chain_*.py): the values templates/python/chain.py.jinja prints for tests/test_chain_c.py's "ur_t"
(a UR5e-type arm), without the compiled extension. Never inlined: it lets the sources be imported, linted and
tested as they are (tests/test_chain_runtime.py)."""

from __future__ import annotations

import math

from _runtime import (  # noqa: F401  (re-exported: the runtime's names a generated module binds)
    FLAG_DOUBLE_ROOT,
    FLAG_INDETERMINATE,
    FLAG_PROJECTED,
    FLAG_SINGULAR_INVERSE,
    STATUS_INDETERMINATE,
    STATUS_NAMES,
    STATUS_OK,
    STATUS_UNREACHABLE,
    BatchSolutions,
    InvalidDesign,
    InvalidInput,
    Solutions,
    WristkinError,
    _array,
    _as_rotation,
    _projected_note,
    _rows,
    _stack,
    _vector,
    _wrap,
)

NAME = "ur_t"
JOINT_NAMES = (
    "q1", "q2", "q3", "q4",
    "q5", "q6",
)
JOINT_KINDS = ("R", "R", "R", "R", "R", "R", )
POSE_NAMES = ("r00", "r01", "r02", "px", "r10", "r11", "r12", "py", "r20", "r21", "r22", "pz")
# the free joint of a redundant chain is a design parameter: its value for the call (IKFast's free joint)
DESIGN_NAMES = ()
DESIGN_DEFAULT = ()
ANGLE_NAMES = tuple(n for n, k in zip(JOINT_NAMES, JOINT_KINDS, strict=True) if k == "R")
N_JOINTS = 6
MAX_IK = 8
MAX_FK = 1
IK_AUX_NAMES = ("residual",)
FK_AUX_NAMES = ("manipulability",)
# joint limits of the description (select uses them)
LOWER = (
    -math.inf, -math.inf, -math.inf, -math.inf,
    -math.inf, -math.inf,
)
UPPER = (
    math.inf, math.inf, math.inf, math.inf,
    math.inf, math.inf,
)
DECOMPOSITION = (
    'three parallel axes q2, q3, q4: joint q1 from the plane normal to them, the orientation by (their '
    'sum, q5, q6), then the planar pair'
)
CONTROLS = (
    'the full pose (position and orientation)'
)
# branch -> its two labels (branch_of, select(branch=...))
BRANCHES = {"elbow": ["up", "down"], "shoulder": ["front", "back"], "wrist": ["noflip", "flip"]}

# |u| of acos(u) may exceed 1 by TANGENT_TOL (a pose at the reach boundary); 1 - u^2 at or below
# DOUBLE_ROOT_TOL is one double root, reported once and flagged
TANGENT_TOL = 1e-9
DOUBLE_ROOT_TOL = 32 * 2.220446049250313e-16
# A stage after a near-singular orientation (the family's middle angle g = |sin| small but resolved: two regular
# sets) reads points placed through angles fixed only to eps / g each (their sum or difference is well conditioned),
# moved by that times a lever of about the chain's size: its u carries ~ eps / g (measured: 1e-9 at g = 1e-7 on a
# UR5e). Its tangent and double-root bands grow to STAGE_NOISE / g and twice that, so that the decision sits well
# above the noise (C and Python round differently) and a stretched or folded elbow behind a near-singular wrist
# stays one root; the FK check and the polish decide the clamped or merged root.
STAGE_NOISE = 16 * 2.220446049250313e-16
IK_VERIFY_TOL = 1e-9  # max |FK(q) - pose| (entries of [R | p]) for a valid IK solution
ROTATION_TOL = 1e-6  # pose rotations: projected onto SO(3) up to this deviation (ROTATION_PROJECT_TOL)
LENGTH_MAX = 1e6  # metres: largest pose translation and prismatic joint value
SINGULAR_EPS = 1e-6  # sigma_min / sigma_max of J at or below this: flagged singular
SCALE = 0.8520575626094753  # metres: the chain's size (coefficient tolerances scale with it)
DEGENERATE_EPS = 1e-12  # a subproblem's coefficient norm (relative to SCALE) below this: a one-parameter family
# subproblem 2's two roots within this (g relative to |p|: |sin| of a wrist's middle angle) are one, the singular
# family: the stages before an orientation (the degree-8 polynomial, subproblem 6's Newton steps) leave ~1e-12 in
# its rotation, which a tighter threshold would split into two "regular" sets of a singular pose
FAMILY_TOL = 1e-12
ON_AXIS_TOL = 64 * 2.220446049250313e-16
# a singular orientation family's free angle when no `previous` is given: the first of these (every degree, nearest
# to 0 first) for which the rest of the decomposition has a verified solution (with a parallel group the position
# depends on it, and only an interval of angles reaches the pose); the search stops at the first success
FAMILY_ANGLES = (0.0,) + tuple(s * k * math.pi / 180 for k in range(1, 181) for s in (1, -1))[:-1]
POLISH_STEPS = 8  # Gauss-Newton steps on the true chain (near-special geometry, tangent roots)
# a polished set is driven to this (max |FK(q) - pose|, scaled by the chain's size) or as far as steps improve:
# Gauss-Newton converges quadratically from the ideal geometry's ~1e-7 to rounding in two steps
POLISH_TOL = 1e-12 * max(1.0, SCALE)
GEOMETRY_TOL = 1e-06  # the planner's tolerance on parallel / intersecting axes
GEOMETRY_DEVIATION = 2.7755575615628914e-17  # largest deviation of the true axes from the ideal ones used
CALIBRATED = False
_DEGENERATE_HELD = ()  # (held value, why) pairs the IK refuses: a self-motion, or a relation of the plan broken

# The chain at q = 0, base frame: axis, a point on it (revolute), end frame M. _IDEAL_*: the same with the
# relations the decomposition relies on made exact (equal to the true data when they already were).
_AXES = (
    (0.0, 0.0, 1.0),
    (0.0, -1.0, 1.1102230246251565e-16),
    (0.0, -1.0, 1.1102230246251565e-16),
    (0.0, -1.0, 1.1102230246251565e-16),
    (0.0, -2.220446049250313e-16, -1.0),
    (0.0, -1.0, 1.1102230246251565e-16),
)
_POINTS = (
    (0.0, 0.0, 0.0),
    (0.0, 1.8041124150158794e-17, 0.1625),
    (-0.425, 1.8041124150158794e-17, 0.1625),
    (-0.8171999999999999, 1.8041124150158794e-17, 0.1625),
    (-0.8171999999999999, -0.13330000000000003, 2.7755575615628914e-17),
    (-0.8171999999999999, 0.0, 0.06280000000000002),
)
_HOME = (
    (1.0, 0.0, 0.0, -0.8171999999999999),
    (0.0, 1.1102230246251565e-16, -1.0, -0.23290000000000002),
    (0.0, 1.0, 1.1102230246251565e-16, 0.06280000000000005),
    (0.0, 0.0, 0.0, 1.0),
)
_IDEAL_AXES = (
    (0.0, 0.0, 1.0),
    (0.0, -1.0, 1.1102230246251565e-16),
    (0.0, -1.0, 1.1102230246251565e-16),
    (0.0, -1.0, 1.1102230246251565e-16),
    (0.0, -2.220446049250313e-16, -1.0),
    (0.0, -1.0, 1.1102230246251565e-16),
)
_IDEAL_POINTS = (
    (0.0, 0.0, 0.0),
    (0.0, 1.8041124150158794e-17, 0.1625),
    (-0.425, 1.8041124150158794e-17, 0.1625),
    (-0.8171999999999999, 1.8041124150158794e-17, 0.1625),
    (-0.8171999999999999, -0.13330000000000006, 2.7755575615628914e-17),
    (-0.8171999999999999, 0.0, 0.06280000000000002),
)
_IDEAL_HOME = (
    (1.0, 0.0, 0.0, -0.8171999999999999),
    (0.0, 1.1102230246251565e-16, -1.0, -0.23290000000000002),
    (0.0, 1.0, 1.1102230246251565e-16, 0.06280000000000005),
    (0.0, 0.0, 0.0, 1.0),
)
_BASE = (
    (1.0, 0.0, 0.0, 0.0),
    (0.0, 1.0, 0.0, 0.0),
    (0.0, 0.0, 1.0, 0.0),
    (0.0, 0.0, 0.0, 1.0),
)
_TOOL = (
    (1.0, 0.0, 0.0, 0.0),
    (0.0, 1.0, 0.0, 0.0),
    (0.0, 0.0, 1.0, 0.0),
    (0.0, 0.0, 0.0, 1.0),
)
_FREE = -1  # index of the free joint, or -1
_ARM_ANGLE = False  # the run-time parameter is the arm angle of an S-R-S arm (chain_arm_angle.py)
_REVERSED = False  # the decomposition reads the chain from the tool
# (op, args...): the decomposition as data; _solve below interprets it (see the module docstring of
# derive/families/chain/planner.py for each op's equation)
_PLAN = (
    ("begin", ('meet', 4, 5), 0, 5),
    ("first_plane", 0, "R", ('dir', 1)),
    ("orient", ((1, 2, 3), (4,), (5,)), 1, 5),
    ("begin", ('on', 3), 1, 3),
    ("last_dist", 2, "R", ('on', 1), True),
    ("single", 1, "R"),
    ("group_rest", 3, (1, 2, 3)),
)
# per branching op: (branch name, kind, joint index in the solver's chain, reference points)
_ROLES = (('shoulder',
  'shoulder',
  0,
  (6,
   (-0.8171999999999999, -0.13330000000000003, 0.06280000000000004),
   (-0.9869559962909829, -0.16099025245421936, 0.0))),
 ('wrist', 'wrist', 4, ()),
 ('elbow',
  'elbow',
  2,
  (1,
   (0.0, 1.8041124150158794e-17, 0.1625),
   4,
   (-0.8171999999999999, 1.8041124150158794e-17, 0.1625),
   (0.0, 0.0, 1.0))))

INPUTS_HASH = "stand-in"
_C = None  # no compiled extension: every verb runs the numpy path
_C_IK = _C_FK = _C_IK_BATCH = _C_FK_BATCH = _C_JACOBIAN = _C_FK_MATRIX = None
_IK_RESULT = _FK_RESULT = None


def _k_fk(q, c, s):  # the derived kernel reads c and s; the table takes q
    """Stand-in for the robot's derived FK kernel (derive/families/chain/kernels.py prints it straight-line): the same
    12 entries of [R | p] from the chain's table."""
    from chain_poe import _fk_chain, _full_chain

    r, t = _fk_chain(_full_chain(_AXES, _POINTS, _HOME), q)
    return (*r[0], t[0], *r[1], t[1], *r[2], t[2])


def _k_jacobian(q, c, s):
    """Stand-in for the derived Jacobian kernel: the 6 x n Jacobian row-major."""
    from chain_poe import _full_chain
    from chain_verify import _jacobian_chain

    return tuple(float(v) for v in _jacobian_chain(_full_chain(_AXES, _POINTS, _HOME), q).ravel())
