"""Independent numeric reference for serial chains described as URDF, DH tables or POE (numpy + scipy only).

Nothing here imports ``derive/``, ``generated/`` or any symbolic code. Each description format is read by its
own code and evaluated in its own way, so that two formats agreeing is evidence that both files are right:

* ``urdf_fk(path, base, tip)``: parses the URDF XML itself (``xml.etree``) and multiplies 4 x 4 matrices along
  the joint path from ``base`` to ``tip``: per joint ``origin(xyz, rpy) @ motion(axis, q)``, fixed joints
  included (``rpy`` is fixed-axis roll-pitch-yaw, R = Rz(yaw) Ry(pitch) Rx(roll)).
* ``dh_fk(toml_path)``: a ``convention = "standard"`` or ``"modified"`` table, by DH matrix products::

      standard  A_i = Rz(theta_i + dir_i q_i) Tz(d_i) Tx(a_i) Rx(alpha_i)
      modified  A_i = Rx(alpha_{i-1}) Tx(a_{i-1}) Rz(theta_i + dir_i q_i) Tz(d_i)    (row i holds a_{i-1}, alpha_{i-1})
      T(q) = base @ A_1 ... A_n @ tool

  (a prismatic joint adds ``dir_i q_i`` to ``d_i`` instead).
* ``poe_fk(toml_path)``: a ``convention = "poe"`` file, by exponentials of twists::

      T(q) = base @ exp([S_1] q_1) ... exp([S_n] q_n) @ M @ tool

  with S_i = (w_i, -w_i x p_i) for a revolute joint (``axis`` w_i, ``point`` p_i), S_i = (0, axis) for a
  prismatic one, M the ``[home]`` pose; axes, points and home are in the base frame (the frame after
  ``[base]``) with every joint at 0.

Every loader returns a ``Chain``: calling it with a joint vector gives the base -> tip 4 x 4 transform; it also
has ``names``, ``types`` (``"revolute"`` / ``"prismatic"``), ``lower``, ``upper``, ``limits`` (list of
``(lower, upper)``), ``n``, ``axes_points(q)`` (world joint axes and points at ``q``) and ``jacobian(q)`` (the
6 x n geometric Jacobian, rows = tip-point velocity then angular velocity, world frame).

``ik_all`` is a multistart numeric IK that returns every distinct solution it finds: each start is refined by
``scipy.optimize.least_squares(method="lm")`` on the 6-vector pose error (tip position error, rotation vector of
R(q) R_T^T) with the exact Jacobian when the FK callable has ``jacobian`` (finite differences otherwise). The
starts are ``starts`` seeded random joint vectors plus, for every new solution, "flip seeds" next to the
solutions it usually comes with (each joint turned by pi; each run of three joints turned by (pi, negate, pi),
the wrist flip). Measured completeness (``measure_completeness``, 200 random poses per arm from uniform random
joints in (-pi, pi]^6, no joint limits, default ``starts = 20``, no early stop; the true number of real
solutions of each pose from geometry: ``offset_wrist_solution_count`` / ``ur_solution_count``)::

    arm      poses with 8 solutions   all found   every pose's count exact   s / pose (load ~3 on 2 cores)
    kr6      186 / 200                186 / 186   200 / 200 (14 with 4)      0.57
    irb120   200 / 200                200 / 200   200 / 200                  0.53
    tx2_60   200 / 200                200 / 200   200 / 200                  0.51
    lrmate   170 / 200                170 / 170   200 / 200 (30 with 4)      0.51
    ur5e     162 / 200                162 / 162   200 / 200 (2, 4, 6 also)   0.47

so 100 % (918 / 918 poses with 8 solutions), and never a solution more than the geometry allows. Times were
taken with other processes keeping the 2-core machine at load ~3; ``max_solutions=8`` (stop at the generic
count) took 0.16 s per pose under the same load. Without the flip seeds (``flips=False``), random starts alone
needed up to 108 starts on kr6 (60 for 99 % of poses). Also checked with the defaults: iiwa14 with a3 fixed
(40 poses, 8 solutions each, 0.48 s per pose), youbot (40 poses, 2 or 4 solutions, 0.22 s) and tx2_60 (40) give
the same sets as 200 random starts without flip seeds; 100 poses each of small DH chains (1R roll, 3R wrist,
RRPR SCARA, RPP + spherical wrist) give their generic counts (1, 2, 2, 4).
"""

from __future__ import annotations

import ast
import math
import operator
import tomllib
import xml.etree.ElementTree as ET
from collections import deque
from collections.abc import Callable, Iterable, Mapping, Sequence
from pathlib import Path

import numpy as np
from scipy.optimize import least_squares, minimize_scalar

PI = math.pi
TWO_PI = 2.0 * math.pi

DEFAULT_STARTS = 20    # random starts (plus flip seeds); see the measured completeness in the module docstring
POSE_TOL = 1e-10       # a solution reproduces the pose to this (pose_error: metres / radians)
DEDUP_TOL = 1e-6       # two solutions closer than this (max-norm, wrapped angles) are the same


# ----------------------------------------------------------------------------------------------------------
# small transforms
# ----------------------------------------------------------------------------------------------------------

def cross(a, b) -> np.ndarray:
    """a x b for 3-vectors or rows of (k, 3) arrays (np.cross is slow on small arrays)."""
    a = np.asarray(a, dtype=float)
    b = np.asarray(b, dtype=float)
    if a.ndim == 1 and b.ndim == 1:
        return np.array([a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]])
    return np.stack([a[..., 1] * b[..., 2] - a[..., 2] * b[..., 1],
                     a[..., 2] * b[..., 0] - a[..., 0] * b[..., 2],
                     a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]], axis=-1)


def skew(w: Sequence[float]) -> np.ndarray:
    return np.array([[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]])


def rot_x(t: float) -> np.ndarray:
    c, s = math.cos(t), math.sin(t)
    return np.array([[1.0, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1.0]])


def rot_z(t: float) -> np.ndarray:
    c, s = math.cos(t), math.sin(t)
    return np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1.0, 0], [0, 0, 0, 1.0]])


def trans(x: float = 0.0, y: float = 0.0, z: float = 0.0) -> np.ndarray:
    T = np.eye(4)
    T[:3, 3] = (x, y, z)
    return T


def rpy_matrix(rpy: Sequence[float]) -> np.ndarray:
    """Fixed-axis roll-pitch-yaw (URDF): R = Rz(yaw) Ry(pitch) Rx(roll)."""
    r, p, y = (float(v) for v in rpy)
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return np.array([
        [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
        [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
        [-sp, cp * sr, cp * cr],
    ])


def xyz_rpy(xyz: Sequence[float] = (0.0, 0.0, 0.0), rpy: Sequence[float] = (0.0, 0.0, 0.0)) -> np.ndarray:
    T = np.eye(4)
    T[:3, :3] = rpy_matrix(rpy)
    T[:3, 3] = [float(v) for v in xyz]
    return T


def axis_angle(axis: Sequence[float], angle: float) -> np.ndarray:
    """3 x 3 rotation about a unit axis (Rodrigues)."""
    K = skew(axis)
    return np.eye(3) + math.sin(angle) * K + (1.0 - math.cos(angle)) * (K @ K)


def log_rot(R: np.ndarray) -> np.ndarray:
    """Rotation vector (axis * angle, angle in [0, pi]) of a rotation matrix, accurate at small angles."""
    w = np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]])
    s = 0.5 * math.sqrt(w @ w)
    c = 0.5 * (R[0, 0] + R[1, 1] + R[2, 2] - 1.0)
    theta = math.atan2(s, c)
    if theta < 1e-6:
        return (0.5 + theta * theta / 12.0) * w
    if theta < PI - 1e-4:
        return (0.5 * theta / s) * w
    B = 0.5 * (R + R.T) - c * np.eye(3)          # = (1 - c) u u^T
    k = int(np.argmax(np.diag(B)))
    u = B[:, k] / math.sqrt(B[k, k] * (1.0 - c))
    if u @ w < 0:
        u = -u
    return theta * u / np.linalg.norm(u)


def _left_jacobian_inverse(phi: np.ndarray) -> np.ndarray:
    """d log(exp([delta]) R) / d delta at delta = 0, for log(R) = phi."""
    theta = math.sqrt(phi @ phi)
    K = skew(phi)
    if theta < 1e-4:
        coef = 1.0 / 12.0 + theta * theta / 720.0
    else:
        theta_c = min(theta, PI - 1e-6)
        coef = 1.0 / theta_c**2 - (1.0 + math.cos(theta_c)) / (2.0 * theta_c * math.sin(theta_c))
    return np.eye(3) - 0.5 * K + coef * (K @ K)


def pose_error(T1: np.ndarray, T2: np.ndarray) -> float:
    """max(|p1 - p2| in metres, rotation angle between R1 and R2 in radians); accurate down to ~1e-16."""
    dp = float(np.linalg.norm(np.asarray(T1)[:3, 3] - np.asarray(T2)[:3, 3]))
    M = np.asarray(T1)[:3, :3].T @ np.asarray(T2)[:3, :3]
    w = np.array([M[2, 1] - M[1, 2], M[0, 2] - M[2, 0], M[1, 0] - M[0, 1]])
    angle = math.atan2(0.5 * float(np.linalg.norm(w)), 0.5 * (float(np.trace(M)) - 1.0))
    return max(dp, angle)


def wrap_angle(x):
    """Angles wrapped to (-pi, pi]."""
    y = np.mod(np.asarray(x, dtype=float) + PI, TWO_PI) - PI    # [-pi, pi)
    return np.where(y <= -PI, y + TWO_PI, y)


def random_joints(limits: Sequence[tuple[float, float]], rng: np.random.Generator) -> np.ndarray:
    """One joint vector, uniform within each (lower, upper); an infinite bound is replaced by +-pi."""
    lo = np.array([lim[0] if math.isfinite(lim[0]) else -PI for lim in limits], dtype=float)
    hi = np.array([lim[1] if math.isfinite(lim[1]) else PI for lim in limits], dtype=float)
    return lo + (hi - lo) * rng.random(len(limits))


# ----------------------------------------------------------------------------------------------------------
# numbers in the TOML files: a number, or an expression of pi, + - * / and numbers
# ----------------------------------------------------------------------------------------------------------

_BINOPS = {ast.Add: operator.add, ast.Sub: operator.sub, ast.Mult: operator.mul, ast.Div: operator.truediv}
_UNOPS = {ast.UAdd: operator.pos, ast.USub: operator.neg}


def number(value) -> float:
    """A TOML value as a float: an int/float, or a string such as "-pi/2" or "3*pi/4 + 0.1"."""
    if isinstance(value, bool):
        raise ValueError(f"not a number: {value!r}")
    if isinstance(value, (int, float)):
        return float(value)
    if not isinstance(value, str):
        raise ValueError(f"not a number: {value!r}")

    def ev(node):
        if isinstance(node, ast.Expression):
            return ev(node.body)
        if isinstance(node, ast.Constant) and isinstance(node.value, (int, float)) and not isinstance(
                node.value, bool):
            return float(node.value)
        if isinstance(node, ast.Name) and node.id == "pi":
            return PI
        if isinstance(node, ast.BinOp) and type(node.op) in _BINOPS:
            return _BINOPS[type(node.op)](ev(node.left), ev(node.right))
        if isinstance(node, ast.UnaryOp) and type(node.op) in _UNOPS:
            return _UNOPS[type(node.op)](ev(node.operand))
        raise ValueError(f"not an expression of pi, + - * / and numbers: {value!r}")

    return ev(ast.parse(value, mode="eval"))


def _vector(values, length: int = 3) -> list[float]:
    out = [number(v) for v in values]
    if len(out) != length:
        raise ValueError(f"expected {length} numbers, got {values!r}")
    return out


def _frame(table: Mapping | None) -> np.ndarray:
    """[base] / [tool] / [home]-style table (xyz or position, rpy) as a 4 x 4."""
    if not table:
        return np.eye(4)
    xyz = table.get("xyz", table.get("position", (0.0, 0.0, 0.0)))
    return xyz_rpy(_vector(xyz), _vector(table.get("rpy", (0.0, 0.0, 0.0))))


# ----------------------------------------------------------------------------------------------------------
# chains
# ----------------------------------------------------------------------------------------------------------

class Chain:
    """A serial chain's FK. Subclasses implement ``axes_points``; everything else is shared."""

    def __init__(self, name: str, names: Sequence[str], types: Sequence[str], lower: Sequence[float],
                 upper: Sequence[float]):
        for t in types:
            if t not in ("revolute", "prismatic"):
                raise ValueError(f"unknown joint type {t!r}")
        self.name = name
        self.names = tuple(names)
        self.types = tuple(types)
        self.n = len(self.names)
        self.lower = np.array(lower, dtype=float)
        self.upper = np.array(upper, dtype=float)
        self.limits = list(zip(self.lower.tolist(), self.upper.tolist(), strict=True))

    def _q(self, q) -> np.ndarray:
        q = np.asarray(q, dtype=float).reshape(-1)
        if q.shape != (self.n,):
            raise ValueError(f"{self.name}: expected {self.n} joint values, got {q.shape[0]}")
        return q

    def axes_points(self, q) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(T, axes (n x 3), points (n x 3)): the tip pose and every joint's world axis and a point on it."""
        raise NotImplementedError

    def __call__(self, q) -> np.ndarray:
        return self.axes_points(q)[0]

    def jacobian(self, q) -> np.ndarray:
        T, axes, points = self.axes_points(q)
        return _geometric_jacobian(T, axes, points, self.types)

    def __repr__(self) -> str:
        return f"<{type(self).__name__} {self.name}: {self.n} joints>"


def _geometric_jacobian(T, axes, points, types) -> np.ndarray:
    revolute = np.array([t == "revolute" for t in types])
    J = np.zeros((6, len(types)))
    J[:3] = np.where(revolute[:, None], cross(axes, T[:3, 3] - points), axes).T
    J[3:] = np.where(revolute[:, None], axes, 0.0).T
    return J


class UrdfChain(Chain):
    """Path of a URDF from ``base`` to ``tip``: per joint origin @ motion, fixed joints folded as they come."""

    def __init__(self, name, steps, names, types, lower, upper):
        super().__init__(name, names, types, lower, upper)
        self._steps = steps     # [(origin 4x4, kind "fixed"|"revolute"|"prismatic", unit axis, joint index)]
        self._skew = {i: (skew(axis), skew(axis) @ skew(axis)) for _, kind, axis, i in steps if kind == "revolute"}

    def axes_points(self, q):
        q = self._q(q)
        T = np.eye(4)
        axes = np.zeros((self.n, 3))
        points = np.zeros((self.n, 3))
        for origin, kind, axis, i in self._steps:
            T = T @ origin
            if kind == "fixed":
                continue
            axes[i] = T[:3, :3] @ axis
            points[i] = T[:3, 3]
            M = np.eye(4)
            if kind == "revolute":     # Rodrigues: I + sin q K + (1 - cos q) K^2
                K, K2 = self._skew[i]
                M[:3, :3] += math.sin(q[i]) * K + (1.0 - math.cos(q[i])) * K2
            else:
                M[:3, 3] = axis * q[i]
            T = T @ M
        return T, axes, points


def _floats(text: str | None, default: Sequence[float]) -> np.ndarray:
    if text is None:
        return np.array(default, dtype=float)
    values = [float(v) for v in text.split()]
    if len(values) != 3:
        raise ValueError(f"expected 3 numbers, got {text!r}")
    return np.array(values)


def urdf_fk(path, base: str = "base_link", tip: str = "tool0") -> UrdfChain:
    """FK from link ``base`` to link ``tip`` of a URDF file (``base`` must be an ancestor of ``tip``)."""
    root = ET.parse(path).getroot()
    if root.tag != "robot":
        raise ValueError(f"{path}: not a URDF (root <{root.tag}>)")
    links = {link.get("name") for link in root.findall("link")}
    for name in (base, tip):
        if name not in links:
            raise ValueError(f"{path}: no link {name!r}")
    by_child = {}
    for joint in root.findall("joint"):
        child = joint.find("child").get("link")
        if child in by_child:
            raise ValueError(f"{path}: link {child!r} has two parent joints")
        by_child[child] = joint
    path_joints = []
    link = tip
    while link != base:
        if link not in by_child:
            raise ValueError(f"{path}: {base!r} is not an ancestor of {tip!r}")
        joint = by_child[link]
        path_joints.append(joint)
        link = joint.find("parent").get("link")
    path_joints.reverse()

    steps, names, types, lower, upper = [], [], [], [], []
    for joint in path_joints:
        jtype = joint.get("type")
        o = joint.find("origin")
        origin = xyz_rpy(_floats(None if o is None else o.get("xyz"), (0, 0, 0)),
                         _floats(None if o is None else o.get("rpy"), (0, 0, 0)))
        if jtype == "fixed":
            steps.append((origin, "fixed", None, -1))
            continue
        if jtype not in ("revolute", "continuous", "prismatic"):
            raise ValueError(f"{path}: joint {joint.get('name')!r} of type {jtype!r} is not supported")
        if joint.find("mimic") is not None:
            raise ValueError(f"{path}: mimic joint {joint.get('name')!r} is not supported")
        a = joint.find("axis")
        axis = _floats(None if a is None else a.get("xyz"), (1, 0, 0))
        axis = axis / np.linalg.norm(axis)
        kind = "prismatic" if jtype == "prismatic" else "revolute"
        lim = joint.find("limit")
        if jtype == "continuous" or lim is None:
            lo, hi = -math.inf, math.inf
        else:
            lo, hi = float(lim.get("lower", 0.0)), float(lim.get("upper", 0.0))
        steps.append((origin, kind, axis, len(names)))
        names.append(joint.get("name"))
        types.append(kind)
        lower.append(lo)
        upper.append(hi)
    return UrdfChain(root.get("name"), steps, names, types, lower, upper)


def _load_toml(path, conventions: Iterable[str]) -> dict:
    with open(path, "rb") as f:
        data = tomllib.load(f)
    if data.get("family") != "chain":
        raise ValueError(f"{path}: family must be 'chain', got {data.get('family')!r}")
    if data.get("convention") not in conventions:
        raise ValueError(f"{path}: convention {data.get('convention')!r} is not one of {tuple(conventions)}")
    if not data.get("joint"):
        raise ValueError(f"{path}: no [[joint]]")
    return data


def _joint_meta(joints) -> tuple[list, list, list, list]:
    names, types, lower, upper = [], [], [], []
    for j in joints:
        names.append(j["name"])
        types.append(j.get("type", "revolute"))
        lower.append(number(j.get("lower", -math.inf)))
        upper.append(number(j.get("upper", math.inf)))
    return names, types, lower, upper


class DhChain(Chain):
    def __init__(self, name, convention, rows, base, tool, names, types, lower, upper):
        super().__init__(name, names, types, lower, upper)
        self.convention = convention
        self.rows = rows        # [(a, alpha, d, theta, direction)]
        self.base = base
        self.tool = tool

    def axes_points(self, q):
        q = self._q(q)
        T = self.base.copy()
        axes = np.zeros((self.n, 3))
        points = np.zeros((self.n, 3))
        for i, ((a, alpha, d, theta, direction), kind) in enumerate(zip(self.rows, self.types, strict=True)):
            if kind == "revolute":
                th, dd = theta + direction * q[i], d
            else:
                th, dd = theta, d + direction * q[i]
            ct, st, ca, sa = math.cos(th), math.sin(th), math.cos(alpha), math.sin(alpha)
            if self.convention == "standard":
                axes[i] = direction * T[:3, 2]
                points[i] = T[:3, 3]
                # Rz(th) Tz(d) Tx(a) Rx(alpha)
                A = np.array([[ct, -st * ca, st * sa, a * ct],
                              [st, ct * ca, -ct * sa, a * st],
                              [0.0, sa, ca, dd],
                              [0.0, 0.0, 0.0, 1.0]])
            else:
                # Rx(alpha) Tx(a): the frame on axis i before the joint's own motion
                axes[i] = direction * (T[:3, :3] @ (0.0, -sa, ca))
                points[i] = T[:3, 3] + a * T[:3, 0]
                # Rx(alpha) Tx(a) Rz(th) Tz(d)
                A = np.array([[ct, -st, 0.0, a],
                              [st * ca, ct * ca, -sa, -sa * dd],
                              [st * sa, ct * sa, ca, ca * dd],
                              [0.0, 0.0, 0.0, 1.0]])
            T = T @ A
        return T @ self.tool, axes, points


def dh_fk(path) -> DhChain:
    """FK of a ``family = "chain"`` DH table (``convention = "standard"`` or ``"modified"``)."""
    data = _load_toml(path, ("standard", "modified"))
    rows = []
    for j in data["joint"]:
        direction = number(j.get("direction", 1))
        if direction not in (1.0, -1.0):
            raise ValueError(f"{path}: joint {j['name']!r}: direction must be +1 or -1")
        rows.append((number(j.get("a", 0.0)), number(j.get("alpha", 0.0)), number(j.get("d", 0.0)),
                     number(j.get("theta", 0.0)), direction))
    return DhChain(data["name"], data["convention"], rows, _frame(data.get("base")), _frame(data.get("tool")),
                   *_joint_meta(data["joint"]))


def twist_exp(w: np.ndarray, v: np.ndarray, theta: float) -> np.ndarray:
    """exp([S] theta) of a twist S = (w, v): |w| = 1 (revolute) or w = 0 (prismatic, |v| = 1)."""
    T = np.eye(4)
    if not w.any():
        T[:3, 3] = v * theta
        return T
    K = skew(w)
    K2 = K @ K
    s, c = math.sin(theta), math.cos(theta)
    T[:3, :3] = np.eye(3) + s * K + (1.0 - c) * K2
    T[:3, 3] = (theta * np.eye(3) + (1.0 - c) * K + (theta - s) * K2) @ v
    return T


class PoeChain(Chain):
    def __init__(self, name, twists, home, base, tool, names, types, lower, upper):
        super().__init__(name, names, types, lower, upper)
        self.twists = twists    # [(w, v)] in the base frame at home
        self.home = home
        self.base = base
        self.tool = tool
        # per joint: K = [w], K^2, K v, K^2 v and the point w x v = p - (w . p) w on a revolute axis
        self._terms = []
        for w, v in twists:
            K = skew(w)
            K2 = K @ K
            self._terms.append((K, K2, K @ v, K2 @ v, cross(w, v)))

    def axes_points(self, q):
        q = self._q(q)
        P = self.base.copy()
        axes = np.zeros((self.n, 3))
        points = np.zeros((self.n, 3))
        for i, ((w, v), (K, K2, Kv, K2v, on_axis)) in enumerate(zip(self.twists, self._terms, strict=True)):
            R = P[:3, :3]
            E = np.eye(4)
            t = q[i]
            if self.types[i] == "revolute":
                axes[i] = R @ w
                points[i] = R @ on_axis + P[:3, 3]
                # exp([S] t) = [I + sin t K + (1 - cos t) K^2,  (t I + (1 - cos t) K + (t - sin t) K^2) v]
                s, c = math.sin(t), math.cos(t)
                E[:3, :3] += s * K + (1.0 - c) * K2
                E[:3, 3] = t * v + (1.0 - c) * Kv + (t - s) * K2v
            else:
                axes[i] = R @ v
                E[:3, 3] = t * v
            P = P @ E
        return P @ self.home @ self.tool, axes, points


def poe_fk(path) -> PoeChain:
    """FK of a ``family = "chain"``, ``convention = "poe"`` file (axes and points at home, base frame)."""
    data = _load_toml(path, ("poe",))
    names, types, lower, upper = _joint_meta(data["joint"])
    twists = []
    for j, kind in zip(data["joint"], types, strict=True):
        axis = np.array(_vector(j["axis"]))
        norm = np.linalg.norm(axis)
        if abs(norm - 1.0) > 1e-9:
            raise ValueError(f"{path}: joint {j['name']!r}: axis is not a unit vector (|axis| = {norm!r})")
        axis = axis / norm
        if kind == "revolute":
            point = np.array(_vector(j["point"]))
            twists.append((axis, -cross(axis, point)))
        else:
            twists.append((np.zeros(3), axis))
    if "home" not in data:
        raise ValueError(f"{path}: no [home]")
    return PoeChain(data["name"], twists, _frame(data["home"]), _frame(data.get("base")),
                    _frame(data.get("tool")), names, types, lower, upper)


def load(path, base: str = "base_link", tip: str = "tool0") -> Chain:
    """``urdf_fk`` for ``*.urdf``, else ``dh_fk`` or ``poe_fk`` by the file's ``convention``."""
    path = Path(path)
    if path.suffix == ".urdf":
        return urdf_fk(path, base, tip)
    with open(path, "rb") as f:
        convention = tomllib.load(f).get("convention")
    return poe_fk(path) if convention == "poe" else dh_fk(path)


def finite_difference_jacobian(fk: Callable, q, h: float = 1e-7) -> np.ndarray:
    """Central differences of the tip pose (position; rotation vector of R(q + h e_i) R(q - h e_i)^T / 2h)."""
    q = np.asarray(q, dtype=float)
    J = np.zeros((6, len(q)))
    for i in range(len(q)):
        e = np.zeros(len(q))
        e[i] = h
        Tp, Tm = fk(q + e), fk(q - e)
        J[:3, i] = (Tp[:3, 3] - Tm[:3, 3]) / (2 * h)
        J[3:, i] = log_rot(Tp[:3, :3] @ Tm[:3, :3].T) / (2 * h)
    return J


# ----------------------------------------------------------------------------------------------------------
# multistart IK
# ----------------------------------------------------------------------------------------------------------

def _in_limits(q: np.ndarray, types, limits, tol: float = 1e-9) -> np.ndarray | None:
    """q with each revolute value moved by a multiple of 2 pi into its limits (the wrapped value kept when it
    is inside), or None when some joint cannot be."""
    out = q.copy()
    for i, (kind, (lo, hi)) in enumerate(zip(types, limits, strict=True)):
        x = out[i]
        if lo - tol <= x <= hi + tol:
            continue
        if kind != "revolute":
            return None
        k = math.ceil((lo - tol - x) / TWO_PI)
        if x + k * TWO_PI > hi + tol:
            return None
        out[i] = x + k * TWO_PI
    return out


def _same(q1: np.ndarray, q2: np.ndarray, revolute: np.ndarray, tol: float) -> bool:
    d = q1 - q2
    d = np.where(revolute, wrap_angle(d), d)
    return float(np.max(np.abs(d))) < tol


def _flip_seeds(q: np.ndarray, free: np.ndarray, revolute: np.ndarray) -> list[np.ndarray]:
    """Starts near the solutions a found one usually comes with: each free revolute joint turned by pi, and
    each run of three consecutive free revolute joints turned by (pi, negate, pi) -- the identity
    Rx(a + pi) Ry(-b) Rx(c + pi) = Rx(a) Ry(b) Rx(c) of a wrist whose first and third axes line up."""
    seeds = []
    movable = [i for i in free if revolute[i]]
    for i in movable:
        s = q.copy()
        s[i] += PI
        seeds.append(s)
    for i in movable:
        if i + 1 in movable and i + 2 in movable:
            s = q.copy()
            s[i] += PI
            s[i + 1] = -s[i + 1]
            s[i + 2] += PI
            seeds.append(s)
    return seeds


def ik_all(fk: Callable, n: int, T: np.ndarray, limits: Sequence[tuple[float, float]] | None = None,
           starts: int = DEFAULT_STARTS, fixed: Mapping[int, float] | None = None, seed: int = 0,
           max_solutions: int | None = None, tol: float = POSE_TOL, dedup: float = DEDUP_TOL,
           max_nfev: int = 60, flips: bool = True) -> list[np.ndarray]:
    """Every distinct IK solution found for the pose ``T`` of the n-joint chain ``fk`` (q -> 4 x 4).

    ``starts`` deterministic random starts (``seed``): q = 0, then uniform random joint vectors (revolute joints
    in (-pi, pi], or within their limits when ``limits`` are given and narrower than a turn; prismatic joints
    within ``limits``, or ``fk.limits``, or [-1, 1] when all are infinite); with ``flips`` (default), every new
    solution also queues the seeds of ``_flip_seeds`` (run before the next random start). Each start is refined
    by Levenberg-Marquardt on the 6-vector pose error ``[p(q) - p_T, log(R(q) R_T^T)]`` over the free joints
    (every joint not in ``fixed = {index: value}``; a chain with more than 6 joints needs ``fixed`` so that at
    most 6 are free; a chain with fewer than 6 joints solves the 6 equations in the least-squares sense, so
    only a reachable pose has solutions). A converged point is kept when ``pose_error(fk(q), T) < tol``
    (1e-10); revolute values are wrapped to (-pi, pi]; solutions closer than ``dedup`` (1e-6, max-norm of
    wrapped differences) are merged. With ``limits``, a solution is kept only if every joint can be brought
    inside its limits (revolute joints by multiples of 2 pi; the in-limit value is returned, which is the
    wrapped one whenever that is inside). ``max_solutions`` stops early once that many are found. Returns the
    solutions (full joint vectors, fixed joints included) sorted lexicographically. Completeness and time:
    module docstring.
    """
    T = np.asarray(T, dtype=float)
    fixed = dict(fixed or {})
    for i in fixed:
        if not 0 <= i < n:
            raise ValueError(f"fixed joint index {i} out of range for {n} joints")
    free = np.array([i for i in range(n) if i not in fixed], dtype=int)
    if len(free) > 6:
        raise ValueError(f"{n} joints with {len(free)} free: pass fixed={{index: value}} to leave at most 6 free")
    if len(free) == 0:
        raise ValueError("no free joint")
    types = tuple(getattr(fk, "types", None) or ("revolute",) * n)
    if len(types) != n:
        raise ValueError(f"fk has {len(types)} joints, n = {n}")
    revolute = np.array([t == "revolute" for t in types])
    chain_limits = getattr(fk, "limits", None)

    lo = np.full(n, -PI)
    hi = np.full(n, PI)
    for i in range(n):
        lim = limits[i] if limits is not None else (chain_limits[i] if chain_limits is not None and
                                                     not revolute[i] else (-math.inf, math.inf))
        finite = math.isfinite(lim[0]) and math.isfinite(lim[1])
        if revolute[i]:
            if finite and lim[1] - lim[0] < TWO_PI:
                lo[i], hi[i] = lim
        elif finite:
            lo[i], hi[i] = lim
        else:
            lo[i], hi[i] = -1.0, 1.0

    q_full = np.zeros(n)
    for i, v in fixed.items():
        q_full[i] = v
    R_T = T[:3, :3]
    p_T = T[:3, 3]
    has_jacobian = callable(getattr(fk, "jacobian", None)) and callable(getattr(fk, "axes_points", None))
    cache: dict = {}

    def full(x):
        q = q_full.copy()
        q[free] = x
        return q

    def evaluate(x):
        key = x.tobytes()
        if cache.get("key") != key:
            q = full(x)
            if has_jacobian:
                Tq, axes, points = fk.axes_points(q)
            else:
                Tq, axes, points = np.asarray(fk(q), dtype=float), None, None
            phi = log_rot(Tq[:3, :3] @ R_T.T)
            cache.update(key=key, T=Tq, axes=axes, points=points, phi=phi)
        return cache

    def fun(x):
        c = evaluate(x)
        return np.concatenate([c["T"][:3, 3] - p_T, c["phi"]])

    def jac(x):
        c = evaluate(x)
        J = _geometric_jacobian(c["T"], c["axes"], c["points"], types)[:, free]
        J[3:] = _left_jacobian_inverse(c["phi"]) @ J[3:]
        return J

    found: list[np.ndarray] = []     # returned solutions (within the limits, if any)
    seen: list[np.ndarray] = []      # every distinct solution reached, wrapped (flip seeds start from these)

    def search(budget):
        """LM from q = 0, the random starts and the flip seeds of every new solution, `budget` evaluations each."""
        rng = np.random.default_rng(seed)
        flip_seeds: deque[np.ndarray] = deque()
        k = 0
        while flip_seeds or k < starts:
            if flip_seeds:
                x0 = flip_seeds.popleft()
            else:
                x0 = (np.clip(np.zeros(n), lo, hi) if k == 0 else lo + (hi - lo) * rng.random(n))[free]
                k += 1
            try:
                res = least_squares(fun, x0, jac=jac if has_jacobian else "2-point", method="lm",
                                    xtol=1e-15, ftol=1e-15, gtol=1e-15, max_nfev=budget)
            except (ValueError, np.linalg.LinAlgError):
                continue
            q = full(res.x)
            q = np.where(revolute, wrap_angle(q), q)
            if pose_error(np.asarray(fk(q), dtype=float), T) >= tol:
                continue
            if any(_same(q, s, revolute, dedup) for s in seen):
                continue
            seen.append(q)
            if flips:
                for seed_q in _flip_seeds(q, free, revolute):
                    flip_seeds.append(seed_q[free])
            if limits is not None:
                q = _in_limits(q, types, limits)
                if q is None:
                    continue
            found.append(q)
            if max_solutions is not None and len(found) >= max_solutions:
                return

    # a pose where no start converges within max_nfev is searched again with four times the budget: near a
    # singularity LM converges linearly (a KR 6 with its wrist centre 0.17 mm from axis 1, sigma_min 1e-4, seed
    # 88213: 0 of 8 found from 20 starts at 60 evaluations, 8 of 8 at 200)
    search(max_nfev)
    if not seen:
        search(4 * max_nfev)
    return sorted(found, key=lambda s: tuple(s.tolist()))


# ----------------------------------------------------------------------------------------------------------
# how many real IK solutions a pose has, by geometry (the truth ik_all is measured against)
# ----------------------------------------------------------------------------------------------------------

def family_solutions(fk: Callable, T: np.ndarray, start, hold: int, points: int = 360,
                     tol: float = 1e-13) -> list[np.ndarray]:
    """The solutions along a one-parameter family of near solutions through joints ``start`` of a 6-joint chain
    (a calibrated arm's broken self-motion): joint ``hold`` at ``points`` values round the circle, the other five
    fitted by Levenberg-Marquardt with it held (each from the fit before); each local minimum of the fit's pose
    residual (max entry of [R | p]) refined by a bounded 1-D minimisation over the held joint within a grid step,
    kept when its residual is within ``tol``. A grid ten times finer than the module's scan and no search along a
    near-null direction: an independent reading of the same question."""
    T = np.asarray(T, dtype=float)
    start = np.asarray(start, dtype=float)

    def fit(v, x0):
        def res(x):
            Tq = fk(np.insert(x, hold, v))
            return np.concatenate([(Tq[:3, :3] - T[:3, :3]).ravel(), Tq[:3, 3] - T[:3, 3]])
        sol = least_squares(res, x0, xtol=1e-15, ftol=1e-15, gtol=1e-15, method="lm", max_nfev=400)
        return sol.x, float(np.max(np.abs(res(sol.x))))

    step = 2.0 * PI / points
    grid = start[hold] + step * np.arange(points)
    x, fits = np.delete(start, hold), []
    for v in grid:
        x, e = fit(v, x)
        fits.append((e, x))
    out = []
    for i, (e, x) in enumerate(fits):
        if not (e <= fits[i - 1][0] and e <= fits[(i + 1) % points][0]):
            continue
        best = minimize_scalar(lambda v, x=x: fit(v, x)[1], bounds=(grid[i] - step, grid[i] + step),
                               method="bounded", options={"xatol": 1e-12})
        xv, ev = fit(best.x, x)
        if ev <= tol:
            out.append(wrap_angle(np.insert(xv, hold, best.x)))
    return out


def offset_wrist_solution_count(T: np.ndarray, d1: float, a1: float, a2: float, a3: float, d4: float,
                                d6: float, lateral: float = 0.0) -> int:
    """Real IK solutions (no joint limits) of a 6R arm with a spherical wrist (KUKA / ABB / FANUC / Staubli
    type), at a generic pose ``T`` of its flange (z out of the flange) in its base frame (axis 1 = z through
    the origin): axis 2 at height d1 and a1 off axis 1, upper arm a2, elbow offset a3, forearm d4, wrist
    centre to flange d6, ``lateral`` offset of the forearm along axis 2 (Staubli's 20 mm). The wrist centre
    must be within [|a2 - L3|, a2 + L3] (L3 = hypot(a3, d4)) of axis 2, with the shoulder facing it (front)
    or turned away (back); each reachable shoulder has 2 elbows and each arm pose 2 wrists."""
    c = T[:3, 3] - d6 * T[:3, 2]
    rho2 = c[0] ** 2 + c[1] ** 2 - lateral**2
    if rho2 <= 0.0:
        return 0
    rho, h = math.sqrt(rho2), c[2] - d1
    L3 = math.hypot(a3, d4)
    count = 0
    for shoulder in (rho - a1, rho + a1):
        if abs(a2 - L3) < math.hypot(shoulder, h) < a2 + L3:
            count += 4
    return count


def ur_solution_count(T: np.ndarray, d1: float, a2: float, a3: float, d4: float, d5: float, d6: float) -> int:
    """Real IK solutions (no joint limits) of a UR-type 6R arm (axes 2, 3, 4 parallel; standard DH d1, a2, a3,
    d4, d5, d6) at a generic flange pose ``T`` in its base frame (axis 1 = z through the origin). The common
    direction u of axes 2-4 is horizontal with o5 . u = d4 (o5 = flange - d6 z6: 0 or 2 choices); axis 5
    is perpendicular to u and to axis 6: z4 = +-(u x z6) / |u x z6|; the 2R elbow then has 2 solutions when
    |o5 - d5 z4 - d4 u - (0, 0, d1)| lies strictly between ||a2| - |a3|| and |a2| + |a3|."""
    z6 = T[:3, 2]
    o5 = T[:3, 3] - d6 * z6
    rho = math.hypot(o5[0], o5[1])
    if rho <= abs(d4):
        return 0
    phi = math.atan2(o5[1], o5[0])
    delta = math.acos(d4 / rho)
    count = 0
    for angle in (phi + delta, phi - delta):       # u = (cos, sin, 0) with o5 . u = d4
        u = np.array([math.cos(angle), math.sin(angle), 0.0])
        w = cross(u, z6)
        w = w / np.linalg.norm(w)
        for z4 in (w, -w):
            r = np.linalg.norm(o5 - d5 * z4 - d4 * u - np.array([0.0, 0.0, d1]))
            if abs(abs(a2) - abs(a3)) < r < abs(a2) + abs(a3):
                count += 2
    return count


def measure_completeness(fk: Chain, count: Callable[[np.ndarray], int], poses: int = 200, seed: int = 2024,
                         starts: int = DEFAULT_STARTS, max_solutions: int | None = None) -> dict:
    """Random poses (uniform joints in (-pi, pi]^n): how often ``ik_all`` (no limits) finds every real solution
    (``count(T)``, e.g. ``offset_wrist_solution_count`` with the arm's numbers); also split out the poses with
    8 solutions, the mean time per pose and the poses it missed (the numbers in the module docstring)."""
    import time

    rng = np.random.default_rng(seed)
    complete = complete8 = poses8 = 0
    elapsed, missed = 0.0, []
    for k in range(poses):
        q = rng.uniform(-PI, PI, fk.n)
        T = fk(q)
        truth = count(T)
        t0 = time.perf_counter()
        sols = ik_all(fk, fk.n, T, starts=starts, seed=k, max_solutions=max_solutions)
        elapsed += time.perf_counter() - t0
        ok = len(sols) == truth
        complete += ok
        poses8 += truth == 8
        complete8 += ok and truth == 8
        if not ok:
            missed.append((k, truth, len(sols)))
    return {"poses": poses, "complete": complete, "poses_with_8": poses8, "complete_with_8": complete8,
            "seconds_per_pose": elapsed / poses, "missed": missed}
