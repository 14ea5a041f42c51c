"""The arm angle of a 7R arm with a spherical shoulder and a spherical wrist (an S-R-S arm: the iiwa's), as the
redundancy parameter, for the interpreted plan: the op ("arm_angle", (a, b, c), e, s) solves the shoulder joints a,
b, c and the elbow e for the wrist centre y the previous op placed and the design's arm angle psi (the chain-free core
arm_angle.py on the chain's axes, with the chain's tolerances); the wrist's orientation op follows.

A wristkin runtime source: every user robot's generated module inlines it from the marker line on when its plan
has the op (derive/runtime_files.py), after the robot's constants and arm_angle.py; above the marker, what it reads
from them and from the other sources (chain_stand_in.py: a stand-in robot), so that it is linted and tested as it is
(tests/test_chain_runtime.py)."""

from __future__ import annotations

from arm_angle import _aa_angle_of, _arm_angle_core
from chain_points import _point
from chain_rigid import _add, _apply, _compose, _dot, _mv, _scale, _screw, _sub
from chain_stages import _OP_READERS, _OP_STAGES
from chain_stand_in import DEGENERATE_EPS, DOUBLE_ROOT_TOL, FAMILY_TOL, ON_AXIS_TOL, SCALE, TANGENT_TOL

# wristkin: inlined from here
# the core's tolerances (arm_angle.py): the chain's
ARM_ANGLE_TOLS = (SCALE, DEGENERATE_EPS, DOUBLE_ROOT_TOL, TANGENT_TOL, ON_AXIS_TOL, FAMILY_TOL)


def _elbow_point(ch, je, s):
    """The elbow point: on the elbow axis je, nearest the shoulder centre s."""
    he, pe = ch.axes[je], ch.points[je]
    return _add(pe, _scale(he, _dot(he, _sub(s, pe))))


def _arm_angle_at(ch, op, q):
    """psi of the chain's joints q (the op ("arm_angle", (a, b, c), e, s) names the shoulder, the elbow and the
    shoulder centre; the wrist centre is the point the plan's first op places): where the joints put the elbow
    point on its circle."""
    _, (ja, jb, jc), je, ss = op
    s = _point(ch, ss)
    he, pe = ch.axes[je], ch.points[je]
    elbow = _elbow_point(ch, je, s)
    shoulder = _compose(_compose(_screw("R", ch.axes[ja], ch.points[ja], q[ja]),
                                 _screw("R", ch.axes[jb], ch.points[jb], q[jb])),
                        _screw("R", ch.axes[jc], ch.points[jc], q[jc]))
    w = _apply(_compose(shoulder, _screw("R", he, pe, q[je])), _point(ch, ("meet", *range(je + 1, je + 4))))
    return _aa_angle_of(ch.axes[ja], s, _apply(shoulder, elbow), w, _mv(shoulder[0], he), ARM_ANGLE_TOLS)


def _arm_angle_stage(ch, g, prev, op, x, y, q, count, go_on, family, params=(0.0,)):
    """The op ("arm_angle", (a, b, c), e, s): x is the wrist centre at home, y its target w, s the shoulder centre
    (the shoulder axes' common point); every set of the core (two elbows, two shoulders each), the rest of the plan
    run on each."""
    _, (ja, jb, jc), je, ss = op
    for (qa, qb, qc, qe), f in _arm_angle_core(ch.axes[ja], ch.axes[jb], ch.axes[jc], _point(ch, ss), ch.axes[je],
                                               ch.points[je], x, y, params[0], None if prev is None else prev[ja],
                                               ARM_ANGLE_TOLS):
        q[ja], q[jb], q[jc], q[je] = qa, qb, qc, qe
        go_on(f)


_OP_STAGES["arm_angle"] = _arm_angle_stage
_OP_READERS["arm_angle"] = _arm_angle_at
