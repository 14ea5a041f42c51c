"""Three revolute axes in general position placing a point: every real solution (runtime/c/wk_spatial3.c's twin,
step for step; read its comment for the method).

The position problem rot_a rot_b rot_c x = y of three lines (unit direction h_i through point r_i): joint a keeps
the distance of the point to r_a and its component along h_a, two equations bilinear in (1, cos q_b, sin q_b) x
(1, cos q_c, sin q_c); cos^2 + sin^2 = 1 of the (cos q_c, sin q_c) they give is a degree-8 polynomial in
tan(q_b / 2) (the extraneous (1 + t^2)^2 of the substitution in it: at most four real roots, Pieper's bound). q_a
then by subproblem 1, and Newton steps on the point bring a simple root to rounding. A double root of the polynomial
(a pair it merged below its sqrt(eps)) is split into that pair: along the surface's line through the target's small
circle about axis a (_s3_split), else along the point Jacobian's null vector (_s3_pair), then damped Newton steps.

A wristkin runtime source: a serial arm's module with a spatial3 stage (serial_spatial3.py) inlines it from the marker
line on (derive/runtime_files.py), after poly_real_roots.py and chain_poly.py; above the marker, what it reads from the
runtime, so that it is linted and tested as it is (tests/test_spatial3_runtime.py)."""

from __future__ import annotations

import math

from _runtime import FLAG_DOUBLE_ROOT, FLAG_INDETERMINATE, FLAG_SINGULAR_INVERSE
from chain_poly import _poly_add, _poly_mul
from geom3 import _g3_axpy, _g3_cross, _g3_dot, _g3_sp1, _g3_turn, _g3_turn_dir
from poly_real_roots import _POLY_EPS, _POLY_FLAG_DOUBLE, _POLY_TOL_TOUCH, _poly_real_roots

# wristkin: inlined from here
S3_REFINE_STEPS = 8  # Newton steps at most (a simple root: 1-2 to rounding, then a step stops lowering it; near a
# pair the polynomial's root starts further off and converges slower: 2 steps left 10 of 200 near-axis poses off)
S3_CIRCLE_TOL = 1e-6  # |(cos, sin)| of q_c off 1 by more: the root at infinity, or a poorly resolved one
S3_MAX = 12  # candidates: eight roots, q_b = pi, and the pairs split from merged ones (wk_spatial3.c's WK_S3_MAX)
S3_SPLIT_STEPS = 8  # Newton steps from each of a merged pair's two starts (linear convergence near the pair)
S3_SPLIT_TOL = 1e-10  # a split root's point residual (relative to the lengths' size) at most this: it stands
S3_SPLIT_APART = 0.25  # the two split roots at least this part of their starts' gap apart: a pair, not one root twice
S3_SPLIT_HALVINGS = 10  # a split's Newton step halved up to this many times until the residual shrinks
S3_SPLIT_STEP_MAX = 0.5  # rad: a split's Newton step at most this in any joint before it is halved
S3_SPLIT_NEAR = 1e-3  # rad: a split root keeps the merged root's q_b, q_c to this (a merged pair is closer)
S3_CURVATURE_STEP = 1e-3  # rad: the central difference of the point's second derivative (its error ~ step^2)
S3_ROUNDING = 32.0  # the polynomial's rounding: at most this many eps of its terms' sizes, coefficientwise (about
# 30 roundings on the longest path from the lines to a coefficient; measured against mpmath on the same doubles: at most
# 8.8 eps on 1,900 random instances, tests/test_spatial3_runtime.py)


def _s3_mul_abs(a, b, out):
    """out += |a| |b| coefficientwise: the size of the terms of a b, which bounds its rounding. Returns out."""
    for i, x in enumerate(a):
        for j, y in enumerate(b):
            out[i + j] += abs(x) * abs(y)
    return out


def _s3_touch_tol(poly, terms):
    """The root finder's touch tolerance for `poly` whose coefficients sum terms of sizes `terms`: its rounding
    relative to its largest coefficient (S3_ROUNDING eps of the terms), at least the finder's own. A pair that the
    target near axis a merges leaves a minimum of |poly| at this rounding, which must count as a touching root: the
    finder's default assumes coefficients exact to 1e-12, and cancellation in nc^2 + ns^2 - det^2 left 7e-12."""
    big = max(abs(c) for c in poly)
    if not big > 0.0:
        return _POLY_TOL_TOUCH
    return max(_POLY_TOL_TOUCH, S3_ROUNDING * _POLY_EPS * max(terms) / big)


def _s3_bilinear(h2, u, vs):
    """Rows of u . R(h2, q2) v_j over (1, cos q2, sin q2), for each v_j: (h.u)(h.v), u.v - (h.u)(h.v), u.(h x v)."""
    hu = _g3_dot(h2, u)
    return [[hu * _g3_dot(h2, v) for v in vs], [_g3_dot(u, v) - hu * _g3_dot(h2, v) for v in vs],
            [_g3_dot(u, _g3_cross(h2, v)) for v in vs]]


def _s3_point(h0, r0, q, x, y):
    """(the point rot_a rot_b rot_c x at q, the lines of a, b, c moved by the joints before them, |p - y|)."""
    p, h, r = tuple(x), [tuple(v) for v in h0], [tuple(v) for v in r0]
    for i in (2, 1, 0):  # the last joint first: each turn moves the point and the lines after it
        p = _g3_turn(h0[i], r0[i], q[i], p)
        for k in range(i + 1, 3):
            r[k] = _g3_turn(h0[i], r0[i], q[i], r[k])
            h[k] = _g3_turn_dir(h0[i], q[i], h[k])
    d = _g3_axpy(p, -1.0, y)
    return p, h, r, math.sqrt(_g3_dot(d, d))


def _s3_refine(h0, r0, x, y, eps3, q, steps=S3_REFINE_STEPS, halvings=0):
    """Newton steps on rot_a rot_b rot_c x = y (Cramer's rule on the columns h_i x (p - r_i)): a step is kept only
    while the residual shrinks, halved up to `halvings` times until it does (a split's starts, where J is
    near-singular and the full step overshoots). Returns (q, residual)."""
    q = list(q)
    p, h, r, err = _s3_point(h0, r0, q, x, y)
    for _ in range(steps):
        c = [_g3_cross(h[i], _g3_axpy(p, -1.0, r[i])) for i in range(3)]
        b = _g3_axpy(y, -1.0, p)
        x12 = _g3_cross(c[1], c[2])
        det = _g3_dot(c[0], x12)
        if not abs(det) > eps3:
            break
        dq = (_g3_dot(b, x12) / det, _g3_dot(c[0], _g3_cross(b, c[2])) / det, _g3_dot(c[0], _g3_cross(c[1], b)) / det)
        if halvings:  # damped: at most S3_SPLIT_STEP_MAX in any joint (a near-singular J's full step is huge)
            big = max(abs(d) for d in dq)
            if big > S3_SPLIT_STEP_MAX:
                dq = tuple(d * (S3_SPLIT_STEP_MAX / big) for d in dq)
        for _halving in range(halvings + 1):
            trial = [v + d for v, d in zip(q, dq, strict=True)]
            p2, h2, r2, err2 = _s3_point(h0, r0, trial, x, y)
            if err2 < err:
                break
            dq = tuple(0.5 * d for d in dq)
        if not err2 < err:
            break
        q, p, h, r, err = trial, p2, h2, r2, err2
    return q, err


def _s3_gap(a, b):
    """The largest joint difference of two sets (wrapped)."""
    return max(abs(math.remainder(u - v, 2.0 * math.pi)) for u, v in zip(a, b, strict=True))


def _s3_pair_converges(h, r, x, y, scale, starts, qb, qc):
    """Damped Newton on the point from each of a split's two starts (any step that lowers the residual: J is
    near-singular near a pair): the pair when both reach S3_SPLIT_TOL x scale, keep the merged root's q_b and q_c to
    S3_SPLIT_NEAR (the pair it merged, not roots elsewhere) and stay S3_SPLIT_APART of their starts' gap apart (not
    one root twice); else []."""
    pair = []
    for start in starts:
        q, err = _s3_refine(h, r, x, y, 0.0, start, S3_SPLIT_STEPS, S3_SPLIT_HALVINGS)
        if not err <= S3_SPLIT_TOL * scale or not max(abs(math.remainder(q[1] - qb, 2.0 * math.pi)),
                                                       abs(math.remainder(q[2] - qc, 2.0 * math.pi))) <= S3_SPLIT_NEAR:
            return []
        pair.append(q)
    return pair if _s3_gap(*pair) > S3_SPLIT_APART * _s3_gap(*starts) else []


def _s3_split(h, r, x, y, yr, rho, scale, qb, qc):
    """The pair a merged double root of the polynomial stands for, where the target is near axis a (distance rho):
    the point's image w = rot_b rot_c x must lie on the circle of radius rho about axis a, which the surface w(q_b,
    q_c) crosses twice. Near the merged root the surface meets the circle's plane along the line through w in the
    direction d = n x h_a (n its normal there): its two points on the circle (the line's centre-nearest point +-rho
    along d where rounding hides the gap) give q_a by subproblem 1 and (q_b, q_c) moved along the surface to them,
    then Newton on the point from each. The two roots separate at eps / rho, not the polynomial's sqrt(eps). [] where
    they do not both converge to distinct roots (the merged root stands)."""
    w = _g3_turn(h[1], r[1], qb, _g3_turn(h[2], r[2], qc, x))
    hc, rc = _g3_turn_dir(h[1], qb, h[2]), _g3_turn(h[1], r[1], qb, r[2])
    jb, jc = _g3_cross(h[1], _g3_axpy(w, -1.0, r[1])), _g3_cross(hc, _g3_axpy(w, -1.0, rc))
    normal = _g3_cross(jb, jc)
    d = _g3_cross(normal, h[0])
    size = math.sqrt(_g3_dot(d, d))
    if not size > 0.0:
        return []
    d = tuple(v / size for v in d)
    v0 = _g3_axpy(w, -1.0, r[0])
    v0 = _g3_axpy(v0, -_g3_dot(h[0], v0), h[0])  # w's offset from axis a, normal to it
    mid = -_g3_dot(v0, d)
    disc = mid * mid - _g3_dot(v0, v0) + rho * rho
    half = math.sqrt(disc) if disc > 0.0 else rho
    # (q_b, q_c) per unit of d on the surface: jb db + jc dc = d (|jb x jc|^2 = the 2 x 2 system's determinant)
    gbb, gbc, gcc, det = _g3_dot(jb, jb), _g3_dot(jb, jc), _g3_dot(jc, jc), _g3_dot(normal, normal)
    db = (gcc * _g3_dot(jb, d) - gbc * _g3_dot(jc, d)) / det
    dc = (gbb * _g3_dot(jc, d) - gbc * _g3_dot(jb, d)) / det
    starts = []
    for t in (mid + half, mid - half):
        qa = _g3_sp1(h[0], _g3_axpy(v0, t, d), yr, 0.0)
        if qa is None:
            return []
        # the start on the surface, off axis a as the root is: from w itself (on the axis when the pair is symmetric
        # about it) J's column of q_a vanishes and Newton's step is noise
        starts.append([qa, qb + t * db, qc + t * dc])
    return _s3_pair_converges(h, r, x, y, scale, starts, qb, qc)


def _s3_pair(h, r, x, y, scale, q0):
    """The pair a merged double root q0 of the point equations stands for (the surface w(q_b, q_c) near-tangent to
    the target's circle about axis a): at q0 the Jacobian J is singular, right and left null vectors v, u (the
    largest cross products of its rows, of its columns); along v the residual's part on u is quadratic, u.(y - p) =
    s^2 u.H / 2 with H the point's second derivative along v (central differences), so the pair starts at q0 +- s v and
    Newton takes each to its root. [] where s^2 <= 0 (a complex pair) or they do not both converge to distinct roots."""
    p0, hh, rr, _err = _s3_point(h, r, q0, x, y)
    cols = [_g3_cross(hh[i], _g3_axpy(p0, -1.0, rr[i])) for i in range(3)]
    rows = [tuple(cols[j][i] for j in range(3)) for i in range(3)]

    def largest(vs):
        best = max((_g3_cross(vs[i], vs[j]) for i, j in ((0, 1), (0, 2), (1, 2))), key=lambda c: _g3_dot(c, c))
        size = math.sqrt(_g3_dot(best, best))
        return tuple(c / size for c in best) if size > 0.0 else None
    v, u = largest(rows), largest(cols)
    if v is None or u is None:
        return []
    step = S3_CURVATURE_STEP
    plus = _s3_point(h, r, [a + step * b for a, b in zip(q0, v, strict=True)], x, y)[0]
    minus = _s3_point(h, r, [a - step * b for a, b in zip(q0, v, strict=True)], x, y)[0]
    curv = _g3_dot(u, tuple((plus[m] - 2.0 * p0[m] + minus[m]) / (step * step) for m in range(3)))
    if not abs(curv) > 0.0:
        return []
    s2 = 2.0 * _g3_dot(u, _g3_axpy(y, -1.0, p0)) / curv
    if not s2 > 0.0:
        return []
    half = math.sqrt(s2)
    starts = [[a + t * b for a, b in zip(q0, v, strict=True)] for t in (half, -half)]
    return _s3_pair_converges(h, r, x, y, scale, starts, q0[1], q0[2])


def _s3_qc_dependent(pv, qv, d_target, h_target, scale, eps):
    """Axes a and c parallel: the distance and component equations at a root q_b, pv and qv over (1, cos q_c,
    sin q_c), are one equation in q_c (their (cos, sin) parts parallel). The better conditioned of them, A cos + B sin
    = C, gives q_c = atan2(B, A) +- acos(C / |(A, B)|): both roots (one at a tangency) where the other equation holds
    too, None where none does, the point is on axis c (A = B = 0: the joint does not move it) or C / |(A, B)| is past
    1 beyond the circle's tolerance."""
    dist, comp = (pv[1], pv[2], d_target - pv[0]), (qv[1], qv[2], h_target - qv[0])
    (a, b, c), other = (dist, comp) if math.hypot(pv[1], pv[2]) >= scale * math.hypot(qv[1], qv[2]) else (comp, dist)
    norm = math.hypot(a, b)
    if not norm > eps * scale * scale:
        return None
    u = c / norm
    if not abs(u) <= 1.0 + S3_CIRCLE_TOL:
        return None
    phi, gap = math.atan2(b, a), math.acos(max(-1.0, min(1.0, u)))
    # the other equation holds too where q_b is the eliminant's root (not at the q_b = pi tried beside them)
    size = abs(other[0]) + abs(other[1]) + abs(other[2])
    return [t for t in ([phi + gap, phi - gap] if gap > 0.0 else [phi])
            if abs(other[0] * math.cos(t) + other[1] * math.sin(t) - other[2]) <= S3_CIRCLE_TOL * size] or None


def _spatial3_lines(h, r, x, y, scale, eps, on_axis):
    """The candidates [(q_a, q_b, q_c), flags] of rot_a rot_b rot_c x = y, h[i] / r[i] the lines of a, b, c at the
    joints' zero (flags: a double root of the polynomial, FLAG_DOUBLE_ROOT; the point on axis a, FLAG_INDETERMINATE
    with q_a = 0). `scale` the lengths' size, `eps` the relative size below which a coefficient is degenerate,
    `on_axis` the relative distance from axis a within which the point is on it (the caller's rounding band: farther
    off, q_a is read from the point's offset, accurate to ~eps scale / rho, as the pose determines it). The caller
    verifies them."""
    h1, r1, h2, r2, h3, r3 = h[0], r[0], h[1], r[1], h[2], r[2]
    eps3 = eps * scale ** 3
    v = _g3_axpy(x, -1.0, r3)
    hv = _g3_dot(h3, v)
    vb0 = _g3_axpy(_g3_axpy(r3, hv, h3), -1.0, r2)  # z - r2 over (1, cos q_c, sin q_c)
    vb = [vb0, _g3_axpy(v, -hv, h3), _g3_cross(h3, v)]
    u = _g3_axpy(r2, -1.0, r1)
    f = [[2.0 * e for e in row] for row in _s3_bilinear(h2, u, vb)]
    g = _s3_bilinear(h2, h1, vb)
    f[0][0] += _g3_dot(vb[0], vb[0]) + _g3_dot(vb[1], vb[1]) + _g3_dot(u, u)
    f[0][1] += 2.0 * _g3_dot(vb[0], vb[1])
    f[0][2] += 2.0 * _g3_dot(vb[0], vb[2])
    g[0][0] += _g3_dot(h1, u)
    yr = _g3_axpy(y, -1.0, r1)
    d_target, h_target = _g3_dot(yr, yr), _g3_dot(h1, yr)
    # (1, cos q_b, sin q_b) times (1 + t^2): (1 + t^2, 1 - t^2, 2 t), polynomials in t = tan(q_b / 2)
    apoly = ((1.0, 0.0, 1.0), (1.0, 0.0, -1.0), (0.0, 2.0, 0.0))
    p = [[apoly[0][i] * f[0][j] + apoly[1][i] * f[1][j] + apoly[2][i] * f[2][j] for i in range(3)] for j in range(3)]
    pq = [[apoly[0][i] * g[0][j] + apoly[1][i] * g[1][j] + apoly[2][i] * g[2][j] for i in range(3)] for j in range(3)]
    dt = [apoly[0][i] * d_target - p[0][i] for i in range(3)]
    ht = [apoly[0][i] * h_target - pq[0][i] for i in range(3)]
    det = _poly_add(_poly_mul(p[1], pq[2]), _poly_mul(p[2], pq[1]), -1.0)
    nc = _poly_add(_poly_mul(dt, pq[2]), _poly_mul(p[2], ht), -1.0)
    ns = _poly_add(_poly_mul(p[1], ht), _poly_mul(pq[1], dt), -1.0)
    # axes a and c parallel: the two equations' (cos q_c, sin q_c) parts (P, Q at q_b) are parallel at every q_b (det
    # vanishes identically) and the degree-8 polynomial is nc^2 + ns^2, whose roots are all double (resolved to
    # sqrt(eps) only, and q_c not read from the singular system). The equations agree where the distance's right side
    # is the component's times |P| / |Q|: (d - P_0) |Q|^2 = (h - Q_0) P.Q, which is Q_2 nc - Q_1 ns (degree 6, simple
    # roots; nc alone has Q_2's roots too). q_c then comes from one of the two equations (two roots, those the other
    # equation holds at kept)
    dependent = max(abs(e) for e in det) <= eps3
    # the sizes of nc's, ns's and det's terms (dt's and ht's before their cancellation): their rounding's scale
    sdt = [abs(apoly[0][i]) * d_target + abs(p[0][i]) for i in range(3)]
    sht = [abs(apoly[0][i] * h_target) + abs(pq[0][i]) for i in range(3)]
    snc = _s3_mul_abs(p[2], sht, _s3_mul_abs(sdt, pq[2], [0.0] * 5))
    sns = _s3_mul_abs(pq[1], sdt, _s3_mul_abs(p[1], sht, [0.0] * 5))
    if dependent:
        poly = _poly_add(_poly_mul(pq[2], nc), _poly_mul(pq[1], ns), -1.0)
        terms = _s3_mul_abs(pq[1], sns, _s3_mul_abs(pq[2], snc, [0.0] * 7))
    else:
        poly = _poly_add(_poly_add(_poly_mul(nc, nc), _poly_mul(ns, ns), 1.0), _poly_mul(det, det), -1.0)
        sdet = _s3_mul_abs(p[2], pq[1], _s3_mul_abs(p[1], pq[2], [0.0] * 5))
        terms = _s3_mul_abs(det, sdet, _s3_mul_abs(ns, sns, _s3_mul_abs(nc, snc, [0.0] * 9)))
    roots, rflags, _status = _poly_real_roots(poly, _s3_touch_tol(poly, terms))
    angles = [(2.0 * math.atan(t), FLAG_DOUBLE_ROOT | FLAG_SINGULAR_INVERSE if fl & _POLY_FLAG_DOUBLE else 0)
              for t, fl in zip(roots, rflags, strict=True)]
    angles.append((math.pi, 0))  # tan(q_b / 2) = infinity is no root of the polynomial: tried directly
    yr_perp = _g3_axpy(yr, -h_target, h1)
    rho = math.sqrt(_g3_dot(yr_perp, yr_perp))  # the target's distance from axis a (|yr|^2 - (h.yr)^2 cancels)

    def q_c(qb):
        """q_c of the root q_b (the two equations linear in its cos and sin), None where they do not fix it."""
        cb, sb = math.cos(qb), math.sin(qb)
        pv = [f[0][j] + cb * f[1][j] + sb * f[2][j] for j in range(3)]
        qv = [g[0][j] + cb * g[1][j] + sb * g[2][j] for j in range(3)]
        if dependent:
            return _s3_qc_dependent(pv, qv, d_target, h_target, scale, eps)
        dd = pv[1] * qv[2] - pv[2] * qv[1]
        if abs(dd) <= eps3:
            return None
        cc = ((d_target - pv[0]) * qv[2] - pv[2] * (h_target - qv[0])) / dd
        ss = (pv[1] * (h_target - qv[0]) - qv[1] * (d_target - pv[0])) / dd
        return math.atan2(ss, cc) if abs(math.hypot(cc, ss) - 1.0) <= S3_CIRCLE_TOL else None
    near_axis = on_axis * scale < rho <= S3_SPLIT_NEAR * scale
    out = []
    i = 0
    while i < len(angles) and len(out) < S3_MAX:
        qb, fl = angles[i]
        i += 1
        if (near_axis and not dependent and not fl & FLAG_DOUBLE_ROOT and i < len(angles) - 1
                and not angles[i][1] & FLAG_DOUBLE_ROOT and len(out) + 2 <= S3_MAX):
            # two simple roots a hair apart near axis a: a pair the polynomial resolved only to its sqrt(eps), whose
            # images sit near the axis, where q_a is noise: split from their midpoint
            gap = math.remainder(angles[i][0] - qb, 2.0 * math.pi)
            mid = qb + 0.5 * gap
            qc = q_c(mid) if abs(gap) <= S3_SPLIT_NEAR else None
            pair = _s3_split(h, r, x, y, yr, rho, scale, mid, qc) if qc is not None else []
            if pair:
                out += [(tuple(q), FLAG_SINGULAR_INVERSE) for q in pair]
                i += 1
                continue
        qc = q_c(qb)
        if qc is None:
            continue
        if dependent:  # a and c parallel: no merged pairs to split (the eliminant's roots are simple)
            for qcv in qc:
                w = _g3_axpy(_g3_turn(h2, r2, qb, _g3_turn(h3, r3, qcv, x)), -1.0, r1)
                qa = _g3_sp1(h1, w, yr, on_axis * scale)
                if qa is None:
                    out.append(((0.0, qb, qcv), fl | FLAG_INDETERMINATE | FLAG_SINGULAR_INVERSE))
                    continue
                q, _err = _s3_refine(h, r, x, y, eps3, [qa, qb, qcv])
                out.append((tuple(q), fl))
            continue
        if fl & FLAG_DOUBLE_ROOT and rho > on_axis * scale and len(out) + 2 <= S3_MAX:
            # a merged pair: near axis a its two roots differ by ~rho, below the polynomial's resolution
            pair = _s3_split(h, r, x, y, yr, rho, scale, qb, qc)
            if pair:
                out += [(tuple(q), FLAG_SINGULAR_INVERSE) for q in pair]
                continue
        w = _g3_axpy(_g3_turn(h2, r2, qb, _g3_turn(h3, r3, qc, x)), -1.0, r1)
        qa = _g3_sp1(h1, w, yr, on_axis * scale)
        if qa is None:
            out.append(((0.0, qb, qc), fl | FLAG_INDETERMINATE | FLAG_SINGULAR_INVERSE))
            continue
        q = [qa, qb, qc]
        if fl & FLAG_DOUBLE_ROOT and len(out) + 2 <= S3_MAX:
            # a merged pair elsewhere: the surface near-tangent to the target's circle, split along J's null vector
            pair = _s3_pair(h, r, x, y, scale, q)
            if pair:
                out += [(tuple(v), FLAG_SINGULAR_INVERSE) for v in pair]
                continue
        if not fl & FLAG_DOUBLE_ROOT:
            q, _err = _s3_refine(h, r, x, y, eps3, q)
        out.append((tuple(q), fl))
    return out
