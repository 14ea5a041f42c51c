"""Independent numeric reference for the finite-screw 3T2R robots (plain numpy + scipy, nothing from derive/).

A robot is a list of joints (kind, s, r): kind "R" (rotation q about the line through r along the unit s) or "P"
(slide q along s), all at the initial pose. Pose = displacement of the end frame from the initial pose.

* FK: the product of 4x4 matrix exponentials expm([xi_k] q_k) (scipy.linalg.expm of the se(3) matrix of the twist
  xi = (s; r x s) or (0; s)): no Rodrigues, no finite screws, no half-angle tangents.
* Jacobian: spatial twists Ad(T_{<k}) xi_k, moved to the end point (v_p = v_0 + w x p).
* IK: multistart Levenberg-Marquardt (scipy.optimize.least_squares, method "lm", analytic Jacobian) on the 12
  entries of [R | p] - [R_T | p_T] over the joints, with FK by unit quaternions for speed (`fk_fast`, tested equal
  to `fk`); converged points (max entry error <= tol = 1e-10) are wrapped and merged
  within 1e-6. Starts: q = 0, then uniform (angles in (-pi, pi], slides in [-L, L], L = 2 + |p| + the robot's
  scale); stops early after `max_solutions` distinct solutions.

Design vectors follow the generated modules' DESIGN_NAMES order (written out here, not imported).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.linalg import expm
from scipy.optimize import least_squares

# generic real IK solution counts (upper bounds) of each structure
MAX_SOLUTIONS = {"p1p2p3rarb": 1, "rarararbrb": 4}


def axes(name: str, params) -> list[tuple[str, np.ndarray, np.ndarray]]:
    """Joints of robot `name` from its design vector (layout of DESIGN_NAMES)."""
    v = [np.asarray(params[3 * i:3 * i + 3], dtype=float) for i in range(len(params) // 3)]
    zero = np.zeros(3)
    if name == "p1p2p3rarb":  # p1, p2, p3, a, ra, b, rb
        p1, p2, p3, a, ra, b, rb = v
        return [("P", p1, zero), ("P", p2, zero), ("P", p3, zero), ("R", a, ra), ("R", b, rb)]
    if name == "rarararbrb":  # a, r1, r2, r3, b, r4, r5
        a, r1, r2, r3, b, r4, r5 = v
        return [("R", a, r1), ("R", a, r2), ("R", a, r3), ("R", b, r4), ("R", b, r5)]
    raise KeyError(name)


def _hat(kind: str, s, r) -> np.ndarray:
    m = np.zeros((4, 4))
    if kind == "R":
        m[:3, :3] = [[0, -s[2], s[1]], [s[2], 0, -s[0]], [-s[1], s[0], 0]]
        m[:3, 3] = np.cross(r, s)
    else:
        m[:3, 3] = s
    return m


def fk(robot, q) -> np.ndarray:
    T = np.eye(4)
    for (kind, s, r), qk in zip(robot, q, strict=True):
        T = T @ expm(_hat(kind, s, r) * qk)
    return T


def jacobian(robot, q) -> np.ndarray:
    """6 x n geometric Jacobian at the end point: linear velocity rows first."""
    T = np.eye(4)
    cols = []
    for (kind, s, r), qk in zip(robot, q, strict=True):
        R, p = T[:3, :3], T[:3, 3]
        if kind == "R":
            w = R @ s
            v0 = np.cross(R @ r + p, w)  # moment of the current axis about the origin
        else:
            w, v0 = np.zeros(3), R @ s
        cols.append((v0, w))
        T = T @ expm(_hat(kind, s, r) * qk)
    p_end = T[:3, 3]
    return np.array([np.concatenate([v0 + np.cross(w, p_end), w]) for v0, w in cols]).T


def _quat_matrix(s, q) -> np.ndarray:
    """Rotation by q about the unit s through the unit quaternion (cos q/2, sin q/2 s) (LM inner loop only)."""
    w, (x, y, z) = math.cos(q / 2), math.sin(q / 2) * np.asarray(s)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def fk_fast(robot, q) -> tuple[np.ndarray, list]:
    """FK by quaternion rotations, with each joint's current (w, v0) for the analytic LM Jacobian."""
    R, p = np.eye(3), np.zeros(3)
    twists = []
    for (kind, s, r), qk in zip(robot, q, strict=True):
        if kind == "R":
            w = R @ s
            twists.append((w, np.cross(R @ r + p, w)))
            Rk = _quat_matrix(s, qk)
            p = p + R @ (r - Rk @ r)
            R = R @ Rk
        else:
            twists.append((np.zeros(3), R @ s))
            p = p + qk * (R @ s)
    T = np.eye(4)
    T[:3, :3], T[:3, 3] = R, p
    return T, twists


def pose_error(robot, q, T) -> float:
    return float(np.max(np.abs(fk(robot, q)[:3] - np.asarray(T)[:3])))


def _wrap(robot, q) -> np.ndarray:
    return np.array([math.remainder(x, 2 * math.pi) if k == "R" else x for (k, _, _), x in zip(robot, q,
                                                                                               strict=True)])


def distance(robot, a, b) -> float:
    d = np.asarray(a) - np.asarray(b)
    return float(np.max(np.abs([math.remainder(x, 2 * math.pi) if k == "R" else x
                                for (k, _, _), x in zip(robot, d, strict=True)])))


def ik_reference(robot, T, max_solutions: int, starts: int = 60, seed: int = 0, tol: float = 1e-10) -> list:
    T = np.asarray(T, dtype=float)
    rng = np.random.default_rng(seed)
    L = 2.0 + float(np.linalg.norm(T[:3, 3])) + max(float(np.linalg.norm(r)) for _, _, r in robot)
    n = len(robot)

    def res(q):
        return (fk_fast(robot, q)[0][:3] - T[:3]).ravel()

    def jac(q):
        F, tw = fk_fast(robot, q)
        cols = []
        for w, v0 in tw:  # d/dq_k of [R | p] = [w]x [R | p] + [0 | v0]
            d = np.zeros((3, 4))
            d[:, :3] = np.cross(w[:, None], F[:3, :3], axis=0)
            d[:, 3] = np.cross(w, F[:3, 3]) + v0
            cols.append(d.ravel())
        return np.array(cols).T
    found: list[np.ndarray] = []

    def solve_from(q0) -> bool:
        # near a fold LM converges linearly: 1000 evaluations let it reach a simple root 1e-5 from its twin
        sol = least_squares(res, q0, jac=jac, method="lm", xtol=1e-15, ftol=1e-15, gtol=1e-15, max_nfev=1000)
        q = _wrap(robot, sol.x)
        if pose_error(robot, q, T) <= tol and all(distance(robot, q, f) > 1e-6 for f in found):
            found.append(q)
        return len(found) >= max_solutions

    for i in range(starts):
        q0 = np.zeros(n) if i == 0 else np.array([rng.uniform(-math.pi, math.pi) if k == "R" else
                                                  rng.uniform(-L, L) for k, _, _ in robot])
        if solve_from(q0):
            return found
    # A root at a fold (the Jacobian near rank-deficient) has a twin along the weak direction that random starts
    # rarely reach (its basin is as narrow as their separation): start on both sides of each such root.
    for f in list(found):
        _, sv, vt = np.linalg.svd(jac(f))
        if sv[-1] > 1e-3 * sv[0]:
            continue
        for h in (1e-5, 1e-4, 1e-3, 1e-2):
            for sign in (1.0, -1.0):
                if solve_from(f + sign * h * vt[-1]):
                    return found
    return found


def refine(robot, T, q, max_nfev: int = 5000) -> float:
    """The pose error LM reaches from q with tight tolerances: rounding (~1e-15) at a root, simple or double; a point
    where it stalls well above that (2e-11 in a fold's flat valley, Haswell, WRISTKIN_TEST_SEED=481689) is no root,
    though ik_reference's tol admitted it."""
    T = np.asarray(T, dtype=float)

    def res(x):
        return (fk_fast(robot, x)[0][:3] - T[:3]).ravel()
    sol = least_squares(res, np.asarray(q, dtype=float), method="lm", xtol=1e-15, ftol=1e-15, gtol=1e-15,
                        max_nfev=max_nfev)
    return pose_error(robot, sol.x, T)
