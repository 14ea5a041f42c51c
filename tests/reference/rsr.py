"""Independent numeric reference for the 3-RSR parallel wrist and the SCARA + 3-RSR hybrid robot (numpy + scipy).

Nothing here imports ``derive/``, ``generated/`` or any symbolic code, and no closed form of the
mirror-symmetric assembly mode is used anywhere: the wrist is handled only through its six raw
loop equations, rotation matrices and 4x4 products, and every solve is numeric:

* IK (``ik_all``): per leg, dense sampling of |S_i(phi) - p|^2 - L^2 + ``brentq`` on sign changes
  + bounded minimisation at sampled minima of |f| (tangential double roots); a root is kept when
  the platform-plane equation also holds; legs are combined by Cartesian product.
* FK (``fk_all``): multistart nonlinear least squares on the 6 loop residuals. Seeded random
  starts are first carried by a vectorised Levenberg-Marquardt on SO(3) x R^3 (numpy, all starts
  at once: that is what makes thousands of starts affordable), then every distinct survivor is
  refined by ``scipy.optimize.least_squares`` (LM, rotation-vector parameterisation, analytic
  Jacobian) and polished by Gauss-Newton. The mirror-symmetric mode is only *selected* afterwards
  (``is_mirror_symmetric``), never constructed.
* Hybrid IK (``hybrid_ik_all``): multistart ``least_squares`` over (theta1, theta2, d3, theta4,
  alpha, beta) with the wrist restricted to the ``pose_from_params`` family, legs from ``ik_all``.

The one formula taken as given is the *definition* of the wrist pose parameters (seed eq. 9),
``pose_from_params``.

Wrist (3-RSR, metres and radians; L = link length of both base and platform links)::

    a_i  = 2 (i - 1) pi / 3,  u_i = (cos a_i, sin a_i, 0)        base joint axis through O_B = 0
    S_i  = Rz(a_i) (0, L cos phi_i, L sin phi_i)                  spherical joint centre
    w_i  = R u_i                                                  platform joint axis through p
    r_i      = (|S_i - p|^2 - L^2) / (2 L)     (= |S_i - p| - L to first order; metres)
    r_{3+i}  = (S_i - p) . w_i                 (metres)

Any solution has |S_i| = |S_i - p| = L, so the three S_i lie in the bisector plane of O_B and p;
consequently p is either O_B itself (a "coincident" branch: (I, 0) always solves the equations) or
the mirror image of O_B in the plane of S_1, S_2, S_3. ``fk_all`` reports both branches (the
coincident one can be dropped with ``include_coincident=False``); measured with 2000 starts
against 8000: 8 modes (4 + 4 coincident) or 16 modes (8 + 8), exactly one mirror-symmetric.
For the same reason both roots of a leg's distance equation lie in the bisector plane, so a
mirror-symmetric pose has 2 roots per leg (generically) and 8 leg triples.

Hybrid robot: T = T_s(theta1, theta2, d3, theta4) T_c T_w with T_s the modified (Craig) DH product
Rx(alpha_{i-1}) Tx(a_{i-1}) Rz(theta_i) Tz(d_i) of the rows (0, 0, d, theta1), (L1, 0, 0, theta2),
(L2, 0, -d3, 0), (0, 0, 0, theta4), T_c = [Rx(pi) | (0, 0, -d_f)] (wrist base mounted upside down
under the flange) and T_w = [R | p].

Tolerances (metres for residuals, unless said otherwise): polished assembly modes have
max |r| < 1e-12 (``FK_POLISH_TOL``); modes are merged when max(|R - R'|_max, |p - p'|_max / L)
< 1e-6 (``FK_DEDUPE_TOL``); a leg root is kept when |r_{3+i}| <= 1e-9 (``IK_LEG_TOL``); hybrid IK
solutions converge to max |T - T_target| <= 1e-10 (``HYBRID_TOL``, entries of [R | p]) and are
merged when the max-norm joint difference (angles wrapped) is < 1e-6 (``HYBRID_DEDUPE_TOL``).
Everything is deterministic: sampling grids are fixed and random starts use fixed seeds.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq, least_squares, minimize_scalar
from scipy.spatial.transform import Rotation

PI = math.pi
TWO_PI = 2.0 * math.pi
DEFAULT_L = 0.06
LEG_ANGLES = (0.0, TWO_PI / 3.0, 2.0 * TWO_PI / 3.0)

FK_POLISH_TOL = 1e-12
FK_DEDUPE_TOL = 1e-6
IK_LEG_TOL = 1e-9
HYBRID_TOL = 1e-10
HYBRID_DEDUPE_TOL = 1e-6


# --------------------------------------------------------------------------------------------
# Rotations and homogeneous transforms
# --------------------------------------------------------------------------------------------


def rot_x(a: float) -> np.ndarray:
    """Right-handed rotation about x by angle a."""
    c, s = math.cos(a), math.sin(a)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def rot_y(a: float) -> np.ndarray:
    """Right-handed rotation about y by angle a."""
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def rot_z(a: float) -> np.ndarray:
    """Right-handed rotation about z by angle a."""
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def skew(w: Sequence[float]) -> np.ndarray:
    """Cross-product matrix: skew(w) @ v == cross(w, v)."""
    return np.array([[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]])


def expm_so3(w: Sequence[float]) -> np.ndarray:
    """Rodrigues' formula for exp(skew(w)), series form for tiny |w| to stay accurate."""
    w = np.asarray(w, dtype=float)
    th = float(np.linalg.norm(w))
    K = skew(w)
    if th < 1e-8:
        return np.eye(3) + K + 0.5 * K @ K
    return np.eye(3) + (math.sin(th) / th) * K + ((1.0 - math.cos(th)) / th**2) * (K @ K)


def homogeneous(R: np.ndarray, p: Sequence[float]) -> np.ndarray:
    """4x4 [R | p; 0 0 0 1]."""
    T = np.eye(4)
    T[:3, :3] = R
    T[:3, 3] = p
    return T


def h_rot_x(a: float) -> np.ndarray:
    return homogeneous(rot_x(a), np.zeros(3))


def h_rot_z(a: float) -> np.ndarray:
    return homogeneous(rot_z(a), np.zeros(3))


def h_trans(x: float, y: float, z: float) -> np.ndarray:
    return homogeneous(np.eye(3), (x, y, z))


def wrap_angle(a: float | np.ndarray) -> float | np.ndarray:
    """Wrap to (-pi, pi]."""
    w = np.mod(np.asarray(a, dtype=float) + PI, TWO_PI) - PI
    w = np.where(w <= -PI, w + TWO_PI, w)
    return float(w) if np.ndim(w) == 0 else w


# --------------------------------------------------------------------------------------------
# Wrist geometry and loop residuals
# --------------------------------------------------------------------------------------------


def base_axis(i: int) -> np.ndarray:
    """u_i for leg i in {1, 2, 3} (the brief's 1-based numbering)."""
    a = LEG_ANGLES[i - 1]
    return np.array([math.cos(a), math.sin(a), 0.0])


def leg_point(i: int, phi: float, L: float = DEFAULT_L) -> np.ndarray:
    """Spherical joint centre S_i = Rz(a_i) (0, L cos phi, L sin phi), leg i in {1, 2, 3}."""
    return rot_z(LEG_ANGLES[i - 1]) @ np.array([0.0, L * math.cos(phi), L * math.sin(phi)])


def leg_points(phis: Sequence[float], L: float = DEFAULT_L) -> np.ndarray:
    """S_1, S_2, S_3 as rows of a (3, 3) array."""
    return np.stack([leg_point(i + 1, phis[i], L) for i in range(3)])


BASE_AXES = np.array([[math.cos(a), math.sin(a), 0.0] for a in LEG_ANGLES])  # rows u_1, u_2, u_3


def _cross_rows(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Row-wise cross product of (n, 3) arrays (np.cross is slow for tiny arrays in hot loops)."""
    return np.stack([a[:, 1] * b[:, 2] - a[:, 2] * b[:, 1], a[:, 2] * b[:, 0] - a[:, 0] * b[:, 2],
                     a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]], axis=1)


def _residual(R: np.ndarray, p: np.ndarray, S: np.ndarray, L: float) -> np.ndarray:
    """Loop residuals from precomputed leg points S (rows); see ``constraint_residual``."""
    D = S - p
    return np.concatenate([(np.sum(D * D, axis=1) - L * L) / (2.0 * L), np.sum(D * (BASE_AXES @ R.T), axis=1)])


def _jacobian(R: np.ndarray, p: np.ndarray, S: np.ndarray, L: float) -> np.ndarray:
    """Twist Jacobian from precomputed leg points S (rows); see ``constraint_jacobian``."""
    D = S - p
    W = BASE_AXES @ R.T
    J = np.zeros((6, 6))
    J[:3, 3:] = -D / L
    J[3:, :3] = _cross_rows(W, D)
    J[3:, 3:] = -W
    return J


def constraint_residual(R: np.ndarray, p: Sequence[float], phis: Sequence[float], L: float = DEFAULT_L
                        ) -> np.ndarray:
    """The 6 loop residuals (metres): (|S_i - p|^2 - L^2) / (2L) for i = 1..3, then (S_i - p) . R u_i.

    The distance equation is divided by 2L so that both halves are lengths of comparable size.
    """
    return _residual(np.asarray(R, dtype=float), np.asarray(p, dtype=float), leg_points(phis, L), L)


def is_assembly(R: np.ndarray, p: Sequence[float], phis: Sequence[float], L: float = DEFAULT_L,
                tol: float = 1e-9) -> bool:
    """True if (R, p) closes the loops for phis: max |residual| <= tol (metres) and R is a rotation."""
    R = np.asarray(R, dtype=float)
    if np.max(np.abs(R.T @ R - np.eye(3))) > 1e-9 or np.linalg.det(R) < 0.0:
        return False
    return float(np.max(np.abs(constraint_residual(R, p, phis, L)))) <= tol


def constraint_jacobian(R: np.ndarray, p: Sequence[float], phis: Sequence[float], L: float = DEFAULT_L
                        ) -> np.ndarray:
    """Analytic d(residual)/d(twist), shape (6, 6); columns (omega, v), omega the world-frame
    angular velocity (dR = skew(omega) R) and v the velocity of p.

    Derived by hand from the residual definitions: with d_i = S_i - p and w_i = R u_i,
    d r_i = -d_i . v / L and d r_{3+i} = (w_i x d_i) . omega - w_i . v.
    """
    return _jacobian(np.asarray(R, dtype=float), np.asarray(p, dtype=float), leg_points(phis, L), L)


def constraint_singularity_measure(R: np.ndarray, p: Sequence[float], phis: Sequence[float],
                                   L: float = DEFAULT_L) -> float:
    """sigma_min / sigma_max of the constraint Jacobian with the omega columns divided by L.

    The scaling makes every entry dimensionless (omega columns are metres per radian, v columns
    are pure numbers), so the ratio does not depend on the unit of length. 0 at a singularity.
    """
    J = constraint_jacobian(R, p, phis, L) @ np.diag([1.0 / L] * 3 + [1.0] * 3)
    s = np.linalg.svd(J, compute_uv=False)
    return float(s[-1] / s[0])


# --------------------------------------------------------------------------------------------
# Wrist pose parameters (seed eq. 9: a definition, not a solution)
# --------------------------------------------------------------------------------------------


def pose_from_params(alpha: float, beta: float, l_bw: float) -> tuple[np.ndarray, np.ndarray]:
    """(R, p) with R = Rz(alpha) Ry(beta) Rz(-alpha), p = l_bw (sin(b/2) cos a, sin(b/2) sin a, cos(b/2)).

    (alpha, beta) and (alpha + pi, -beta) give the same pose; beta in (pi, 2pi) puts p below the base plane.
    """
    R = rot_z(alpha) @ rot_y(beta) @ rot_z(-alpha)
    h = 0.5 * beta
    p = l_bw * np.array([math.sin(h) * math.cos(alpha), math.sin(h) * math.sin(alpha), math.cos(h)])
    return R, p


def params_from_pose(R: np.ndarray, p: Sequence[float]) -> tuple[float, float, float]:
    """(alpha, beta, l_bw) with l_bw = |p|, beta / 2 = polar angle of p (beta in [0, 2pi]) and alpha
    the azimuth of p (0 when p is on the z axis, where alpha is undefined).

    Read from p only because p is 4pi-periodic in beta while R is 2pi-periodic: beta in (pi, 2pi]
    (p below the base plane) is reachable for actuated angles far from the working range.
    R is not used; this inverts ``pose_from_params`` only on that family, see ``is_mirror_symmetric``.
    """
    del R
    p = np.asarray(p, dtype=float)
    rho = math.hypot(p[0], p[1])
    l_bw = float(np.linalg.norm(p))
    beta = 2.0 * math.atan2(rho, p[2])
    alpha = math.atan2(p[1], p[0]) if rho > 1e-14 * max(l_bw, 1e-300) else 0.0
    return alpha, beta, l_bw


def is_mirror_symmetric(R: np.ndarray, p: Sequence[float], tol: float = 1e-9, min_l_bw: float = 1e-9) -> bool:
    """True if (R, p) belongs to the ``pose_from_params`` family (the mirror-symmetric mode).

    The coincident pose p = 0 is excluded (|p| < min_l_bw) because there the family degenerates.
    """
    alpha, beta, l_bw = params_from_pose(R, p)
    if l_bw < min_l_bw:
        return False
    R2, p2 = pose_from_params(alpha, beta, l_bw)
    return max(float(np.max(np.abs(R2 - R))), float(np.max(np.abs(p2 - np.asarray(p)))) / l_bw) <= tol


# --------------------------------------------------------------------------------------------
# Forward kinematics: multistart least squares + Gauss-Newton polish on SO(3) x R^3
# --------------------------------------------------------------------------------------------


def _left_jacobian_so3(w: np.ndarray) -> np.ndarray:
    """J_l(w) with d exp(skew(w)) = skew(J_l(w) dw) exp(skew(w)): maps rotation-vector steps to
    world-frame angular velocity, so the analytic twist Jacobian can be reused for least_squares."""
    th = float(np.linalg.norm(w))
    K = skew(w)
    if th < 1e-6:
        return np.eye(3) + 0.5 * K + (K @ K) / 6.0
    return np.eye(3) + ((1.0 - math.cos(th)) / th**2) * K + ((th - math.sin(th)) / th**3) * (K @ K)


def _fk_problem(S: np.ndarray, L: float, R0: np.ndarray, p0: np.ndarray
                ) -> tuple[Callable[[np.ndarray], np.ndarray], Callable[[np.ndarray], np.ndarray]]:
    """Residual and Jacobian in local coordinates x around (R0, p0): R = expm(x[:3]) R0 (rotation
    vector of the correction, never near its pi singularity), p = p0 + L x[3:]; scaled by 1/L."""

    def fun(x: np.ndarray) -> np.ndarray:
        return _residual(expm_so3(x[:3]) @ R0, p0 + L * x[3:], S, L) / L

    def jac(x: np.ndarray) -> np.ndarray:
        J = _jacobian(expm_so3(x[:3]) @ R0, p0 + L * x[3:], S, L)
        J[:, :3] = J[:, :3] @ _left_jacobian_so3(x[:3]) / L
        return J  # v columns: the 1/L of the residual cancels the L of p = p0 + L x[3:]

    return fun, jac


def _batch_expm(W: np.ndarray) -> np.ndarray:
    """Rodrigues for a stack of rotation vectors (n, 3) -> (n, 3, 3)."""
    th = np.linalg.norm(W, axis=1)
    small = th < 1e-8
    ths = np.where(small, 1.0, th)
    a = np.where(small, 1.0, np.sin(ths) / ths)
    b = np.where(small, 0.5, (1.0 - np.cos(ths)) / ths**2)
    K = np.zeros((len(W), 3, 3))
    K[:, 0, 1], K[:, 0, 2], K[:, 1, 2] = -W[:, 2], W[:, 1], -W[:, 0]
    K[:, 1, 0], K[:, 2, 0], K[:, 2, 1] = W[:, 2], -W[:, 1], W[:, 0]
    return np.eye(3) + a[:, None, None] * K + b[:, None, None] * (K @ K)


def _batch_residual_jacobian(R: np.ndarray, P: np.ndarray, S: np.ndarray, L: float
                             ) -> tuple[np.ndarray, np.ndarray]:
    """Scaled residuals r / L (n, 6) and Jacobians (n, 6, 6) w.r.t. (omega, v / L) for n poses at once."""
    D = S[None, :, :] - P[:, None, :]
    W = np.einsum("nij,kj->nki", R, BASE_AXES)  # rows w_k = R u_k
    r = np.concatenate([(np.sum(D * D, axis=2) - L * L) / (2.0 * L), np.sum(D * W, axis=2)], axis=1) / L
    J = np.zeros((len(R), 6, 6))
    J[:, :3, 3:] = -D / L
    J[:, 3:, :3] = np.cross(W, D) / L
    J[:, 3:, 3:] = -W
    return r, J


def _batch_lm(R: np.ndarray, P: np.ndarray, S: np.ndarray, L: float, iters: int = 60
              ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Levenberg-Marquardt run on all starts at once (vectorised numpy, one damping factor per start),
    stepping on SO(3) x R^3 through expm. Returns final poses and their max |residual| (metres).

    Only a cheap way to carry many starts near their solutions; every survivor is then refined by
    ``scipy.optimize.least_squares`` and Gauss-Newton (see ``fk_all``)."""
    lam = np.full(len(R), 1e-3)
    r, J = _batch_residual_jacobian(R, P, S, L)
    cost = np.sum(r * r, axis=1)
    for _ in range(iters):
        if np.all(cost < 1e-30):
            break
        A = np.einsum("nki,nkj->nij", J, J)
        g = np.einsum("nki,nk->ni", J, r)
        damp = lam[:, None] * (np.einsum("nii->ni", A) + 1e-12)
        A[:, np.arange(6), np.arange(6)] += damp
        step = -np.linalg.solve(A, g[:, :, None])[:, :, 0]
        R_t = _batch_expm(step[:, :3]) @ R
        P_t = P + L * step[:, 3:]
        r_t, J_t = _batch_residual_jacobian(R_t, P_t, S, L)
        cost_t = np.sum(r_t * r_t, axis=1)
        ok = cost_t < cost
        R[ok], P[ok], r[ok], J[ok], cost[ok] = R_t[ok], P_t[ok], r_t[ok], J_t[ok], cost_t[ok]
        lam = np.clip(np.where(ok, lam / 3.0, lam * 4.0), 1e-12, 1e12)
    return R, P, L * np.max(np.abs(r), axis=1)


def _fk_polish(R: np.ndarray, p: np.ndarray, S: np.ndarray, L: float, iters: int = 10
               ) -> tuple[np.ndarray, np.ndarray, float]:
    """Gauss-Newton with the analytic twist Jacobian, R updated through expm so it stays a rotation;
    returns the best iterate and its max |residual| (stops once an iteration no longer improves)."""
    best = (R, p, float(np.max(np.abs(_residual(R, p, S, L)))))
    for _ in range(iters):
        if best[2] < 1e-3 * FK_POLISH_TOL:
            break
        R, p = best[0], best[1]
        step = np.linalg.lstsq(_jacobian(R, p, S, L), -_residual(R, p, S, L), rcond=None)[0]
        R, p = expm_so3(step[:3]) @ R, p + step[3:]
        err = float(np.max(np.abs(_residual(R, p, S, L))))
        if err >= best[2]:
            break
        best = (R, p, err)
    return best


def _same_pose(a: tuple[np.ndarray, np.ndarray], b: tuple[np.ndarray, np.ndarray], L: float, tol: float) -> bool:
    return max(float(np.max(np.abs(a[0] - b[0]))), float(np.max(np.abs(a[1] - b[1]))) / L) < tol


def _pose_key(pose: tuple[np.ndarray, np.ndarray], L: float) -> tuple[float, ...]:
    """Deterministic sort key: rounded p / L, then rounded R entries."""
    R, p = pose
    return tuple(np.round(np.concatenate([np.asarray(p) / L, R.ravel()]), 6).tolist())


def _fk_starts(n_starts: int, seed: int, L: float) -> tuple[np.ndarray, np.ndarray]:
    """Start poses: uniform random rotations (scipy ``Rotation.random``) and p uniform in the ball
    |p| <= 2L (every solution has |p| <= |S_i| + |S_i - p| = 2L)."""
    rng = np.random.default_rng(seed)
    R = Rotation.random(n_starts, random_state=rng).as_matrix()
    d = rng.normal(size=(n_starts, 3))
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    return R, 2.0 * L * rng.uniform(size=(n_starts, 1)) ** (1.0 / 3.0) * d


def _representatives(R: np.ndarray, P: np.ndarray, L: float, tol: float) -> list[tuple[np.ndarray, np.ndarray]]:
    """Greedy clustering of a stack of poses: one representative per group closer than tol (vectorised,
    so thousands of converged starts cost one pass per distinct mode)."""
    out = []
    left = np.arange(len(R))
    while left.size:
        k = left[0]
        dist = np.maximum(np.max(np.abs(R[left] - R[k]), axis=(1, 2)), np.max(np.abs(P[left] - P[k]), axis=1) / L)
        out.append((R[k], P[k]))
        left = left[dist >= tol]
    return out


def _fk_refine(R: np.ndarray, p: np.ndarray, S: np.ndarray, L: float) -> tuple[np.ndarray, np.ndarray, float]:
    """``least_squares`` (LM, local rotation-vector coordinates, analytic Jacobian), then GN polish."""
    fun, jac = _fk_problem(S, L, R, p)
    res = least_squares(fun, np.zeros(6), jac=jac, method="lm", xtol=1e-15, ftol=1e-15, gtol=1e-15, max_nfev=100)
    return _fk_polish(expm_so3(res.x[:3]) @ R, p + L * res.x[3:], S, L)


def fk_all(phis: Sequence[float], L: float = DEFAULT_L, n_starts: int = 2000, seed: int = 0,
           include_coincident: bool = True) -> list[tuple[np.ndarray, np.ndarray]]:
    """All assembly modes (R, p) for the actuated angles phis that the multistart finds.

    ``n_starts`` seeded random poses are driven towards the solution set of the 6 loop residuals by a
    vectorised Levenberg-Marquardt (``_batch_lm``); those within 1e-8 m are deduplicated coarsely
    (1e-4) and each is refined by ``scipy.optimize.least_squares`` (LM, rotation-vector
    parameterisation of the correction, analytic Jacobian) and Gauss-Newton on SO(3) x R^3. A mode
    is kept when max |residual| < FK_POLISH_TOL (1e-12 m) and merged with an earlier one when the
    pose difference max(|dR|_max, |dp|_max / L) is < FK_DEDUPE_TOL (1e-6). ``include_coincident=False``
    drops modes with |p| < 1e-6 L (platform centre on the base centre). Sorted by (p / L, R) rounded
    to 1e-6.
    """
    S = leg_points([float(v) for v in phis], L)
    R0, P0 = _fk_starts(n_starts, seed, L)
    Rb, Pb, err = _batch_lm(R0, P0, S, L)
    modes: list[tuple[np.ndarray, np.ndarray]] = []
    for Rc, pc in _representatives(Rb[err < 1e-8], Pb[err < 1e-8], L, 1e-4):
        R, p, e = _fk_refine(Rc, pc, S, L)
        if e < FK_POLISH_TOL and not any(_same_pose((R, p), m, L, FK_DEDUPE_TOL) for m in modes):
            modes.append((R, p))
    if not include_coincident:
        modes = [m for m in modes if np.linalg.norm(m[1]) >= 1e-6 * L]
    modes.sort(key=lambda m: _pose_key(m, L))
    return modes


def fk_contains(phis: Sequence[float], L: float, R: np.ndarray, p: Sequence[float], tol: float = 1e-8,
                modes: Sequence[tuple[np.ndarray, np.ndarray]] | None = None, **fk_kwargs) -> bool:
    """True if (R, p) matches (max-norm on R and p / L within tol) one of the modes of ``fk_all``
    (pass ``modes`` to reuse an earlier ``fk_all`` result)."""
    target = (np.asarray(R, dtype=float), np.asarray(p, dtype=float))
    if modes is None:
        modes = fk_all(phis, L, **fk_kwargs)
    return any(_same_pose(target, m, L, tol) for m in modes)


def fk_symmetric(phis: Sequence[float], L: float = DEFAULT_L, tol: float = 1e-9, **fk_kwargs
                 ) -> list[tuple[np.ndarray, np.ndarray]]:
    """The modes of ``fk_all`` that are mirror-symmetric (selected numerically, no closed form)."""
    return [m for m in fk_all(phis, L, **fk_kwargs) if is_mirror_symmetric(*m, tol=tol)]


# --------------------------------------------------------------------------------------------
# Inverse kinematics: per-leg 1-D root finding
# --------------------------------------------------------------------------------------------


def _brent(f: Callable[[float], float], a: float, b: float) -> float:
    """brentq to full double precision."""
    return brentq(f, a, b, xtol=1e-15, rtol=4 * np.finfo(float).eps, maxiter=200)


def _leg_distance_fn(i: int, p: np.ndarray, L: float) -> Callable[[np.ndarray], np.ndarray]:
    """f(phi) = (|S_i(phi) - p|^2 - L^2) / (2L), vectorised over phi."""
    Rz = rot_z(LEG_ANGLES[i - 1])

    def f(phi: np.ndarray) -> np.ndarray:
        phi = np.asarray(phi, dtype=float)
        local = np.stack([np.zeros_like(phi), L * np.cos(phi), L * np.sin(phi)], axis=-1)
        d = local @ Rz.T - p
        return (np.sum(d * d, axis=-1) - L * L) / (2.0 * L)

    return f


def _periodic_roots(fvec: Callable[[np.ndarray], np.ndarray], n: int, touch_tol: float) -> list[float]:
    """Roots of a 2pi-periodic function on (-pi, pi]: brentq on every sampled sign change, plus a
    bounded minimisation of |f| around sampled local minima of |f| (not next to a sign change) to
    catch tangential double roots (kept once when |f| <= touch_tol) or two hidden close roots."""
    h = TWO_PI / n
    xs = -PI + h * (np.arange(n) + 0.5)  # offset grid: never samples the wrap point itself
    v = fvec(xs)

    def f(x: float) -> float:
        return float(fvec(np.array([x]))[0])

    roots: list[float] = []
    for k in range(n):
        j = (k + 1) % n
        if v[k] == 0.0:
            roots.append(xs[k])
        elif v[k] * v[j] < 0.0:
            roots.append(_brent(f, xs[k], xs[k] + h))
    av = np.abs(v)
    for k in range(n):
        km, kp = (k - 1) % n, (k + 1) % n
        if v[k] == 0.0 or av[k] > av[km] or av[k] > av[kp] or v[km] * v[k] <= 0.0 or v[kp] * v[k] <= 0.0:
            continue
        sgn = 1.0 if v[k] > 0.0 else -1.0
        lo, hi = xs[k] - h, xs[k] + h
        xm = float(minimize_scalar(lambda x, s=sgn: s * f(x), bounds=(lo, hi), method="bounded",
                                   options={"xatol": 1e-14, "maxiter": 500}).x)
        fm = f(xm)
        if abs(fm) <= touch_tol:
            roots.append(xm)
        elif sgn * fm < 0.0:
            roots += [_brent(f, lo, xm), _brent(f, xm, hi)]
    return sorted(float(wrap_angle(r)) for r in roots)


@dataclass
class LegRoots:
    """Per-leg IK detail: ``distance_roots`` solve only |S_i - p| = L; ``roots`` also satisfy the
    platform-plane equation within IK_LEG_TOL."""

    distance_roots: list[float]
    roots: list[float]


def ik_leg(i: int, R: np.ndarray, p: Sequence[float], L: float = DEFAULT_L, n_samples: int = 720,
           touch_tol: float = 1e-13, tol: float = IK_LEG_TOL) -> LegRoots:
    """All phi_i in (-pi, pi] closing leg i for platform pose (R, p); leg i in {1, 2, 3}."""
    p = np.asarray(p, dtype=float)
    w = np.asarray(R, dtype=float) @ base_axis(i)
    dist = _periodic_roots(_leg_distance_fn(i, p, L), n_samples, touch_tol)
    keep = [phi for phi in dist if abs((leg_point(i, phi, L) - p) @ w) <= tol]
    return LegRoots(dist, keep)


def ik_all(R: np.ndarray, p: Sequence[float], L: float = DEFAULT_L, **leg_kwargs
           ) -> list[tuple[float, float, float]]:
    """Every (phi1, phi2, phi3) in (-pi, pi]^3 placing the platform at (R, p): Cartesian product of
    the per-leg roots of ``ik_leg``; [] when any leg is unreachable."""
    per_leg = [ik_leg(i, R, p, L, **leg_kwargs).roots for i in (1, 2, 3)]
    return [tuple(t) for t in itertools.product(*per_leg)]


# --------------------------------------------------------------------------------------------
# Hybrid SCARA + 3-RSR robot
# --------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class HybridDesign:
    """SCARA link lengths L1, L2, base offset d, flange-to-wrist offset d_f and wrist link length L."""

    L1: float = 0.25
    L2: float = 0.25
    d: float = 0.0
    d_f: float = 0.05
    L: float = DEFAULT_L


def as_hybrid_design(design: HybridDesign | Mapping[str, float] | Sequence[float] | None) -> HybridDesign:
    """Accept a HybridDesign, a mapping with L1/L2/d/d_f/L, a 5-sequence in that order, or None (defaults)."""
    if design is None:
        return HybridDesign()
    if isinstance(design, HybridDesign):
        return design
    if isinstance(design, Mapping):
        return HybridDesign(**{k: float(v) for k, v in design.items()})
    return HybridDesign(*(float(v) for v in design))


def _mdh(a_prev: float, alpha_prev: float, d: float, theta: float) -> np.ndarray:
    """Modified (Craig) DH link transform Rx(alpha_{i-1}) Tx(a_{i-1}) Rz(theta_i) Tz(d_i)."""
    return h_rot_x(alpha_prev) @ h_trans(a_prev, 0.0, 0.0) @ h_rot_z(theta) @ h_trans(0.0, 0.0, d)


def scara_fk(q_scara: Sequence[float], design: HybridDesign | Mapping[str, float] | None = None) -> np.ndarray:
    """T_s(theta1, theta2, d3, theta4): literal product of the four modified-DH link matrices."""
    ds = as_hybrid_design(design)
    t1, t2, d3, t4 = (float(v) for v in q_scara[:4])
    rows = [(0.0, 0.0, ds.d, t1), (ds.L1, 0.0, 0.0, t2), (ds.L2, 0.0, -d3, 0.0), (0.0, 0.0, 0.0, t4)]
    T = np.eye(4)
    for row in rows:
        T = T @ _mdh(*row)
    return T


def mount_transform(design: HybridDesign | Mapping[str, float] | None = None) -> np.ndarray:
    """T_c: the wrist base mounted upside down, d_f below the flange."""
    ds = as_hybrid_design(design)
    return np.array([[1.0, 0.0, 0.0, 0.0], [0.0, -1.0, 0.0, 0.0], [0.0, 0.0, -1.0, -ds.d_f], [0.0, 0.0, 0.0, 1.0]])


def hybrid_fk_with_wrist(q_scara: Sequence[float], R: np.ndarray, p: Sequence[float],
                         design: HybridDesign | Mapping[str, float] | None = None) -> np.ndarray:
    """T = T_s(q_scara) T_c [R | p] for a given wrist platform pose."""
    return scara_fk(q_scara, design) @ mount_transform(design) @ homogeneous(np.asarray(R, dtype=float), p)


def hybrid_fk_all(q: Sequence[float], design: HybridDesign | Mapping[str, float] | None = None,
                  **fk_kwargs) -> list[np.ndarray]:
    """One T per wrist assembly mode of ``fk_all(q[4:7])``, in the order of ``fk_all``."""
    ds = as_hybrid_design(design)
    return [hybrid_fk_with_wrist(q[:4], R, p, ds) for R, p in fk_all(q[4:7], ds.L, **fk_kwargs)]


def _hybrid_residual(x: np.ndarray, T_target: np.ndarray, l_bw: float, ds: HybridDesign, scale: float
                     ) -> np.ndarray:
    """12 entries of T_s T_c T_w(alpha, beta, l_bw) - T_target, position rows divided by ``scale``."""
    Rw, pw = pose_from_params(x[4], x[5], l_bw)
    T = hybrid_fk_with_wrist(x[:4], Rw, pw, ds)
    diff = T[:3, :] - T_target[:3, :]
    diff[:, 3] /= scale
    return diff.ravel()


def _same_q(a: np.ndarray, b: np.ndarray, tol: float) -> bool:
    """Max-norm difference with revolute joints (all but index 2, the prismatic d3) wrapped."""
    diff = np.asarray(a) - np.asarray(b)
    ang = [0, 1, 3, 4, 5, 6]
    diff[ang] = wrap_angle(diff[ang])
    return float(np.max(np.abs(diff))) < tol


def _canonical_q(x: np.ndarray, phis: Sequence[float]) -> np.ndarray:
    """(theta1, theta2, d3, theta4, phi1, phi2, phi3) with angles wrapped to (-pi, pi]."""
    q = np.array([x[0], x[1], x[2], x[3], *phis], dtype=float)
    ang = [0, 1, 3, 4, 5, 6]
    q[ang] = wrap_angle(q[ang])
    return q


def hybrid_ik_all(T_target: np.ndarray, l_bw: float, design: HybridDesign | Mapping[str, float] | None = None,
                  n_starts: int = 32, seed: int = 0, tol: float = HYBRID_TOL) -> list[np.ndarray]:
    """Every joint vector q (7,) with the hybrid pose T_target and the wrist mirror-symmetric at |p_w| = l_bw.

    Unknowns (theta1, theta2, d3, theta4, alpha, beta): the wrist is restricted to the
    ``pose_from_params`` family, which is the definition of its 3 DOF. ``n_starts`` seeded starts
    (angles uniform in (-pi, pi], d3 uniform in +-(reach), beta uniform in (-pi/2, pi/2)) are
    refined by Levenberg-Marquardt on the 12 entries of [R | p] (position divided by the reach
    L1 + L2 + |d| + d_f + l_bw). A start counts when max |T - T_target| <= tol; the legs then
    come from ``ik_all`` and every resulting q is re-checked by forward composition and the loop
    residual. Distinct q (HYBRID_DEDUPE_TOL, angles modulo 2pi) are returned sorted.
    """
    ds = as_hybrid_design(design)
    T_target = np.asarray(T_target, dtype=float)
    scale = ds.L1 + ds.L2 + abs(ds.d) + ds.d_f + l_bw
    rng = np.random.default_rng(seed)
    sols: list[np.ndarray] = []
    for _ in range(n_starts):
        x0 = np.array([rng.uniform(-PI, PI), rng.uniform(-PI, PI), rng.uniform(-scale, scale),
                       rng.uniform(-PI, PI), rng.uniform(-PI, PI), rng.uniform(-PI / 2, PI / 2)])
        res = least_squares(_hybrid_residual, x0, args=(T_target, l_bw, ds, scale), method="lm",
                            xtol=1e-15, ftol=1e-15, gtol=1e-15, max_nfev=600)
        Rw, pw = pose_from_params(res.x[4], res.x[5], l_bw)
        if np.max(np.abs(hybrid_fk_with_wrist(res.x[:4], Rw, pw, ds) - T_target)) > tol:
            continue
        for phis in ik_all(Rw, pw, ds.L):
            q = _canonical_q(res.x, phis)
            if not is_assembly(Rw, pw, phis, ds.L, tol=IK_LEG_TOL):
                continue
            if not any(_same_q(q, s, HYBRID_DEDUPE_TOL) for s in sols):
                sols.append(q)
    sols.sort(key=lambda q: tuple(np.round(q, 6).tolist()))
    return sols


def hybrid_ik_contains(sols: Sequence[np.ndarray], q: Sequence[float], tol: float = 1e-7) -> bool:
    """True if q equals one of ``sols`` (angles modulo 2pi, max-norm tol)."""
    q = np.asarray(q, dtype=float)
    return any(_same_q(q, s, tol) for s in sols)
