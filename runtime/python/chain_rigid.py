"""Rigid-body algebra of the user-robot solver: 3-vectors, rotations, transforms, screws.

A wristkin runtime source: every user robot's generated module inlines it from the marker line on
(derive/runtime_files.py), after the robot's constants; above the marker, what it reads from them and from the
other sources (own_stand_in.py: a stand-in robot), so that it is linted and tested as it is
(tests/test_shared_runtime.py)."""

from __future__ import annotations

import math


# wristkin: inlined from here
# ---------------------------------------------------------------------------- small rigid-body algebra
def _dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def _cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def _add(a, b):
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def _scale(a, s):
    return (a[0] * s, a[1] * s, a[2] * s)


def _rot(k, t):
    """Rotation about the unit axis k by t (Rodrigues), rows."""
    c, s = math.cos(t), math.sin(t)
    v = 1.0 - c
    x, y, z = k
    return ((c + x * x * v, x * y * v - z * s, x * z * v + y * s),
            (y * x * v + z * s, c + y * y * v, y * z * v - x * s),
            (z * x * v - y * s, z * y * v + x * s, c + z * z * v))


def _mv(r, v):
    return (_dot(r[0], v), _dot(r[1], v), _dot(r[2], v))


def _mm(a, b):
    (a0, a1, a2), (b0, b1, b2) = a, b
    return ((a0[0] * b0[0] + a0[1] * b1[0] + a0[2] * b2[0], a0[0] * b0[1] + a0[1] * b1[1] + a0[2] * b2[1],
             a0[0] * b0[2] + a0[1] * b1[2] + a0[2] * b2[2]),
            (a1[0] * b0[0] + a1[1] * b1[0] + a1[2] * b2[0], a1[0] * b0[1] + a1[1] * b1[1] + a1[2] * b2[1],
             a1[0] * b0[2] + a1[1] * b1[2] + a1[2] * b2[2]),
            (a2[0] * b0[0] + a2[1] * b1[0] + a2[2] * b2[0], a2[0] * b0[1] + a2[1] * b1[1] + a2[2] * b2[1],
             a2[0] * b0[2] + a2[1] * b1[2] + a2[2] * b2[2]))


def _mt(a):
    (a0, a1, a2) = a
    return ((a0[0], a1[0], a2[0]), (a0[1], a1[1], a2[1]), (a0[2], a1[2], a2[2]))


_I3 = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))
_ID = (_I3, (0.0, 0.0, 0.0))


def _compose(a, b):
    return _mm(a[0], b[0]), _add(_mv(a[0], b[1]), a[1])


def _inverse(a):
    rt = _mt(a[0])
    return rt, _scale(_mv(rt, a[1]), -1.0)


def _apply(a, x):
    return _add(_mv(a[0], x), a[1])


def _screw(kind, h, p, q):
    """exp(S q): rotation about the line (h, p), or translation along h."""
    if kind == "P":
        return _I3, _scale(h, q)
    r = _rot(h, q)
    return r, _sub(p, _mv(r, p))


def _as_rt(m):
    return tuple(tuple(m[i][:3]) for i in range(3)), (m[0][3], m[1][3], m[2][3])
