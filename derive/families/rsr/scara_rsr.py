"""Hybrid robot of seed 002: a 4-DOF SCARA (modified DH) carrying the 3-RSR wrist upside down, T = T_s T_c T_w.

Joints q = (theta1, theta2, d3, theta4, phi1, phi2, phi3); d3 is the downward stroke (flange height d - d3).
Pose = the platform frame [R | p] (12 entries, row-major) plus the centre distance l_bw of the wrist, the
redundant coordinate. Orientation split (derived below): R = Rz(theta) C Rz(alpha1) Ry(beta) Rz(-alpha1) with
theta = theta1 + theta2 + theta4 and C = diag(1, -1, -1), so the tool approach R e_z points down, swung by beta
towards azimuth alpha = theta - alpha1.
"""

from __future__ import annotations

import math

import numpy as np
import sympy as sp

from ...checks import numeric_predicate, symbolic_identity
from ...identities.dh import dh_modified
from ...identities.frames import rot_x, rot_z
from ...mechanism import CApi
from ...model import Derivation, Finding, Step
from ...report_numbers import measured
from . import rsr_geometry as g
from . import rsr_wrist
from .rsr_geometry import BETA, LBW, PHI, L

# name, title, source and the default design come from the spec (catalogue/scara_rsr.toml)
FAMILY = "rsr"
VECTORISED_KERNELS = ()
DERIVE_GROUP = "rsr"  # regenerated in the wrist's process: it builds on the wrist's cached derivation
DERIVE_SECONDS = 3
TEMPLATES = ("python/scara_rsr.py.jinja", "c/scara_rsr.h.jinja", "c/scara_rsr.c.jinja")
C_API = CApi(jacobian=True, fk_matrix=True)
CASADI_DESIGN_NAMES = None  # the solver's DESIGN_NAMES
TH1, TH2, D3, TH4 = sp.symbols("theta1 theta2 d3 theta4", real=True)
L1, L2, D, DF = sp.symbols("L1 L2 d d_f", real=True)
ALPHA1, THETA = sp.symbols("alpha1 theta", real=True)
JOINTS = (TH1, TH2, D3, TH4, *PHI)
DESIGN_NAMES = ("L1", "L2", "d", "d_f", *rsr_wrist.DESIGN_NAMES)
C_FLIP = sp.diag(1, -1, -1)


def scara_rows(sign_d3: int):
    """Seed Table I rows (a_{i-1}, alpha_{i-1}, d_i, theta_i); sign_d3 = +1 as printed, -1 = eq. (1)."""
    return ((0, 0, D, TH1), (L1, 0, 0, TH2), (L2, 0, sign_d3 * D3, 0), (0, 0, 0, TH4))


def scara_product(sign_d3: int = -1) -> sp.Matrix:
    """T_s as the plain product of the link transforms."""
    t = sp.eye(4)
    for row in scara_rows(sign_d3):
        t = t * dh_modified(*row)
    return t


def scara_transform(sign_d3: int = -1) -> sp.Matrix:
    return scara_product(sign_d3).applyfunc(sp.simplify)


def t_c() -> sp.Matrix:
    m = sp.eye(4)
    m[:3, :3] = C_FLIP
    m[2, 3] = -DF
    return m


def wrist_transform(alpha1=ALPHA1, beta=BETA, lbw=LBW) -> sp.Matrix:
    m = sp.eye(4)
    m[:3, :3] = g.tilt_rotation(alpha1, beta)
    m[:3, 3] = lbw * g.mirror_normal(alpha1, beta)
    return m


def eq1_matrix() -> sp.Matrix:
    s124, c124 = sp.sin(TH1 + TH2 + TH4), sp.cos(TH1 + TH2 + TH4)
    return sp.Matrix([[c124, -s124, 0, L2 * sp.cos(TH1 + TH2) + L1 * sp.cos(TH1)],
                      [s124, c124, 0, L2 * sp.sin(TH1 + TH2) + L1 * sp.sin(TH1)],
                      [0, 0, 1, D - D3], [0, 0, 0, 1]])


def derive() -> Derivation:
    dv = Derivation(FAMILY, FAMILY, "", {s.name: s for s in (TH1, TH2, D3, TH4, *PHI, L1, L2, D, DF, L, ALPHA1,
                                                             BETA, LBW, THETA)})
    ts = scara_transform(-1)
    ts_printed = scara_product(+1)  # only its height is compared (the check proves it unsimplified)
    dv.add(Step(
        "scara_fk", "SCARA forward kinematics T_s by modified DH",
        "Craig's A_i = Rx(alpha_{i-1}) Tx(a_{i-1}) Rz(theta_i) Tz(d_i) over seed Table I; the stroke d3 enters with "
        "d_3 -> -d3 (downward), which is eq. (1)",
        (), {"T_s": ts},
        (symbolic_identity(ts, eq1_matrix(), "T_s (d_3 := -d3) equals seed eq. (1)"),
         symbolic_identity(ts_printed[2, 3], D + D3, "Table I as printed gives z = d + d3, not eq. (1)'s d - d3")),
        source="seed 002, Table I and eq. (1)"))
    tw = wrist_transform()
    total = ts * t_c() * tw
    dv.add(Step(
        "hybrid_fk", "Hybrid forward kinematics T = T_s T_c T_w",
        "serial composition; T_w = [Rz(alpha1) Ry(beta) Rz(-alpha1) | l_bw n(alpha1, beta)] from the wrist "
        "derivation (steps zero_torsion, centre of rsr_wrist)",
        ("scara_fk",), {"T_c": t_c(), "T": total},
        (symbolic_identity(t_c()[:3, :3] * t_c()[:3, :3].T, sp.eye(3), "T_c is a rigid transform (C C^T = I)"),),
        source="seed 002, eqs. (6)-(8)"))
    rt = total[:3, :3]
    split = rot_z(THETA - ALPHA1) * g.rot_y(-BETA) * rot_z(ALPHA1) * rot_x(sp.pi)
    dv.add(Step(
        "orientation_split", "Orientation split: SCARA rotation theta, wrist azimuth alpha1, swing beta",
        "C Rz(a) = Rz(-a) C and C Ry(b) = Ry(-b) C (C = Rx(pi)): R = Rz(theta - alpha1) Ry(-beta) Rz(alpha1) Rx(pi), "
        "theta = theta1 + theta2 + theta4; the approach R e_z = (sin beta cos alpha, sin beta sin alpha, -cos beta) "
        "with alpha = theta - alpha1. Inverse: beta = atan2(|a_xy|, -a_z), alpha = atan2(a_y, a_x), and with "
        "N = Rz(-alpha) R Rx(pi) = Ry(-beta) Rz(alpha1): alpha1 = atan2(N_10, N_11); at beta = 0 the wrist does "
        "not depend on alpha1, which is set to 0",
        ("hybrid_fk",), {"R": split},
        (symbolic_identity(rt.subs(TH4, THETA - TH1 - TH2), split,
                           "R(theta1, theta2, theta4, alpha1, beta) = Rz(theta - alpha1) Ry(-beta) Rz(alpha1) Rx(pi)"),
         symbolic_identity((rot_z(-(THETA - ALPHA1)) * split * rot_x(sp.pi))[1, :],
                           sp.Matrix([[sp.sin(ALPHA1), sp.cos(ALPHA1), 0]]),
                           "row 1 of N = (sin alpha1, cos alpha1, 0)"),
         numeric_predicate(_orientation_roundtrip, "extraction (alpha, beta, alpha1) from R recovers theta and alpha1",
                           samples=300, tol=1e-12)),
        source="seed 002, Sec. III-B-1 and eq. (11)"))
    offset = rot_z(THETA) * (C_FLIP * LBW * g.mirror_normal(ALPHA1, BETA) + sp.Matrix([0, 0, -DF]))
    p_total = total[:3, 3].subs(TH4, THETA - TH1 - TH2)
    p4 = ts[:3, 3]
    dv.add(Step(
        "position_split", "Position split: flange point from the tool point",
        "p = p_4 + Rz(theta) (C l_bw n(alpha1, beta) + (0, 0, -d_f)), p_4 = (L1 c1 + L2 c12, L1 s1 + L2 s12, d - d3)",
        ("orientation_split",), {"offset": offset},
        (symbolic_identity(p_total, p4 + offset, "translation of T_s T_c T_w = p_4 + offset"),),
        source="seed 002, Fig. 8 and eq. (9)"))
    dv.add(Step(
        "scara_ik", "Planar two-link IK, both elbows; stroke and fourth joint",
        "law of cosines, factored so neither fold cancels: "
        "1 + cos theta2 = (r - |L1 - L2|)(r + |L1 - L2|) / (2 L1 L2), "
        "1 - cos theta2 = (L1 + L2 - r)(L1 + L2 + r) / (2 L1 L2), sin theta2 = +/- sqrt of their product; "
        "theta1 = atan2(y, x) - atan2(L2 sin theta2, (L1 - L2) + L2 (1 + cos theta2)); d3 = d - z_4; "
        "theta4 = theta - theta1 - theta2 (wrapped)",
        ("position_split", "scara_fk"), {},
        (numeric_predicate(_scara_ik_error, "both elbow solutions reproduce p_4, random L1, L2 and joints, a third "
                           "folded with L1 = L2",
                           samples=300, tol=1e-12),)))
    from .rsr_jacobian import LEG_RANGE, jacobian_step, wrist_transform_of_joints

    t_q = ts * t_c() * wrist_transform_of_joints(rsr_wrist.derive_cached())
    step, jac = jacobian_step("geometric_jacobian", t_q, JOINTS, (L1, L2, D, DF, L),
                              [(-3.0, 3.0), (-3.0, 3.0), (0.0, 0.3), (-3.0, 3.0)] + [LEG_RANGE] * 3,
                              ("hybrid_fk",))
    dv.add(step)
    dv.exports.update({"T": total, "offset": offset, "T_s": ts, "jacobian": jac})
    dv.findings.extend(_findings())
    return dv


def _orientation_roundtrip(rng) -> float:
    theta, a1, beta = rng.uniform(-math.pi, math.pi), rng.uniform(-math.pi, math.pi), rng.uniform(1e-3, 2.5)
    r = (_rz(theta) @ np.diag([1.0, -1.0, -1.0]) @ _rz(a1) @ _ry(beta) @ _rz(-a1))
    alpha, beta_x, a1_x = extract_orientation(r)
    return max(abs(beta_x - beta), abs(math.remainder(a1_x - a1, 2 * math.pi)),
               abs(math.remainder(alpha + a1_x - theta, 2 * math.pi)))


def extract_orientation(r):
    """(alpha, beta, alpha1) from the platform rotation (numpy mirror of the generated code, for the checks)."""
    ax, ay, az = r[0, 2], r[1, 2], r[2, 2]
    beta = math.atan2(math.hypot(ax, ay), -az)
    alpha = math.atan2(ay, ax)
    ca, sa = math.cos(alpha), math.sin(alpha)
    n10 = -sa * r[0, 0] + ca * r[1, 0]
    n11 = -(-sa * r[0, 1] + ca * r[1, 1])
    return alpha, beta, math.atan2(n10, n11)


def _rz(a):
    return np.array([[math.cos(a), -math.sin(a), 0.0], [math.sin(a), math.cos(a), 0.0], [0.0, 0.0, 1.0]])


def _ry(a):
    return np.array([[math.cos(a), 0.0, math.sin(a)], [0.0, 1.0, 0.0], [-math.sin(a), 0.0, math.cos(a)]])


def scara_elbows(x: float, y: float, l1: float, l2: float):
    """Both elbows (theta1, theta2) of the planar two-link at (x, y), as the generated solvers compute them: 1 +/- cos
    theta2 from factored differences of squares, so neither fold cancels."""
    r, dl = math.hypot(x, y), abs(l1 - l2)
    opc = max(0.0, (r - dl) * (r + dl) / (2 * l1 * l2))
    omc = max(0.0, (l1 + l2 - r) * (l1 + l2 + r) / (2 * l1 * l2))
    c2 = opc - 1.0 if opc <= omc else 1.0 - omc
    sg = math.sqrt(opc * omc)
    k = (l1 - l2) + l2 * opc  # L1 + L2 cos theta2
    return [(math.atan2(y, x) - math.atan2(l2 * s2, k), math.atan2(s2, c2)) for s2 in (sg, -sg)]


def _scara_ik_error(rng) -> float:
    """Both elbows reproduce p_4: random links and joints, a third of the samples folded to within 1e-3 .. 1e-9 rad of
    theta2 = pi with L1 = L2 (the flange nanometres from axis 1, where the plain law of cosines lost theta1)."""
    l1, l2 = rng.uniform(0.1, 0.4, 2)
    t1, t2 = rng.uniform(-math.pi, math.pi, 2)
    if rng.uniform() < 1 / 3:
        l2 = l1
        t2 = math.copysign(math.pi - 10.0 ** rng.uniform(-9, -3), t2)
    x, y = l1 * math.cos(t1) + l2 * math.cos(t1 + t2), l1 * math.sin(t1) + l2 * math.sin(t1 + t2)
    worst = 0.0
    for th1, th2 in scara_elbows(x, y, l1, l2):
        worst = max(worst, abs(l1 * math.cos(th1) + l2 * math.cos(th1 + th2) - x),
                    abs(l1 * math.sin(th1) + l2 * math.sin(th1 + th2) - y))
    return worst


def _findings() -> list[Finding]:
    # Eq. (13) with L1 = L2 = 0.25 at a point in the second quadrant, both sign pairings.
    l1, x, y = 0.25, -0.2, 0.3
    phi1_atan = math.atan(y / x)
    phi1 = math.atan2(y, x)
    phi2 = math.acos(math.hypot(x, y) / (2 * l1))

    def reach(t1, t2):
        return math.hypot(l1 * math.cos(t1) + l1 * math.cos(t1 + t2) - x,
                          l1 * math.sin(t1) + l1 * math.sin(t1 + t2) - y)

    same = reach(phi1 + phi2, 2 * phi2)
    opposite = reach(phi1 + phi2, -2 * phi2)
    atan_err = reach(phi1_atan - phi2, 2 * phi2)
    a1, beta = math.radians(30.0), math.radians(40.0)
    rw = _rz(a1) @ _ry(beta) @ _rz(-a1)
    eq10 = rw @ np.diag([1.0, -1.0, -1.0])
    tc = np.diag([1.0, -1.0, -1.0]) @ rw
    # theta1 + theta2 + theta4 versus alpha -/+ alpha1 at theta = 50 deg, alpha1 = 30 deg
    theta = math.radians(50.0)
    r = _rz(theta) @ np.diag([1.0, -1.0, -1.0]) @ rw
    alpha, _, _ = extract_orientation(r)
    circle = [math.hypot(yy, zz + 410.0) for yy, zz in ((-200.0, -63.5898), (0.0, -10.0), (200.0, -63.5898))]
    return [
        Finding("flange height", "Table I: d_3 on joint 3 (modified DH) and eq. (1): z = d - d3",
                "Table I as printed gives z = d + d3 (proven, step scara_fk); eq. (1) and the IK d3 = d - Z_s need "
                "the stroke measured downward (d_3 -> -d3)", "wrong in seed",
                "the symbolic product of Table I's rows has (2, 3) entry d + d3; we adopt eq. (1) (d3 >= 0 lowers "
                "the flange), consistent with the seed's own IK"),
        Finding("SCARA elbow signs (eq. 13)", "theta1 = phi1 +/- phi2 with theta2 = +/- 2 phi2",
                "theta1 = phi1 -/+ phi2 with theta2 = +/- 2 phi2 (opposite signs), phi1 = atan2(Y_s, X_s)",
                "wrong in seed",
                f"L1 = L2 = 0.25 m, target (x, y) = ({x}, {y}) m: same signs miss by {same:.4f} m, opposite signs by "
                f"{measured(opposite)} m; phi1 = arctan(Y/X) (no quadrant) misses by {atan_err:.4f} m"),
        Finding("wrist rotation in the flange frame (eq. 10)", "R = [Wx, -Wy, -Wz]",
                "T_c's rotation C = diag(1, -1, -1) acts from the left: C R_W negates rows 2 and 3, not columns",
                "wrong in seed",
                f"alpha1 = 30 deg, beta = 40 deg: max abs([Wx, -Wy, -Wz] - C R_W) = "
                f"{float(np.max(np.abs(eq10 - tc))):.3f}"),
        Finding("azimuth bookkeeping", "theta1 + theta2 + theta4 = alpha - alpha1",
                "theta1 + theta2 + theta4 = alpha + alpha1 (proven in step orientation_split)", "wrong in seed",
                f"theta = 50 deg, alpha1 = 30 deg: the approach azimuth alpha = {math.degrees(alpha):.1f} deg, so "
                f"alpha + alpha1 = {math.degrees(alpha + a1):.1f} deg = theta, alpha - alpha1 = "
                f"{math.degrees(alpha - a1):.1f} deg; the two agree only where alpha1 = 0 or 180 deg, which is "
                "where the seed's example sits"),
        Finding("arc example path", "P1 (250, -200, -63.5898), P2 (250, 0, -10), P3 (250, 200, -63.5898) mm",
                "a circle of radius 400 mm centred at (250, 0, -410) mm in the plane x = 250", "clarified",
                f"distances from the centre: {', '.join(f'{c:.4f}' for c in circle)} mm"),
    ]


def kernels(dv: Derivation):
    from ...lower import Kernel

    scara = ("qs", (TH1, TH2, D3, TH4))
    design = ("design", (L1, L2, D, DF))
    rwvars = sp.symbols("w0:12", real=True)  # wrist platform pose [R_W | p_W] row-major
    tw = sp.Matrix([[rwvars[0], rwvars[1], rwvars[2], rwvars[3]], [rwvars[4], rwvars[5], rwvars[6], rwvars[7]],
                    [rwvars[8], rwvars[9], rwvars[10], rwvars[11]], [0, 0, 0, 1]])
    composed = dv.exports["T_s"] * t_c() * tw
    offset = dv.exports["offset"]
    unused = ("jacobians", "geometric_jacobian", "atlas_rates")  # the hybrid's own Jacobian is below
    wrist = [k for k in rsr_wrist.kernels(rsr_wrist.derive_cached()) if k.name not in unused]
    return wrist + [
        Kernel("fk_compose", "T = T_s T_c T_w: the 12 entries of [R | p] from the SCARA joints and the wrist pose.",
               (scara, ("tw", rwvars), design),
               tuple((f"t{i}{j}", composed[i, j]) for i in range(3) for j in range(4))),
        Kernel("jacobian", "Geometric Jacobian 6 x 7 (row-major): platform centre velocity, then angular velocity.",
               (("q", JOINTS), ("design", (L1, L2, D, DF, L))),
               tuple((f"j{i}{c}", dv.exports["jacobian"][i, c]) for i in range(6) for c in range(7))),
        Kernel("wrist_offset", "p - p_4 = Rz(theta) (C l_bw n(alpha1, beta) + (0, 0, -d_f)).",
               (("x", (THETA, ALPHA1, BETA, LBW)), design),
               tuple((f"o{c}", offset[k]) for k, c in enumerate("xyz"))),
    ]


def extra_context(ks, name: str, design_default) -> dict:
    return {"name": name, "upper": name.upper(), "design_names": DESIGN_NAMES,
            "design_values": [repr(v) for v in design_default], "joint_kinds": ("R", "R", "P", "R", "R", "R", "R"),
            "leg_angles": [repr(2 * math.pi * i / 3) for i in range(3)]}


def casadi_functions(dv, ks):
    from .rsr_casadi import hybrid_functions

    return hybrid_functions(ks)


def audit_numbers(dv, solver, audit_dir):
    from .rsr_audit import hybrid_audit_numbers

    return hybrid_audit_numbers(dv, solver, audit_dir)
