"""Independent numeric reference for the underactuated 3-DOF spherical wrist (3 branches).

This module is deliberately built *differently* from the closed-form derivation in ``derive/``:
it uses only rotation matrices, geometric constructions (cones and circles on the unit sphere)
and numeric root finding (dense sampling, ``scipy.optimize.brentq``, bounded 1-D minimisation,
Gauss-Newton on SO(3), multistart ``least_squares``). No polynomial elimination is used.

Geometry (all joint axes pass through the centre O; ``e_z = (0, 0, 1)``)::

    B_i      = Rz(delta_i) Rx(pi - beta1)                  base frame of branch i
    Z_i1     = B_i e_z                                      base (motor) axis
    Z_i2(t)  = B_i Rz(t) Rx(alpha1) e_z                     middle axis, t = theta_i (exterior angle)
    p_i      = Rz(delta_i) Rx(beta2) e_z                    platform axis, platform frame
    Z_i3     = R p_i                                        platform axis, world frame
    R        = Rz(psi) Rx(theta) Rz(phi)                    ZXZ Euler angles
    loop i:    Z_i2(theta_i) . (R p_i) = cos(alpha2)

Everything is deterministic: sampling grids are fixed and random starts use fixed seeds.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import brentq, least_squares, minimize_scalar

TWO_PI = 2.0 * math.pi


# --------------------------------------------------------------------------------------------
# Design
# --------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class WristDesign:
    """Design parameters in radians; ``deltas`` are the branch azimuths delta_1..3."""

    alpha1: float
    alpha2: float
    beta1: float
    beta2: float
    deltas: tuple[float, float, float] = (0.0, TWO_PI / 3.0, 2.0 * TWO_PI / 3.0)

    @property
    def alpha3(self) -> float:
        """Angle between two platform axes p_i and p_j (i != j), from the vectors themselves."""
        p = platform_axes(self)
        return float(np.arccos(np.clip(p[0] @ p[1], -1.0, 1.0)))


PAPER_DESIGN = WristDesign(
    alpha1=math.radians(60.0),
    alpha2=math.radians(60.0),
    beta1=math.radians(30.0),
    beta2=math.radians(43.89),
)


def as_design(design: WristDesign | Mapping[str, float] | None) -> WristDesign:
    """Accept a ``WristDesign``, a mapping with alpha1/alpha2/beta1/beta2 (radians) or None (paper)."""
    if design is None:
        return PAPER_DESIGN
    if isinstance(design, WristDesign):
        return design
    kw = {k: float(design[k]) for k in ("alpha1", "alpha2", "beta1", "beta2")}
    if "deltas" in design:
        kw["deltas"] = tuple(float(d) for d in design["deltas"])
    return WristDesign(**kw)


# --------------------------------------------------------------------------------------------
# Rotations
# --------------------------------------------------------------------------------------------


def rot_x(a: float) -> np.ndarray:
    """Right-handed rotation about x by angle a."""
    c, s = math.cos(a), math.sin(a)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def rot_z(a: float) -> np.ndarray:
    """Right-handed rotation about z by angle a."""
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def skew(w: Sequence[float]) -> np.ndarray:
    """Cross-product matrix: skew(w) @ v == cross(w, v)."""
    return np.array([[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]])


def expm_so3(w: Sequence[float]) -> np.ndarray:
    """Matrix exponential of skew(w) (Rodrigues), accurate for small |w|."""
    w = np.asarray(w, dtype=float)
    th = float(np.linalg.norm(w))
    K = skew(w)
    if th < 1e-8:
        return np.eye(3) + K + 0.5 * K @ K
    return np.eye(3) + (math.sin(th) / th) * K + ((1.0 - math.cos(th)) / th**2) * (K @ K)


def rotation_from_euler(psi: float, theta: float, phi: float) -> np.ndarray:
    """R = Rz(psi) Rx(theta) Rz(phi) (ZXZ: precession, nutation, self-rotation)."""
    return rot_z(psi) @ rot_x(theta) @ rot_z(phi)


def euler_from_rotation(R: np.ndarray, eps: float = 1e-10) -> tuple[float, float, float, bool]:
    """ZXZ angles (psi, theta, phi, degenerate) of R, with theta in [0, pi] and psi, phi in (-pi, pi].

    When sin(theta) < eps only psi + phi (theta ~ 0) or psi - phi (theta ~ pi) is defined;
    then phi = 0 is returned, psi carries the sum/difference and ``degenerate`` is True.
    """
    R = np.asarray(R, dtype=float)
    st = math.hypot(R[0, 2], R[1, 2])
    theta = math.atan2(st, R[2, 2])
    if st < eps:
        # theta ~ 0: R = Rz(psi + phi); theta ~ pi: R = Rz(psi - phi) Rx(pi). Either way R[:2, 0]
        # holds (cos, sin) of the defined combination.
        return math.atan2(R[1, 0], R[0, 0]), theta, 0.0, True
    psi = math.atan2(R[0, 2], -R[1, 2])
    phi = math.atan2(R[2, 0], R[2, 1])
    return psi, theta, phi, False


# --------------------------------------------------------------------------------------------
# Axes and loop residuals
# --------------------------------------------------------------------------------------------


def base_frames(design: WristDesign | Mapping[str, float] | None = None) -> np.ndarray:
    """B_i = Rz(delta_i) Rx(pi - beta1), stacked as (3, 3, 3)."""
    d = as_design(design)
    return np.stack([rot_z(di) @ rot_x(math.pi - d.beta1) for di in d.deltas])


def base_axes(design: WristDesign | Mapping[str, float] | None = None) -> np.ndarray:
    """Z_i1 as rows of a (3, 3) array."""
    return base_frames(design)[:, :, 2].copy()


def platform_axes(design: WristDesign | Mapping[str, float] | None = None) -> np.ndarray:
    """p_i = Rz(delta_i) Rx(beta2) e_z (platform frame) as rows of a (3, 3) array."""
    d = design if isinstance(design, WristDesign) else as_design(design)
    return np.stack([(rot_z(di) @ rot_x(d.beta2))[:, 2] for di in d.deltas])


def middle_axis(i: int, theta: float | np.ndarray, design: WristDesign | Mapping[str, float] | None = None
                ) -> np.ndarray:
    """Z_i2(theta) = B_i Rz(theta) Rx(alpha1) e_z for branch i in {0, 1, 2}; vectorised over theta."""
    d = as_design(design)
    B = base_frames(d)[i]
    t = np.asarray(theta, dtype=float)
    local = np.stack([math.sin(d.alpha1) * np.sin(t), -math.sin(d.alpha1) * np.cos(t),
                      np.full_like(t, math.cos(d.alpha1))], axis=-1)
    return local @ B.T


def middle_axes(thetas: Sequence[float], design: WristDesign | Mapping[str, float] | None = None
                ) -> np.ndarray:
    """Z_12, Z_22, Z_32 for the joint triple as rows of a (3, 3) array."""
    d = as_design(design)
    return np.stack([middle_axis(i, thetas[i], d) for i in range(3)])


def loop_residuals(thetas: Sequence[float] | np.ndarray, R: np.ndarray,
                   design: WristDesign | Mapping[str, float] | None = None) -> np.ndarray:
    """Residuals Z_i2(theta_i) . (R p_i) - cos(alpha2), i = 1..3.

    Vectorised: ``thetas`` of shape (..., 3) and ``R`` of shape (..., 3, 3) broadcast together;
    the result has shape (..., 3).
    """
    d = as_design(design)
    th = np.asarray(thetas, dtype=float)
    R = np.asarray(R, dtype=float)
    P = platform_axes(d)
    out = []
    for i in range(3):
        z2 = middle_axis(i, th[..., i], d)  # (..., 3)
        z3 = R @ P[i]  # (..., 3)
        out.append(np.sum(z2 * z3, axis=-1) - math.cos(d.alpha2))
    return np.stack(out, axis=-1)


# --------------------------------------------------------------------------------------------
# 1-D periodic root finder (dense sampling + brentq + refinement of sampled extrema)
# --------------------------------------------------------------------------------------------


def _brent(f: Callable[[float], float], a: float, b: float) -> float:
    """brentq to full double precision."""
    return brentq(f, a, b, xtol=1e-15, rtol=4 * np.finfo(float).eps, maxiter=200)


@dataclass(frozen=True)
class _Root:
    x: float
    tangent: bool  # found as an extremum touching zero (double root), not as a sign change


def _periodic_roots(fvec: Callable[[np.ndarray], np.ndarray], n: int, touch_tol: float,
                    merge_touching: bool, period: float = TWO_PI, start: float = 0.0) -> list[_Root]:
    """All roots of a smooth ``period``-periodic function on [start, start + period).

    1. sample ``n`` equispaced points; every sign change is solved with brentq;
    2. at every sampled local minimum of |f| not adjacent to a sign change, the extremum of f is
       located with a bounded 1-D minimisation on the two neighbouring sample intervals. If it
       touches zero (|f| <= touch_tol) it is a (near-)double root; if it crosses zero the two
       hidden roots are bracketed and solved with brentq (or, with ``merge_touching``, reported
       once when |f(extremum)| <= touch_tol).
    """
    h = period / n
    xs = start + h * np.arange(n)
    v = np.asarray(fvec(xs), dtype=float)

    def f(x: float) -> float:
        return float(fvec(np.array([x]))[0])

    roots: list[_Root] = []
    for k in range(n):
        j = (k + 1) % n
        a = xs[k]
        if v[k] == 0.0:
            roots.append(_Root(a, False))
        elif v[k] * v[j] < 0.0:
            roots.append(_Root(_brent(f, a, a + h), False))
    av = np.abs(v)
    for k in range(n):
        km, kp = (k - 1) % n, (k + 1) % n
        if v[k] == 0.0 or not (av[k] <= av[km] and av[k] <= av[kp]):
            continue
        if v[km] * v[k] <= 0.0 or v[kp] * v[k] <= 0.0:
            continue  # a sign change next door was already handled
        sgn = 1.0 if v[k] > 0.0 else -1.0
        lo, hi = xs[k] - h, xs[k] + h
        res = minimize_scalar(lambda x, s=sgn: s * f(x), bounds=(lo, hi), method="bounded",
                              options={"xatol": 1e-14, "maxiter": 500})
        xm = float(res.x)
        fm = f(xm)
        if abs(fm) <= touch_tol and (merge_touching or sgn * fm >= 0.0):
            roots.append(_Root(xm, True))
        elif sgn * fm < 0.0:
            roots.append(_Root(_brent(f, lo, xm), False))
            roots.append(_Root(_brent(f, xm, hi), False))
    roots.sort(key=lambda r: r.x)
    return roots


# --------------------------------------------------------------------------------------------
# Inverse kinematics
# --------------------------------------------------------------------------------------------


@dataclass
class IKResult:
    """Result of :func:`ik_reference`.

    ``triples``: all (theta1, theta2, theta3) in [0, 2pi), Cartesian product of ``roots``
    (empty if any branch is unreachable or indeterminate).
    ``roots``: per-branch sorted root lists.
    ``flags``: per branch 'ok' (simple roots), 'unreachable' (no root), 'tangent' (a double
    root, reported once) or 'indeterminate' (f vanishes for every theta; roots then empty).
    """

    triples: list[tuple[float, float, float]]
    roots: tuple[list[float], list[float], list[float]]
    flags: tuple[str, str, str]


def ik_branch_function(i: int, R: np.ndarray, design: WristDesign | Mapping[str, float] | None = None
                       ) -> Callable[[np.ndarray], np.ndarray]:
    """f_i(t) = Z_i2(t) . (R p_i) - cos(alpha2), vectorised over t."""
    d = as_design(design)
    v = np.asarray(R, dtype=float) @ platform_axes(d)[i]
    c2 = math.cos(d.alpha2)
    return lambda t: middle_axis(i, t, d) @ v - c2


def ik_reference(R: np.ndarray, design: WristDesign | Mapping[str, float] | None = None,
                 n_samples: int = 2048, tangent_tol: float = 1e-12, indeterminate_tol: float = 1e-13
                 ) -> IKResult:
    """All real IK solutions of the three independent branch equations for orientation R.

    Each branch f_i(t) is solved on [0, 2pi) by dense sampling + brentq on sign changes plus a
    bounded minimisation at sampled local minima of |f_i| (double roots are reported once, with
    |f_i| <= tangent_tol; two roots closer than ~sqrt(tangent_tol) merge into one tangent root).
    """
    d = as_design(design)
    roots_all: list[list[float]] = []
    flags: list[str] = []
    grid = TWO_PI * np.arange(n_samples) / n_samples
    for i in range(3):
        f = ik_branch_function(i, R, d)
        if np.max(np.abs(f(grid))) <= indeterminate_tol:
            roots_all.append([])
            flags.append("indeterminate")
            continue
        rs = _periodic_roots(f, n_samples, tangent_tol, merge_touching=True)
        xs = sorted(float(np.mod(r.x, TWO_PI)) for r in rs)
        roots_all.append(xs)
        if not rs:
            flags.append("unreachable")
        elif any(r.tangent for r in rs):
            flags.append("tangent")
        else:
            flags.append("ok")
    if "indeterminate" in flags:
        triples: list[tuple[float, float, float]] = []
    else:
        triples = [tuple(t) for t in itertools.product(*roots_all)]
    return IKResult(triples, (roots_all[0], roots_all[1], roots_all[2]),
                    (flags[0], flags[1], flags[2]))


def home_angle(design: WristDesign | Mapping[str, float] | None = None) -> float:
    """theta0: the root in [0, pi] of the branch-1 equation at R = I (same on every branch)."""
    res = ik_reference(np.eye(3), design)
    inside = [t for t in res.roots[0] if 0.0 <= t <= math.pi]
    if len(inside) != 1:
        raise ValueError(f"home angle not unique in [0, pi]: roots {res.roots[0]}")
    return inside[0]


# --------------------------------------------------------------------------------------------
# Forward kinematics: geometric 1-D sweep
# --------------------------------------------------------------------------------------------


def _unit(v: np.ndarray) -> np.ndarray:
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def _perp_basis(n: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Orthonormal a, b with (a, b, n) right-handed."""
    helper = np.array([1.0, 0.0, 0.0]) if abs(n[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    a = _unit(np.cross(helper, n))
    return a, np.cross(n, a)


def polish_rotation(R: np.ndarray, Z2: np.ndarray, P: np.ndarray, c2: float, iters: int = 80
                    ) -> tuple[np.ndarray, float]:
    """Gauss-Newton on r_i = Z2_i . (R p_i) - c2 with R <- R expm(skew(w)); returns (R, max|r|).

    The Jacobian of r_i w.r.t. w at w = 0 is p_i x (R^T Z2_i). Steps use least squares so that
    singular configurations (double roots) still converge (linearly). The best iterate is kept.
    """
    R = np.array(R, dtype=float)
    best_R, best_r = R, math.inf
    for _ in range(iters):
        r = np.einsum("ij,ij->i", Z2, P @ R.T) - c2
        m = float(np.max(np.abs(r)))
        if m < best_r:
            best_R, best_r = R, m
        if m < 1e-15:
            break
        J = np.cross(P, Z2 @ R)  # rows: p_i x (R^T Z2_i)
        w = np.linalg.lstsq(J, -r, rcond=1e-14)[0]
        R = R @ expm_so3(w)
        u, _, vt = np.linalg.svd(R)
        R = u @ vt
    return best_R, best_r


def _dedupe(mats: list[np.ndarray], tol: float) -> list[np.ndarray]:
    out: list[np.ndarray] = []
    for M in mats:
        if all(np.linalg.norm(M - N) >= tol for N in out):
            out.append(M)
    return out


def _sort_rotations(mats: list[np.ndarray]) -> list[np.ndarray]:
    """Deterministic order: by (psi, theta, phi) rounded, for reproducible output."""
    def key(M: np.ndarray) -> tuple[float, ...]:
        psi, th, phi, _ = euler_from_rotation(M)
        return (round(th, 9), round(psi, 9), round(phi, 9))
    return sorted(mats, key=key)


@dataclass
class FKResult:
    """Result of :func:`fk_reference` / :func:`fk_reference_multistart`.

    ``rotations``: distinct proper rotations satisfying all three loops (max |residual| < 1e-10).
    ``residuals``: max |loop residual| of each rotation. ``count`` = len(rotations).
    ``info``: diagnostics (sweep loops used, raw candidates, rejected candidates).
    """

    rotations: list[np.ndarray]
    residuals: list[float]
    info: dict = field(default_factory=dict)

    @property
    def count(self) -> int:
        return len(self.rotations)

    def euler(self) -> list[tuple[float, float, float, bool]]:
        """ZXZ Euler angles of every solution (see :func:`euler_from_rotation`)."""
        return [euler_from_rotation(M) for M in self.rotations]


class _Sweep:
    """Vectorised geometry of the 1-D sweep for one joint triple."""

    def __init__(self, thetas: Sequence[float], d: WristDesign):
        self.d = d
        self.P = platform_axes(d)
        self.Z2 = middle_axes(thetas, d)
        self.c2, self.s2 = math.cos(d.alpha2), math.sin(d.alpha2)
        p1, p2, p3 = self.P
        self.c3 = float(p1 @ p2)  # cos(alpha3)
        # Platform triad (p1, q2, q3) and coordinates of p3 in it.
        q2 = _unit(p2 - self.c3 * p1)
        q3 = np.cross(p1, q2)
        self.Fp = np.stack([p1, q2, q3], axis=1)  # columns
        self.p3_coords = self.Fp.T @ p3
        self.a, self.b = _perp_basis(self.Z2[0])

    def z13(self, zeta: np.ndarray) -> np.ndarray:
        """Z13 on the cone of half-angle alpha2 about Z12, rotated by zeta."""
        zeta = np.asarray(zeta, dtype=float)[..., None]
        return self.c2 * self.Z2[0] + self.s2 * (np.cos(zeta) * self.a + np.sin(zeta) * self.b)

    def disc(self, zeta: np.ndarray) -> np.ndarray:
        """D >= 0 iff cone(Z22, alpha2) and cone(Z13, alpha3) meet; D = (1-G^2) - (ca^2+cb^2-2G ca cb).

        G = Z13 . Z22, ca = cos(alpha2), cb = cos(alpha3).
        """
        G = self.z13(zeta) @ self.Z2[1]
        ca, cb = self.c2, self.c3
        return (1.0 - G * G) - (ca * ca + cb * cb - 2.0 * G * ca * cb)

    def z23(self, zeta: np.ndarray, sign: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Z23 = l1 Z22 + l2 Z13 + mu (Z22 x Z13), mu = sign sqrt(D)/(1-G^2); returns (Z13, Z23)."""
        n1 = self.Z2[1]
        n2 = self.z13(zeta)
        G = n2 @ n1
        one_g2 = 1.0 - G * G
        ca, cb = self.c2, self.c3
        D = np.maximum(one_g2 - (ca * ca + cb * cb - 2.0 * G * ca * cb), 0.0)
        l1 = (ca - G * cb) / one_g2
        l2 = (cb - G * ca) / one_g2
        mu = np.asarray(sign, dtype=float) * np.sqrt(D) / one_g2
        x = l1[..., None] * n1 + l2[..., None] * n2 + mu[..., None] * np.cross(n1, n2)
        return n2, x

    def rotation(self, z13: np.ndarray, z23: np.ndarray) -> np.ndarray:
        """Triad method: the proper rotation with R p1 = z13 and R p2 = z23 (vectorised)."""
        e1 = _unit(z13)
        e2 = _unit(z23 - np.sum(z23 * e1, axis=-1, keepdims=True) * e1)
        e3 = np.cross(e1, e2)
        Fz = np.stack([e1, e2, e3], axis=-1)  # (..., 3, 3), columns
        return Fz @ self.Fp.T

    def g_from(self, z13: np.ndarray, z23: np.ndarray) -> np.ndarray:
        """g = Z32 . (R p3) - cos(alpha2), with R p3 from the triad coordinates of p3."""
        e1 = _unit(z13)
        e2 = _unit(z23 - np.sum(z23 * e1, axis=-1, keepdims=True) * e1)
        e3 = np.cross(e1, e2)
        k = self.p3_coords
        rp3 = k[0] * e1 + k[1] * e2 + k[2] * e3
        return rp3 @ self.Z2[2] - self.c2


def fk_reference(thetas: Sequence[float], design: WristDesign | Mapping[str, float] | None = None,
                 n_zeta: int = 1440, n_loop: int = 2048, res_tol: float = 1e-10, dedupe_tol: float = 1e-7
                 ) -> FKResult:
    """All rotations R with Z_i2(theta_i) . (R p_i) = cos(alpha2), i = 1..3, by a geometric sweep.

    Sweep: Z13(zeta) runs over the cone(Z12, alpha2). Z23 must lie on cone(Z22, alpha2) and at
    angle alpha3 from Z13: two circles on the sphere, intersected in closed form (points exist
    where D(zeta) >= 0; two branches mu = +-sqrt(D)/(1-G^2)). R follows from (p1, p2) -> (Z13, Z23)
    by the triad method, and g = Z32 . (R p3) - cos(alpha2) is solved for its roots.

    Branch endpoints are handled by a smooth loop parameter: each interval [a, b] where D >= 0
    (ends = simple roots of D, found with the same sampled/brentq root finder) is traversed as
    zeta = (a+b)/2 + (b-a)/2 cos(s), with the + branch for s in (0, pi) and the - branch for
    s in (pi, 2pi); since D ~ (b - zeta) ~ s^2 near an end, mu ~ s is smooth through the point
    where the two branches meet, so a root there is an ordinary (sign-changing) root in s.
    If D > 0 for all zeta the two branches are two separate periodic loops in zeta.

    Every candidate is polished by Gauss-Newton on the three loop residuals over SO(3), kept if
    max |residual| < res_tol and de-duplicated by Frobenius distance < dedupe_tol.
    """
    d = as_design(design)
    sw = _Sweep(thetas, d)
    info: dict = {"loops": [], "candidates": 0, "rejected": []}
    # Intervals of zeta where the circles meet.
    droots = _periodic_roots(sw.disc, n_zeta, 1e-14, merge_touching=False)
    simple = [r.x for r in droots if not r.tangent]
    loops: list[tuple[str, float, float]] = []  # ("interval", a, b) or ("full", sign, 0)
    if simple:
        simple = sorted(simple)
        for k, a in enumerate(simple):
            b = simple[(k + 1) % len(simple)]
            if b <= a:
                b += TWO_PI
            if sw.disc(np.array([0.5 * (a + b)]))[0] > 0.0:
                loops.append(("interval", a, b))
    else:
        probe = sw.disc(TWO_PI * np.arange(n_zeta) / n_zeta)
        if np.max(probe) > 0.0:
            loops += [("full", 1.0, 0.0), ("full", -1.0, 0.0)]
    info["loops"] = loops

    def loop_param(loop: tuple[str, float, float]) -> Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]]:
        kind, a, b = loop
        if kind == "full":
            return lambda s: (np.asarray(s, dtype=float), np.full(np.shape(s), a))
        mid, half = 0.5 * (a + b), 0.5 * (b - a)
        return lambda s: (mid + half * np.cos(s), np.sign(np.sin(s)))

    cand: list[np.ndarray] = []
    for loop in loops:
        par = loop_param(loop)

        def g(s: np.ndarray, par=par) -> np.ndarray:
            zeta, sgn = par(s)
            z13, z23 = sw.z23(zeta, sgn)
            return sw.g_from(z13, z23)

        for r in _periodic_roots(g, n_loop, 1e-8, merge_touching=False):
            zeta, sgn = par(np.array([r.x]))
            z13, z23 = sw.z23(zeta, sgn)
            cand.append(sw.rotation(z13, z23)[0])
    # Isolated touching points of the circles (double roots of D with D <= 0 around): mu = 0.
    for r in droots:
        if r.tangent:
            z13, z23 = sw.z23(np.array([r.x]), np.array([0.0]))
            if abs(sw.g_from(z13, z23)[0]) < 1e-6:
                cand.append(sw.rotation(z13, z23)[0])
    info["candidates"] = len(cand)

    sols: list[tuple[np.ndarray, float]] = []
    for R0 in cand:
        if abs(np.linalg.det(R0) - 1.0) > 1e-9:
            info["rejected"].append(("improper", float(np.linalg.det(R0))))
            continue
        R, m = polish_rotation(R0, sw.Z2, sw.P, sw.c2)
        if m < res_tol:
            sols.append((R, m))
        else:
            info["rejected"].append(("residual", m))
    mats = _sort_rotations(_dedupe([R for R, _ in sols], dedupe_tol))
    res = [float(np.max(np.abs(loop_residuals(thetas, M, d)))) for M in mats]
    return FKResult(mats, res, info)


# --------------------------------------------------------------------------------------------
# Forward kinematics: multistart least squares (slow cross-check)
# --------------------------------------------------------------------------------------------


def _random_rotations(n: int, seed: int) -> np.ndarray:
    """n rotations uniformly distributed on SO(3) (random unit quaternions), seeded."""
    q = np.random.default_rng(seed).normal(size=(n, 4))
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    w, x, y, z = q.T
    return np.stack([
        np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)], axis=-1),
        np.stack([2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)], axis=-1),
        np.stack([2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)], axis=-1),
    ], axis=1)


def fk_reference_multistart(thetas: Sequence[float], design: WristDesign | Mapping[str, float] | None = None,
                            starts: int = 300, seed: int = 20240611, res_tol: float = 1e-10,
                            dedupe_tol: float = 1e-7) -> FKResult:
    """Independent slow FK: multistart scipy ``least_squares`` over SO(3).

    Each start R_k (identity plus ``starts`` seeded uniform random rotations) is refined with
    R = R_k expm(skew(w)), w in R^3 (rotation-vector parametrisation), on the three loop
    residuals. Converged points (max |residual| < res_tol) are de-duplicated. Shares no code
    with the sweep except the residual definition.
    """
    d = as_design(design)
    th = np.asarray(thetas, dtype=float)
    Z2 = middle_axes(th, d)
    P = platform_axes(d)
    c2 = math.cos(d.alpha2)
    starts_R = np.concatenate([np.eye(3)[None], _random_rotations(starts, seed)])
    found: list[np.ndarray] = []
    for Rk in starts_R:
        def fun(w: np.ndarray, Rk=Rk) -> np.ndarray:
            R = Rk @ expm_so3(w)
            return np.array([Z2[i] @ (R @ P[i]) - c2 for i in range(3)])

        sol = least_squares(fun, np.zeros(3), method="lm", xtol=1e-15, ftol=1e-15, gtol=1e-15,
                            max_nfev=400)
        R = Rk @ expm_so3(sol.x)
        u, _, vt = np.linalg.svd(R)
        R = u @ vt
        if np.max(np.abs(loop_residuals(th, R, d))) < res_tol:
            found.append(R)
    mats = _sort_rotations(_dedupe(found, dedupe_tol))
    res = [float(np.max(np.abs(loop_residuals(th, M, d)))) for M in mats]
    return FKResult(mats, res, {"starts": len(starts_R), "converged": len(found)})


# --------------------------------------------------------------------------------------------
# Census of FK solution counts (source of tests/reference/fk_count_cases.json)
# --------------------------------------------------------------------------------------------


def fk_jacobian(thetas: Sequence[float], R: np.ndarray,
                design: WristDesign | Mapping[str, float] | None = None) -> np.ndarray:
    """d(loop residuals)/dw for R expm(skew(w)) at w = 0; rows p_i x (R^T Z_i2). Singular = FK singular."""
    d = as_design(design)
    return np.cross(platform_axes(d), middle_axes(thetas, d) @ np.asarray(R, dtype=float))


def fk_count_census(n_samples: int = 2000, seed: int = 2024, per_count: int = 5, stability_step: float = 1e-3,
                    design: WristDesign | Mapping[str, float] | None = None) -> dict:
    """Seeded random search over joint space ([0, 2pi)^3, uniform) for FK solution counts.

    Returns the count distribution and, for every count seen, up to ``per_count`` example
    triples (in sampling order) whose count is unchanged when any single theta_i moves by
    +-stability_step (so the example is not sitting next to a count-changing boundary).
    Cases are sorted by (count, sample_index); with the default seed the first case of each
    count is the first sample with that count (the cases other tests pick with ``next(...)``).
    """
    d = as_design(design)
    thetas = np.random.default_rng(seed).uniform(0.0, TWO_PI, size=(n_samples, 3))
    results = [fk_reference(t, d) for t in thetas]
    dist: dict[int, int] = {}
    for r in results:
        dist[r.count] = dist.get(r.count, 0) + 1
    cases: list[dict] = []
    taken: dict[int, int] = {}
    for k, (t, r) in enumerate(zip(thetas, results, strict=True)):
        if taken.get(r.count, 0) >= per_count:
            continue
        stable = all(fk_reference(t + sgn * stability_step * np.eye(3)[i], d).count == r.count
                     for i in range(3) for sgn in (1.0, -1.0))
        if not stable:
            continue
        taken[r.count] = taken.get(r.count, 0) + 1
        sig = [float(np.linalg.svd(fk_jacobian(t, M, d), compute_uv=False)[-1]) for M in r.rotations]
        cases.append({
            "sample_index": k,
            "joints": [float(x) for x in t],
            "thetas_deg": [round(math.degrees(x), 6) for x in t],
            "count": r.count,
            "min_jacobian_sigma": min(sig) if sig else None,
            "solutions_zxz_deg": [[round(math.degrees(a), 6) for a in euler_from_rotation(M)[:3]]
                                  for M in r.rotations],
        })
    cases.sort(key=lambda c: (c["count"], c["sample_index"]))
    return {
        "seed": seed,
        "n_samples": n_samples,
        "sampling": "theta_i ~ Uniform[0, 2pi) i.i.d.: numpy default_rng(seed).uniform(0, 2pi, (n, 3))",
        "stability_step_rad": stability_step,
        "distribution": {str(c): dist[c] for c in sorted(dist)},
        "cases": cases,
    }


def write_count_fixtures(path: str, census: dict, design: WristDesign | Mapping[str, float] | None = None
                         ) -> None:
    """Write a census (see :func:`fk_count_census`) as the JSON fixtures file."""
    import json

    d = as_design(design)
    doc = {
        "note": ("FK real-solution counts for the underactuated 3-DOF spherical wrist, paper design. "
                 "Produced by fk_reference (geometric sweep + Gauss-Newton polish) in "
                 "tests/reference/underactuated_wrist.py via fk_count_census / write_count_fixtures; "
                 "NOT from the closed-form derivation. joints are the exterior angles theta_i in "
                 "radians (motor angles Phi_i = theta_i - theta0). solutions_zxz_deg = (psi, theta, phi) "
                 "of R = Rz(psi) Rx(theta) Rz(phi). Cases are chosen so the count is unchanged when any "
                 "theta_i moves by +-stability_step_rad."),
        "design_deg": {k: math.degrees(getattr(d, k)) for k in ("alpha1", "alpha2", "beta1", "beta2")},
        "design_rad": {k: getattr(d, k) for k in ("alpha1", "alpha2", "beta1", "beta2")},
        **census,
    }
    with open(path, "w") as fh:
        json.dump(doc, fh, indent=1)
        fh.write("\n")


if __name__ == "__main__":  # regenerate the fixtures: python tests/reference/underactuated_wrist.py
    import os

    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "fk_count_cases.json")
    write_count_fixtures(out, fk_count_census())
    print("wrote", out)
