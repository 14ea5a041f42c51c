"""A serial chain in product-of-exponentials form, the one shape every description becomes.

    T(q) = base . exp(S_1 q_1) ... exp(S_n q_n) . M . tool

Joint i turns about (or slides along) the unit axis `axes[i]` through `points[i]`, both in the base frame with
every joint at zero; `home` is the end frame at zero. Joint values are the user's: a description's offsets
(DH theta / d) are folded into the home geometry and its directions into the axes, so q = 0 is the
description's zero and a positive q turns the way the description says. `base` and `tool` are kept apart
because the generated solvers let a user change them at run time.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from .same_bits import chain_product, dot, matmul, rigid_inverse, unit


def rot(axis, angle: float) -> np.ndarray:
    """Rotation about a unit axis (Rodrigues)."""
    k = np.asarray(axis, dtype=float)
    kx = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])
    return np.eye(3) + math.sin(angle) * kx + (1.0 - math.cos(angle)) * matmul(kx, kx)


def rpy_matrix(rpy) -> np.ndarray:
    """URDF's fixed-axis roll-pitch-yaw: R = Rz(yaw) Ry(pitch) Rx(roll)."""
    r, p, y = rpy
    return chain_product(rot((0, 0, 1), y), rot((0, 1, 0), p), rot((1, 0, 0), r))


def transform(rotation=None, position=None) -> np.ndarray:
    t = np.eye(4)
    if rotation is not None:
        t[:3, :3] = rotation
    if position is not None:
        t[:3, 3] = position
    return t


def screw(kind: str, axis, point, q: float) -> np.ndarray:
    """exp(S q) as a 4x4: rotation about the line (axis, point) or translation along axis."""
    if kind == "P":
        return transform(None, np.asarray(axis) * q)
    r = rot(axis, q)
    return transform(r, np.asarray(point) - matmul(r, point))


@dataclass(frozen=True)
class Chain:
    name: str
    joint_names: tuple[str, ...]
    kinds: tuple[str, ...]  # "R" revolute, "P" prismatic
    axes: np.ndarray  # (n, 3) unit
    points: np.ndarray  # (n, 3) a point on each axis (the foot from the base origin for revolute joints)
    home: np.ndarray  # 4x4 end frame at q = 0, before the tool transform
    lower: np.ndarray = field(default=None)  # (n,) joint limits in the user's units, -inf/inf when none
    upper: np.ndarray = field(default=None)
    base: np.ndarray = field(default_factory=lambda: np.eye(4))
    tool: np.ndarray = field(default_factory=lambda: np.eye(4))
    source_format: str = "poe"  # standard | modified | poe | urdf

    def __post_init__(self):
        n = len(self.kinds)
        object.__setattr__(self, "axes", np.asarray(self.axes, dtype=float).reshape(n, 3))
        object.__setattr__(self, "points", np.asarray(self.points, dtype=float).reshape(n, 3))
        if self.lower is None:
            object.__setattr__(self, "lower", np.full(n, -np.inf))
        if self.upper is None:
            object.__setattr__(self, "upper", np.full(n, np.inf))

    @property
    def n(self) -> int:
        return len(self.kinds)

    def fk(self, q) -> np.ndarray:
        """The end frame without base and tool (the planner's chain)."""
        t = np.eye(4)
        for kind, a, p, v in zip(self.kinds, self.axes, self.points, q, strict=True):
            t = t @ screw(kind, a, p, v)
        return t @ self.home

    def fk_full(self, q) -> np.ndarray:
        return self.base @ self.fk(q) @ self.tool

    def jacobian(self, q) -> np.ndarray:
        """Geometric Jacobian of fk_full (linear velocity of the end frame's origin first, base frame)."""
        t = self.base.copy()
        cols = []
        for kind, a, p, v in zip(self.kinds, self.axes, self.points, q, strict=True):
            w = t[:3, :3] @ a
            o = t[:3, :3] @ p + t[:3, 3]
            cols.append((w, o, kind))
            t = t @ screw(kind, a, p, v)
        end = (t @ self.home @ self.tool)[:3, 3]
        out = np.zeros((6, self.n))
        for i, (w, o, kind) in enumerate(cols):
            out[:, i] = np.concatenate([w, np.zeros(3)]) if kind == "P" else np.concatenate([np.cross(w, end - o), w])
        return out


def normalised(chain: Chain) -> Chain:
    """Unit axes, and each revolute axis's point moved to its foot from the base origin (canonical data)."""
    axes = np.array([unit(a) for a in chain.axes])
    points = np.array([p - dot(p, a) * a if k == "R" else np.zeros(3)
                       for k, a, p in zip(chain.kinds, axes, chain.points, strict=True)])
    return replace(chain, axes=axes, points=points)


def from_frames(name, joint_names, kinds, frames_axes, home, **kw) -> Chain:
    """Axes given as (axis, point) pairs in the base frame at zero."""
    axes = [a for a, _ in frames_axes]
    points = [p for _, p in frames_axes]
    return normalised(Chain(name, tuple(joint_names), tuple(kinds), np.array(axes), np.array(points), home, **kw))


def dh_link(convention: str, a: float, alpha: float, d: float, theta: float) -> np.ndarray:
    """One DH link transform: standard Rz(theta) Tz(d) Tx(a) Rx(alpha); modified Rx(alpha) Tx(a) Rz(theta) Tz(d)."""
    rz = transform(rot((0, 0, 1), theta))
    rx = transform(rot((1, 0, 0), alpha))
    tz, tx = transform(None, (0, 0, d)), transform(None, (a, 0, 0))
    return chain_product(rz, tz, tx, rx) if convention == "standard" else chain_product(rx, tx, rz, tz)


def from_dh(name, convention, rows, **kw) -> Chain:
    """rows: (joint name, kind, a, alpha, d, theta, direction) with theta (revolute) or d (prismatic) the offset
    at q = 0 and direction +1 / -1 the sign of q in it."""
    t = np.eye(4)
    pairs = []
    for _name, _kind, a, alpha, d, theta, direction in rows:
        if convention == "standard":
            pairs.append((direction * t[:3, 2], t[:3, 3].copy()))
            t = matmul(t, dh_link(convention, a, alpha, d, theta))
        else:
            t = matmul(t, dh_link(convention, a, alpha, d, theta))
            pairs.append((direction * t[:3, 2], t[:3, 3].copy()))
    return from_frames(name, [r[0] for r in rows], [r[1] for r in rows], pairs, t, source_format=convention, **kw)


def reduce_free(chain: Chain, index: int, value: float) -> Chain:
    """The chain with joint `index` held at `value` (a redundant arm's free joint): the joints after it and the
    home frame move rigidly with it."""
    m = screw(chain.kinds[index], chain.axes[index], chain.points[index], value)
    keep = [i for i in range(chain.n) if i != index]
    axes = np.array([matmul(m[:3, :3], chain.axes[i]) if i > index else chain.axes[i] for i in keep])
    points = np.array([matmul(m[:3, :3], chain.points[i]) + m[:3, 3] if i > index else chain.points[i]
                       for i in keep])
    return normalised(replace(chain, joint_names=tuple(chain.joint_names[i] for i in keep),
                              kinds=tuple(chain.kinds[i] for i in keep), axes=axes, points=points,
                              home=matmul(m, chain.home), lower=chain.lower[keep], upper=chain.upper[keep]))


def reverse(chain: Chain) -> Chain:
    """The chain read from the tool to the base: T^-1 = M^-1 exp(-S_n q_n) ... exp(-S_1 q_1) becomes a chain in
    the home tool frame whose joint k is joint n-1-k with its value negated (axes flipped instead)."""
    minv = rigid_inverse(chain.home)
    r, t = minv[:3, :3], minv[:3, 3]
    idx = list(range(chain.n))[::-1]
    axes = np.array([-matmul(r, chain.axes[i]) for i in idx])
    points = np.array([matmul(r, chain.points[i]) + t for i in idx])
    return normalised(replace(chain, joint_names=tuple(chain.joint_names[i] for i in idx),
                              kinds=tuple(chain.kinds[i] for i in idx), axes=axes, points=points, home=minv,
                              lower=chain.lower[idx], upper=chain.upper[idx]))
