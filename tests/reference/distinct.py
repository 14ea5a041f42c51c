"""One solution returned twice: pairs of sets the pose cannot tell apart (numpy only; no solver involved).

Two sets near a double root of the chain (a fold: the residual grows with the square of the distance along it) may
both fit the pose to rounding; they are two solutions only where a point between them does not: two distinct roots
leave their midpoint off the pose by curvature x (span / 2)^2. ``indistinct_pairs`` returns the pairs within
``span`` (1e-3 rad in every joint, the runtime's MERGE_SPAN) whose midpoint fits the pose as well as they do, to
16 eps x the pose's size (the FK's own rounding), measured by the caller's ``error`` (an independent FK's).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

import numpy as np

EPS = float(np.finfo(float).eps)


def indistinct_pairs(sets: Sequence[np.ndarray], error: Callable[[np.ndarray], float], size: float,
                     span: float = 1e-3) -> list[tuple[int, int]]:
    """(i, k), i < k: sets i and k within `span` (revolute joints, differences wrapped) whose midpoint's `error`
    (its distance from the pose) is at most the larger of theirs plus 16 eps max(1, size)."""
    floor = 16 * EPS * max(1.0, size)
    vals = [np.asarray(v, dtype=float) for v in sets]
    out = []
    for i in range(len(vals)):
        for k in range(i + 1, len(vals)):
            d = np.remainder(vals[k] - vals[i] + math.pi, 2 * math.pi) - math.pi
            if np.max(np.abs(d)) <= span and error(vals[i] + 0.5 * d) <= max(error(vals[i]), error(vals[k])) + floor:
                out.append((i, k))
    return out
