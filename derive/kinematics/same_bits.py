"""Small-vector and small-matrix products with the same bits on every CPU.

A description's numbers (axes, points, frames, DH rows) reach the generated files as constants, so they must not
depend on the machine that derives them. numpy's reductions do: `@` and `np.dot` call the BLAS (OpenBLAS picks
its kernels per CPU, with or without FMA), and `np.linalg.norm` / `sum` add in SIMD lanes. Elementwise
operations are IEEE-rounded one by one and are the same everywhere; so here every sum is written out in a fixed
order of Python floats (no FMA contraction), which costs microseconds on the 3- and 4-sized arrays of a chain.
The numeric checks that sample thousands of poses keep numpy: their results are stated as machine-independent
buckets (derive/report_numbers.py)."""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np


def dot(u, v) -> float:
    """sum u_i v_i, added left to right."""
    acc = 0.0
    for a, b in zip(np.asarray(u, dtype=float).tolist(), np.asarray(v, dtype=float).tolist(), strict=True):
        acc += a * b
    return acc


def norm(v) -> float:
    return math.sqrt(dot(v, v))


def unit(v) -> np.ndarray:
    v = np.asarray(v, dtype=float)
    return v / norm(v)


def matmul(a, b) -> np.ndarray:
    """a @ b for 2-D a and 1-D or 2-D b, each entry added left to right."""
    a = np.asarray(a, dtype=float)
    b = np.asarray(b, dtype=float)
    rows = a.tolist()
    if b.ndim == 1:
        return np.array([dot(r, b) for r in rows])
    cols = b.T.tolist()
    return np.array([[dot(r, c) for c in cols] for r in rows])


def chain_product(*ms) -> np.ndarray:
    """m_1 @ m_2 @ ... left to right."""
    out = np.asarray(ms[0], dtype=float)
    for m in ms[1:]:
        out = matmul(out, m)
    return out


def rigid_inverse(t) -> np.ndarray:
    """The inverse of a 4x4 rigid transform [R p; 0 1]: [R^T  -R^T p; 0 1] (exact where R is a rotation; the
    LAPACK inverse is neither exact nor the same on every CPU)."""
    t = np.asarray(t, dtype=float)
    rt = t[:3, :3].T.copy()
    out = np.eye(4)
    out[:3, :3] = rt
    out[:3, 3] = -matmul(rt, t[:3, 3])
    return out


def solve_small(a, b, rel_pivot: float = 1e-12) -> np.ndarray | None:
    """a^-1 b for a small square a by elimination with partial pivoting in Python floats (the runtime's
    solve_square, which the C runtime's wk_square_solve mirrors step for step), or None where a pivot is at or below
    rel_pivot of a's largest entry (the caller's least squares decide)."""
    x = _runtime().solve_square(np.asarray(a, dtype=float).tolist(), np.asarray(b, dtype=float).tolist(), rel_pivot)
    return None if x is None else np.array(x)


@lru_cache(maxsize=1)
def _runtime():
    from .. import runtime_files

    return runtime_files.load_python("python/_runtime.py")
