"""Three revolute axes in general position: every real root of their degree-8 polynomial.

A wristkin runtime source: every user robot's generated module inlines it from the marker line on
(derive/runtime_files.py), after the robot's constants; above the marker, what it reads from them and from the
other sources (chain_stand_in.py: a stand-in robot), so that it is linted and tested as it is
(tests/test_chain_runtime.py)."""

from __future__ import annotations

import math

from chain_poly import _poly_add, _poly_mul, _scale3
from chain_rigid import _ID, _add, _apply, _compose, _cross, _dot, _mv, _norm, _scale, _screw, _sub
from chain_stages import _OP_STAGES
from chain_stand_in import DEGENERATE_EPS, FLAG_DOUBLE_ROOT, FLAG_INDETERMINATE, FLAG_SINGULAR_INVERSE, SCALE
from chain_subproblems import _sp1
from poly_real_roots import _POLY_FLAG_DOUBLE, _poly_real_roots

# wristkin: inlined from here
SPATIAL3_REFINE_STEPS = 2  # Newton steps on a simple root (quadratic: 1e-10 -> 1e-20, i.e. rounding)


def _bilinear(h2, u, vs):
    """Rows of u . R(h2, q2) v_j over a = (1, cos q2, sin q2): u.R v = (h.u)(h.v) + c (u.v - (h.u)(h.v)) +
    s u.(h x v), for each v_j (columns over b = (1, cos q3, sin q3))."""
    hu = _dot(h2, u)
    rows = [[hu * _dot(h2, v) for v in vs], [_dot(u, v) - hu * _dot(h2, v) for v in vs],
            [_dot(u, _cross(h2, v)) for v in vs]]
    return rows


def _spatial3(ch, ja, jb, jc, x, y):
    """(q_a, q_b, q_c, flags) with e_a e_b e_c x = y for three revolute axes in general position (subproblem 5
    in effect): joint a keeps the distance to its axis point r1 and the component along h1, two equations
    bilinear in (1, cos q_b, sin q_b) x (1, cos q_c, sin q_c); for each q_b they are linear in (cos q_c,
    sin q_c), and cos^2 + sin^2 = 1 gives a degree-8 polynomial in tan(q_b / 2) whose real roots are kept."""
    h1, r1, h2, r2, h3, r3 = ch.axes[ja], ch.points[ja], ch.axes[jb], ch.points[jb], ch.axes[jc], ch.points[jc]
    v = _sub(x, r3)
    hv = _dot(h3, v)
    vb = [_sub(_add(r3, _scale(h3, hv)), r2), _sub(v, _scale(h3, hv)), _cross(h3, v)]  # z - r2 over (1, c3, s3)
    u = _sub(r2, r1)
    bu, bh = _bilinear(h2, u, vb), _bilinear(h2, h1, vb)
    f = [[2.0 * e for e in row] for row in bu]
    f[0][0] += _dot(vb[0], vb[0]) + _dot(vb[1], vb[1]) + _dot(u, u)
    f[0][1] += 2.0 * _dot(vb[0], vb[1])
    f[0][2] += 2.0 * _dot(vb[0], vb[2])
    g = [list(row) for row in bh]
    g[0][0] += _dot(h1, u)
    d_target, h_target = _dot(_sub(y, r1), _sub(y, r1)), _dot(h1, _sub(y, r1))
    # a = (1, c2, s2) times (1 + t^2): (1 + t^2, 1 - t^2, 2 t), polynomials in t (ascending)
    apoly = ([1.0, 0.0, 1.0], [1.0, 0.0, -1.0], [0.0, 2.0, 0.0])

    def row(m, j):
        return _poly_add(_poly_add(_scale3(apoly[0], m[0][j]), _scale3(apoly[1], m[1][j])), _scale3(apoly[2], m[2][j]))
    p0, p1, p2 = row(f, 0), row(f, 1), row(f, 2)
    q0, q1, q2 = row(g, 0), row(g, 1), row(g, 2)
    dt = _poly_add(_scale3(apoly[0], d_target), p0, -1.0)
    ht = _poly_add(_scale3(apoly[0], h_target), q0, -1.0)
    det = _poly_add(_poly_mul(p1, q2), _poly_mul(p2, q1), -1.0)
    nc = _poly_add(_poly_mul(dt, q2), _poly_mul(p2, ht), -1.0)
    ns = _poly_add(_poly_mul(p1, ht), _poly_mul(q1, dt), -1.0)
    poly = _poly_add(_poly_add(_poly_mul(nc, nc), _poly_mul(ns, ns)), _poly_mul(det, det), -1.0)
    roots, rflags, _status = _poly_real_roots(poly)
    angles = [(2.0 * math.atan(r), FLAG_DOUBLE_ROOT | FLAG_SINGULAR_INVERSE if fl & _POLY_FLAG_DOUBLE else 0)
              for r, fl in zip(roots, rflags, strict=True)]
    angles.append((math.pi, 0))  # tan(q_b / 2) = infinity is no root of the polynomial: tried directly
    out = []
    for qb, fl in angles:
        cb, sb = math.cos(qb), math.sin(qb)
        pv = [f[0][j] + cb * f[1][j] + sb * f[2][j] for j in range(3)]
        qv = [g[0][j] + cb * g[1][j] + sb * g[2][j] for j in range(3)]
        dd = pv[1] * qv[2] - pv[2] * qv[1]
        if abs(dd) <= DEGENERATE_EPS * SCALE ** 3:
            continue
        cc = ((d_target - pv[0]) * qv[2] - pv[2] * (h_target - qv[0])) / dd
        ss = (pv[1] * (h_target - qv[0]) - qv[1] * (d_target - pv[0])) / dd
        if abs(math.hypot(cc, ss) - 1.0) > 1e-6:  # the root at infinity, or a poorly resolved one: not on the circle
            continue
        qc = math.atan2(ss, cc)
        w = _apply(_compose(_screw("R", h2, r2, qb), _screw("R", h3, r3, qc)), x)
        qa = _sp1(h1, _sub(w, r1), _sub(y, r1), SCALE)
        if qa is None:
            qa, fl = 0.0, fl | FLAG_INDETERMINATE | FLAG_SINGULAR_INVERSE
        elif not fl & FLAG_DOUBLE_ROOT:
            qa, qb, qc = _spatial3_refine(ch, ja, jb, jc, x, y, qa, qb, qc)
        out.append((qa, qb, qc, fl))
    return out


def _spatial3_refine(ch, ja, jb, jc, x, y, qa, qb, qc):
    """Newton steps on e_a e_b e_c x = y (Cramer's rule on the three columns h_i x (p - r_i)): the degree-8
    polynomial's roots carry ~1e-10 of its rounding, which a wrist after them would read as a turn off its singular
    family; two steps bring a simple root to rounding (a step is kept only while the residual shrinks)."""
    q = [qa, qb, qc]
    js = (ja, jb, jc)

    def point(q):
        e = _ID
        frames = []
        for j, v in zip(js, q, strict=True):
            frames.append((_mv(e[0], ch.axes[j]), _apply(e, ch.points[j])))
            e = _compose(e, _screw("R", ch.axes[j], ch.points[j], v))
        p = _apply(e, x)
        return p, frames, _norm(_sub(p, y))
    p, frames, err = point(q)
    for _ in range(SPATIAL3_REFINE_STEPS):
        c0, c1, c2 = (_cross(h, _sub(p, r)) for h, r in frames)
        b = _sub(y, p)
        det = _dot(c0, _cross(c1, c2))
        if not abs(det) > DEGENERATE_EPS * SCALE ** 3:
            break
        dq = (_dot(b, _cross(c1, c2)) / det, _dot(c0, _cross(b, c2)) / det, _dot(c0, _cross(c1, b)) / det)
        trial = [v + d for v, d in zip(q, dq, strict=True)]
        p2, frames2, err2 = point(trial)
        if not err2 < err:
            break
        q, p, frames, err = trial, p2, frames2, err2
    return q[0], q[1], q[2]




def _spatial3_stage(ch, g, prev, op, x, y, q, count, go_on, family, params=()):
    """The op ("spatial3", a, b, c): every real root of the polynomial."""
    _, ja, jb, jc = op
    for qa, qb, qc, f in _spatial3(ch, ja, jb, jc, x, y):
        q[ja], q[jb], q[jc] = qa, qb, qc
        go_on(f)


_OP_STAGES["spatial3"] = _spatial3_stage
