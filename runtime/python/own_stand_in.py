"""A stand-in for the names a user robot's derived module defines before the own-robot runtime sources it inlines
(runtime/python/chain_rigid.py, chain_poe.py, serial_own.py, own_api.py): the constants the serial family prints
for a UR5e-type arm (its joints, limits, named branches and ideal chain at q = 0). Never inlined: it lets the sources
be imported and linted as they are; the verbs own_api.py calls come from the serial stand-in (serial_stand_in.py)."""

from __future__ import annotations

import math

from _runtime import STATUS_NAMES, InvalidInput, Solutions, WristkinError  # noqa: F401  (re-exported)

NAME = "ur_t"
JOINT_NAMES = (
    "q1", "q2", "q3", "q4",
    "q5", "q6",
)
JOINT_KINDS = ("R", "R", "R", "R", "R", "R", )
N_JOINTS = 6
# joint limits of the description (select uses them)
LOWER = (
    -math.inf, -math.inf, -math.inf, -math.inf,
    -math.inf, -math.inf,
)
UPPER = (
    math.inf, math.inf, math.inf, math.inf,
    math.inf, math.inf,
)
# branch -> its two labels (branch_of, select(branch=...))
BRANCHES = {"elbow": ["up", "down"], "shoulder": ["front", "back"], "wrist": ["noflip", "flip"]}

ROTATION_TOL = 1e-6  # pose rotations: projected onto SO(3) up to this deviation (ROTATION_PROJECT_TOL)

# the ideal chain at q = 0, base frame: axis, a point on it (revolute), end frame M (the relations the
# decomposition relies on made exact)
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
_FREE = -1  # index of the free joint, or -1
_ARM_ANGLE = False  # the run-time parameter is the arm angle of an S-R-S arm (serial_arm_angle.py)
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
