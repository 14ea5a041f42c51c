"""Local conditioning index 1/kappa_F of batched 3x3 Jacobians J = diag(1/g) X (rows x_i / g_i), where the loop
equations give g_i qdot_i = x_i . v (inverse Jacobian in rows X, the joint factors g).

kappa_F = ||J||_F ||J^-1||_F / 3 is the Frobenius-norm condition number that Gosselin & Angeles (1991) average
over the workspace into the global conditioning index; 1/kappa_F lies in [0, 1], 1 where J is a multiple of a
rotation (isotropic), 0 at a singularity (a g_i -> 0: inverse, det X -> 0: direct). Against the 2-norm
condition number kappa_2 = sigma_max / sigma_min: kappa_2 / 3 <= kappa_F <= kappa_2, i.e. 1/kappa_2 <= 1/kappa_F
<= 3/kappa_2 (both are 0 at the same singularities and 1 at the same isotropic points).

With P = g1 g2 g3, c_i = x_j x x_k ((i, j, k) cyclic) and D = det X:
    1/kappa_F = 3 |D| |P| / ( sqrt(sum_i |x_i|^2 (g_j g_k)^2) * sqrt(sum_i |c_i|^2 g_i^2) ),
finite everywhere (no division by g_i), 0 when the denominator vanishes. Elementwise numpy only: no LAPACK call
per matrix, so the cost stays a small fraction of the C solve."""

from __future__ import annotations

import numpy as np


def _dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def _cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def inverse_kappa_f(rows, g) -> np.ndarray:
    """1/kappa_F of J with rows rows[i] / g[i]; rows: three 3-tuples of arrays (x_i components), g: 3 arrays."""
    x1, x2, x3 = rows
    g1, g2, g3 = g
    c1, c2, c3 = _cross(x2, x3), _cross(x3, x1), _cross(x1, x2)
    det = _dot(x1, c1)
    n_j = _dot(x1, x1) * (g2 * g3) ** 2 + _dot(x2, x2) * (g3 * g1) ** 2 + _dot(x3, x3) * (g1 * g2) ** 2
    n_adj = _dot(c1, c1) * g1 * g1 + _dot(c2, c2) * g2 * g2 + _dot(c3, c3) * g3 * g3
    den = np.sqrt(n_j) * np.sqrt(n_adj)
    num = 3.0 * np.abs(det * g1 * g2 * g3)
    with np.errstate(divide="ignore", invalid="ignore"):
        out = np.where(den > 0.0, num / np.where(den > 0.0, den, 1.0), 0.0)
    return np.minimum(out, 1.0)  # rounding can put an isotropic J a few ulps above 1
