"""Geometric Jacobians of the 3-RSR wrist and the hybrid: differentiate T(q) with the mirror-plane FK substituted.

Column j = (dp/dq_j; vee(dR/dq_j R^T)): linear velocity of the platform centre and angular velocity, base frame.
T does not depend on the sign chosen for the plane normal (R_W = (I - 2 n n^T) diag(1, 1, -1) and O_W = 2 (n . S1) n
are even in n), so the unnormalised N = S1S2 x S1S3 can be used as it is.
"""

from __future__ import annotations

import math

import numpy as np
import sympy as sp

from ...checks import numeric_predicate, sampler
from ...model import Step
from . import rsr_geometry as g


def wrist_transform_of_joints(dv) -> sp.Matrix:
    nvec, s1 = dv.exports["plane_N"], dv.exports["leg_points"][0]
    n = nvec / sp.sqrt(nvec.dot(nvec))
    t = sp.eye(4)
    t[:3, :3] = g.platform_rotation_mirror(n)
    t[:3, 3] = 2 * n.dot(s1) * n
    return t


def geometric_jacobian(t: sp.Matrix, joints) -> sp.Matrix:
    r, p = t[:3, :3], t[:3, 3]
    cols = []
    for q in joints:
        w = r.diff(q) * r.T
        cols.append([*p.diff(q), w[2, 1], w[0, 2], w[1, 0]])
    return sp.Matrix(cols).T


def jacobian_step(name: str, t: sp.Matrix, joints, params, ranges, depends_on) -> tuple[Step, sp.Matrix]:
    """The derived Jacobian and its check: central differences of T(q) at seeded joints (finite plane)."""
    jac = geometric_jacobian(t, joints)
    # T and its Jacobian repeat the plane normal's terms (~70k operations unshared): printed unshared they took
    # seconds to compile, and so did each evaluation
    f_t = sampler((joints, params), t)
    f_j = sampler((joints, params), jac)

    def error(rng) -> float:
        q = np.array([rng.uniform(*r) for r in ranges])
        prm = [v for v in _param_values(params)]
        jn = np.asarray(f_j(q, prm), dtype=float)
        eps, worst = 1e-6, 0.0
        for j in range(len(joints)):
            dq = np.zeros(len(joints))
            dq[j] = eps
            tp, tm = np.asarray(f_t(q + dq, prm), float), np.asarray(f_t(q - dq, prm), float)
            dr = (tp[:3, :3] - tm[:3, :3]) / (2 * eps) @ np.asarray(f_t(q, prm), float)[:3, :3].T
            fd = np.r_[(tp[:3, 3] - tm[:3, 3]) / (2 * eps), dr[2, 1], dr[0, 2], dr[1, 0]]
            worst = max(worst, float(np.max(np.abs(fd - jn[:, j]))))
        return worst

    step = Step(name, "Geometric Jacobian (platform twist per joint rate)",
                "differentiate T(q) with the mirror-plane FK substituted: column j = (dp/dq_j; vee(dR/dq_j R^T)); "
                "T is even in the plane normal's sign, so N need not be oriented",
                depends_on, {}, (numeric_predicate(error, "central differences of T(q) at seeded joints",
                                                   samples=40, tol=1e-7),))
    return step, jac


def _param_values(params):
    defaults = {"L": 0.06, "L1": 0.25, "L2": 0.25, "d": 0.2, "d_f": 0.05}
    return [defaults[str(s)] for s in params]


LEG_RANGE = (math.radians(20.0), math.radians(80.0))
