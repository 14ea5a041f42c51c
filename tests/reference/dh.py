"""Independent numeric reference for the standard-DH serial mechanisms (plain numpy + scipy).

Nothing here imports ``derive/`` or any symbolic code: forward kinematics is the literal product of
numeric link matrices, the Jacobian is built geometrically from the frames, and inverse kinematics
is multistart Levenberg-Marquardt (``scipy.optimize.least_squares(method="lm")``).

Convention (standard DH)::

    A_i = Rz(theta_i) Tz(d_i) Tx(a_i) Rx(alpha_i)

Each row of ``MECHANISMS[name]["rows"]`` is ``(a, alpha, d, theta_offset, kind)``. For a revolute
joint (``kind == "R"``) ``theta_i = q_i + theta_offset`` and ``d_i = d``; for a prismatic joint
(``kind == "P"``) ``theta_i = theta_offset`` and ``d_i = d + q_i``. Any of ``a, alpha, d,
theta_offset`` may be a string naming a design parameter (defaults in ``MECHANISMS[name]["design"]``,
overridable with the ``design=`` argument of every function).

IK reference (``ik_reference``): ``starts`` deterministic starts (fixed ``seed``; the first start is
q = 0, the rest uniform: angles in (-pi, pi], prismatic joints in [-L, L] with L = |p| + the sum of
the constant lengths), each refined by LM on the 12 entries of [R | p] - [R_T | p_T] with the exact
Jacobian (d R / d q_i = [z_{i-1}]x R for a revolute joint). A converged point is kept when its
largest entry error is <= ``tol`` (1e-9); angles are wrapped to (-pi, pi] and points closer than
``dedupe_tol`` (1e-6, max-norm, angle differences wrapped) are merged. The loop stops early once
``max_solutions`` distinct solutions are found (the generic solution count: PUMA 8, RPP 4, SCARA 2,
spherical wrist 2, 1-DOF 1). If nothing reaches ``tol`` -- e.g. a pose outside the reachable subset
of a mechanism with fewer than 6 DOF -- the result is ``[]``.

Default starts and measured reliability (``measure_reliability``: generic poses from uniform random
joints, 1000 trials per mechanism): see ``DEFAULT_STARTS`` below; the numbers are recorded next to
it. Because of the early stop, a generic pose typically costs far fewer LM runs than ``starts``
(PUMA: about 0.1 s per call).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

import numpy as np
from scipy.optimize import least_squares

PI = math.pi

# name -> rows (a, alpha, d, theta_offset, kind), design defaults, joint names, generic IK solution count
MECHANISMS: dict[str, dict] = {
    "wrist_1dof": {
        "rows": [(0.0, 0.0, "dw", 0.0, "R")],
        "design": {"dw": 0.1},
        "joints": ("theta",),
        "max_solutions": 1,
    },
    "spherical_wrist": {
        "rows": [
            (0.0, -PI / 2, 0.0, 0.0, "R"),
            (0.0, PI / 2, 0.0, 0.0, "R"),
            (0.0, 0.0, "d6", 0.0, "R"),
        ],
        "design": {"d6": 0.1},
        "joints": ("theta4", "theta5", "theta6"),
        "max_solutions": 2,
    },
    "rpp_wrist": {
        "rows": [
            (0.0, 0.0, "d1", 0.0, "R"),
            (0.0, -PI / 2, 0.0, 0.0, "P"),
            (0.0, 0.0, 0.0, 0.0, "P"),
            (0.0, -PI / 2, 0.0, 0.0, "R"),
            (0.0, PI / 2, 0.0, 0.0, "R"),
            (0.0, 0.0, "d6", 0.0, "R"),
        ],
        "design": {"d1": 0.5, "d6": 0.1},
        "joints": ("theta1", "d2", "d3", "theta4", "theta5", "theta6"),
        "max_solutions": 4,
    },
    "scara_wrist": {
        "rows": [
            ("a1", 0.0, 0.0, 0.0, "R"),
            ("a2", PI, 0.0, 0.0, "R"),
            (0.0, 0.0, 0.0, 0.0, "P"),
            (0.0, 0.0, "d4", 0.0, "R"),
        ],
        "design": {"a1": 0.4, "a2": 0.3, "d4": 0.1},
        "joints": ("theta1", "theta2", "d3", "theta4"),
        "max_solutions": 2,
    },
    "puma560": {
        "rows": [
            (0.0, PI / 2, "d1", 0.0, "R"),
            ("a2", 0.0, 0.0, 0.0, "R"),
            ("a3", -PI / 2, "d3", 0.0, "R"),
            (0.0, PI / 2, "d4", 0.0, "R"),
            (0.0, -PI / 2, 0.0, 0.0, "R"),
            (0.0, 0.0, "d6", 0.0, "R"),
        ],
        "design": {"d1": 0.6718, "a2": 0.4318, "d3": 0.15005, "a3": 0.0203, "d4": 0.4318, "d6": 0.0},
        "joints": ("theta1", "theta2", "theta3", "theta4", "theta5", "theta6"),
        "max_solutions": 8,
    },
}

# Default number of multistart LM starts per mechanism. Measured misses (a generic pose from uniform
# random joints whose returned list lacked the generating q, or had fewer than max_solutions entries),
# measure_reliability(name, trials=1000, seed=12345), with these defaults:
#   wrist_1dof 0/1000, spherical_wrist 0/1000, scara_wrist 0/1000, rpp_wrist 0/1000 (generating q always found),
#   puma560: generating q always found, 1/1000 returned 7 of 8 (trial 353: q3 within 2e-4 rad of the elbow
#   singularity pi/2 + atan(a3/d4) and theta1 branches only 6e-4 apart, so two branches have tiny LM basins;
#   seed=1 finds all 8). Fewer starts, 100 trials: puma560 at 32 starts 8/100 short, at 64 0/100;
#   rpp_wrist at 16 5/100 short; scara_wrist at 8 1/100. Near-singular poses are the weak spot.
# With early stop, a non-degenerate singular pose (a continuum of solutions) returns max_solutions samples of it.
DEFAULT_STARTS: dict[str, int] = {
    "wrist_1dof": 8,
    "spherical_wrist": 32,
    "rpp_wrist": 96,
    "scara_wrist": 32,
    "puma560": 256,
}


# --------------------------------------------------------------------------------------------
# Numeric DH
# --------------------------------------------------------------------------------------------


def _design(name: str, design: Mapping[str, float] | None) -> dict[str, float]:
    d = dict(MECHANISMS[name]["design"])
    if design:
        unknown = set(design) - set(d)
        if unknown:
            raise KeyError(f"{name}: unknown design parameters {sorted(unknown)}")
        d.update(design)
    return d


def _value(x, design: Mapping[str, float]) -> float:
    return float(design[x]) if isinstance(x, str) else float(x)


def numeric_rows(name: str, design: Mapping[str, float] | None = None) -> list[tuple[float, float, float, float, str]]:
    """The DH rows of ``name`` with every design parameter replaced by its value."""
    des = _design(name, design)
    return [(_value(a, des), _value(al, des), _value(d, des), _value(th, des), k) for a, al, d, th, k in
            MECHANISMS[name]["rows"]]


def dh_matrix(a: float, alpha: float, d: float, theta: float) -> np.ndarray:
    """A = Rz(theta) Tz(d) Tx(a) Rx(alpha), as a 4x4 array."""
    ct, st, ca, sa = math.cos(theta), math.sin(theta), math.cos(alpha), math.sin(alpha)
    return np.array([
        [ct, -st * ca, st * sa, a * ct],
        [st, ct * ca, -ct * sa, a * st],
        [0.0, sa, ca, d],
        [0.0, 0.0, 0.0, 1.0],
    ])


def link_matrices(name: str, q: Sequence[float], design: Mapping[str, float] | None = None) -> list[np.ndarray]:
    """[A_1, ..., A_n] at joint values q."""
    rows = numeric_rows(name, design)
    q = np.asarray(q, dtype=float).reshape(-1)
    if q.shape[0] != len(rows):
        raise ValueError(f"{name}: expected {len(rows)} joint values, got {q.shape[0]}")
    out = []
    for (a, alpha, d, th, kind), qi in zip(rows, q, strict=True):
        if kind == "R":
            out.append(dh_matrix(a, alpha, d, th + qi))
        else:
            out.append(dh_matrix(a, alpha, d + qi, th))
    return out


def frames(name: str, q: Sequence[float], design: Mapping[str, float] | None = None) -> list[np.ndarray]:
    """[T_1^0, ..., T_n^0]."""
    out = []
    T = np.eye(4)
    for A in link_matrices(name, q, design):
        T = T @ A
        out.append(T)
    return out


def fk(name: str, q: Sequence[float], design: Mapping[str, float] | None = None) -> np.ndarray:
    """T_n^0 = A_1 ... A_n (4x4)."""
    return frames(name, q, design)[-1]


def geometric_jacobian(name: str, q: Sequence[float], design: Mapping[str, float] | None = None) -> np.ndarray:
    """6 x n geometric Jacobian [J_v; J_w] of the origin of frame n, in base coordinates.

    Column i: revolute [z_{i-1} x (p_n - p_{i-1}); z_{i-1}], prismatic [z_{i-1}; 0]; z_0 = e_z, p_0 = 0.
    """
    Ts = [np.eye(4), *frames(name, q, design)]
    kinds = [r[4] for r in MECHANISMS[name]["rows"]]
    pn = Ts[-1][:3, 3]
    J = np.zeros((6, len(kinds)))
    for i, kind in enumerate(kinds):
        z, p = Ts[i][:3, 2], Ts[i][:3, 3]
        if kind == "R":
            J[:3, i] = np.cross(z, pn - p)
            J[3:, i] = z
        else:
            J[:3, i] = z
    return J


def _vee(S: np.ndarray) -> np.ndarray:
    return np.array([S[2, 1] - S[1, 2], S[0, 2] - S[2, 0], S[1, 0] - S[0, 1]]) / 2.0


def finite_difference_jacobian(name: str, q: Sequence[float], design: Mapping[str, float] | None = None,
                               h: float = 1e-6) -> np.ndarray:
    """Central-difference 6 x n Jacobian from ``fk`` alone: dp/dq and vee(dR/dq R^T)."""
    q = np.asarray(q, dtype=float)
    R = fk(name, q, design)[:3, :3]
    J = np.zeros((6, q.size))
    for i in range(q.size):
        e = np.zeros_like(q)
        e[i] = h
        Tp, Tm = fk(name, q + e, design), fk(name, q - e, design)
        J[:3, i] = (Tp[:3, 3] - Tm[:3, 3]) / (2 * h)
        J[3:, i] = _vee((Tp[:3, :3] - Tm[:3, :3]) / (2 * h) @ R.T)
    return J


def jacobian_fd_error(name: str, q: Sequence[float], design: Mapping[str, float] | None = None,
                      h: float = 1e-6) -> float:
    """max |geometric_jacobian - finite_difference_jacobian| (O(h^2) truncation + O(eps/h) rounding)."""
    return float(np.max(np.abs(geometric_jacobian(name, q, design) - finite_difference_jacobian(name, q, design, h))))


# --------------------------------------------------------------------------------------------
# IK reference: multistart Levenberg-Marquardt
# --------------------------------------------------------------------------------------------


def wrap_angle(x):
    """Wrap to (-pi, pi]."""
    y = np.mod(np.asarray(x, dtype=float) + PI, 2 * PI) - PI  # [-pi, pi)
    return np.where(y <= -PI, y + 2 * PI, y) if np.ndim(y) else (y + 2 * PI if y <= -PI else float(y))


def wrap_joints(name: str, q: Sequence[float]) -> np.ndarray:
    """Revolute joints wrapped to (-pi, pi]; prismatic joints unchanged."""
    q = np.array(q, dtype=float)
    rev = np.array([r[4] == "R" for r in MECHANISMS[name]["rows"]])
    q[rev] = wrap_angle(q[rev])
    return q


def joint_distance(name: str, q1: Sequence[float], q2: Sequence[float]) -> float:
    """Max-norm distance with revolute differences wrapped (so -pi+e and pi-e are 2e apart)."""
    diff = np.asarray(q1, dtype=float) - np.asarray(q2, dtype=float)
    rev = np.array([r[4] == "R" for r in MECHANISMS[name]["rows"]])
    diff[rev] = np.abs(wrap_angle(diff[rev]))
    return float(np.max(np.abs(diff))) if diff.size else 0.0


def pose_error(name: str, q: Sequence[float], T: np.ndarray, design: Mapping[str, float] | None = None) -> float:
    """max |[R | p](q) - [R | p]_T| over the 12 entries."""
    return float(np.max(np.abs(fk(name, q, design)[:3, :] - np.asarray(T, dtype=float)[:3, :])))


def _start_points(name: str, T: np.ndarray, starts: int, seed: int, des: Mapping[str, float]) -> np.ndarray:
    rows = numeric_rows(name, des)
    kinds = np.array([r[4] for r in rows])
    L = float(np.linalg.norm(T[:3, 3])) + sum(abs(r[0]) + abs(r[2]) for r in rows)
    rng = np.random.default_rng(seed)
    X = np.where(kinds == "R", rng.uniform(-PI, PI, (starts, kinds.size)), rng.uniform(-L, L, (starts, kinds.size)))
    X[0] = 0.0
    return X


def ik_reference(name: str, T: np.ndarray, design: Mapping[str, float] | None = None, starts: int | None = None,
                 seed: int = 0, tol: float = 1e-9, dedupe_tol: float = 1e-6,
                 max_solutions: int | None = None) -> list[np.ndarray]:
    """All distinct joint vectors q (revolute wrapped to (-pi, pi]) with pose_error(q, T) <= tol.

    Deterministic for given arguments. Sorted lexicographically. See the module docstring.
    """
    des = _design(name, design)
    T = np.asarray(T, dtype=float)
    target = T[:3, :].reshape(-1)
    kinds = [r[4] for r in MECHANISMS[name]["rows"]]
    n = len(kinds)
    if starts is None:
        starts = DEFAULT_STARTS[name]
    if max_solutions is None:
        max_solutions = MECHANISMS[name]["max_solutions"]

    def fun(q):
        return fk(name, q, des)[:3, :].reshape(-1) - target

    def jac(q):
        Ts = [np.eye(4), *frames(name, q, des)]
        R, pn = Ts[-1][:3, :3], Ts[-1][:3, 3]
        J = np.zeros((12, n))
        for i, kind in enumerate(kinds):
            z, p = Ts[i][:3, 2], Ts[i][:3, 3]
            D = np.zeros((3, 4))
            if kind == "R":
                D[:, :3] = np.cross(z[:, None], R, axis=0)  # [z]x R, column by column
                D[:, 3] = np.cross(z, pn - p)
            else:
                D[:, 3] = z
            J[:, i] = D.reshape(-1)
        return J

    sols: list[np.ndarray] = []
    for x0 in _start_points(name, T, starts, seed, des):
        res = least_squares(fun, x0, jac=jac, method="lm", xtol=1e-15, ftol=1e-15, gtol=1e-15, max_nfev=200 * n)
        if np.max(np.abs(res.fun)) > tol:
            continue
        q = wrap_joints(name, res.x)
        if pose_error(name, q, T, des) > tol:
            continue
        if all(joint_distance(name, q, s) > dedupe_tol for s in sols):
            sols.append(q)
            if len(sols) >= max_solutions:
                break
    sols.sort(key=lambda s: tuple(np.round(s, 9)))
    return sols


def random_joints(name: str, rng: np.random.Generator,
                  prismatic_range: tuple[float, float] = (-0.5, 0.5)) -> np.ndarray:
    """Uniform random joints: angles in (-pi, pi], prismatic in ``prismatic_range``."""
    kinds = [r[4] for r in MECHANISMS[name]["rows"]]
    return np.array([rng.uniform(-PI, PI) if k == "R" else rng.uniform(*prismatic_range) for k in kinds])


def measure_reliability(name: str, trials: int = 1000, seed: int = 12345, starts: int | None = None) -> dict:
    """Run ``ik_reference`` on poses of random joints; count misses.

    A miss is a trial whose result lacks the generating q (within 1e-6) or has fewer than the generic
    ``max_solutions`` entries. Returns {"trials", "missing_q", "short_count", "counts"}.
    """
    rng = np.random.default_rng(seed)
    missing = short = 0
    counts: dict[int, int] = {}
    expected = MECHANISMS[name]["max_solutions"]
    for _ in range(trials):
        q = random_joints(name, rng)
        sols = ik_reference(name, fk(name, q), starts=starts)
        counts[len(sols)] = counts.get(len(sols), 0) + 1
        if not any(joint_distance(name, q, s) <= 1e-6 for s in sols):
            missing += 1
        if len(sols) < expected:
            short += 1
    return {"trials": trials, "missing_q": missing, "short_count": short, "counts": counts}
