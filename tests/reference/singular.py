"""Singular configurations of a serial arm, found from its Jacobian alone (numpy only; no solver involved).

``singular_configurations(jacobian, n, rng)`` scans each joint q_j over a 720-point grid of (-pi, pi] at a few
random joint sets and bisects every sign change of det J (the square Jacobian: 6 x 6) to the last bit: each
returned (j, q) has det J(q) = 0 to rounding, a wrist, elbow or shoulder singularity according to which joint
crosses it. Moving q_j off by delta then gives a pose delta from the singularity, whose generating joints the
input determines to about eps / delta.
"""

from __future__ import annotations

import math

import numpy as np

GRID = np.linspace(-math.pi, math.pi, 721)
# a base where two of det J's zeros along q_j meet shows no sign change (the irb120's elbow and shoulder
# singularities along q3 with q2 = 0: the upper arm along axis 1, seed 904638): another base is drawn, up to this
# many more per joint
SPARE_BASES = 3


def _bisect(det, lo: float, hi: float, flo: float) -> float:
    while True:
        mid = 0.5 * (lo + hi)
        if mid in (lo, hi):
            return lo
        fm = det(mid)
        if fm == 0.0:
            return mid
        if fm * flo > 0:
            lo, flo = mid, fm
        else:
            hi = mid


def singular_configurations(jacobian, n: int, rng, joints=None, bases: int = 2, per_base: int = 2,
                            fixed: dict | None = None):
    """[(j, q)]: q with det jacobian(q) = 0, found along joint j (for j in `joints`, default all) from `bases`
    random joint sets with a crossing (with `fixed` joints held at their values; up to SPARE_BASES more drawn where one
    shows none), at most `per_base` crossings each."""
    out = []
    for j in range(n) if joints is None else joints:
        kept = drawn = 0
        while kept < bases and drawn < bases + SPARE_BASES:
            drawn += 1
            q = rng.uniform(-math.pi, math.pi, n)
            for k, v in (fixed or {}).items():
                q[k] = v

            def det(t, q=q, j=j):
                x = q.copy()
                x[j] = t
                return float(np.linalg.det(jacobian(x)))
            vals = [det(t) for t in GRID]
            found = 0
            for a, b, fa, fb in zip(GRID, GRID[1:], vals, vals[1:], strict=False):
                if found == per_base or fa == 0.0 or fa * fb > 0:
                    continue
                x = q.copy()
                x[j] = _bisect(det, a, b, fa)
                out.append((j, x))
                found += 1
            kept += found > 0
    return out
