"""Subproblem 6, two joints from two invariants: every real solution (runtime/c/wk_sp6.c's twin, step for step;
read its comment for the method).

(q0, q4) with n.rot(h0, -q0) p0 - n.rot(h4, q4) p4 = d0 and n.rot(h0, -q0) g - n.rot(h4, q4) h5 = e0 (a UR-type arm
with an offset wrist: the parallel group keeps the component along n of a point and of the last axis). (cos q4,
sin q4) is affine in (cos q0, sin q0) by Cramer's rule, and cos^2 + sin^2 = 1 a quartic in tan(q0 / 2). Near the
wrist singularity a merged pair is split and refined on the second equation's parts normal to n, and the singular
configurations are tried directly.

A wristkin runtime source: a serial arm's module with an sp6 stage (serial_sp6.py) inlines it from the marker line on
(derive/runtime_files.py), after poly_real_roots.py, chain_poly.py and geom3.py; above the marker, what it reads from
them, so that it is linted and tested as it is (tests/test_shared_runtime.py)."""

from __future__ import annotations

import math

from _runtime import FLAG_DOUBLE_ROOT, FLAG_SINGULAR_INVERSE, _wrap
from chain_poly import _poly_add, _poly_mul, _scale3
from geom3 import _g3_axpy, _g3_cross, _g3_dot, _g3_norm, _g3_sp1, _g3_trig, _g3_turn_dir
from poly_real_roots import _POLY_FLAG_DOUBLE, _poly_real_roots

# wristkin: inlined from here
# q0 = pi (tan(q0 / 2) infinite) is a candidate when cos^2 + sin^2 of the q4 it gives is 1 within this: rounding of
# the 2x2 solve (a root of the quartic near pi would pass a looser test and be found twice)
SP6_AT_PI_TOL = 1e-9
# |n . rot(h4, q4) h5| at or above this: the wrist near its singularity (|n . z5| = 1 there), where a root of the
# quartic is refined on the second equation's parts normal to n (_sp6_newton_perp); below it their difference
# |n x w0|^2 - |n x z5|^2 = (n.z5 - n.w0)(n.z5 + n.w0) loses the factor n.z5 + n.w0 ~ 2 n.z5
SP6_NEAR_WRIST = 0.5
# a regular root within this of a split root near the wrist singularity is that root found twice (both are refined
# to ~eps; two distinct roots there are ~delta apart and both the split's)
SP6_SAME_ROOT = 1e-9
# Newton steps on the equations from a root (quadratic convergence from a root of the quartic or of the local
# model: 3 suffice)
SP6_NEWTON_STEPS = 3


def _sp6_core(nv, h0, p0, h4, p4, d0, e0, g, h5, tols):
    """The candidates [(q0, q4, flags, order)] of subproblem 6, the regular ones first. `tols`: the caller's
    (scale, degenerate, double_root, tangent, on_axis, family) (wk_sp6.c's wk_sp6_tols says what each is). `order`:
    how q4's
    error grows near the wrist singularity: 2 from the quartic and Newton on its equations (eps / g), 1 from the
    split or the normal parts' Newton (~eps). A merged double root far from the wrist stays, flagged."""
    scale, degenerate, double_root, _tangent, _on_axis, family = tols

    def coef(k, p, sign):
        kp = _g3_dot(k, p)
        perp = _g3_axpy(p, -kp, k)
        return _g3_dot(nv, perp), sign * _g3_dot(nv, _g3_cross(k, p)), kp * _g3_dot(nv, k)
    a1, b1, k1 = coef(h0, p0, -1.0)
    c1, d1, m1 = coef(h4, p4, 1.0)
    a2, b2, k2 = coef(h0, g, -1.0)
    c2, d2, m2 = coef(h4, h5, 1.0)
    # a c0 + b s0 - (c c4 + d s4) = rhs
    e1, e2 = d0 - k1 + m1, e0 - k2 + m2
    det = c1 * d2 - d1 * c2
    if abs(det) <= degenerate * scale:
        return []
    # c4 det = (a1 c0 + b1 s0 - e1) d2 - d1 (a2 c0 + b2 s0 - e2); s4 det = c1 (a2 c0 + b2 s0 - e2) - c2 (...1)
    al = (-e1 * d2 + d1 * e2, a1 * d2 - d1 * a2, b1 * d2 - d1 * b2)
    be = (-c1 * e2 + c2 * e1, c1 * a2 - c2 * a1, c1 * b2 - c2 * b1)
    apoly = ([1.0, 0.0, 1.0], [1.0, 0.0, -1.0], [0.0, 2.0, 0.0])
    pa = _poly_add(_poly_add(_scale3(apoly[0], al[0]), _scale3(apoly[1], al[1])), _scale3(apoly[2], al[2]))
    pb = _poly_add(_poly_add(_scale3(apoly[0], be[0]), _scale3(apoly[1], be[1])), _scale3(apoly[2], be[2]))
    pd = _scale3(apoly[0], det)
    poly = _poly_add(_poly_add(_poly_mul(pa, pa), _poly_mul(pb, pb)), _poly_mul(pd, pd), -1.0)
    roots, rflags, _status = _poly_real_roots(poly)
    # tan(q0 / 2) = infinity is no root of the polynomial: q0 = pi is tried directly, kept only when it solves the
    # system to rounding (else a root near pi, which the polynomial has, would be taken twice)
    cands = [(2.0 * math.atan(r), FLAG_DOUBLE_ROOT | FLAG_SINGULAR_INVERSE if fl & _POLY_FLAG_DOUBLE else 0, 1e-6)
             for r, fl in zip(roots, rflags, strict=True)][:4] + [(math.pi, 0, SP6_AT_PI_TOL)]
    # The wrist singularity: where rot(h4, q4) h5 = +-n the second equation holds for every q0 (its quartic has a
    # double root there, which rounding may hide), so those q4 are tried directly with q0 from the first
    # equation alone. Where the second then holds to rounding (the pose's axis within on_axis of +-n, read from the
    # cross product) the configuration is the singular family; where it holds within the double-root tolerance
    # (within ~1e-6 rad) the pose is near it, and the two roots there come from the split (each to ~eps; the quartic
    # resolves them to sqrt(eps), and a family member searched over a grid stood in for them, 2.7 rad off, at 180x
    # the median call). A regular root within 1e-6 of either is the same configuration and is dropped.
    singular, split, anchors = [], [], []
    t4 = _g3_sp1(h4, h5, nv, degenerate)
    if t4 is not None:
        for q4 in (t4, t4 + math.pi):
            side = _g3_dot(nv, _g3_turn_dir(h4, q4, h5))
            if abs(abs(side) - 1.0) > 1e-12:
                continue
            for t0, fl in _sp6_sp4(nv, h0, p0, d0 + _g3_dot(nv, _g3_turn_dir(h4, q4, p4)), tols):
                q0 = -t0
                # the second equation at this q0: n . rot(h0, -q0) g must be n . R4 h5 = side (+-1)
                w = _g3_turn_dir(h0, t0, g)
                dn = _g3_dot(nv, w)
                if dn * side > 0.0 and 1.0 - dn * dn <= double_root:
                    anchors.append((q0, q4))
                    if _g3_norm(_g3_cross(nv, w)) <= family:  # closed-form inputs: rounding, not a band's noise
                        singular.append((q0, _wrap(q4), fl | FLAG_SINGULAR_INVERSE, 2))
                    else:
                        pair = _sp6_split(nv, h0, p0, h4, p4, d0, g, h5, q0, q4, tols)
                        split += [(a, b, fl | _merged(pair) | FLAG_SINGULAR_INVERSE, 1) for a, b in pair]
    kept = []
    for q0, fl, tol in cands:
        c0, s0 = math.cos(q0), math.sin(q0)
        cc = (al[0] + al[1] * c0 + al[2] * s0) / det
        ss = (be[0] + be[1] * c0 + be[2] * s0) / det
        if abs(math.hypot(cc, ss) - 1.0) > tol:  # the root at infinity, or a poorly resolved one
            continue
        q4 = math.atan2(ss, cc)
        near = abs(_g3_dot(nv, _g3_turn_dir(h4, q4, h5))) >= SP6_NEAR_WRIST
        if fl and near:  # a merged double root near the wrist singularity: its two roots, each to ~eps (a merged
            # root 3e-7 rad off the singularity verified within IK_VERIFY_TOL with q5 0.05 rad off)
            pair = _sp6_split(nv, h0, p0, h4, p4, d0, g, h5, q0, q4, tols)
            if pair:
                kept += [(a, b, (fl & ~FLAG_DOUBLE_ROOT) | _merged(pair) | FLAG_SINGULAR_INVERSE, 1)
                         for a, b in pair if not _taken((a, b), anchors, split)]
                continue
        order = 2
        if not fl:  # a merged double root far from the wrist stays (Newton is ill-conditioned there)
            if near:  # on the second's normal parts: q4 to ~eps
                q0, q4 = _sp6_newton_perp(nv, h0, p0, h4, p4, d0, g, h5, q0, q4)
                order = 1
            else:
                q0, q4 = _sp6_newton(nv, h0, p0, h4, p4, d0, e0, g, h5, q0, q4)
        if not _taken((q0, q4), anchors, split):
            kept.append((q0, q4, fl, order))
    return kept + split + singular


def _taken(root, anchors, split):
    """Whether a regular root is a configuration the wrist singularity's candidates already give: within 1e-6 of a
    candidate (at or near it), or within SP6_SAME_ROOT of one of its split roots (one 1.03e-6 from its candidate
    was returned twice, and the generating set fell past the solver's set count)."""
    return _within(root, anchors, 1e-6) or _within(root, split, SP6_SAME_ROOT)


def _within(root, others, tol):
    """Whether (q0, q4) of root is within tol of one of others' in both angles."""
    return any(abs(_wrap(root[0] - o[0])) <= tol and abs(_wrap(root[1] - o[1])) <= tol for o in others)


def _sp6_sp4(nv, h0, p0, d, tols):
    """t with n . rot(h0, t) p0 = d (subproblem 4): [(t, flags)] (_g3_trig)."""
    scale, _degenerate, double_root, tangent, on_axis, _family = tols
    kp = _g3_dot(h0, p0)
    return _g3_trig(_g3_dot(nv, _g3_axpy(p0, -kp, h0)), _g3_dot(nv, _g3_cross(h0, p0)), d - kp * _g3_dot(nv, h0), scale,
                    on_axis, tangent, double_root)


def _sp6_eval(nv, h0, p0, h4, p4, g, h5, q0, q4):
    """(F1, F2) without the constants, and their gradients."""
    w0, wg = _g3_turn_dir(h0, -q0, p0), _g3_turn_dir(h0, -q0, g)
    z4, z5 = _g3_turn_dir(h4, q4, p4), _g3_turn_dir(h4, q4, h5)
    f = (_g3_dot(nv, w0) - _g3_dot(nv, z4), _g3_dot(nv, wg) - _g3_dot(nv, z5))
    jac = ((-_g3_dot(nv, _g3_cross(h0, w0)), -_g3_dot(nv, _g3_cross(h4, z4))),
           (-_g3_dot(nv, _g3_cross(h0, wg)), -_g3_dot(nv, _g3_cross(h4, z5))))
    return f, jac


def _sp6_normal_parts(nv, h0, h4, g, h5, q0, q4):
    """The second equation's parts normal to n at (q0, q4): u = n x w0, r = n x z5 (w0 = rot(h0, -q0) g,
    z5 = rot(h4, q4) h5) and their derivatives -n x (h0 x w0) along q0, n x (h4 x z5) along q4 (without the sign)."""
    w0, z5 = _g3_turn_dir(h0, -q0, g), _g3_turn_dir(h4, q4, h5)
    return (_g3_cross(nv, w0), _g3_cross(nv, z5), _g3_cross(nv, _g3_cross(h0, w0)), _g3_cross(nv, _g3_cross(h4, z5)))


def _sp6_split(nv, h0, p0, h4, p4, d0, g, h5, q0, q4, tols):
    """The two roots near (q0, q4), a merged near-double root (a double root of the quartic, or the wrist
    singularity's candidate near, not at, it). Along the first equation's solution curve through it (tangent t, arc
    s) the second, n.w0 = n.z5 for the unit vectors w0 = rot(h0, -q0) g and z5 = rot(h4, q4) h5, is read as
    |n x w0|^2 = |n x z5|^2: near the singularity both n-components are stationary at +-1 and their difference
    (~delta^2) is read only to eps, so its roots to sqrt(eps); the parts normal to n (~delta) are read to eps each.
    To second order in s that is qa s^2 + qb s + qc = 0 with u = n x w0, r = n x z5 and their derivatives along t;
    its two roots, polished by Newton on the same parts (_sp6_newton_perp), are the nearby solutions, ~delta apart
    and each to ~eps. Where the two curves are near tangent the pair merges: one root, a double one (_merged)."""
    (f1, _f2), ((a, b), _) = _sp6_eval(nv, h0, p0, h4, p4, g, h5, q0, q4)
    gn = math.hypot(a, b)
    if gn <= tols[1] * tols[0]:
        return []
    # onto the first equation's curve (one Newton step along its gradient), then along its tangent t
    r = -(f1 - d0) / gn
    q0, q4 = q0 + r * a / gn, q4 + r * b / gn
    t0, t4 = -b / gn, a / gn
    u, rz, du0, dr4 = _sp6_normal_parts(nv, h0, h4, g, h5, q0, q4)
    du = tuple(x * -t0 for x in du0)  # along the tangent: d w0 / d q0 = -h0 x w0, d z5 / d q4 = h4 x z5
    dr = tuple(x * t4 for x in dr4)
    qa = _g3_dot(du, du) - _g3_dot(dr, dr)
    qb = 2.0 * (_g3_dot(u, du) - _g3_dot(rz, dr))
    qc = _g3_dot(u, u) - _g3_dot(rz, rz)
    disc = qb * qb - 4.0 * qa * qc
    if qa == 0.0 or not math.isfinite(disc):
        return []
    if disc > 0.0:
        qq = -0.5 * (qb + math.copysign(math.sqrt(disc), qb))  # the larger root's numerator: no cancellation
        steps = (qq / qa, qc / qq)
    else:  # the curve's tangent touches the second's pair of lines: one double root at the vertex (the model's
        # cubic term, ~|s|^3, moved the discriminant below 0 by 3e-6 of qb^2 at delta = 1e-6)
        steps = (-0.5 * qb / qa,)
    out = []
    for s_ in steps:
        x0, x4 = _sp6_newton_perp(nv, h0, p0, h4, p4, d0, g, h5, q0 + s_ * t0, q4 + s_ * t4)
        out.append((_wrap(x0), _wrap(x4)))
    return out


def _merged(pair):
    """FLAG_DOUBLE_ROOT when the split returned its pair merged (one root), else 0."""
    return FLAG_DOUBLE_ROOT if len(pair) == 1 else 0


def _sp6_newton(nv, h0, p0, h4, p4, d0, e0, g, h5, q0, q4):
    """(q0, q4) after Newton steps on both equations, each kept only when it lowers the residual: the quartic
    resolves two roots ~delta apart only to ~sqrt(eps) in tan(q0 / 2), the equations to eps / delta in the angles,
    and the stages after it need the better one near the wrist singularity."""
    (f1, f2), jac = _sp6_eval(nv, h0, p0, h4, p4, g, h5, q0, q4)
    res = max(abs(f1 - d0), abs(f2 - e0))
    for _ in range(SP6_NEWTON_STEPS):
        (ja, jb), (jc, jd) = jac
        dt = ja * jd - jb * jc
        if res == 0.0 or dt == 0.0:
            break
        r1, r2 = f1 - d0, f2 - e0
        n0, n4 = q0 - (jd * r1 - jb * r2) / dt, q4 - (ja * r2 - jc * r1) / dt
        (f1, f2), jac = _sp6_eval(nv, h0, p0, h4, p4, g, h5, n0, n4)
        new = max(abs(f1 - d0), abs(f2 - e0))
        if not new < res:
            break
        q0, q4, res = n0, n4, new
    return q0, q4


def _sp6_newton_perp(nv, h0, p0, h4, p4, d0, g, h5, q0, q4):
    """(q0, q4) after Newton steps on the first equation and the second read as |n x w0|^2 - |n x z5|^2 (its parts
    normal to n: _sp6_split), each kept only when it lowers the residuals measured over their gradients (metres and
    a squared sine: compared raw, the first's rounding stopped the steps with q4 1e-11 off at delta = 3e-6). Near
    the wrist singularity the second's n-components are stationary, so Newton on them moves q4 by eps / delta
    (3.8e-10 at delta = 3e-7, which turned q5's angle 1e-4 off); the normal parts' residual is eps delta against a
    gradient ~delta: q4 to ~eps."""
    def resid(a0, a4):
        u, rz, du0, dr4 = _sp6_normal_parts(nv, h0, h4, g, h5, a0, a4)
        w, z4 = _g3_turn_dir(h0, -a0, p0), _g3_turn_dir(h4, a4, p4)
        f = (_g3_dot(nv, w) - _g3_dot(nv, z4) - d0, _g3_dot(u, u) - _g3_dot(rz, rz))
        jac = ((-_g3_dot(nv, _g3_cross(h0, w)), -_g3_dot(nv, _g3_cross(h4, z4))),
               (-2.0 * _g3_dot(u, du0), -2.0 * _g3_dot(rz, dr4)))
        return f, jac

    def size(f, jac):  # each residual over its gradient: a distance in radians (the two differ in units)
        return max(abs(f[0]) / max(math.hypot(*jac[0]), 1e-300), abs(f[1]) / max(math.hypot(*jac[1]), 1e-300))
    f, jac = resid(q0, q4)
    res = size(f, jac)
    for _ in range(SP6_NEWTON_STEPS):
        (ja, jb), (jc, jd) = jac
        dt = ja * jd - jb * jc
        if res == 0.0 or dt == 0.0:
            break
        n0, n4 = q0 - (jd * f[0] - jb * f[1]) / dt, q4 - (ja * f[1] - jc * f[0]) / dt
        f, jac = resid(n0, n4)
        new = size(f, jac)
        if not new < res:
            break
        q0, q4, res = n0, n4, new
    return q0, q4
