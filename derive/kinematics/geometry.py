"""Relations between joint axes, each with its measured deviation (the planner compares it with the geometry
tolerance and the audit reports it)."""

from __future__ import annotations

import numpy as np

from .same_bits import matmul, norm, solve_small


def parallel_deviation(a, b) -> float:
    """sin of the angle between two axis directions (0: parallel or anti-parallel)."""
    return float(np.linalg.norm(np.cross(a, b)))


def line_distance(pa, a, pb, b) -> float:
    """Distance between the lines (pa, a) and (pb, b); for parallel lines the distance between them."""
    c = np.cross(a, b)
    d = pb - pa
    if np.linalg.norm(c) < 1e-12:
        return float(np.linalg.norm(d - np.dot(d, a) * a))
    return float(abs(np.dot(d, c)) / np.linalg.norm(c))


def common_point(points, dirs) -> tuple[np.ndarray, float]:
    """The least-squares point nearest to every line, and its largest distance from one of them (the same bits on
    every CPU where the lines are not all parallel: an ideal chain's points become generated constants)."""
    m = np.zeros((3, 3))
    v = np.zeros(3)
    for p, a in zip(points, dirs, strict=True):
        proj = np.eye(3) - np.outer(a, a)
        m += proj
        v += matmul(proj, p)
    w = solve_small(m, v)
    if w is None:  # parallel lines: every point of a common perpendicular line fits; the least-norm one
        w = np.linalg.lstsq(m, v, rcond=None)[0]
    dev = max(norm(matmul(np.eye(3) - np.outer(a, a), w - p)) for p, a in zip(points, dirs, strict=True))
    return w, dev


def meet(pa, a, pb, b) -> np.ndarray:
    """Midpoint of the common perpendicular of two non-parallel lines."""
    d = pb - pa
    ab = float(np.dot(a, b))
    den = 1.0 - ab * ab
    s = (np.dot(d, a) - ab * np.dot(d, b)) / den
    t = (ab * np.dot(d, a) - np.dot(d, b)) / den
    return 0.5 * ((pa + s * a) + (pb + t * b))
