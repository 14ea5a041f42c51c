"""The arm angle of a 7R arm with a spherical shoulder and a spherical wrist (an S-R-S arm: the iiwa's), as the
redundancy parameter: the op ("arm_angle", (a, b, c), e, s) solves the shoulder joints a, b, c and the elbow e for
the wrist centre y the previous op placed and the design's arm angle psi; the wrist's orientation op follows.

psi is where the elbow is on its circle about the shoulder-wrist line: 0 in the plane of that line and the first
joint's axis, on the side the axis points to; positive turning about the line from the shoulder to the wrist.
(derive/kinematics/arm_angle.py derives and checks it; the audit states it.)

A wristkin runtime source: every user robot's generated module inlines it from the marker line on when its plan
has the op (derive/runtime_files.py), after the robot's constants; above the marker, what it reads from them and
from the other sources (chain_stand_in.py: a stand-in robot), so that it is linted and tested as it is
(tests/test_chain_runtime.py)."""

from __future__ import annotations

import math

from chain_points import _point
from chain_rigid import _add, _apply, _compose, _cross, _dot, _mm, _mt, _mv, _norm, _scale, _screw, _sub
from chain_stages import _OP_READERS, _OP_STAGES
from chain_stand_in import (
    DOUBLE_ROOT_TOL,
    FLAG_DOUBLE_ROOT,
    FLAG_INDETERMINATE,
    FLAG_SINGULAR_INVERSE,
    ON_AXIS_TOL,
    SCALE,
)
from chain_subproblems import _orient_rest, _perpendicular, _sp2, _sp3

# wristkin: inlined from here
# ---------------------------------------------------------------------------- the arm angle (an S-R-S arm)


def _arm_plane(h1, s, w):
    """(u, n1, n2, flags): u the unit from the shoulder centre s to the wrist centre w; n1 the first axis h1's part
    normal to u, unit (psi = 0 there), n2 = u x n1. With w on the first axis (|h1 x u| <= ON_AXIS_TOL) the plane is
    the pose's to choose: n1 any unit normal to u, flagged indeterminate."""
    sw = _sub(w, s)
    length = _norm(sw)
    u = _scale(sw, 1.0 / length)
    n1 = _sub(h1, _scale(u, _dot(h1, u)))
    m = _norm(n1)
    flags = 0
    if not m > ON_AXIS_TOL:
        n1, flags = _perpendicular(u), FLAG_INDETERMINATE
    else:
        n1 = _scale(n1, 1.0 / m)
    return u, n1, _cross(u, n1), flags


def _arm_angle_of(h1, s, e, w, axis):
    """psi of an elbow point e (shoulder s, wrist w, first axis h1; axis: the elbow axis's direction there): the
    angle about u from n1 to e's part normal to u. With the elbow on the line (stretched or folded, within
    DOUBLE_ROOT_TOL of SCALE) the side is axis x u, as the stage reads it there: every psi is then the same elbow
    point, the shoulder turned about the line by psi."""
    u, n1, n2, _ = _arm_plane(h1, s, w)
    se = _sub(e, s)
    side = _sub(se, _scale(u, _dot(se, u)))
    if not _norm(side) > DOUBLE_ROOT_TOL * SCALE:
        side = _cross(axis, u)
    return math.atan2(_dot(side, n2), _dot(side, n1))


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
    return _arm_angle_of(ch.axes[ja], s, _apply(shoulder, elbow), w, _mv(shoulder[0], he))


def _frame_of(a, b):
    """The rotation whose columns are a (unit), b (unit, normal to a) and a x b."""
    c = _cross(a, b)
    return ((a[0], b[0], c[0]), (a[1], b[1], c[1]), (a[2], b[2], c[2]))


def _arm_angle_stage(ch, g, prev, op, x, y, q, count, go_on, family, params=(0.0,)):
    """The op ("arm_angle", (a, b, c), e, s): x is the wrist centre at home, y its target w, s the shoulder centre
    (the shoulder axes' common point). The elbow joint e from |e_e x - s| = |w - s| (subproblem 3: two roots, the
    elbow bent either way); then the shoulder's rotation R about s maps the home side's frame (the unit from s to
    the turned wrist centre, and the unit from that line to the elbow point) onto the target's (s -> w, and the
    side psi gives), and subproblem 2 then 1 read the three shoulder joints from R (two roots; q_b = 0 lines up a
    and c: a family, q_a from previous else 0)."""
    _, (ja, jb, jc), je, ss = op
    psi = params[0]
    s = _point(ch, ss)
    ha, hb, hc, he, pe = ch.axes[ja], ch.axes[jb], ch.axes[jc], ch.axes[je], ch.points[je]
    w = y
    length = _norm(_sub(w, s))
    if not length > 0.0:
        return
    u, n1, n2, plane_flags = _arm_plane(ha, s, w)
    side = _add(_scale(n1, math.cos(psi)), _scale(n2, math.sin(psi)))  # the elbow's side of the line s -> w
    target = _frame_of(u, side)
    elbow = _elbow_point(ch, je, s)
    roots = _sp3(he, _sub(x, pe), _sub(s, pe), length, SCALE)
    if len(roots) == 1 and roots[0][1] & FLAG_DOUBLE_ROOT:
        # the arm (nearly) stretched or folded: the distance fixes the elbow only to ~sqrt(eps), and its two roots,
        # merged, are the elbow bent to either side of the line, where the shoulder and wrist differ by a half turn
        # (q3 and q5 of an iiwa): both sides, each a band's width off the line, so that the elbow's side (and the
        # arm angle read back) is defined; the pose does not tell them apart beyond its rounding
        t, f = roots[0]
        band = math.sqrt(DOUBLE_ROOT_TOL)
        roots = [(t + band, f), (t - band, f)]
    for t, f in roots:
        q[je] = t
        v = _sub(_apply(_screw("R", he, pe, t), x), s)  # the wrist centre with the elbow turned, shoulder at home
        v = _scale(v, 1.0 / _norm(v))
        off = _sub(elbow, s)
        off = _sub(off, _scale(v, _dot(off, v)))
        if _norm(off) > DOUBLE_ROOT_TOL * SCALE:
            home_side = _scale(off, 1.0 / _norm(off))
        else:  # stretched or folded: the elbow on the line, any turn about it the same pose; the axis x v stands in
            home_side = _cross(he, v)
            home_side = _scale(home_side, 1.0 / _norm(home_side))
            f |= FLAG_DOUBLE_ROOT | FLAG_SINGULAR_INVERSE
        r = _mm(target, _mt(_frame_of(v, home_side)))
        for t1, t2, f2 in _sp2(_mv(r, hc), ha, hc, hb, 1.0):
            if t1 is None:  # a and c line up: the family's q_a from previous, else 0
                t1 = -(prev[ja] if prev is not None else 0.0)
                f2 |= FLAG_INDETERMINATE | FLAG_SINGULAR_INVERSE
            q[ja], q[jb], q[jc] = _orient_rest((ha, hb, hc), r, t1, t2)  # as the orientation op reads its units
            go_on(f | f2 | plane_flags)


_OP_STAGES["arm_angle"] = _arm_angle_stage
_OP_READERS["arm_angle"] = _arm_angle_at
