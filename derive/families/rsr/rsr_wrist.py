"""3-RSR (2R1T) symmetric parallel wrist of seed 002: FK by the mirror-plane construction, exact IK per leg,
the swing-rotation attitude angle gamma, and rate Jacobians; every step checked as it is recorded.

Pose = (alpha, beta, l_bw): azimuth and swing of the platform normal and the signed centre distance (|O_B O_W|
up to sign: l_bw = 2 h along the mirror plane's normal n with n_z >= 0)
(seed eq. 9). Joints = (phi1, phi2, phi3), the swing angles of the three base links.
"""

from __future__ import annotations

import functools
import math

import numpy as np
import sympy as sp

from ...checks import Check, numeric_identity, numeric_predicate, sampler, symbolic_identity
from ...mechanism import CApi
from ...model import Derivation, Finding, Step
from ...report_numbers import measured
from . import rsr_geometry as g
from .rsr_geometry import ALPHA, BETA, LBW, PHI, L, max_gamma_difference, seed_fd

# name, title, source and the default design come from the spec (catalogue/rsr_wrist.toml)
FAMILY = "rsr"
VECTORISED_KERNELS = ("atlas_rates",)  # the atlas's numpy path (no C extension)
DERIVE_SECONDS = 5  # a scheduling hint for parallel regeneration (seconds on a 2-core 2026 EPYC)
DERIVE_GROUP = "rsr"  # the hybrid builds on this derivation (cached per process): one process for both
TEMPLATES = ("python/rsr_wrist.py.jinja", "c/rsr_wrist.h.jinja", "c/rsr_wrist.c.jinja")
C_API = CApi(jacobian=True, atlas=True)
# Design: link length and the workspace limits the middle curve is taken between (explicit, not published).
DESIGN_NAMES = ("L", "phi_min", "phi_max", "lbw_min", "lbw_max")
CASADI_DESIGN_NAMES = ("L",)  # the CasADi functions take the platform link length only (limits do not enter)
GAMMA, ALPHA1 = sp.symbols("gamma alpha_1", real=True)
CQ = sp.symbols("c1:4", real=True)  # cos phi_i
SQ = sp.symbols("s1:4", real=True)  # sin phi_i
_CS = {**{sp.cos(PHI[i]): CQ[i] for i in range(3)}, **{sp.sin(PHI[i]): SQ[i] for i in range(3)}}

_PHI_RANGE = (-0.6, 2.2)
_POSE_RANGES = {ALPHA: (-math.pi, math.pi), BETA: (0.05, 2.0), L: (0.03, 0.2)}


@functools.cache
def _leg_points():
    """S_1, S_2, S_3 as one numeric function of (phi, L) for the sampled checks (evalf of the symbolic S_i at
    every sample took most of their time)."""
    return sampler((PHI, L), [g.leg_point(i) for i in range(3)])


@functools.cache
def _base_axes() -> tuple:
    return tuple(np.array(g.base_axis(i).evalf(), dtype=float).ravel() for i in range(3))


def _sample_pose(rng, length=0.06):
    """A reachable pose: random phi, then the plane through the S_i (so every leg closes)."""
    while True:
        phis = rng.uniform(*_PHI_RANGE, 3)
        pts = [np.asarray(s, dtype=float).ravel() for s in _leg_points()(phis, length)]
        nvec = np.cross(pts[1] - pts[0], pts[2] - pts[0])
        if np.linalg.norm(nvec) > 1e-3 * length**2:
            n = nvec / np.linalg.norm(nvec)
            h = float(n @ pts[0])
            if n[2] < 0:
                n, h = -n, -h
            return phis, pts, n, h


def _np_reflection(n):
    return np.eye(3) - 2.0 * np.outer(n, n)


_CACHE: dict = {}


def derive() -> Derivation:
    """The wrist derivation, once per process (the hybrid builds on its checked kernels; never mutated)."""
    if "dv" not in _CACHE:
        _CACHE["dv"] = _derive()
    return _CACHE["dv"]


derive_cached = derive


def _derive() -> Derivation:
    dv = Derivation(FAMILY, FAMILY, "", {s.name: s for s in (L, *PHI, ALPHA, BETA, LBW, GAMMA, ALPHA1)})
    _forward(dv)
    _mirror_proofs(dv)
    _inverse(dv)
    _attitude(dv)
    _rates(dv)
    from .rsr_jacobian import LEG_RANGE, jacobian_step, wrist_transform_of_joints

    step, jac = jacobian_step("geometric_jacobian", wrist_transform_of_joints(dv), PHI, (L,), [LEG_RANGE] * 3,
                              ("legs_close",))
    dv.add(step)
    dv.exports["geometric_jacobian"] = jac
    dv.findings.extend(_findings())
    return dv


# ------------------------------------------------------------------------------------------- forward kinematics
def _forward(dv: Derivation) -> None:
    pts = [g.leg_point(i) for i in range(3)]
    u = [g.base_axis(i) for i in range(3)]
    dv.add(Step(
        "leg_points", "Spherical-joint centres S_i",
        "base link of length L perpendicular to its joint axis u_i = Rz(a_i) e_x, turned by phi_i: "
        "S_i = Rz(a_i) (0, L cos phi_i, L sin phi_i), a_i = 0, 120, 240 deg",
        (), {f"S{i + 1}": pts[i] for i in range(3)},
        (symbolic_identity(sp.Matrix([pts[i].dot(u[i]) for i in range(3)]), sp.zeros(3, 1), "S_i . u_i = 0"),
         symbolic_identity(sp.Matrix([pts[i].dot(pts[i]) for i in range(3)]), sp.Matrix([L**2] * 3),
                           "|O_B S_i| = L")),
        source="seed 002, eq. (2)"))
    nvec = g.plane_normal_unnormalised(pts)
    dv.add(Step(
        "plane", "Mirror plane S1 S2 S3: normal N and offset h",
        "N = S1S2 x S1S3, n = N/|N| oriented so that n_z >= 0, h = n . S1 (signed distance of the plane from O_B)",
        ("leg_points",), {"N": nvec},
        (symbolic_identity(sp.Matrix([nvec.dot(pts[1] - pts[0]), nvec.dot(pts[2] - pts[0])]), sp.zeros(2, 1),
                           "N is perpendicular to S1S2 and S1S3, so n . S_i = h for every leg"),),
        source="seed 002, eq. (3)"))
    dv.exports["plane_N"] = nvec
    dv.exports["leg_points"] = pts
    n = g.mirror_normal()
    ow = LBW * n
    dv.add(Step(
        "centre", "Platform centre O_W = mirror image of O_B",
        "reflection of O_B about the plane n . x = h: O_W = 2 h n, so l_bw = 2 h (signed; |l_bw| = |O_B O_W|) "
        "and, with "
        "n = (sin(beta/2) cos alpha, sin(beta/2) sin alpha, cos(beta/2)), O_W = l_bw n (seed eq. 9)",
        ("plane",), {"n": n, "O_W": ow},
        (symbolic_identity(n.dot(n), sp.Integer(1), "n(alpha, beta) is a unit vector"),
         symbolic_identity(n.dot(g.E_Z), sp.cos(BETA / 2), "angle(n, e_z) = beta / 2"),
         symbolic_identity(-2 * (sp.zeros(3, 1).dot(n) - LBW / 2) * n, ow,
                           "reflection x - 2 (n . x - h) n of x = O_B with h = l_bw / 2 is l_bw n")),
        source="seed 002, eqs. (3) and (9)"))


def _mirror_proofs(dv: Derivation) -> None:
    n = g.mirror_normal()
    m = g.reflection(n)
    rw = g.platform_rotation_mirror(n)
    tilt = g.tilt_rotation()
    y = sp.Matrix(sp.symbols("y1:4", real=True))

    def seed_frame_error(rng) -> float:
        # seed eqs. 4-6 literally: R_i = Rz(a_i)(R, 0, 0), R_{i+3} = R_i + 2 (n . R_iS_i) n, Wx, Wz, Wy normalised;
        # two different base radii R give the same frame, so R drops out.
        phis, pts, nn, h = _sample_pose(rng)
        frames = []
        for radius in (0.02, 0.11):
            r_pts = [u * radius for u in _base_axes()]
            ow = 2 * h * nn
            r_m = [r_pts[i] + 2 * float(nn @ (pts[i] - r_pts[i])) * nn for i in range(2)]
            wx = (r_m[0] - ow) / np.linalg.norm(r_m[0] - ow)
            wz = np.cross(r_m[0] - ow, r_m[1] - ow)
            wz /= np.linalg.norm(wz)
            wy = np.cross(wz, wx)
            frames.append(np.column_stack([wx, wy / np.linalg.norm(wy), wz]))
        rw_n = _np_reflection(nn) @ np.diag([1.0, 1.0, -1.0])
        return max(float(np.max(np.abs(f - rw_n))) for f in frames)

    dv.add(Step(
        "platform_rotation", "Platform frame = reflection composed with the base-plane flip",
        "the platform axes are the mirror images M u_i (M = I - 2 n n^T); the seed's frame Wx = M u1, "
        "Wz = unit(M u1 x M u2) = -M e_z, Wy = Wz x Wx gives R_W = M diag(1, 1, -1), a proper rotation; "
        "the base radius R of eq. (4) drops out",
        ("centre",), {"R_W": rw},
        (symbolic_identity(rw.T * rw, sp.eye(3), "R_W^T R_W = I"),
         symbolic_identity(rw.det(), sp.Integer(1), "det R_W = +1 (two reflections)"),
         numeric_predicate(seed_frame_error, "seed eqs. (4)-(6) built literally with base radius R = 0.02 and "
                           "0.11 equal M diag(1, 1, -1)", samples=100, tol=1e-12)),
        source="seed 002, eqs. (4)-(6)"))
    dv.add(Step(
        "zero_torsion", "The platform attitude is a pure tilt: zero torsion",
        "two reflections (planes z = 0 and n . x = h) compose to the rotation by twice their dihedral angle, "
        "beta = 2 angle(n, e_z), about their line of intersection, horizontal axis (-sin alpha, cos alpha, 0): "
        "R_W = Rz(alpha) Ry(beta) Rz(-alpha), the tilt-and-torsion form with torsion 0",
        ("platform_rotation",), {"R_W": tilt},
        (symbolic_identity(rw, tilt, "M(n(alpha, beta)) diag(1, 1, -1) = Rz(alpha) Ry(beta) Rz(-alpha)"),
         symbolic_identity(tilt * sp.Matrix([0, 0, 1]), sp.Matrix([sp.sin(BETA) * sp.cos(ALPHA),
                                                                   sp.sin(BETA) * sp.sin(ALPHA), sp.cos(BETA)]),
                           "platform normal W_z has azimuth alpha and swing beta")),
        source="seed 002, Sec. I (middle symmetric plane) and Sec. II-A"))
    h = sp.Symbol("h", real=True)
    svec = sp.Matrix(sp.symbols("s1:4", real=True))
    dv.add(Step(
        "legs_close", "Every leg closes on the mirrored platform",
        "with S_i on the plane (n . S_i = h), S_i - O_W = M (S_i - O_B); M is an isometry, so the platform link "
        "has length L and stays perpendicular to the mirrored platform axis R_W u_i: (M S_i) . (M diag(1,1,-1) u_i) "
        "= S_i . u_i = 0",
        ("zero_torsion", "leg_points"), {},
        (symbolic_identity(svec - 2 * h * n - m * svec, 2 * n * (n.dot(svec) - h),
                           "S - O_W - M S = 2 n (n . S - h): zero exactly when S is on the plane"),
         symbolic_identity(m.T * m, sp.eye(3), "M^T M = I (isometry: |S_i - O_W| = |S_i - O_B| = L)"),
         symbolic_identity(sp.diag(1, 1, -1) * sp.Matrix([y[0], y[1], 0]), sp.Matrix([y[0], y[1], 0]),
                           "diag(1,1,-1) u = u for horizontal u, so with M^T M = I: (M S) . (M diag(1,1,-1) u) = "
                           "S . u"),
         numeric_predicate(_leg_closure_error, "closure residuals (S_i - O_W) . w_i and |S_i - O_W| - L on the "
                           "FK platform, random phi", samples=200, tol=1e-13)),
        source="seed 002, Sec. I: 'the moving platform and the base are always symmetrical'"))


def _leg_closure_error(rng) -> float:
    phis, pts, n, h = _sample_pose(rng)
    rw = _np_reflection(n) @ np.diag([1.0, 1.0, -1.0])
    ow = 2 * h * n
    worst = 0.0
    for i in range(3):
        w = rw @ _base_axes()[i]
        d = pts[i] - ow
        worst = max(worst, abs(float(d @ w)), abs(float(np.linalg.norm(d)) - 0.06))
    return worst


# ------------------------------------------------------------------------------------------- inverse kinematics
def _inverse(dv: Derivation) -> None:
    n = g.mirror_normal()
    coeffs = {}
    checks = []
    for i in range(3):
        a_i, b = g.leg_equation_coefficients(i)
        coeffs[f"A{i + 1}"] = a_i
        coeffs["B"] = b
        checks.append(symbolic_identity(n.dot(g.leg_point(i)), L * (a_i * sp.cos(PHI[i]) + b * sp.sin(PHI[i])),
                                        f"n . S{i + 1} = L (A{i + 1} cos phi{i + 1} + B sin phi{i + 1})"))
    dv.add(Step(
        "leg_equations", "One trigonometric equation per leg",
        "S_i lies on the mirror plane: n . S_i = l_bw / 2, i.e. A_i cos phi_i + B sin phi_i = C with "
        "A_i = sin(beta/2) sin(alpha - a_i), B = cos(beta/2), C = l_bw / (2 L); the legs decouple",
        ("centre", "leg_points"), {**coeffs, "C": LBW / (2 * L)}, tuple(checks),
        source="seed 002, Sec. III-B-2 (replaces the 9-equation solve)"))

    def ik_residual(rng) -> float:
        alpha, beta = rng.uniform(-math.pi, math.pi), rng.uniform(0.0, 1.3)
        lbw = rng.uniform(0.03, 0.11)
        worst = 0.0
        for i in range(3):
            a_i = math.sin(beta / 2) * math.sin(alpha - 2 * math.pi * i / 3)
            b = math.cos(beta / 2)
            rho, c = math.hypot(a_i, b), lbw / (2 * 0.06)
            if abs(c) > rho:
                continue
            for sgn in (1, -1):
                phi = math.atan2(b, a_i) + sgn * math.acos(c / rho)
                worst = max(worst, abs(a_i * math.cos(phi) + b * math.sin(phi) - c))
        return worst

    dv.add(Step(
        "leg_roots", "Both roots of each leg, reachability",
        "A cos phi + B sin phi = rho cos(phi - atan2(B, A)) with rho = sqrt(A^2 + B^2): "
        "phi_i = atan2(B, A_i) +/- acos(C / rho_i), real iff |C| <= rho_i; 2 x 2 x 2 = 8 joint sets",
        ("leg_equations",), {"phi_i": sp.atan2(sp.Symbol("B"), sp.Symbol("A_i")) + sp.acos(
            sp.Symbol("C") / sp.sqrt(sp.Symbol("A_i") ** 2 + sp.Symbol("B") ** 2))},
        (numeric_predicate(ik_residual, "leg equation residual of both roots, random reachable poses",
                           samples=300, tol=1e-14),),
        source="seed 002, eq. (12)"))


# ------------------------------------------------------------------------------------------------- attitude
def _attitude(dv: Derivation) -> None:
    gamma_expr = sp.atan2(sp.sin(ALPHA1), sp.cos(BETA) * sp.cos(ALPHA1))
    alpha_expr = sp.atan2(sp.cos(BETA) * sp.sin(GAMMA), sp.cos(GAMMA))

    tilt = sp.lambdify((ALPHA, BETA), g.tilt_rotation(), "numpy")

    def seed_reading_error(rng) -> float:
        # The seed's words: frame (1) = attitude at azimuth 0, frame (2) at azimuth alpha1, frame (3) = frame (1)
        # turned about the base normal by alpha1; gamma = angle of X(3) relative to X(2), seen in the base plane.
        a1, beta = rng.uniform(-math.pi, math.pi), rng.uniform(0.0, 1.4)
        x2 = np.asarray(tilt(a1, beta), dtype=float)[:, 0]
        x3 = np.array([math.cos(a1) * math.cos(beta), math.sin(a1) * math.cos(beta), -math.sin(beta)])
        rel = math.atan2(x3[1], x3[0]) - math.atan2(x2[1], x2[0])
        gam = math.atan2(math.sin(a1), math.cos(beta) * math.cos(a1))
        return abs(math.remainder(rel - gam, 2 * math.pi))

    dv.add(Step(
        "gamma", "Swing-rotation angle gamma, defined precisely",
        "gamma = the angle, in the base plane, from the projected X-axis of the wrist frame at azimuth alpha1 "
        "(frame 2 of the seed's Fig. 3a) to the projected X-axis of the azimuth-0 frame turned about the base "
        "normal by alpha1 (frame 3): tan gamma = tan alpha1 / cos beta, gamma = atan2(sin alpha1, cos beta cos alpha1)",
        ("zero_torsion",), {"gamma": gamma_expr, "alpha1": alpha_expr},
        (numeric_predicate(seed_reading_error, "gamma equals the base-plane angle between the projected X axes of "
                           "frames (3) and (2)", samples=200, tol=1e-12),
         numeric_identity(alpha_expr.subs(GAMMA, gamma_expr), ALPHA1, "alpha1(gamma(alpha1, beta), beta) = alpha1 "
                          "(exact inverse: no curve fit, no bisection)", {ALPHA1: (-3.1, 3.1), BETA: (0.0, 1.5)},
                          tol=1e-12),
         symbolic_identity(sp.diff(sp.atan(sp.tan(ALPHA1) / sp.cos(BETA)), ALPHA1),
                           sp.cos(BETA) / (sp.cos(BETA) ** 2 * sp.cos(ALPHA1) ** 2 + sp.sin(ALPHA1) ** 2),
                           "d gamma / d alpha1 = cos beta / (cos^2 beta cos^2 alpha1 + sin^2 alpha1) > 0 for "
                           "beta < 90 deg: one-to-one, singular only at beta = 90 deg")),
        source="seed 002, Sec. II-B (swing-rotation angle method)"))
    dv.exports["gamma"] = gamma_expr
    dv.exports["alpha1_of_gamma"] = alpha_expr


# ---------------------------------------------------------------------------------------------------- rates
def _rates(dv: Derivation) -> None:
    f = []
    for i in range(3):
        a_i, b = g.leg_equation_coefficients(i)
        f.append(L * (a_i * sp.cos(PHI[i]) + b * sp.sin(PHI[i])) - LBW / 2)
    fvec = sp.Matrix(f)
    jq = sp.Matrix([sp.diff(f[i], PHI[i]) for i in range(3)])
    jx = -fvec.jacobian(sp.Matrix([ALPHA, BETA, LBW]))
    dv.exports["jacobians"] = (jq, jx)

    fq = sp.lambdify((PHI, (ALPHA, BETA, LBW), L), (jq, jx), "numpy")

    def rate_error(rng) -> float:
        # closed-form IK (branch +) along x(t) = x0 + t v: finite-difference phi_dot against Jq^-1 Jx v
        x0 = np.array([rng.uniform(-3, 3), rng.uniform(0.2, 1.0), rng.uniform(0.07, 0.09)])
        v = rng.normal(size=3) * np.array([1.0, 1.0, 0.01])

        def ik(x):
            out = []
            for i in range(3):
                a_i = math.sin(x[1] / 2) * math.sin(x[0] - 2 * math.pi * i / 3)
                b = math.cos(x[1] / 2)
                out.append(math.atan2(b, a_i) + math.acos(x[2] / 0.12 / math.hypot(a_i, b)))
            return np.array(out)

        eps = 1e-6
        qdot = (ik(x0 + eps * v) - ik(x0 - eps * v)) / (2 * eps)
        jqv, jxv = fq(ik(x0), x0, 0.06)
        pred = (np.asarray(jxv, dtype=float) @ v) / np.asarray(jqv, dtype=float).ravel()
        return float(np.max(np.abs(pred - qdot)))

    dv.add(Step(
        "jacobians", "Rate Jacobians and the singular sets",
        "differentiate F_i = L (A_i cos phi_i + B sin phi_i) - l_bw/2 = 0: Jq phi_dot = Jx (alpha, beta, l_bw)_dot "
        "with Jq = diag(dF_i/dphi_i) (zero: the two roots of leg i merge, an inverse singularity) and "
        "Jx = -dF/d(alpha, beta, l_bw); the mirror plane is undefined when S1, S2, S3 are collinear (N = 0, a direct "
        "singularity of the symmetric model); alpha is undefined at beta = 0 (representation, not mechanism)",
        ("leg_equations",), {"Jq": jq, "Jx": jx},
        (numeric_predicate(rate_error, "Jq^-1 Jx v equals finite differences of the closed-form IK",
                           samples=60, tol=1e-7),)))
    _atlas_rates(dv, jq, jx)


def _atlas_rates(dv: Derivation, jq, jx) -> None:
    """The rates on the design atlas's velocity v = (sin beta alpha_dot, beta_dot, l_bw_dot / L) (docs/atlas.md):
    the platform normal's velocity on the unit sphere and the centre distance in link lengths, so the Jacobian is
    dimensionless and free of the azimuth's representation singularity at beta = 0. Jx's alpha column carries
    sin(beta/2); dividing it by sin(beta) = 2 sin(beta/2) cos(beta/2) cancels exactly (finite at beta = 0)."""
    half = 2 * sp.sin(BETA / 2) * sp.cos(BETA / 2)
    rows = sp.Matrix(3, 3, lambda i, j: sp.cancel(jx[i, 0] / half) if j == 0 else jx[i, j] * (L if j == 2 else 1))
    dv.exports["atlas_rates"] = (jq, rows)
    dv.add(Step(
        "atlas_rates", "Rate Jacobian of the design atlas",
        "Jq phi_dot = X v with v = (sin beta alpha_dot, beta_dot, l_bw_dot / L): X = Jx diag(1 / sin beta, 1, L), "
        "the sin(beta/2) of Jx's alpha column cancelled against sin beta = 2 sin(beta/2) cos(beta/2), so X is "
        "finite at beta = 0 (the atlas's local index 1/kappa_F(Jq^-1 X), docs/atlas.md)",
        ("jacobians",), {"X": rows},
        (symbolic_identity(rows * sp.diag(sp.sin(BETA), 1, 1 / L), jx, "X diag(sin beta, 1, 1/L) = Jx"),
         Check("symbolic", "X's alpha column has no sin(beta/2) left (no 0/0 at beta = 0)",
               not any(r.has(sp.sin(BETA / 2)) for r in rows[:, 0])))))


# ------------------------------------------------------------------------------------------------- findings
def _findings() -> list[Finding]:
    rows = ", ".join(f"{b} deg: {max_gamma_difference(math.radians(b)):.2f} vs {seed_fd(b):.2f}"
                     for b in (15, 30, 45, 60, 65))
    s2 = g.leg_point(1, sp.Rational(7, 10), 1)
    s3 = g.leg_point(2, sp.Rational(7, 10), 1)
    s1 = g.leg_point(0, sp.Rational(3, 5), 1)
    n = g.mirror_normal(sp.Rational(1, 2), sp.Rational(3, 5))
    lbw = sp.Rational(8, 100)
    return [
        Finding("leg-plane conditions", "S2(x) - sqrt(S2(y)) = 0 and S3(x) + sqrt(S3(y)) = 0",
                "S2x - sqrt(3) S2y = 0 and S3x + sqrt(3) S3y = 0 (S_i lies in the plane perpendicular to u_i)",
                "wrong in seed",
                f"phi = 0.7 rad, L = 1: S2 = ({float(s2[0]):.4f}, {float(s2[1]):.4f}): S2x - sqrt(3) S2y = "
                f"{measured(float(s2[0] - sp.sqrt(3) * s2[1]))}, while S2x - sqrt(S2y) is undefined (S2y < 0); "
                f"S3x + sqrt(3) S3y = {measured(float(s3[0] + sp.sqrt(3) * s3[1]))}"),
        Finding("mid-plane condition", "O_B S_1 . O_B O_W = L_BW / 2",
                "O_B S_i . n = L_BW / 2 (equivalently O_B S_i . O_B O_W = L_BW^2 / 2)", "wrong in seed",
                "dimensions: the left side is a length squared; with L_BW = 0.08 m, O_B S_i . O_B O_W = 0.0032 m^2 "
                "and n . O_B S_i = 0.04 m = L_BW / 2"),
        Finding("IK of the wrist", "9 unknowns (S1..S3) from 9 simultaneous equations, then eq. (12)",
                "three decoupled equations A_i cos phi_i + B sin phi_i = l_bw / (2L), two roots each (8 sets)",
                "clarified",
                "the leg equations are proven symbolically (step leg_equations); eq. (12) phi_i = "
                "arctan(S_z / sqrt(S_x^2 + S_y^2)) only returns phi in (-90, 90) deg: it misses every root with "
                "cos phi < 0, e.g. the second root of each leg at alpha = 0, beta = 0, l_bw = 0.08 m, L = 0.06 m "
                f"is {math.degrees(math.pi - math.asin(0.08 / 0.12)):.2f} deg"),
        Finding("platform torsion", "platform and base symmetric about the plane S1S2S3",
                "R_W = Rz(alpha) Ry(beta) Rz(-alpha): a pure tilt, torsion 0 (proven symbolically)", "reproduced",
                "steps platform_rotation, zero_torsion, legs_close; the base radius R of eq. (4) drops out"),
        Finding("rotation angle gamma and f_d(beta)",
                "gamma from Fig. 3(a); fitted max(gamma - alpha) = f_d(beta) (k1..k5, omega); alpha from gamma by "
                "bisection; critical swing angle between 60 and 65 deg",
                "gamma = atan2(sin alpha1, cos beta cos alpha1) (our precise reading of Fig. 3a), max(gamma - alpha1) "
                "= asin(tan^2(beta/2)) in closed form, inverse alpha1 = atan2(cos beta sin gamma, cos gamma)",
                "not reproducible",
                f"max difference, ours vs seed's f_d: {rows}; f_d(0) = {seed_fd(0):.3f} deg. The seed's text does "
                "not define gamma precisely enough to reproduce its curves; under our definition gamma(alpha1) is "
                "one-to-one for every beta < 90 deg (d gamma/d alpha1 > 0, proven), so the representation's only "
                "critical swing is 90 deg, not 60-65 deg"),
        Finding("centre position (eq. 9)", "X_w = L_BW sin(beta/2) cos alpha1, ..., Z_w = L_BW cos(beta/2)",
                "O_W = l_bw n(alpha, beta)", "reproduced",
                f"step centre; e.g. alpha = 0.5, beta = 0.6, l_bw = 0.08: O_W_z = {float(lbw * n[2]):.6f} m"),
        Finding("symmetric plane", "the plane through S1, S2, S3", "N = S1S2 x S1S3", "reproduced",
                f"collinear S_i (N = 0) is the direct singularity of the construction; e.g. S1 = "
                f"({float(s1[0]):.3f}, {float(s1[1]):.3f}, {float(s1[2]):.3f}) at phi = 0.6"),
    ]


# --------------------------------------------------------------------------------------------------- kernels
def kernels(dv: Derivation):
    from ...lower import Kernel

    design = ("design", (L,))
    pose = ("pose", (ALPHA, BETA, LBW))
    q = ("q", PHI)
    coeffs = dv["leg_equations"].result
    nvec = dv.exports["plane_N"]
    pts = dv.exports["leg_points"]
    jq, jx = dv.exports["jacobians"]
    xa = dv.exports["atlas_rates"][1]
    nx, ny, nz, h = sp.symbols("nx ny nz h", real=True)
    plane = ("plane", (nx, ny, nz, h))
    nn = sp.Matrix([nx, ny, nz])
    rw = g.platform_rotation_mirror(nn)
    return [
        Kernel("ik_coeffs", "Leg equations A_i cos phi_i + B sin phi_i = C.", (pose, design),
               (("A1", coeffs["A1"]), ("A2", coeffs["A2"]), ("A3", coeffs["A3"]), ("B", coeffs["B"]),
                ("C", coeffs["C"]))),
        Kernel("fk_plane", "Mirror plane: unnormalised normal N = S1S2 x S1S3 and the point S1.", (q, design),
               tuple((f"N{c}", nvec[k]) for k, c in enumerate("xyz")) +
               tuple((f"S1{c}", pts[0][k]) for k, c in enumerate("xyz"))),
        Kernel("fk_plane_cs", "fk_plane on (cos phi_i, sin phi_i): lets IK check each set without trigonometry.",
               (("cs", (*CQ, *SQ)), design),
               tuple((f"N{c}", nvec[k].subs(_CS)) for k, c in enumerate("xyz")) +
               tuple((f"S1{c}", pts[0][k].subs(_CS)) for k, c in enumerate("xyz"))),
        Kernel("fk_pose", "Platform pose from the unit plane normal n and offset h: R_W = (I - 2 n n^T) "
               "diag(1, 1, -1), O_W = 2 h n, as the 12 entries of [R_W | O_W] row-major.", (plane,),
               tuple((f"r{i}{j}", rw[i, j]) if j < 3 else ("pxyz"[i + 1], 2 * h * nn[i])
                     for i in range(3) for j in range(4))),
        Kernel("geometric_jacobian", "Geometric Jacobian 6 x 3 (row-major): platform centre velocity, then "
               "angular velocity, per phi_dot.", (q, design),
               tuple((f"j{i}{c}", dv.exports["geometric_jacobian"][i, c]) for i in range(6) for c in range(3))),
        Kernel("jacobians", "Rate Jacobians: Jq (diagonal, 3) and Jx (3x3 row-major) with Jq phi_dot = Jx "
               "(alpha, beta, l_bw)_dot.", (q, pose, design),
               tuple((f"jq{i}", jq[i]) for i in range(3)) +
               tuple((f"jx{i}{j}", jx[i, j]) for i in range(3) for j in range(3))),
        Kernel("atlas_rates", "The design atlas's rates: Jq (3) and X (3x3 row-major) with Jq phi_dot = X v, "
               "v = (sin beta alpha_dot, beta_dot, l_bw_dot / L); finite at beta = 0.", (q, pose, design),
               tuple((f"g{i}", jq[i]) for i in range(3)) +
               tuple((f"x{i}{j}", xa[i, j]) for i in range(3) for j in range(3))),
    ]


def extra_context(ks, name: str, design_default) -> dict:
    return {"name": name, "upper": name.upper(), "design_names": DESIGN_NAMES,
            "design_values": [repr(v) for v in design_default], "leg_angles": [repr(2 * math.pi * i / 3)
                                                                                for i in range(3)]}


def casadi_functions(dv, ks):
    from .rsr_casadi import wrist_functions

    return wrist_functions(ks)


def audit_numbers(dv, solver, audit_dir):
    from .rsr_audit import wrist_audit_numbers

    return wrist_audit_numbers(dv, solver, audit_dir, kernels(dv))
