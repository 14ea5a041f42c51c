"""The Paden-Kahan subproblems 1-4 (and subproblem 2's height) and a trig equation.

A wristkin runtime source: every user robot's generated module inlines it from the marker line on
(derive/runtime_files.py), after the robot's constants; above the marker, what it reads from them and from the
other sources (chain_stand_in.py: a stand-in robot), so that it is linted and tested as it is
(tests/test_chain_runtime.py)."""

from __future__ import annotations

import math

from chain_rigid import _add, _cross, _dot, _mm, _mtv, _mv, _norm, _rot, _scale, _sub
from chain_stand_in import (
    DEGENERATE_EPS,
    DOUBLE_ROOT_TOL,
    FAMILY_TOL,
    FLAG_DOUBLE_ROOT,
    FLAG_INDETERMINATE,
    FLAG_SINGULAR_INVERSE,
    ON_AXIS_TOL,
    STAGE_NOISE,
    TANGENT_TOL,
)


# wristkin: inlined from here
# ---------------------------------------------------------------------------- subproblems
def _trig(a, b, c, scale, noise=1.0, gap=None):
    """Roots t of a cos t + b sin t = c: a list of (t, flags); a double root once (flagged), a vanishing
    equation one representative t = 0 (flagged indeterminate). `noise`: 1 / g of an upstream near-singular
    orientation (STAGE_NOISE), else 1. `gap`: a planar distance stage's (Dm, Dp, narrow) (_sp3): 1 - u^2 read as
    Dm Dp / (4 R^2), each factor to its own precision, and its double-root band times `narrow`."""
    r = math.hypot(a, b)
    if r <= ON_AXIS_TOL * scale:
        return [(0.0, FLAG_INDETERMINATE | FLAG_SINGULAR_INVERSE)] if abs(c) <= ON_AXIS_TOL * scale else []
    u = c / r
    if not abs(u) <= 1.0 + max(TANGENT_TOL, STAGE_NOISE * noise):
        return []
    u = max(-1.0, min(1.0, u))
    phi = math.atan2(b, a)
    band = max(DOUBLE_ROOT_TOL, 2.0 * STAGE_NOISE * noise)
    s2 = 1.0 - u * u if gap is None else max(gap[0] * gap[1], 0.0) / (4.0 * r * r)
    if s2 <= band * (1.0 if gap is None else gap[2]):
        return [(phi + (0.0 if u > 0.0 else math.pi), FLAG_DOUBLE_ROOT | FLAG_SINGULAR_INVERSE)]
    w = math.acos(u) if gap is None else math.atan2(math.sqrt(s2), u)
    return [(phi + w, 0), (phi - w, 0)]


def _sp1(k, p, q, scale):
    """t with rot(k, t) p = q (least squares when |p| != |q| or k.p != k.q); None when p or q is on the axis
    (within DEGENERATE_EPS of `scale`: SCALE for points, 1 for directions)."""
    pp = _sub(p, _scale(k, _dot(k, p)))
    qq = _sub(q, _scale(k, _dot(k, q)))
    if _norm(pp) <= DEGENERATE_EPS * scale or _norm(qq) <= DEGENERATE_EPS * scale:
        return None
    return math.atan2(_dot(k, _cross(pp, qq)), _dot(pp, qq))


def _sp3(k, p1, p2, d, scale, noise=1.0, target=None, amp=1.0):
    """t with |rot(k, t) p1 - p2| = d: (p2 . p1_perp) cos t + (p2 . k x p1) sin t = (|p1|^2 + |p2|^2 - d^2) / 2
    - (k.p1)(k.p2). `target`: the vector of length d when the stage is planar (the other joints keep parts normal to
    k): then 1 - u^2 = Dm Dp / (4 R^2) with Dm = e^2 - (l1 - l2)^2, Dp = (l1 + l2)^2 - e^2 (l1, l2 the lever arms
    |p1'|, |p2'|, e = |target'|, primes: normal to k), each to its own precision: a SCARA with equal links folded
    1e-8 rad read 1 - u^2 next to l1 l2 and merged its elbows (its first joint then a family). The double-root band
    narrows by Em amp / (2R) where Dm is the small factor (Em: the size of Dm's terms and what the inputs' rounding
    at `scale` does to them; amp: the angle stages' amplification before it)."""
    kp1 = _dot(k, p1)
    perp = _sub(p1, _scale(k, kp1))
    c = 0.5 * (_dot(p1, p1) + _dot(p2, p2) - d * d) - kp1 * _dot(k, p2)
    a, b = _dot(p2, perp), _dot(p2, _cross(k, p1))
    gap = None
    if target is not None:
        l1, l2 = _norm(perp), _norm(_sub(p2, _scale(k, _dot(k, p2))))
        e = _norm(_sub(target, _scale(k, _dot(k, target))))
        diff = abs(l1 - l2)
        dm, dp = (e - diff) * (e + diff), (l1 + l2 - e) * (l1 + l2 + e)
        em = e * e + diff * diff + 2.0 * (e + diff) * scale
        gap = (dm, dp, min(1.0, em * amp / (2.0 * math.hypot(a, b))) if abs(dm) <= abs(dp) else 1.0)
    return _trig(a, b, c, scale * scale, noise, gap)


def _sp4(h, k, p, d, scale, noise=1.0):
    """t with h . rot(k, t) p = d: (h . p_perp) cos t + (h . k x p) sin t = d - (k.p)(h.k)."""
    kp = _dot(k, p)
    perp = _sub(p, _scale(k, kp))
    return _trig(_dot(h, perp), _dot(h, _cross(k, p)), d - kp * _dot(h, k), scale, noise)


def _sp2_height2(p1, k1, p2, k2, c, a1, a2, den, scale):
    """(g^2, its rounding scale) of subproblem 2's common vector w = alpha k1 + beta k2 + g k1 x k2. g^2 is read
    without cancellation where one can be avoided: |w|^2 - |alpha k1 + beta k2|^2 = (den |k1 x p1|^2 -
    (a2 - c a1)^2) / den^2 (w on p1's circle about k1), or the same from p2's circle about k2 (equal when
    |p1| = |p2|), on the circle of the smaller radius. Near a singular family (w near k1: a wrist with |sin q5|
    small, or the arm folded onto the shoulder axis) that radius and the other term are both small, so g is
    resolved to rounding, where the difference of squared norms left eps / g (|sin q5| from cos q5: the near-
    singular sets missed the pose by 1e-11 and moved every later stage). The rounding scale: the inputs' own
    rounding (relative to the larger of |p| and `scale`) through the two terms, |p| (sqrt(n) + |e|) / den."""
    r1, r2 = _cross(k1, p1), _cross(k2, p2)
    n1, n2 = _dot(r1, r1), _dot(r2, r2)
    n, e = (n1, a2 - c * a1) if n1 <= n2 else (n2, a1 - c * a2)
    size = max(math.sqrt(0.5 * (_dot(p1, p1) + _dot(p2, p2))), scale)
    return (den * n - e * e) / (den * den), size * (math.sqrt(n) + abs(e)) / den


def _root_amplification(roots, outer):
    """How much a trig stage's two roots amplify the rounding of its inputs: 1 / |sin w| for roots phi +- w (a
    root moves by du / |sin w| for a change du of u = cos w), times `outer` (the stages before: each reads the joints
    they solved, so the errors compound, as the serial runtime's wrist band has them); a double root within the
    band: 1 / sqrt(DOUBLE_ROOT_TOL)."""
    if len(roots) == 2:
        return outer / max(abs(math.sin(0.5 * (roots[0][0] - roots[1][0]))), 1e-300)
    if len(roots) == 1 and roots[0][1] & FLAG_DOUBLE_ROOT:
        return outer / math.sqrt(DOUBLE_ROOT_TOL)
    return outer


def _sp2(p1, k1, p2, k2, scale, split=False, amp=1.0, family_tol=FAMILY_TOL):
    """(t1, t2, flags) with rot(k1, t1) p1 = rot(k2, t2) p2, k1 not parallel to k2: the common vector w has
    k1.w = k1.p1, k2.w = k2.p2 and |w| = |p1|. t1 is None when p1 lies on k1 (any t1: a singular family).
    Within DOUBLE_ROOT_TOL the two roots are one (rounding of g^2 at an exact double root would split it by
    sqrt(eps)); `split`: only the two roots of such a near-double root, for a caller whose merged root verified
    nothing (a pose near, not at, a singular family: the merged w lies on k1, the true ones do not). `amp`: how
    much the stages before amplified the input's rounding (_root_amplification): the bands grow with it (a
    shoulder angle 0.008 rad from its tangent left 1.2e-13 in g at an exact wrist singularity). `family_tol`: the
    family band on g and on p1's distance from k1, relative: FAMILY_TOL for a rotation's unit vectors, ON_AXIS_TOL
    for points the pose places (a position pair)."""
    c = _dot(k1, k2)
    a1, a2 = _dot(k1, p1), _dot(k2, p2)
    den = 1.0 - c * c
    if den <= 0.0:  # parallel axes (the planner never pairs them)
        return []
    alpha, beta = (a1 - c * a2) / den, (a2 - c * a1) / den
    kk = _cross(k1, k2)
    base = _add(_scale(k1, alpha), _scale(k2, beta))
    g2, res2 = _sp2_height2(p1, k1, p2, k2, c, a1, a2, den, scale)
    scale2 = _dot(p1, p1) + _dot(p2, p2)
    if g2 < -TANGENT_TOL * scale2:
        return []
    # one double root where g^2 is within DOUBLE_ROOT_TOL of what rounding leaves in it: near a singular family g^2
    # is resolved far below scale2 (two regular sets, q5 = +-s), down to FAMILY_TOL
    family = family_tol * amp
    near = g2 <= DOUBLE_ROOT_TOL * amp * res2 or g2 <= family * family * scale2
    if split and not (near and g2 > 0.0):
        return []
    if near and not split:
        ws, flag = [base], FLAG_DOUBLE_ROOT | FLAG_SINGULAR_INVERSE
    else:
        g = math.sqrt(g2)
        ws, flag = [_add(base, _scale(kk, g)), _add(base, _scale(kk, -g))], FLAG_SINGULAR_INVERSE if split else 0
    out = []
    axis_scale = scale * (family / DEGENERATE_EPS)
    for w in ws:
        # p1 on the axis k1 (the family) at FAMILY_TOL, as g above: sp1's own DEGENERATE_EPS band would call a
        # wrist with |sin| between them a family (the generating set was lost at |sin q5| = 1e-12)
        t1, t2 = _sp1(k1, p1, w, axis_scale), _sp1(k2, p2, w, axis_scale)
        if t2 is None or (split and t1 is None):
            continue
        out.append((t1, t2, flag if t1 is not None else flag | FLAG_INDETERMINATE | FLAG_SINGULAR_INVERSE))
        if t1 is None:
            break  # p1 on the axis k1: both w coincide (one family)
    return out


def _perpendicular(k):
    """A unit vector normal to k."""
    e = (1.0, 0.0, 0.0) if abs(k[0]) <= min(abs(k[1]), abs(k[2])) else (
        (0.0, 1.0, 0.0) if abs(k[1]) <= abs(k[2]) else (0.0, 0.0, 1.0))
    v = _cross(k, e)
    return _scale(v, 1.0 / _norm(v))


def _orient_rest(u, rd, t1, t2):
    """The unit angles of R(u0, a0) R(u1, a1) [R(u2, a2)] = rd given a0 = -t1 (and a1 = t2 for three units)."""
    r1 = _rot(u[0], -t1)
    if len(u) == 3:
        r12 = _mm(r1, _rot(u[1], t2))
        w = _perpendicular(u[2])
        t3 = _sp1(u[2], w, _mtv(r12, _mv(rd, w)), 1.0)
        return [-t1, t2, 0.0 if t3 is None else t3]
    w = _perpendicular(u[1])
    t2b = _sp1(u[1], w, _mtv(r1, _mv(rd, w)), 1.0)
    return [-t1, 0.0 if t2b is None else t2b]


