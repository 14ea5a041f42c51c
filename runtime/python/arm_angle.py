"""The arm angle of a 7R arm with a spherical shoulder and a spherical wrist (an S-R-S arm: the iiwa's) as its
redundancy parameter: the shoulder's three joints and the elbow for a wrist centre and an arm angle psi, every set
(runtime/c/wk_arm_angle.c's twin, step for step; derive/kinematics/arm_angle.py derives and checks the definition).

psi is where the elbow is on its circle about the shoulder-wrist line: 0 in the plane of that line and the first
joint's axis, on the side the axis points to; positive turning about the line from the shoulder to the wrist. The
elbow from the distance |rot(h_e, q_e) (x - p_e) - (s - p_e)| = |w - s| (subproblem 3: the elbow bent either way);
the shoulder's rotation about s maps the home side's frame (s -> the turned wrist centre, and that line's unit to
the elbow point) onto the target's (s -> w, the side psi gives); subproblem 2 then 1 read the three shoulder joints
from it (two sets; q_b = 0 lines up a and c: a family, q_a from previous else 0).

A wristkin runtime source: a serial arm's module with an arm_angle stage (serial_arm_angle.py) inlines it from the
marker line on (derive/runtime_files.py), after geom3.py; above the marker, what it reads from the runtime, so that it
is linted and tested as it is (tests/test_arm_angle.py)."""

from __future__ import annotations

import math

from _runtime import FLAG_DOUBLE_ROOT, FLAG_INDETERMINATE, FLAG_SINGULAR_INVERSE
from geom3 import _g3_axpy, _g3_cross, _g3_dot, _g3_norm, _g3_sp1, _g3_trig, _g3_turn, _g3_turn_dir

# wristkin: inlined from here
# The core's tolerances, the caller's (wk_arm_angle.c's wk_aa_tols says what each is):
# (scale, degenerate, double_root, tangent, on_axis, family)
# The bands (double_root, tangent, on_axis, family) on the closed-form stages' inputs of an S-R-S arm (the stages'
# DOUBLE_ROOT_TOL, TANGENT_TOL, ON_AXIS_TOL and FAMILY_TOL), which the serial stage and the audit's check run it at
# (wk_arm_angle.c's WK_AA_* twins)
AA_BANDS = (32 * 2.220446049250313e-16, 1e-9, 64 * 2.220446049250313e-16, 1e-12)


def _aa_unit(v):
    n = _g3_norm(v)
    return (v[0] / n, v[1] / n, v[2] / n)


def _aa_perpendicular(k):
    """A unit vector normal to k."""
    e = (1.0, 0.0, 0.0) if abs(k[0]) <= min(abs(k[1]), abs(k[2])) else (
        (0.0, 1.0, 0.0) if abs(k[1]) <= abs(k[2]) else (0.0, 0.0, 1.0))
    return _aa_unit(_g3_cross(k, e))


def _aa_plane(h1, s, w, on_axis):
    """(u, n1, n2, flags), None when w = s: u the unit from the shoulder centre s to the wrist centre w; n1 the
    first axis h1's part normal to u, unit (psi = 0 there), n2 = u x n1. With w on the first axis (|h1 x u| within
    on_axis) the plane is the pose's to choose: n1 any unit normal to u, flagged indeterminate."""
    sw = _g3_axpy(w, -1.0, s)
    m = _g3_norm(sw)
    if not m > 0.0:
        return None
    u = (sw[0] / m, sw[1] / m, sw[2] / m)
    n1 = _g3_axpy(h1, -_g3_dot(h1, u), u)
    m = _g3_norm(n1)
    flags = 0
    if not m > on_axis:
        n1, flags = _aa_perpendicular(u), FLAG_INDETERMINATE
    else:
        n1 = (n1[0] / m, n1[1] / m, n1[2] / m)
    return u, n1, _g3_cross(u, n1), flags


def _aa_angle_of(h1, s, e, w, axis, tols):
    """psi of an elbow point e (shoulder s, wrist w, first axis h1; axis: the elbow axis's direction there): the
    angle about u from n1 to e's part normal to u. With the elbow on the line (stretched or folded, within
    double_root of the scale) the side is axis x u, as the stage reads it there: every psi is then the same elbow
    point, the shoulder turned about the line by psi."""
    plane = _aa_plane(h1, s, w, tols[4])
    if plane is None:
        return 0.0
    u, n1, n2, _ = plane
    se = _g3_axpy(e, -1.0, s)
    side = _g3_axpy(se, -_g3_dot(se, u), u)
    if not _g3_norm(side) > tols[2] * tols[0]:
        side = _g3_cross(axis, u)
    return math.atan2(_g3_dot(side, n2), _g3_dot(side, n1))


def _aa_sp3(k, p1, p2, d, tols):
    """t with |rot(k, t) p1 - p2| = d (subproblem 3): (p2 . p1_perp) cos t + (p2 . k x p1) sin t = (|p1|^2 +
    |p2|^2 - d^2) / 2 - (k.p1)(k.p2)."""
    kp1 = _g3_dot(k, p1)
    perp = _g3_axpy(p1, -kp1, k)
    c = 0.5 * (_g3_dot(p1, p1) + _g3_dot(p2, p2) - d * d) - kp1 * _g3_dot(k, p2)
    scale, _, double_root, tangent, on_axis, _ = tols
    return _g3_trig(_g3_dot(p2, perp), _g3_dot(p2, _g3_cross(k, p1)), c, scale * scale, on_axis, tangent, double_root)


def _aa_sp2(p1, k1, p2, k2, tols):
    """(t1, t2, flags) with rot(k1, t1) p1 = rot(k2, t2) p2 for unit vectors p1, p2 (subproblem 2): the common
    vector w = alpha k1 + beta k2 +- g k1 x k2, g^2 read on the circle of the smaller radius (no cancellation near a
    family); one double root within double_root of g^2's rounding or the family band; t1 None where p1 lies on k1
    (any t1: a singular family)."""
    _, _, double_root, tangent, _, family = tols
    c = _g3_dot(k1, k2)
    a1, a2 = _g3_dot(k1, p1), _g3_dot(k2, p2)
    den = 1.0 - c * c
    if not den > 0.0:
        return []
    alpha, beta = (a1 - c * a2) / den, (a2 - c * a1) / den
    kk = _g3_cross(k1, k2)
    base = _g3_axpy(_g3_axpy((0.0, 0.0, 0.0), alpha, k1), beta, k2)
    r1, r2 = _g3_cross(k1, p1), _g3_cross(k2, p2)
    n1, n2 = _g3_dot(r1, r1), _g3_dot(r2, r2)
    n, e = (n1, a2 - c * a1) if n1 <= n2 else (n2, a1 - c * a2)
    g2 = (den * n - e * e) / (den * den)
    res2 = max(math.sqrt(0.5 * (_g3_dot(p1, p1) + _g3_dot(p2, p2))), 1.0) * (math.sqrt(n) + abs(e)) / den
    scale2 = _g3_dot(p1, p1) + _g3_dot(p2, p2)
    if g2 < -tangent * scale2:
        return []
    if g2 <= double_root * res2 or g2 <= family * family * scale2:
        ws, flag = [base], FLAG_DOUBLE_ROOT | FLAG_SINGULAR_INVERSE
    else:
        g = math.sqrt(g2)
        ws, flag = [_g3_axpy(base, g, kk), _g3_axpy(base, -g, kk)], 0
    out = []
    for w in ws:
        # p1 on the axis k1 (the family) at the family band, as g above (unit vectors: the band is the distance)
        t1, t2 = _g3_sp1(k1, p1, w, family), _g3_sp1(k2, p2, w, family)
        if t2 is None:
            continue
        out.append((t1, t2, flag if t1 is not None else flag | FLAG_INDETERMINATE | FLAG_SINGULAR_INVERSE))
        if t1 is None:
            break  # p1 on the axis k1: both w coincide (one family)
    return out


def _aa_rotation(a, b, c, d):
    """The rotation that maps the frame (c, d, c x d) onto (a, b, a x b) (units, b normal to a, d to c), rows."""
    ab, cd = _g3_cross(a, b), _g3_cross(c, d)
    return tuple(tuple(a[i] * c[j] + b[i] * d[j] + ab[i] * cd[j] for j in range(3)) for i in range(3))


def _aa_mv(r, v):
    return tuple(r[i][0] * v[0] + r[i][1] * v[1] + r[i][2] * v[2] for i in range(3))


def _aa_orient_rest(ha, hb, hc, r, t1, t2, tols):
    """The shoulder's angles of rot(h_a, q_a) rot(h_b, q_b) rot(h_c, q_c) = r given q_a = -t1, q_b = t2: q_c by
    subproblem 1 on a unit w normal to h_c, (rot(h_a, q_a) rot(h_b, q_b))^T r w = rot(h_c, q_c) w."""
    w = _aa_perpendicular(hc)
    v = _g3_turn_dir(hb, -t2, _g3_turn_dir(ha, t1, _aa_mv(r, w)))
    t3 = _g3_sp1(hc, w, v, tols[1])
    return -t1, t2, 0.0 if t3 is None else t3


def _arm_angle_core(ha, hb, hc, s, he, pe, x, w, psi, prev_a, tols, held=None):
    """The sets [((q_a, q_b, q_c, q_e), flags)], at most four (two elbows x two shoulders): h_a, h_b, h_c the
    shoulder's axes (meeting at s), h_e / p_e the elbow's axis and a point on it, x the wrist centre at home, w its
    target, psi the arm angle; prev_a: previous's q_a (a shoulder family's member), or None. held: the elbow held at
    this value (None: solved), the arm a self-motion: w within the tangent band of the distance it leaves the wrist
    centre from s, else no set; the sets at psi, flagged indeterminate (every psi reaches the pose)."""
    scale, _, double_root, tangent, on_axis, _ = tols
    plane = _aa_plane(ha, s, w, on_axis)
    if plane is None:
        return []
    u, n1, n2, plane_flags = plane
    side = _g3_axpy(_g3_axpy((0.0, 0.0, 0.0), math.cos(psi), n1), math.sin(psi), n2)  # the elbow's side of s -> w
    elbow = _g3_axpy(pe, _g3_dot(he, _g3_axpy(s, -1.0, pe)), he)  # the elbow axis's point nearest s
    if held is not None:
        reach = _g3_norm(_g3_axpy(_g3_turn(he, pe, held, x), -1.0, s))
        if not abs(reach - _g3_norm(_g3_axpy(w, -1.0, s))) <= tangent * scale:
            return []
        roots = [(held, FLAG_INDETERMINATE | FLAG_SINGULAR_INVERSE)]
    else:
        roots = _aa_sp3(he, _g3_axpy(x, -1.0, pe), _g3_axpy(s, -1.0, pe), _g3_norm(_g3_axpy(w, -1.0, s)), tols)
    if held is None and len(roots) == 1 and roots[0][1] & FLAG_DOUBLE_ROOT:
        # the arm (nearly) stretched or folded: the distance fixes the elbow only to ~sqrt(eps), and its two roots,
        # merged, are the elbow bent to either side of the line, where the shoulder and wrist differ by a half turn
        # (q3 and q5 of an iiwa): both sides, each a band's width off the line, so that the elbow's side (and the
        # arm angle read back) is defined; the pose does not tell them apart beyond its rounding
        t, f = roots[0]
        band = math.sqrt(double_root)
        roots = [(t + band, f), (t - band, f)]
    out = []
    for t, f in roots:
        v = _aa_unit(_g3_axpy(_g3_turn(he, pe, t, x), -1.0, s))  # the wrist centre, elbow turned, shoulder home
        off = _g3_axpy(elbow, -1.0, s)
        off = _g3_axpy(off, -_g3_dot(off, v), v)
        if _g3_norm(off) > double_root * scale:
            home_side = _aa_unit(off)
        else:  # stretched or folded: the elbow on the line, any turn about it the same pose; the axis x v stands in
            home_side = _aa_unit(_g3_cross(he, v))
            f |= FLAG_DOUBLE_ROOT | FLAG_SINGULAR_INVERSE
        r = _aa_rotation(u, side, v, home_side)
        for t1, t2, f2 in _aa_sp2(_aa_mv(r, hc), ha, hc, hb, tols):
            if t1 is None:  # a and c line up: the family's q_a from previous, else 0
                t1 = -(prev_a if prev_a is not None else 0.0)
                f2 |= FLAG_INDETERMINATE | FLAG_SINGULAR_INVERSE
            out.append(((*_aa_orient_rest(ha, hb, hc, r, t1, t2, tols), t), f | f2 | plane_flags))
    return out[:4]
