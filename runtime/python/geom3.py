"""3-vector helpers, subproblem 1 and a trig equation for the chain-free cores (spatial3.py, sp6.py, arm_angle.py):
runtime/c/wk_geom3.c's twin, step for step.

A wristkin runtime source: a generated module with a spatial 3R or subproblem 6 inlines it from the marker line on
(derive/runtime_files.py), before those cores; it imports nothing, so that it is linted and tested as it is
(tests/test_spatial3_runtime.py, tests/test_shared_runtime.py)."""

from __future__ import annotations

import math

from _runtime import FLAG_DOUBLE_ROOT, FLAG_INDETERMINATE, FLAG_SINGULAR_INVERSE

# wristkin: inlined from here


def _g3_dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def _g3_cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _g3_axpy(a, s, b):
    """a + s b"""
    return (a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2])


def _g3_norm(a):
    return math.sqrt(_g3_dot(a, a))


def _g3_turn(h, r, q, p):
    """p turned by q about the line (h, r): r + R (p - r), R by Rodrigues."""
    c, s = math.cos(q), math.sin(q)
    d = (p[0] - r[0], p[1] - r[1], p[2] - r[2])
    hd = _g3_dot(h, d) * (1.0 - c)
    hx = _g3_cross(h, d)
    return tuple(r[m] + c * d[m] + s * hx[m] + hd * h[m] for m in range(3))


def _g3_turn_dir(h, q, v):
    """The direction v turned by q about h: rot(h, q) v."""
    return _g3_turn(h, (0.0, 0.0, 0.0), q, v)


def _g3_sp1(k, p, q, eps_scale):
    """t with rot(k, t) p = q seen normal to k (subproblem 1); None when either is within eps_scale of the axis."""
    pp, qq = _g3_axpy(p, -_g3_dot(k, p), k), _g3_axpy(q, -_g3_dot(k, q), k)
    if _g3_norm(pp) <= eps_scale or _g3_norm(qq) <= eps_scale:
        return None
    return math.atan2(_g3_dot(k, _g3_cross(pp, qq)), _g3_dot(pp, qq))


def _g3_trig(a, b, c, scale, on_axis, tangent, double_root):
    """Roots t of a cos t + b sin t = c: [(t, flags)], a double root once (flagged) where 1 - u^2 is within
    double_root; a vanishing equation (|(a, b)| and |c| within on_axis of `scale`) one representative t = 0, flagged
    indeterminate; |u| = |c| / |(a, b)| up to 1 + tangent counts as a root."""
    r = math.hypot(a, b)
    if r <= on_axis * scale:
        return [(0.0, FLAG_INDETERMINATE | FLAG_SINGULAR_INVERSE)] if abs(c) <= on_axis * scale else []
    u = c / r
    if not abs(u) <= 1.0 + tangent:
        return []
    u = max(-1.0, min(1.0, u))
    phi = math.atan2(b, a)
    if 1.0 - u * u <= double_root:
        return [(phi + (0.0 if u > 0.0 else math.pi), FLAG_DOUBLE_ROOT | FLAG_SINGULAR_INVERSE)]
    w = math.acos(u)
    return [(phi + w, 0), (phi - w, 0)]
