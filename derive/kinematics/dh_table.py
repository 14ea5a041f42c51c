"""A serial chain's standard DH table, read from its axes (a product of exponentials) by common normals.

Frame k has its z axis on joint k's axis (k = 0 .. n-1) and its x axis along the common normal from axis k-1 to
axis k; row k carries frame k to frame k+1: A_k = Rz(q_k + theta_k) Tz(d_k) Tx(a_k) Rx(alpha_k). The last frame
is frame n-1 turned by q_{n-1} (its row has a = alpha = d = theta = 0): whatever the end frame adds is the
constant `tool`. Frame 0 sits in the chain's base frame at `frame0`: the identity when axis 0 runs along the base
z axis through the base origin (the usual URDF and DH robot), else a constant the caller carries as the base.

Where the common normal is not unique (parallel axes) it is taken through the previous frame's origin (d = 0);
where two axes coincide the frame is the previous one. A slide (prismatic joint k: A_k = Rz(theta_k)
Tz(d_k + q_k) Tx(a_k) Rx(alpha_k)) moves along a direction, not a line: its axis is placed through the previous
frame's origin (the base origin for the first joint), so that its common normal with the axis before has no length
(a = 0, d = 0) and the table no parameter the robot does not have."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from .poe import Chain
from .same_bits import chain_product, dot, norm, rigid_inverse, unit

# |z_{k} x z_{k+1}| below this: parallel axes (the common normal through the previous origin); a distance below it
# (metres, relative to the chain's size): the axes meet
PARALLEL_TOL = 1e-12


class NoDHTable(ValueError):
    """The chain has no standard DH table this reader builds."""


@dataclass(frozen=True)
class DHTable:
    rows: tuple[tuple[float, float, float, float], ...]  # (a, alpha, d, theta offset) per joint
    frame0: np.ndarray  # 4x4: frame 0 in the chain's base frame
    tool: np.ndarray  # 4x4: the chain's end frame (its home and tool) in frame n at every q
    kinds: tuple[str, ...] = ()  # "R" (q adds to theta) or "P" (q adds to d) per row; () for all revolute

    def fk(self, q) -> np.ndarray:
        """The end frame in the chain's base frame (before the chain's own base transform)."""
        t = self.frame0.copy()
        kinds = self.kinds or ("R",) * len(self.rows)
        for (a, alpha, d, theta), v, kind in zip(self.rows, q, kinds, strict=True):
            t = t @ (link(a, alpha, d + v, theta) if kind == "P" else link(a, alpha, d, theta + v))
        return t @ self.tool


def link(a: float, alpha: float, d: float, theta: float) -> np.ndarray:
    """Rz(theta) Tz(d) Tx(a) Rx(alpha)."""
    ct, st, ca, sa = math.cos(theta), math.sin(theta), math.cos(alpha), math.sin(alpha)
    return np.array([[ct, -st * ca, st * sa, a * ct], [st, ct * ca, -ct * sa, a * st], [0.0, sa, ca, d],
                     [0.0, 0.0, 0.0, 1.0]])


def _unit(v: np.ndarray) -> np.ndarray:
    return unit(v)


def _angle(u: np.ndarray, v: np.ndarray, about: np.ndarray) -> float:
    """The angle turning unit u onto unit v about the unit axis normal to both."""
    return math.atan2(dot(np.cross(u, v), about), dot(u, v))


def standard_dh(chain: Chain) -> DHTable:
    """The chain's standard DH table (module docstring): frame0 @ A_0(q_0) ... A_{n-1}(q_{n-1}) @ tool equals
    chain.fk(q) @ chain.tool at every q (checked by the callers' derivation on sampled joints)."""
    size = max(1.0, float(np.max(np.abs(chain.points))), float(np.max(np.abs(chain.home[:3, 3]))))
    axes = [_unit(np.asarray(h, float)) for h in chain.axes]
    slide = [k == "P" for k in chain.kinds]
    z = axes[0]
    # the base origin's foot on axis 0 (a slide's axis placed through the base origin)
    o = np.zeros(3) if slide[0] else chain.points[0] - dot(chain.points[0], z) * z
    if norm(np.cross(z, [0.0, 0.0, 1.0])) <= PARALLEL_TOL:
        x = np.array([1.0, 0.0, 0.0])  # axis 0 along +-z: x as the base's (frame 0 = the base when on it)
    else:
        x = _unit(np.cross([0.0, 0.0, 1.0], z))
    frame0 = np.eye(4)
    frame0[:3, :3] = np.column_stack([x, np.cross(z, x), z])
    frame0[:3, 3] = o
    rows = []
    for k in range(chain.n - 1):
        zn, rn = axes[k + 1], o if slide[k + 1] else chain.points[k + 1]  # a slide's axis through this origin
        c = np.cross(z, zn)
        w = rn - o
        if norm(c) <= PARALLEL_TOL:  # parallel: the normal through o (d = 0)
            perp = w - dot(w, z) * z
            t = 0.0
            xn = _unit(perp) if norm(perp) > PARALLEL_TOL * size else x
            on = o + perp
        else:  # the feet of the common normal: o + t z on axis k, rn + s zn on axis k+1
            zz = float(dot(z, zn))
            t = (dot(w, z) - zz * dot(w, zn)) / (1.0 - zz * zz)
            s = (zz * dot(w, z) - dot(w, zn)) / (1.0 - zz * zz)
            foot, on = o + t * z, rn + s * zn
            gap = on - foot
            xn = _unit(gap) if norm(gap) > PARALLEL_TOL * size else _unit(c)
        a = float(dot(on - (o + t * z), xn))
        rows.append((a, _angle(z, zn, xn), float(t), _angle(x, xn, z)))
        z, x, o = zn, xn, on
    rows.append((0.0, 0.0, 0.0, 0.0))
    last = np.eye(4)
    last[:3, :3] = np.column_stack([x, np.cross(z, x), z])
    last[:3, 3] = o
    tool = chain_product(rigid_inverse(last), chain.home, chain.tool)
    return DHTable(tuple(rows), frame0, tool, tuple(chain.kinds))


@dataclass(frozen=True)
class RobotTable:
    """A user's robot as the derived stages take it (a robot family's Mechanism.robot_table): its DH table, the
    constant base in the world, its description's own FK (for the proof that the table is the robot) and what
    its own decomposition needs (to say why where the derived stages do not cover it)."""

    name: str
    title: str
    source: str
    rule: str  # how the description composes
    joint_names: tuple[str, ...]
    table: DHTable
    base: np.ndarray  # 4x4: the world frame's base times frame0
    description_fk: Callable  # q -> 4x4, the description's own products, base and tool included
    size: float  # metres: the robot's scale (lengths below LENGTH_ZERO of it are 0)
    ops: frozenset  # its op kinds
    deviation: float  # the description's axes and points off the ideal ones the table is read from (metres, sines)
    api: OwnRobotApi  # what the robot's module offers beyond the verbs, the same whichever way its IK runs
    held: int = -1  # a joint held at a run-time value (a 7-joint arm's free joint), or -1
    # (value, why) per held value at which the IK is undefined (the others a self-motion, or the decomposition's
    # meeting point at infinity): refused within the geometry tolerance
    degenerate_held: tuple = ()
    chain: object = None  # the description's true chain (kinematics/poe.Chain, base and tool included)
    arm_angle: bool = False  # an S-R-S arm whose run-time parameter is its arm angle (kinematics/arm_angle.py)


@dataclass(frozen=True)
class OwnRobotApi:
    """A user robot's module beyond the verbs (runtime/python/own_api.py): the description's joint limits, the
    named branches (labels, and the roles that read them on the ideal chain: its axes, points and home frame,
    before the base) and the words for its decomposition and what it controls."""

    lower: np.ndarray
    upper: np.ndarray
    branches: dict  # name -> (label of the first set, label of the other)
    roles: tuple  # (name, kind, joint, reference data) per branch, on the ideal chain
    ideal_axes: np.ndarray
    ideal_points: np.ndarray
    ideal_home: np.ndarray
    strategy: str  # the planner's decomposition, in words
    controls: str
    base: np.ndarray  # 4x4: the description's base and tool frames (make_design(base=, tool=) replaces them)
    tool: np.ndarray
    scale: float  # metres: the robot's size
    geometry_tol: float  # the planner's tolerance on parallel / meeting axes
    deviation: float  # largest deviation of the description's axes from the ideal ones the stages solve
    calibrated: bool  # that deviation beyond rounding (every set polished on the true chain)
    # the module's FK off the description's own product by at most this (metres and rotation entries): rounding on
    # the true axes; the derived stages' exact geometry adds the description's rounding (from_table)
    description_tol: float
    free_note: str = ""  # how the held joint was chosen when the command named none (said after the strategy)

    @property
    def decomposition(self) -> str:
        """The module's DECOMPOSITION: the strategy, then the free-joint note where there is one."""
        return f"{self.strategy}; {self.free_note}" if self.free_note else self.strategy
