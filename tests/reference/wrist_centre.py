"""A spherical wrist's centre and its Jacobian in the first three joints, from an arm's forward kinematics alone
(numpy only; no solver or derivation involved).

``centre_in_end_frame(fk, q0, rng)``: the point of the end frame that joints 4-6 do not move (least squares over six
wrist configurations at q0's first three joints). ``centre_jacobian(fk, centre, q)``: the 3 x 3 derivative of that
point in the world by joints 1-3 (central differences, h = 1e-6: error ~h^2 / 6 times the third derivative, ~1e-13 m,
plus eps |p| / h, ~2e-10). ``kappa(fk, centre, q)``: size / sigma_min of it, size = max(1, |position|_inf), how much
joints 1-3 amplify the pose's rounding into the wrist's rotation.
"""

from __future__ import annotations

import numpy as np


def centre_in_end_frame(fk, q0, rng) -> np.ndarray:
    t0 = np.asarray(fk(q0), float)
    rows, rhs = [], []
    for _ in range(6):
        q = np.array(q0, float)
        q[3:6] = rng.uniform(-3.0, 3.0, 3)
        t = np.asarray(fk(q), float)
        rows.append(t[:3, :3] - t0[:3, :3])
        rhs.append(t0[:3, 3] - t[:3, 3])
    return np.linalg.lstsq(np.vstack(rows), np.concatenate(rhs), rcond=None)[0]


def centre_jacobian(fk, centre, q, h: float = 1e-6) -> np.ndarray:
    def point(x):
        t = np.asarray(fk(x), float)
        return t[:3, :3] @ centre + t[:3, 3]
    jac = np.zeros((3, 3))
    for i in range(3):
        a, b = np.array(q, float), np.array(q, float)
        a[i] += h
        b[i] -= h
        jac[:, i] = (point(a) - point(b)) / (2.0 * h)
    return jac


def kappa(fk, centre, q) -> float:
    size = max(1.0, float(np.max(np.abs(np.asarray(fk(q), float)[:3, 3]))))
    return size / float(np.linalg.svd(centre_jacobian(fk, centre, q), compute_uv=False)[-1])
