"""Standard Denavit-Hartenberg frames of a revolute chain in POE form, built from its axis lines.

    chain.fk(q) = base_dh . A_1(q_1 + theta0_1) ... A_n(q_n + theta0_n) . end_dh,
    A_i(theta) = Rz(theta) Tz(d_i) Tx(a_i) Rx(alpha_i),

with the last link's (d, a, alpha) folded into end_dh (d_n = a_n = alpha_n = 0). Frame i - 1 has its z axis on
joint i's line, pointing along the POE axis (so the DH angle grows with q); its x axis is the common normal from
line i - 1 to line i (z_{i-2} x z_{i-1} for skew or meeting lines, the perpendicular between parallel lines, any
normal of coincident ones), its origin where that normal meets line i. The elimination of the general 6R
(general6r.py) is written in these parameters.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .poe import Chain


@dataclass(frozen=True)
class DHChain:
    theta0: np.ndarray  # (n,) DH angle at q = 0
    d: np.ndarray  # (n,)
    a: np.ndarray  # (n,)
    alpha: np.ndarray  # (n,)
    base: np.ndarray  # 4x4: the chain's base frame -> DH frame 0
    end: np.ndarray  # 4x4: DH frame n (joint n's frame turned by q_n) -> the chain's end frame

    def link(self, i: int, theta: float) -> np.ndarray:
        return dh_matrix(theta, self.d[i], self.a[i], self.alpha[i])

    def constant_link(self, i: int) -> np.ndarray:
        """Tz(d_i) Tx(a_i) Rx(alpha_i): link i after its turn (A_i = Rz(theta) . this)."""
        return dh_matrix(0.0, self.d[i], self.a[i], self.alpha[i])

    def fk(self, q) -> np.ndarray:
        t = self.base.copy()
        for i, v in enumerate(q):
            t = t @ self.link(i, self.theta0[i] + v)
        return t @ self.end


def dh_matrix(theta: float, d: float, a: float, alpha: float) -> np.ndarray:
    ct, st, ca, sa = math.cos(theta), math.sin(theta), math.cos(alpha), math.sin(alpha)
    return np.array([[ct, -st * ca, st * sa, a * ct],
                     [st, ct * ca, -ct * sa, a * st],
                     [0.0, sa, ca, d],
                     [0.0, 0.0, 0.0, 1.0]])


def _unit(v) -> np.ndarray:
    return np.asarray(v, dtype=float) / float(np.linalg.norm(v))


def _any_normal(z) -> np.ndarray:
    e = np.eye(3)[int(np.argmin(np.abs(z)))]
    return _unit(np.cross(z, e))


def _common_normal(p0, z0, p1, z1, tol: float):
    """(x, foot on line 0, foot on line 1): the common normal's direction from line 0 to line 1 and its feet."""
    c = np.cross(z0, z1)
    w = p1 - p0
    if np.linalg.norm(c) > tol:
        x = _unit(c)
        # feet: p0 + s z0 and p1 + t z1 with their difference along x
        m = np.array([[z0 @ z0, -(z0 @ z1)], [z0 @ z1, -(z1 @ z1)]])
        s, t = np.linalg.solve(m, [w @ z0, w @ z1])
        f0, f1 = p0 + s * z0, p1 + t * z1
        if (f1 - f0) @ x < 0.0:
            x = -x
        return x, f0, f1
    # parallel: the perpendicular from line 0 through p0's foot (d = 0 on this link)
    perp = w - (w @ z0) * z0
    f0 = p0
    if np.linalg.norm(perp) > tol:
        return _unit(perp), f0, f0 + perp
    return _any_normal(z0), f0, f0


def _frame(x, z, o) -> np.ndarray:
    t = np.eye(4)
    t[:3, 0], t[:3, 2] = x, z
    t[:3, 1] = np.cross(z, x)
    t[:3, 3] = o
    return t


def dh_from_chain(chain: Chain, tol: float = 1e-12) -> DHChain:
    """The DH description of a revolute chain (base and tool excluded: chain.fk's frames)."""
    if any(k != "R" for k in chain.kinds):
        raise ValueError("dh_from_chain: revolute joints only")
    n = chain.n
    z = [_unit(a) for a in chain.axes]
    p = [np.asarray(v, dtype=float) for v in chain.points]
    frames = []
    # frame i - 1 (i = 1..n): z on line i; its x is the normal from line i - 1 to line i (frame 0: to line 2)
    x1, f_on_1, _ = _common_normal(p[0], z[0], p[1], z[1], tol) if n > 1 else (_any_normal(z[0]), p[0], p[0])
    frames.append(_frame(x1, z[0], f_on_1))  # frame 0: x along the first common normal, so theta0_1 = 0
    for i in range(1, n):
        x, _, foot = _common_normal(p[i - 1], z[i - 1], p[i], z[i], tol)
        frames.append(_frame(x, z[i], foot))
    # frames[i] has z on line i + 1; the DH frame i (after joint i) is frames[i] for i >= 1, frame 0 = frames[0]
    theta0, d, a, alpha = (np.zeros(n) for _ in range(4))
    for i in range(n - 1):
        rel = np.linalg.inv(frames[i]) @ frames[i + 1]
        theta0[i] = math.atan2(rel[1, 0], rel[0, 0])
        alpha[i] = math.atan2(rel[2, 1], rel[2, 2])
        d[i] = rel[2, 3]
        a[i] = rel[0, 3] * math.cos(theta0[i]) + rel[1, 3] * math.sin(theta0[i])
    base = frames[0]
    dh = DHChain(theta0, d, a, alpha, base, np.eye(4))
    # the last frame turns with q_n about line n; the rest of the end frame is constant
    t = base.copy()
    for i in range(n):
        t = t @ dh.link(i, theta0[i])
    end = np.linalg.inv(t) @ chain.home
    return DHChain(theta0, d, a, alpha, base, end)
