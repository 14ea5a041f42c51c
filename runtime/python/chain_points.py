"""The points and directions an op reads off the ideal chain.

A wristkin runtime source: every user robot's generated module inlines it from the marker line on
(derive/runtime_files.py), after the robot's constants; above the marker, what it reads from them and from the
other sources (chain_stand_in.py: a stand-in robot), so that it is linted and tested as it is
(tests/test_chain_runtime.py)."""

from __future__ import annotations

import numpy as np
from chain_rigid import _cross, _norm, _scale


# wristkin: inlined from here
def _meet(ch, js):
    """The point nearest to the axes js (their common point), by least squares."""
    m = [[0.0] * 3 for _ in range(3)]
    v = [0.0, 0.0, 0.0]
    for j in js:
        a, p = ch.axes[j], ch.points[j]
        for r in range(3):
            for c in range(3):
                pr = (1.0 if r == c else 0.0) - a[r] * a[c]
                m[r][c] += pr
                v[r] += pr * p[c]
    return tuple(float(x) for x in np.linalg.lstsq(np.array(m), np.array(v), rcond=None)[0])


def _point(ch, spec):
    if spec[0] == "meet":
        w = ch.meets.get(spec)
        if w is None:
            w = ch.meets[spec] = _meet(ch, spec[1:])
        return w
    if spec[0] == "on":
        return ch.points[spec[1]]
    return ch.home[1]


def _direction(ch, spec):
    if spec[0] == "dir":
        return ch.axes[spec[1]]
    n = _cross(ch.axes[spec[1]], ch.axes[spec[2]])
    return _scale(n, 1.0 / _norm(n))

