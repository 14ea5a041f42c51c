"""Underactuated 3-DOF spherical wrist (seed 000): derivation of IK, FK and rates.

Every quantity is derived from the geometry (unit axes through O, rotation
products, spherical-triangle laws) and checked before it is stored. The
generated solvers consume only the `kernels` this module exposes.
"""

from __future__ import annotations

import math

import numpy as np
import sympy as sp

from ...checks import identity, numeric_identity, numeric_predicate, sampler, symbolic_identity
from ...identities.frames import E_Z, rot_x, rot_z, rot_zxz, zxz_rate_matrix
from ...identities.polynomial import (
    affine_cs_coefficients,
    cramer_cs,
    elimination_identity,
    half_angle_quadratic,
    weierstrass,
)
from ...identities.spherical import (
    cos_angle_between_cone_axes,
    equilateral_interior_angle_cos,
    polygon_vertex,
    triangle_direction_cosines,
)
from ...model import Check, Derivation, Step
from . import wrist_casadi

# name, title and source come from the spec (catalogue/underactuated_wrist.toml); the derivation is the same
FAMILY = "spherical_parallel"

DESIGN_NAMES = ("alpha1", "alpha2", "beta1", "beta2")
CASADI_DOCS = wrist_casadi.FUNCTION_DOCS  # the CasADi index's function descriptions
DERIVE_SECONDS = 10  # a scheduling hint for parallel regeneration (seconds on a 2-core 2026 EPYC)
VECTORISED_KERNELS = ("ik_abc", "middle_axes", "platform_axes", "base_axes", "fk_def", "fk_rotation")
# the paper's design (alpha1 = alpha2 = 60 deg, beta1 = 30 deg, beta2 = 43.89 deg): its printed numbers hold there
DESIGN_DEFAULT_DEG = (60.0, 60.0, 30.0, 43.89)
JOINT_NAMES = ("theta1", "theta2", "theta3")
POSE_NAMES = ("psi", "theta", "phi")

a1, a2, b1, b2 = sp.symbols("alpha1 alpha2 beta1 beta2", real=True)
A3S, KPS = sp.symbols("alpha3 kappa", positive=True)  # platform cone angle, platform triangle interior angle
th = sp.symbols("theta1:4", real=True)
psi, nu, phi = sp.symbols("psi theta phi", real=True)
zeta, eta = sp.symbols("zeta eta", real=True)
x = sp.Symbol("x", real=True)
c_, s_ = sp.symbols("c s", real=True)  # stand-ins for cos/sin of the angle being collected
DELTA = (0, 2 * sp.pi / 3, 4 * sp.pi / 3)

# Design constants precomputed once per design (names used by the generated code).
ca1, sa1, ca2, sa2, cb1, sb1 = sp.symbols("ca1 sa1 ca2 sa2 cb1 sb1", real=True)
ca3, sa3, ck, sk = sp.symbols("ca3 sa3 ck sk", real=True)
G = sp.Matrix(3, 3, sp.symbols("g00 g01 g02 g10 g11 g12 g20 g21 g22", real=True))
P = sp.Matrix(3, 3, sp.symbols("p0x p0y p0z p1x p1y p1z p2x p2y p2z", real=True))  # row i: platform axis i
Rm = sp.Matrix(3, 3, sp.symbols("r00 r01 r02 r10 r11 r12 r20 r21 r22", real=True))
wv = sp.Matrix(sp.symbols("wx wy wz", real=True))
qd = sp.Matrix(sp.symbols("thetad1:4", real=True))

DESIGN_RANGES = {a1: (0.3, 2.8), a2: (0.3, 2.8), b1: (0.0, 1.5), b2: (0.1, 1.5)}
ANGLE = (-math.pi, math.pi)


def _trig_to_constants() -> dict:
    return {sp.cos(a1): ca1, sp.sin(a1): sa1, sp.cos(a2): ca2, sp.sin(a2): sa2,
            sp.cos(b1): cb1, sp.sin(b1): sb1}


def base_axis(i: int) -> sp.Matrix:
    return rot_z(DELTA[i]) * rot_x(sp.pi - b1) * E_Z


def middle_axis(i: int, q) -> sp.Matrix:
    return rot_z(DELTA[i]) * rot_x(sp.pi - b1) * rot_z(q) * rot_x(a1) * E_Z


def platform_axis_home(i: int) -> sp.Matrix:
    return rot_z(DELTA[i]) * rot_x(b2) * E_Z


def g_matrix() -> sp.Matrix:
    """Constant platform rotation: maps p1 -> e_z and p2 -> Rx(alpha3) e_z."""
    return rot_z(-sp.pi / 2 - sp.atan(sp.sqrt(3) * sp.cos(b2))) * rot_x(-b2)


def alpha3_of(beta2):
    return sp.acos(cos_angle_between_cone_axes(beta2))


def kappa_of(alpha3):
    return sp.acos(equilateral_interior_angle_cos(alpha3))


# ---------------------------------------------------------------- numeric helpers (checks only)
def _rand_design(rng):
    return [rng.uniform(*DESIGN_RANGES[s]) for s in (a1, a2, b1, b2)]


def derive() -> Derivation:
    """Run the whole derivation; every step is checked as it is added."""
    dv = Derivation(FAMILY, FAMILY, "", {s.name: s for s in (a1, a2, b1, b2, *th, psi, nu, phi, zeta, eta)})
    _design_relations(dv)
    _inverse_kinematics(dv)
    _forward_kinematics(dv)
    _rates(dv)
    return dv


# ------------------------------------------------------------------------------ design relations
def _design_relations(dv: Derivation) -> None:
    p = [platform_axis_home(i) for i in range(3)]
    z1 = [base_axis(i) for i in range(3)]
    dv.add(Step(
        "platform_axes_home", "Platform axes in the platform frame",
        "axes on a cone of half-angle beta2 about Z', 120 deg apart: p_i = Rz(delta_i) Rx(beta2) e_z",
        (), {"p1": p[0], "p2": p[1], "p3": p[2]},
        (symbolic_identity(sp.Matrix([p[i].dot(E_Z) for i in range(3)]),
                           sp.Matrix([sp.cos(b2)] * 3), "angle(p_i, Z') = beta2"),
         symbolic_identity(sp.Matrix([p[i].dot(p[i]) for i in range(3)]), sp.ones(3, 1), "|p_i| = 1")),
        source="seed 000, design parameter 4"))
    cos_a3 = cos_angle_between_cone_axes(b2)
    dv.add(Step(
        "alpha3", "Platform cone angle alpha3 from beta2",
        "dot product of two cone axes 120 deg apart: cos alpha3 = cos^2 beta2 + sin^2 beta2 cos 120deg",
        ("platform_axes_home",), {"cos_alpha3": cos_a3, "sin_half_alpha3": sp.sqrt(3) / 2 * sp.sin(b2)},
        (symbolic_identity(sp.Matrix([p[0].dot(p[1]), p[1].dot(p[2]), p[2].dot(p[0])]),
                           sp.Matrix([cos_a3] * 3), "p_i . p_j = 1 - 3/2 sin^2 beta2 for all pairs"),
         symbolic_identity(1 - 2 * (sp.sqrt(3) / 2 * sp.sin(b2)) ** 2, cos_a3,
                           "equivalently sin(alpha3/2) = (sqrt 3 / 2) sin beta2")),
        source="seed 000, relation between beta2 and alpha3 (formula lost in seed)"))
    dv.add(Step(
        "base_axes", "Base axes Zi1",
        "angle(Z, Zi1) = pi - beta1 (axes point outward-down), rotated by delta_i about Z",
        (), {"Z11": z1[0], "Z21": z1[1], "Z31": z1[2]},
        (symbolic_identity(sp.Matrix([z1[i].dot(E_Z) for i in range(3)]),
                           sp.Matrix([-sp.cos(b1)] * 3), "Z . Zi1 = cos(pi - beta1)"),),
        source="seed 000, coordinate system; notes: Zi1 = Rz(delta_i) Rx(pi - beta1) e_z"))
    gamma1_sin = sp.sqrt(3) / 2 * sp.sin(b1)
    dv.add(Step(
        "gamma1", "Base half-angle gamma1 from beta1 (reading of the seed's eq. 1)",
        "B taken as the midpoint of the chord U1U2 of the base cone's bottom circle, so gamma1 = angle(U1 O B)"
        " is half the angle between two base axes: sin gamma1 = (sqrt 3/2) sin beta1",
        ("base_axes",), {"sin_gamma1": gamma1_sin},
        (symbolic_identity(z1[0].dot(z1[1]), 1 - 2 * gamma1_sin**2, "Z11 . Z21 = cos(2 gamma1)"),),
        source="seed 000, eq. (1) (formula lost); this reading mirrors the beta2-alpha3 relation",
        note="The seed defines gamma1 = angle(U1 O B) with B 'the centre of the conical bottom edge'. If B were "
             "the centre of the bottom circle, gamma1 would equal beta1 and eq. (1) would be empty; the "
             "chord-midpoint reading is the one that makes eq. (1) a relation."))
    a3s = sp.Symbol("alpha3", positive=True)
    cos_k = equilateral_interior_angle_cos(a3s)

    home_axes = sampler((b2,), [platform_axis_home(i) for i in range(3)])  # subs per sample took 10x longer

    def kappa_err(rng):
        bb2 = rng.uniform(0.1, 1.5)
        pp = [np.asarray(v, dtype=float).ravel() for v in home_axes(bb2)]
        ta = pp[1] - pp[0] * pp[0].dot(pp[1])
        tb = pp[2] - pp[0] * pp[0].dot(pp[2])
        ang = math.atan2(pp[0].dot(np.cross(ta, tb)), ta.dot(tb))
        aa3 = math.acos(1 - 1.5 * math.sin(bb2) ** 2)
        return abs(ang - math.acos(math.cos(aa3) / (1 + math.cos(aa3))))
    dv.add(Step(
        "kappa", "Interior angle kappa (and exterior angle mu = pi - kappa) of the platform triangle at Z13",
        "spherical law of cosines for sides on the equilateral triangle (Z13, Z23, Z33) of side alpha3: "
        "cos a = cos^2 a + sin^2 a cos kappa",
        ("alpha3",), {"cos_kappa": cos_k, "sin_kappa": sp.sqrt(1 + 2 * sp.cos(a3s)) / (1 + sp.cos(a3s)),
                      "mu": sp.pi - sp.acos(cos_k)},
        (symbolic_identity(sp.cos(a3s), sp.cos(a3s) ** 2 + sp.sin(a3s) ** 2 * cos_k, "law of cosines holds"),
         numeric_predicate(kappa_err, "angle at p1 from arc(p1,p2) to arc(p1,p3), counter-clockwise, is +kappa",
                           samples=100, tol=1e-12)),
        source="seed 000, Figure 9 and the eta' relation"))
    # Home joint angle: IK at R = I. Derived from the loop condition below; closed form here.
    cth0 = -(sp.cos(a1) * sp.cos(b1 + b2) + sp.cos(a2)) / (sp.sin(a1) * sp.sin(b1 + b2))
    loop_home = middle_axis(0, th[0]).dot(platform_axis_home(0)) - sp.cos(a2)
    dv.add(Step(
        "home_angle", "Home joint angle theta0 (both roots)",
        "loop condition Zi2 . Zi3 = cos alpha2 at psi = theta = phi = 0; by the mirror symmetry of the home pose"
        " about the plane (Z, Zi1) the sine coefficient vanishes, so theta0 = +/- acos(...)",
        ("base_axes", "platform_axes_home"),
        {"cos_theta0": cth0, "theta0": sp.acos(cth0), "theta0_mirror": 2 * sp.pi - sp.acos(cth0)},
        (symbolic_identity(sp.expand_trig(loop_home),
                           -sp.sin(a1) * sp.sin(b1 + b2) * (sp.cos(th[0]) - cth0), "loop at R = I"),),
        source="seed 000, 'theta0 is the value of theta_i at the initial position'",
        note="Convention: theta0 is the root in [0, pi]; the mirror root 2 pi - theta0 is the other assembly "
             "branch of every leg at home. A design whose |cos theta0| > 1 cannot be assembled at home."))


# ------------------------------------------------------------------------------ inverse kinematics
def _inverse_kinematics(dv: Derivation) -> None:
    s12, c12, s23, c23, s2, c2 = sp.symbols("s12 c12 s23 c23 s2 c2", real=True)
    cd = triangle_direction_cosines(s12, c12, s23, c23, s2, c2)
    rot = rot_x(sp.pi - b1) * rot_z(th[0]) * rot_x(a1) * E_Z
    cd_sub = cd.subs({s12: sp.sin(sp.pi - b1), c12: sp.cos(sp.pi - b1), s23: sp.sin(a1), c23: sp.cos(a1),
                      s2: sp.sin(th[0]), c2: sp.cos(th[0])})
    dv.add(Step(
        "middle_axis_direction_cosines", "Middle axis Z12: spherical-triangle direction cosines",
        "spherical triangle (Z, Z11, Z12): sine law X2 = s23 s2, sine-cosine law Y2 = -(s12 c23 + c12 s23 c2),"
        " cosine law Z2 = c12 c23 - s12 s23 c2 (Crane-Duffy), sides pi - beta1 and alpha1, exterior angle theta1",
        ("base_axes",), {"X2, Y2, Z2": cd},
        (symbolic_identity(cd_sub, rot, "Crane-Duffy direction cosines = Rx(pi-beta1) Rz(theta1) Rx(alpha1) e_z"),
         symbolic_identity(polygon_vertex([sp.pi - b1, a1], [th[0]]), rot, "= generic polygon vertex")),
        source="seed 000, formula (6)"))
    z2 = [middle_axis(i, th[i]) for i in range(3)]
    dv.add(Step(
        "middle_axes", "Middle axes of all branches",
        "branch i is branch 1 rotated by delta_i about Z: Zi2 = Rz(delta_i) (X2, Y2, Z2)(theta_i)",
        ("middle_axis_direction_cosines",), {"Z12": z2[0], "Z22": z2[1], "Z32": z2[2]},
        (symbolic_identity(sp.Matrix([base_axis(i).dot(z2[i]) for i in range(3)]),
                           sp.Matrix([sp.cos(a1)] * 3), "angle(Zi1, Zi2) = alpha1"),),
        source="seed 000, formulas (7)-(11)"))
    R = rot_zxz(psi, nu, phi)
    dv.add(Step(
        "euler_rotation", "Platform orientation from ZXZ Euler angles",
        "R = Rz(psi) Rx(theta) Rz(phi): precession, nutation, self-rotation ('313')",
        (), {"R": R},
        (symbolic_identity(R.T * R, sp.eye(3), "R^T R = I"),
         symbolic_identity(R.det(), 1, "det R = 1")),
        source="seed 000, formulas (12)-(13)"))
    z3 = [R * platform_axis_home(i) for i in range(3)]
    dv.add(Step(
        "platform_axes", "Platform axes in the base frame", "Zi3 = R p_i",
        ("euler_rotation", "platform_axes_home"), {"Z13": z3[0], "Z23": z3[1], "Z33": z3[2]},
        identity(sp.Matrix([z3[0].dot(z3[1]), z3[1].dot(z3[2])]),
                 sp.Matrix([cos_angle_between_cone_axes(b2)] * 2), "Zi3 . Zj3 = cos alpha3 for any R",
                 {psi: ANGLE, nu: ANGLE, phi: ANGLE, b2: (0.1, 1.5)}),
        source="seed 000, formula (14)"))
    # Loop condition per branch, linear in (cos theta_i, sin theta_i).
    abc = {}
    checks: list[Check] = []
    for i in range(3):
        loop = z2[i].dot(z3[i]) - sp.cos(a2)
        lin = loop.subs({sp.cos(th[i]): c_, sp.sin(th[i]): s_})
        kc0, kc, ks = affine_cs_coefficients(lin, c_, s_)
        abc[f"A{i + 1}"], abc[f"B{i + 1}"], abc[f"C{i + 1}"] = kc, ks, kc0
        checks.append(numeric_identity(kc * sp.cos(th[i]) + ks * sp.sin(th[i]) + kc0, loop,
                                       f"A{i + 1} cos theta{i + 1} + B{i + 1} sin theta{i + 1} + C{i + 1}"
                                       f" = Z{i + 1}2 . Z{i + 1}3 - cos alpha2",
                                       {psi: ANGLE, nu: ANGLE, phi: ANGLE, th[i]: ANGLE, **DESIGN_RANGES}))
    # Compact form via the branch frame: v_i = (Rz(delta_i) Rx(pi - beta1))^T Zi3.
    vsym = sp.Matrix(sp.symbols("vx vy vz", real=True))
    compact = {"A": -sp.sin(a1) * vsym[1], "B": sp.sin(a1) * vsym[0], "C": sp.cos(a1) * vsym[2] - sp.cos(a2)}
    for i in range(3):
        v = (rot_z(DELTA[i]) * rot_x(sp.pi - b1)).T * z3[i]
        got = sp.Matrix([abc[f"A{i + 1}"], abc[f"B{i + 1}"], abc[f"C{i + 1}"]])
        want = sp.Matrix([compact["A"], compact["B"], compact["C"]]).subs(dict(zip(vsym, v, strict=True)))
        checks.append(numeric_identity(got, want, f"compact form of A{i + 1}, B{i + 1}, C{i + 1}",
                                       {psi: ANGLE, nu: ANGLE, phi: ANGLE, **DESIGN_RANGES}))
    # The same compact form with R given by its entries: what the solvers evaluate (trig of the pose once).
    abc_rot = {}
    for i in range(3):
        v = (rot_z(DELTA[i]) * rot_x(sp.pi - b1)).T * (Rm * platform_axis_home(i))
        vals = sp.Matrix([compact["A"], compact["B"], compact["C"]]).subs(dict(zip(vsym, v, strict=True)))
        abc_rot.update({f"A{i + 1}": vals[0], f"B{i + 1}": vals[1], f"C{i + 1}": vals[2]})
        on_euler = dict(zip(Rm, rot_zxz(psi, nu, phi), strict=True))
        checks.append(numeric_identity(vals.subs(on_euler),
                                       sp.Matrix([abc[f"A{i + 1}"], abc[f"B{i + 1}"], abc[f"C{i + 1}"]]),
                                       f"A{i + 1}, B{i + 1}, C{i + 1} from the entries of R",
                                       {psi: ANGLE, nu: ANGLE, phi: ANGLE, **DESIGN_RANGES}))
    dv.exports["ik_abc_rot"] = abc_rot
    dv.add(Step(
        "ik_loop_coefficients", "IK loop equations Ai cos theta_i + Bi sin theta_i + Ci = 0",
        "fixed angle alpha2 between middle and platform axes: Zi2 . Zi3 = cos alpha2; Zi2 is affine in "
        "(cos theta_i, sin theta_i) so the equation is linear in them",
        ("middle_axes", "platform_axes"), {**compact, **{k: abc[k] for k in ("A1", "B1", "C1")}},
        tuple(checks), source="seed 000, formulas (15)-(19)",
        note="Compact form with v_i = (Rz(delta_i) Rx(pi - beta1))^T Zi3, the platform axis seen from the "
             "branch frame. A2..C3 are A1..C1 with the branch rotation applied (recorded, not printed)."))
    dv.exports["ik_abc"] = abc

    t = sp.Symbol("t", real=True)
    A, B, C = sp.symbols("A B C", real=True)
    quad = half_angle_quadratic(A, B, C, t)
    sub = (A * (1 - t**2) / (1 + t**2) + B * 2 * t / (1 + t**2) + C) * (1 + t**2)
    disc = sp.expand(B**2 - (C - A) * (C + A))
    q = sp.Symbol("q", real=True)

    def closed_form_err(rng):
        aa, bb, cc = rng.normal(size=3)
        r = math.hypot(aa, bb)
        if r < abs(cc):
            return 0.0
        roots = [math.atan2(bb, aa) + sgn * math.acos(-cc / r) for sgn in (1, -1)]
        res = max(abs(aa * math.cos(v) + bb * math.sin(v) + cc) for v in roots)
        tq = sorted(math.tan(v / 2) for v in roots)
        qa, qb, qc = cc - aa, 2 * bb, aa + cc
        dq = math.sqrt(max(qb * qb - 4 * qa * qc, 0.0))
        tt = sorted([(-qb + dq) / (2 * qa), (-qb - dq) / (2 * qa)])
        return res + max(abs(u - v) / (1 + abs(v)) for u, v in zip(tq, tt, strict=True))
    dv.add(Step(
        "ik_half_angle", "tan(theta_i/2) quadratic, its discriminant, and the atan2 closed form",
        "Weierstrass substitution t = tan(theta/2): (Ci - Ai) t^2 + 2 Bi t + (Ai + Ci) = 0; discriminant/4 = "
        "Ai^2 + Bi^2 - Ci^2; equivalently theta_i = atan2(Bi, Ai) +/- acos(-Ci / sqrt(Ai^2 + Bi^2))",
        ("ik_loop_coefficients",),
        {"quadratic": quad, "discriminant_quarter": disc,
         "theta_i": sp.atan2(B, A) + sp.Symbol("sigma") * sp.acos(-C / sp.sqrt(A**2 + B**2))},
        (symbolic_identity(sp.expand(sub), quad, "half-angle substitution"),
         symbolic_identity(disc, A**2 + B**2 - C**2, "real roots iff Ai^2 + Bi^2 >= Ci^2"),
         symbolic_identity(sp.expand_trig(sp.sqrt(A**2 + B**2) * sp.cos(q - sp.atan2(B, A))),
                           A * sp.cos(q) + B * sp.sin(q), "A cos q + B sin q = r cos(q - atan2(B, A))"),
         numeric_predicate(closed_form_err, "atan2/acos roots solve the loop and equal the quadratic's roots",
                           samples=500, tol=1e-9)),
        source="seed 000, formulas (20)-(22)",
        note="The generated code uses the atan2/acos form: it has no division by Ci - Ai, so theta_i = pi (the "
             "quadratic's root at infinity) needs no special case. Both signs give the 2^3 = 8 solution sets; "
             "Ai^2 + Bi^2 < Ci^2 marks branch i unreachable, equality a tangent (double) root."))
    dv.add(Step(
        "motor_angles", "Motor and sensor angles",
        "Phi_i = theta_i - theta0 (counter-clockwise about Zi1 positive)", ("home_angle", "ik_half_angle"),
        {"Phi_i": sp.Symbol("theta_i") - sp.Symbol("theta0")}, (), source="seed 000, formula (23)"))


# ------------------------------------------------------------------------------ forward kinematics
def _forward_kinematics(dv: Derivation) -> None:
    chain = rot_x(sp.pi - b1) * rot_z(th[0]) * rot_x(a1) * rot_z(zeta) * rot_x(a2)
    z13 = chain * E_Z
    a3 = alpha3_of(b2)
    kap = kappa_of(a3)
    a3s = A3S
    # Built with symbols alpha3, kappa (design constants); checks substitute their design relations.
    z23s = chain * rot_z(eta) * rot_x(a3s) * E_Z
    z33s = chain * rot_z(eta + KPS) * rot_x(a3s) * E_Z
    on_design = {A3S: a3, KPS: kap}
    z23, z33 = z23s.subs(on_design), z33s.subs(on_design)
    fk_ranges = {th[0]: ANGLE, zeta: ANGLE, eta: ANGLE, **DESIGN_RANGES}
    dv.add(Step(
        "fk_quadrilateral", "Z13 from the spherical quadrilateral (Z, Z11, Z12, Z13)",
        "polygon direction cosines (quadrilateral sine, sine-cosine and cosine laws): sides pi - beta1, alpha1, "
        "alpha2; exterior angles theta1, zeta",
        ("middle_axes",), {"Z13": z13},
        (symbolic_identity(polygon_vertex([sp.pi - b1, a1, a2], [th[0], zeta]), z13, "quadrilateral vertex"),
         symbolic_identity(z13.dot(middle_axis(0, th[0])), sp.cos(a2), "angle(Z12, Z13) = alpha2")),
        source="seed 000, formulas (24)-(27)"))
    dv.add(Step(
        "fk_pentagon", "Z23 and Z33 from the spherical pentagons",
        "pentagon (Z, Z11, Z12, Z13, Z23) with exterior angle eta at Z13; for Z33 the exterior angle is "
        "eta' = eta + kappa (kappa the interior angle of the platform triangle at Z13)",
        ("fk_quadrilateral", "kappa"), {"Z23": z23s, "Z33": z33s, "eta_prime": eta + KPS},
        (symbolic_identity(polygon_vertex([sp.pi - b1, a1, a2, a3s], [th[0], zeta, eta]), z23s,
                           "pentagon vertex"),
         numeric_identity(sp.Matrix([z13.dot(z23), z23.dot(z33), z33.dot(z13)]),
                          sp.Matrix([sp.cos(a3)] * 3), "Z13, Z23, Z33 pairwise at alpha3", fk_ranges)),
        source="seed 000, formulas (28)-(34)",
        note="The seed's mu (exterior angle) is pi - kappa; with the counter-clockwise platform numbering "
             "the pentagon for Z33 turns by +kappa more than the one for Z23."))
    Gm = g_matrix()
    Rfk = chain * rot_z(eta) * Gm
    pp = [platform_axis_home(i) for i in range(3)]
    dv.add(Step(
        "fk_rotation", "Platform rotation from (theta1, zeta, eta)",
        "R = Rx(pi - beta1) Rz(theta1) Rx(alpha1) Rz(zeta) Rx(alpha2) Rz(eta) G with the constant G = "
        "Rz(-pi/2 - atan(sqrt 3 cos beta2)) Rx(-beta2) mapping p1 -> e_z, p2 -> Rx(alpha3) e_z",
        ("fk_pentagon", "platform_axes_home"), {"G": Gm, "R": Rfk},
        (numeric_identity(sp.Matrix.hstack(Gm * pp[0], Gm * pp[1], Gm * pp[2]),
                          sp.Matrix.hstack(E_Z, rot_x(a3) * E_Z, rot_z(kap) * rot_x(a3) * E_Z),
                          "G p1 = e_z, G p2 = Rx(alpha3) e_z, G p3 = Rz(kappa) Rx(alpha3) e_z",
                          {b2: (0.1, 1.5)}),
         numeric_identity(sp.Matrix.hstack(Rfk * pp[0], Rfk * pp[1], Rfk * pp[2]),
                          sp.Matrix.hstack(z13, z23, z33), "R p_i = Zi3 of the polygons", fk_ranges)),
        note="Hence Z13 = R p1, Z23 = R p2, Z33 = R p3: the polygons and the rotation are one construction."))
    # Loop closures of branches 2 and 3 (the seed's i = 1, 2), linear in (cos zeta, sin zeta).
    D, E, F = {}, {}, {}
    cE, sE = sp.symbols("cE sE", real=True)
    coef = {}
    checks = []
    for k, (zi3, i) in enumerate(((z23s, 1), (z33s, 2)), start=1):
        loop = middle_axis(i, th[i]).dot(zi3) - sp.cos(a2)
        lin = loop.subs({sp.cos(zeta): c_, sp.sin(zeta): s_})
        f0, fc, fs = affine_cs_coefficients(sp.expand(lin), c_, s_)
        D[k], E[k], F[k] = fc, fs, f0
        checks.append(numeric_identity((fc * sp.cos(zeta) + fs * sp.sin(zeta) + f0).subs(on_design),
                                       loop.subs(on_design),
                                       f"D{k} cos zeta + E{k} sin zeta + F{k} = Z{i + 1}2 . Z{i + 1}3 - cos alpha2",
                                       {**fk_ranges, th[i]: ANGLE}))
    # Each of D, E, F is affine in (cos eta, sin eta): split it for the polynomial step.
    for k in (1, 2):
        for nm, ex in (("D", D[k]), ("E", E[k]), ("F", F[k])):
            e2 = sp.expand(sp.expand_trig(ex))
            e2 = e2.subs({sp.cos(eta): cE, sp.sin(eta): sE})
            e0, ec, es = affine_cs_coefficients(e2, cE, sE)
            coef[f"{nm}{k}"] = (e0, ec, es)
            checks.append(numeric_identity((e0 + ec * sp.cos(eta) + es * sp.sin(eta)).subs(on_design),
                                           ex.subs(on_design),
                                           f"{nm}{k} = {nm}{k}_0 + {nm}{k}_c cos eta + {nm}{k}_s sin eta",
                                           {**fk_ranges, th[1]: ANGLE, th[2]: ANGLE}, samples=60))
    dv.add(Step(
        "fk_loop_coefficients", "FK loop equations Di cos zeta + Ei sin zeta + Fi = 0 (i = 1, 2)",
        "Zi2 . Zi3 = cos alpha2 for branches 2 and 3 with the pentagon directions; Zi3 = F Rz(zeta) w(eta), "
        "so the dot product is linear in (cos zeta, sin zeta) and each coefficient affine in (cos eta, sin eta)",
        ("fk_rotation", "middle_axes"),
        {"D1": D[1], "E1": E[1], "F1": F[1]}, tuple(checks), source="seed 000, formulas (35)-(36)",
        note="i = 1 is the loop of branch 2 (with Z23), i = 2 that of branch 3 (with Z33); D2, E2, F2 are "
             "D1, E1, F1 with theta2 -> theta3, delta 120 -> 240 deg and eta -> eta + kappa."))
    dv.exports["fk_def"] = coef

    d1, e1, f1, d2, e2, f2 = sp.symbols("D1 E1 F1 D2 E2 F2", real=True)
    nc, ns, den = cramer_cs(d1, e1, f1, d2, e2, f2)
    ident = elimination_identity(d1, e1, f1, d2, e2, f2)
    # numeric check of the identity at genuine assemblies: build R from (theta1, zeta, eta), get theta2/theta3
    f_def = sampler((th[0], th[1], th[2], zeta, eta, a1, a2, b1, b2),
                    [v.subs(on_design) for v in (D[1], E[1], F[1], D[2], E[2], F[2])])
    f_abc = sampler((psi, nu, phi, a1, a2, b1, b2),
                    [dv.exports["ik_abc"][k] for k in ("A2", "B2", "C2", "A3", "B3", "C3")])
    f_R = sampler((th[0], zeta, eta, a1, a2, b1, b2), Rfk)
    f_ident = sampler((d1, e1, f1, d2, e2, f2), ident)

    def assembly(rng):
        while True:
            des = _rand_design(rng)
            t1, ze, et = rng.uniform(-math.pi, math.pi, 3)
            Rn = np.asarray(f_R(t1, ze, et, *des), dtype=float)
            ps = math.atan2(Rn[0, 2], -Rn[1, 2])
            nn = math.atan2(math.hypot(Rn[0, 2], Rn[1, 2]), Rn[2, 2])
            ph = math.atan2(Rn[2, 0], Rn[2, 1])
            A2, B2, C2, A3, B3, C3 = (float(v) for v in f_abc(ps, nn, ph, *des))
            r2, r3 = math.hypot(A2, B2), math.hypot(A3, B3)
            if r2 > abs(C2) and r3 > abs(C3):
                t2 = math.atan2(B2, A2) + math.acos(-C2 / r2)
                t3 = math.atan2(B3, A3) - math.acos(-C3 / r3)
                return des, (t1, t2, t3), ze, et

    def ident_err(rng):
        des, (t1, t2, t3), ze, et = assembly(rng)
        vals = [float(v) for v in f_def(t1, t2, t3, ze, et, *des)]
        scale = sum(abs(v) for v in vals) ** 4
        return abs(float(f_ident(*vals))) / scale
    dv.add(Step(
        "fk_elimination", "Elimination of zeta",
        "Cramer's rule on the two equations linear in (cos zeta, sin zeta), then cos^2 + sin^2 = 1 times "
        "(D1 E2 - D2 E1)^2",
        ("fk_loop_coefficients",),
        {"cos_zeta": nc / den, "sin_zeta": ns / den, "identity": ident},
        (symbolic_identity(sp.Matrix([d1 * nc / den + e1 * ns / den + f1, d2 * nc / den + e2 * ns / den + f2]),
                           sp.zeros(2, 1), "Cramer solution solves both equations"),
         numeric_predicate(ident_err, "identity vanishes at assemblies built from (theta1, zeta, eta)",
                           samples=60, tol=1e-12)),
        source="seed 000, formulas (37)-(39)",
        note="When D2 E1 - D1 E2 = 0 the two equations are proportional: the identity holds but zeta comes "
             "from one equation (two candidates, each checked against the other); the generated code does so."))
    # Polynomial in x = tan((eta - eta_c)/2): coefficients of D, E, F rotated by eta_c, then products.
    ks = sp.symbols("k0:3", real=True)  # generic (k0, kc, ks) of one coefficient
    etac = sp.Symbol("eta_c", real=True)
    rotated = (ks[0], ks[1] * sp.cos(etac) + ks[2] * sp.sin(etac), -ks[1] * sp.sin(etac) + ks[2] * sp.cos(etac))
    quad_x = weierstrass(rotated[0] + rotated[1] * c_ + rotated[2] * s_, c_, s_, x)
    phi_ = sp.Symbol("varphi", real=True)
    orig = ks[0] + ks[1] * sp.cos(etac + phi_) + ks[2] * sp.sin(etac + phi_)
    shifted = rotated[0] + rotated[1] * sp.cos(phi_) + rotated[2] * sp.sin(phi_)
    # K(x) for symbolic quadratics: degree check of the product structure (a polynomial in x and the 18
    # coefficients: expanding it as an expression first and taking the coefficients as a domain cost 4x)
    qd_sym = {nm: sp.symbols(f"{nm}_q0:3", real=True) for nm in ("D1", "E1", "F1", "D2", "E2", "F2")}
    qpoly = {nm: c[0] + c[1] * x + c[2] * x**2 for nm, c in qd_sym.items()}
    deg = sp.Poly(elimination_identity(*(qpoly[n] for n in ("D1", "E1", "F1", "D2", "E2", "F2"))), x,
                  *(s for c in qd_sym.values() for s in c)).degree(x)
    # evaluated in 30-digit mpmath: the check measures the algebra (the identity), not float rounding, and its
    # number is the same on every CPU (numpy's trig and BLAS kernels differ in the last bits)
    coef_mp = {k: sampler((th[0], th[1], th[2], a1, a2, b1, b2), [c.subs(on_design) for c in v], "mpmath")
               for k, v in coef.items()}

    def k_poly_err(rng):
        import mpmath

        des = [float(v) for v in _rand_design(rng)]
        tt = [float(v) for v in rng.uniform(-math.pi, math.pi, 3)]
        ec = float(rng.uniform(-math.pi, math.pi))
        xv = float(rng.uniform(-3, 3))
        with mpmath.workdps(30):
            mec, mx = mpmath.mpf(ec), mpmath.mpf(xv)
            c3 = {k: [mpmath.mpf(c) for c in f(*map(mpmath.mpf, tt), *map(mpmath.mpf, des))]
                  for k, f in coef_mp.items()}
            qs = {}
            for k, (k0, kc, kss) in c3.items():
                rc, rs = kc * mpmath.cos(mec) + kss * mpmath.sin(mec), -kc * mpmath.sin(mec) + kss * mpmath.cos(mec)
                qs[k] = [k0 + rc, 2 * rs, k0 - rc]  # ascending in x

            def mul(p, q):
                out = [mpmath.mpf(0)] * (len(p) + len(q) - 1)
                for i, a in enumerate(p):
                    for j, b in enumerate(q):
                        out[i + j] += a * b
                return out

            def sub(p, q):
                return [a - b for a, b in zip(p, q, strict=True)]

            t1 = sub(mul(qs["E1"], qs["F2"]), mul(qs["E2"], qs["F1"]))
            t2 = sub(mul(qs["D2"], qs["F1"]), mul(qs["D1"], qs["F2"]))
            t3 = sub(mul(qs["D1"], qs["E2"]), mul(qs["D2"], qs["E1"]))
            K = [a + b - c for a, b, c in zip(mul(t1, t1), mul(t2, t2), mul(t3, t3), strict=True)]

            def ident(eta):
                e = {k: v[0] + v[1] * mpmath.cos(eta) + v[2] * mpmath.sin(eta) for k, v in c3.items()}
                return ((e["E1"] * e["F2"] - e["E2"] * e["F1"]) ** 2 + (e["D2"] * e["F1"] - e["D1"] * e["F2"]) ** 2
                        - (e["D1"] * e["E2"] - e["D2"] * e["E1"]) ** 2)

            kx = sum(c * mx**i for i, c in enumerate(K))
            err = abs(kx - (1 + mx * mx) ** 4 * ident(mec + 2 * mpmath.atan(mx))) + abs(K[-1] - ident(mec + mpmath.pi))
            return float(err / (1 + max(abs(c) for c in K)))
    dv.add(Step(
        "fk_polynomial", "The Ki polynomial in x = tan((eta - eta_c)/2)",
        "each of D, E, F is affine in (cos eta, sin eta); a shift eta = eta_c + phi rotates its (cos, sin) "
        "coefficients; the Weierstrass substitution times (1 + x^2) makes each a quadratic in x, so every "
        "product in the identity is a quartic and the identity times (1 + x^2)^4 a polynomial of degree 8",
        ("fk_elimination",),
        {"shifted_coefficients": sp.Matrix(rotated), "quadratic_in_x": quad_x, "degree": sp.Integer(deg),
         "K8": sp.Symbol("f(eta_c + pi)")},
        (symbolic_identity(sp.expand_trig(orig), sp.expand_trig(shifted), "coefficient rotation by eta_c"),
         symbolic_identity(sp.Integer(deg), sp.Integer(8), "K(x) has degree 8 (product structure)"),
         # 30 digits leave >= 20 after the cancellations of the degree-8 products (scaled by 1 + max|K_i|)
         numeric_predicate(k_poly_err, "K(x) = (1 + x^2)^4 f(eta_c + 2 atan x) and K8 = f(eta_c + pi), in "
                           "30-digit arithmetic", samples=200, tol=1e-20, floor=1e-25)),
        source="seed 000, formulas (40)-(41): 'Ki', called a quartic in the seed and in the design card",
        note="The identity is a quartic in (cos eta, sin eta) -- a trigonometric polynomial of order 4 -- which "
             "is a polynomial of degree 8 in the half-angle tangent, matching the at most 8 assembly modes of "
             "spherical 3-DOF parallel mechanisms. K8 is the identity at eta = eta_c + pi: with eta_c = 0 "
             "(the seed's x = tan(eta/2)) a root at eta = pi is a root at infinity, so the generated code picks "
             "eta_c to make |K8| large and no assembly mode is lost."))

    rot_num = sp.lambdify((psi, nu, phi), rot_zxz(psi, nu, phi), "numpy")  # once: subs per sample took 40 ms

    def euler_err(rng):
        ps, ph = rng.uniform(-math.pi, math.pi, 2)
        nn = rng.uniform(1e-3, math.pi - 1e-3)
        Rn = np.array(rot_num(ps, nn, ph), dtype=float)
        back = (math.atan2(Rn[0, 2], -Rn[1, 2]), math.atan2(math.hypot(Rn[0, 2], Rn[1, 2]), Rn[2, 2]),
                math.atan2(Rn[2, 0], Rn[2, 1]))
        return max(abs(math.remainder(u - v, 2 * math.pi)) for u, v in zip(back, (ps, nn, ph), strict=True))
    Rz = rot_zxz(psi, nu, phi)
    dv.add(Step(
        "fk_euler", "Euler angles from the platform rotation",
        "third column (sin psi sin theta, -cos psi sin theta, cos theta) and third row "
        "(sin theta sin phi, sin theta cos phi, cos theta) of Rz(psi) Rx(theta) Rz(phi)",
        ("euler_rotation", "fk_rotation"),
        {"theta": sp.atan2(sp.sqrt(sp.Symbol("R13") ** 2 + sp.Symbol("R23") ** 2), sp.Symbol("R33")),
         "psi": sp.atan2(sp.Symbol("R13"), -sp.Symbol("R23")),
         "phi": sp.atan2(sp.Symbol("R31"), sp.Symbol("R32"))},
        (symbolic_identity(sp.Matrix([Rz[0, 2], Rz[1, 2], Rz[2, 0], Rz[2, 1], Rz[2, 2]]),
                           sp.Matrix([sp.sin(psi) * sp.sin(nu), -sp.cos(psi) * sp.sin(nu), sp.sin(nu) * sp.sin(phi),
                                      sp.sin(nu) * sp.cos(phi), sp.cos(nu)]), "entries used"),
         numeric_predicate(euler_err, "round trip (psi, theta, phi) -> R -> angles for theta in (0, pi)",
                           samples=200, tol=1e-12)),
        source="seed 000, formulas (42)-(46)",
        note="At sin theta = 0 only psi + phi (theta = 0) or psi - phi (theta = pi) is defined: the generated "
             "code then returns phi = 0, psi = the whole in-plane angle, and sets the GIMBAL flag. Near it "
             "(the seed's t = 0.1 s row, theta ~ 0.01 deg) psi and phi are separately ill-conditioned."))
    dv.exports["fk_chain"] = chain


# ------------------------------------------------------------------------------ rates
def _rates(dv: Derivation) -> None:
    # Differentiating Zi2(theta_i) . R p_i = cos alpha2 in time with R' = [w]x R and dZi2/dtheta_i = Zi1 x Zi2.
    z1 = [base_axis(i) for i in range(3)]
    z2 = [middle_axis(i, th[i]) for i in range(3)]
    z3 = [Rm * platform_axis_home(i) for i in range(3)]
    jq = [z1[i].cross(z2[i]).dot(z3[i]) for i in range(3)]
    jx = sp.Matrix.vstack(*[z2[i].cross(z3[i]).T for i in range(3)])
    checks = [symbolic_identity(sp.diff(z2[i], th[i]), z1[i].cross(z2[i]), f"dZ{i + 1}2/dtheta{i + 1} = "
                                f"Z{i + 1}1 x Z{i + 1}2") for i in range(3)]
    f_loop = sampler((*th, a1, a2, b1, b2, *Rm), sp.Matrix([z2[i].dot(z3[i]) for i in range(3)]))
    f_j = sampler((*th, a1, a2, b1, b2, *Rm), (sp.Matrix(jq), jx))

    rot_num = sp.lambdify((psi, nu, phi), rot_zxz(psi, nu, phi), "numpy")

    def rate_err(rng):
        des = _rand_design(rng)
        q = rng.uniform(-math.pi, math.pi, 3)
        Rn = np.array(rot_num(rng.uniform(-3, 3), rng.uniform(0, 3), rng.uniform(-3, 3)), dtype=float)
        qdot, w = rng.normal(size=3), rng.normal(size=3)
        h = 1e-6
        Wm = np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])
        Rp, Rq = Rn + h * Wm @ Rn, Rn - h * Wm @ Rn
        dg = (np.asarray(f_loop(*(q + h * qdot), *des, *Rp.ravel()), dtype=float)
              - np.asarray(f_loop(*(q - h * qdot), *des, *Rq.ravel()), dtype=float)).ravel() / (2 * h)
        Jq, Jx = (np.asarray(m, dtype=float) for m in f_j(*q, *des, *Rn.ravel()))
        return float(np.max(np.abs(dg - (Jq.ravel() * qdot - Jx @ w))))
    checks.append(numeric_predicate(rate_err, "d/dt loop = Jq qdot - Jx w (central differences, h = 1e-6)",
                                    samples=100, tol=1e-7))
    dv.add(Step(
        "loop_jacobians", "Velocity relation Jq qdot = Jx w and the two singularity indicators",
        "time derivative of Zi2 . Zi3 = cos alpha2 with dZi2 = (Zi1 x Zi2) dtheta_i and dZi3 = w x Zi3: "
        "(Zi1 x Zi2) . Zi3 thetadot_i = (Zi2 x Zi3) . w",
        ("middle_axes", "platform_axes"), {"Jq_ii": jq[0], "Jx_row1": jx[0, :]}, tuple(checks),
        note="Inverse (serial) singularity: some Jq_ii = det[Zi1, Zi2, Zi3] = 0, the IK branch's double root "
             "(Ai^2 + Bi^2 = Ci^2). Direct (parallel) singularity: det Jx = 0, rows Zi2 x Zi3 coplanar, where "
             "FK assembly modes merge. The generated code reports both, normalised to [0, 1]."))
    dv.exports["jacobians"] = (sp.Matrix(jq), jx)
    Em = zxz_rate_matrix(psi, nu)
    ed = sp.Matrix(sp.symbols("psid thetad phid", real=True))
    Rz = rot_zxz(psi, nu, phi)
    # R' by the chain rule along (psidot, thetadot, phidot); the check proves vee(R' R^T) = E rates
    Wt = (Rz.diff(psi) * ed[0] + Rz.diff(nu) * ed[1] + Rz.diff(phi) * ed[2]) * Rz.T
    w_expr = sp.Matrix([Wt[2, 1], Wt[0, 2], Wt[1, 0]])
    det_e = sp.simplify(Em.det())
    dv.add(Step(
        "euler_rates", "Angular velocity from Euler-angle rates",
        "w = E(psi, theta) (psidot, thetadot, phidot), columns: Z, Rz(psi) X, Rz(psi) Rx(theta) Z",
        ("euler_rotation",), {"E": Em, "det_E": det_e},
        (symbolic_identity(w_expr, Em * ed, "skew(w) = R' R^T"),
         symbolic_identity(det_e, -sp.sin(nu), "det E = -sin theta (Euler rates undefined at theta = 0, pi)")),
        note="The generated rate functions work with w; Euler-angle rates are offered where sin theta != 0."))
    dv.exports["euler_rate_matrix"] = Em
    # Accelerations: d/dt (Jq qdot - Jx w) = 0.
    wvec = wv
    jq_dot = []
    for i in range(3):
        z2d = z1[i].cross(z2[i]) * qd[i]
        z3d = wvec.cross(z3[i])
        jq_dot.append(z1[i].cross(z2d).dot(z3[i]) + z1[i].cross(z2[i]).dot(z3d))
    jx_dot = sp.Matrix.vstack(*[(z1[i].cross(z2[i]) * qd[i]).cross(z3[i]).T + z2[i].cross(wvec.cross(z3[i])).T
                                for i in range(3)])

    f_jd = sampler((*th, a1, a2, b1, b2, *Rm, *qd, *wvec), (sp.Matrix(jq_dot), jx_dot))

    R0 = np.array(rot_zxz(psi, nu, phi).subs({psi: 0.3, nu: 1.1, phi: -0.7}), dtype=float)  # the same every sample

    def acc_err(rng):
        des = _rand_design(rng)
        q0 = rng.uniform(-math.pi, math.pi, 3)
        qdot, w = rng.normal(size=3), rng.normal(size=3)

        def at(tt):
            ang = w * tt
            th_ = np.linalg.norm(ang)
            K = np.array([[0, -ang[2], ang[1]], [ang[2], 0, -ang[0]], [-ang[1], ang[0], 0]]) / max(th_, 1e-300)
            Rr = np.eye(3) + math.sin(th_) * K + (1 - math.cos(th_)) * K @ K
            return [np.asarray(m, dtype=float) for m in f_j(*(q0 + qdot * tt), *des, *(Rr @ R0).ravel())]
        h = 1e-5
        (jqp, jxp), (jqm, jxm) = at(h), at(-h)
        fd_q, fd_x = (jqp - jqm).ravel() / (2 * h), (jxp - jxm) / (2 * h)
        an_q, an_x = (np.asarray(m, dtype=float) for m in f_jd(*q0, *des, *R0.ravel(), *qdot, *w))
        return float(max(np.max(np.abs(fd_q - an_q.ravel())), np.max(np.abs(fd_x - an_x))))
    dv.add(Step(
        "loop_jacobian_rates", "Acceleration relation",
        "d/dt of Jq qdot = Jx w: Jq qddot + Jq' qdot = Jx w' + Jx' w, with Jq'_ii and Jx' rows from "
        "dZi2 = thetadot_i Zi1 x Zi2 and dZi3 = w x Zi3",
        ("loop_jacobians",), {"Jq_dot_11": jq_dot[0]},
        (numeric_predicate(acc_err, "Jq' and Jx' match central differences along a constant-rate motion",
                           samples=20, tol=1e-7),),
        ))
    dv.exports["jacobian_rates"] = (sp.Matrix(jq_dot), jx_dot)


# ------------------------------------------------------------------------------ kernels for codegen
DESIGN_CONSTANTS = (ca1, sa1, ca2, sa2, cb1, sb1, *sp.symbols("cb2 sb2", real=True), ca3, sa3, ck, sk, *G,
                    sp.Symbol("cth0", real=True))
_cb2, _sb2 = DESIGN_CONSTANTS[6], DESIGN_CONSTANTS[7]


def _to_constants(e):
    """Replace trigonometric functions of design angles by the precomputed constants."""
    rep = {sp.cos(a1): ca1, sp.sin(a1): sa1, sp.cos(a2): ca2, sp.sin(a2): sa2, sp.cos(b1): cb1,
           sp.sin(b1): sb1, sp.cos(b2): _cb2, sp.sin(b2): _sb2, sp.cos(A3S): ca3, sp.sin(A3S): sa3,
           sp.cos(KPS): ck, sp.sin(KPS): sk}
    out = sp.sympify(e).xreplace(rep)
    bad = {f for f in out.atoms(sp.Function) if f.free_symbols & {a1, a2, b1, b2, A3S, KPS}}
    if bad:
        raise ValueError(f"design angle left after constant substitution: {bad}")
    return out


def _trig_free(e):
    """A kernel output written in the cos / sin symbols of its angles: no trigonometric function may remain."""
    left = e.atoms(sp.sin, sp.cos, sp.tan)
    if left:
        raise ValueError(f"trigonometry left in a kernel that takes cos and sin: {left}")
    return e


def kernels(dv: Derivation):
    """Straight-line kernels the solvers are assembled from (all expressions come from checked steps)."""
    from ...lower import Kernel

    params = ("params", (a1, a2, b1, b2))
    dc = ("dc", DESIGN_CONSTANTS)
    cos_a3 = cos_angle_between_cone_axes(b2)
    design_vals = {
        "ca1": sp.cos(a1), "sa1": sp.sin(a1), "ca2": sp.cos(a2), "sa2": sp.sin(a2),
        "cb1": sp.cos(b1), "sb1": sp.sin(b1), "cb2": sp.cos(b2), "sb2": sp.sin(b2),
        "ca3": cos_a3, "sa3": sp.sqrt(1 - cos_a3**2),
        # cos kappa = ca3 / (1 + ca3); sin kappa = sqrt(1 + 2 ca3) / (1 + ca3) and 1 + 2 ca3 = 3 cos^2 beta2
        "ck": cos_a3 / (1 + cos_a3), "sk": sp.sqrt(3) * sp.cos(b2) / (1 + cos_a3),
        **{str(g): v for g, v in zip(G, g_matrix(), strict=True)},
        "cth0": dv["home_angle"].result["cos_theta0"],
    }
    coef = dv.exports["fk_def"]
    chain = dv.exports["fk_chain"]
    jq, jx = dv.exports["jacobians"]
    jqd, jxd = dv.exports["jacobian_rates"]
    em = dv.exports["euler_rate_matrix"]
    ij = [(i, j) for i in range(3) for j in range(3)]
    cq = sp.symbols("c1:4", real=True)
    sq = sp.symbols("s1:4", real=True)
    cs_sub = {**{sp.cos(th[i]): cq[i] for i in range(3)}, **{sp.sin(th[i]): sq[i] for i in range(3)}}
    # the FK kernels take cos and sin (callers have them: no trigonometry repeated per mode)
    cr, sr = sp.symbols("ct1 cz ce", real=True), sp.symbols("st1 sz se", real=True)
    rot_sub = {sp.cos(a): c for a, c in zip((th[0], zeta, eta), cr, strict=True)}
    rot_sub.update({sp.sin(a): s for a, s in zip((th[0], zeta, eta), sr, strict=True)})
    return [
        Kernel("design_constants", "Per-design constants: trig of the design angles, alpha3, kappa, the constant "
               "platform rotation G and cos(theta0).", (params,),
               tuple((str(s), design_vals[str(s)]) for s in DESIGN_CONSTANTS)),
        Kernel("ik_abc", "IK loop coefficients (A_i, B_i, C_i) of A cos theta_i + B sin theta_i + C = 0, from "
               "the entries of R (compact form -sa1 v_y, sa1 v_x, ca1 v_z - ca2 with "
               "v = (Rz(delta_i) Rx(pi - beta1))^T R p_i).",
               (("rot", tuple(Rm)), dc),
               tuple((f"{n}{i}", _to_constants(dv.exports["ik_abc_rot"][f"{n}{i}"])) for i in (1, 2, 3)
                     for n in "ABC")),
        Kernel("fk_def", "FK loop coefficients: D_k, E_k, F_k (k = 1, 2) each as (const, cos eta, sin eta), from "
               "(cos theta_i, sin theta_i).",
               (("c", cq), ("s", sq), dc),
               tuple((f"{n}{k}_{part}", _trig_free(_to_constants(coef[f"{n}{k}"][j]).xreplace(cs_sub)))
                     for k in (1, 2) for n in "DEF" for j, part in enumerate(("0", "c", "s")))),
        Kernel("fk_rotation", "Platform rotation R = Rx(pi - beta1) Rz(theta1) Rx(alpha1) Rz(zeta) Rx(alpha2) "
               "Rz(eta) G, from the cos and sin of (theta1, zeta, eta).", (("c", cr), ("s", sr), dc),
               tuple((f"r{i}{j}", _trig_free(_to_constants((chain * rot_z(eta) * G)[i, j]).xreplace(rot_sub)))
                     for i, j in ij)),
        Kernel("jacobians", "Loop Jacobians: jq_i = det[Zi1, Zi2, Zi3], jx row i = Zi2 x Zi3 (jq qdot = jx w).",
               (("q", th), ("rot", tuple(Rm)), dc),
               tuple((f"jq{i + 1}", _to_constants(jq[i])) for i in range(3))
               + tuple((f"jx{i}{j}", _to_constants(jx[i, j])) for i, j in ij)),
        Kernel("jacobian_rates", "Time derivatives of jq and jx along (qdot, w).",
               (("q", th), ("rot", tuple(Rm)), ("qd", tuple(qd)), ("w", tuple(wv)), dc),
               tuple((f"jqd{i + 1}", _to_constants(jqd[i])) for i in range(3))
               + tuple((f"jxd{i}{j}", _to_constants(jxd[i, j])) for i, j in ij)),
        Kernel("middle_axes", "Middle axes Zi2 from (cos theta_i, sin theta_i): no trigonometry once IK roots "
               "are known.",
               (("c", cq), ("s", sq), dc),
               tuple((f"z{i + 1}2_{ax}", _to_constants(middle_axis(i, th[i]).xreplace(cs_sub)[j]))
                     for i in range(3) for j, ax in enumerate("xyz"))),
        Kernel("platform_axes", "Platform axes Zi3 = R p_i.", (("rot", tuple(Rm)), dc),
               tuple((f"z{i + 1}3_{ax}", _to_constants((Rm * platform_axis_home(i))[j]))
                     for i in range(3) for j, ax in enumerate("xyz"))),
        Kernel("base_axes", "Base axes Zi1 (constant per design).", (dc,),
               tuple((f"z{i + 1}1_{ax}", _to_constants(base_axis(i)[j])) for i in range(3)
                     for j, ax in enumerate("xyz"))),
        Kernel("euler_rate_matrix", "E(psi, theta) with w = E (psidot, thetadot, phidot).",
               (("pose", (psi, nu, phi)),), tuple((f"e{i}{j}", em[i, j]) for i, j in ij)),
    ]


def extra_context(ks, design_deg=DESIGN_DEFAULT_DEG) -> dict:
    """Default design evaluated at generation time, so C needs no initialiser call for it."""
    k = next(k for k in ks if k.name == "design_constants")
    params = [math.radians(v) for v in design_deg]
    f = sp.lambdify([s for s in k.inputs[0][1]], [e for _, e in k.outputs], "math")
    consts = [float(v) for v in f(*params)]
    return {"default_params": [repr(p) for p in params], "default_constants": [repr(c) for c in consts],
            "default_theta0": repr(math.acos(max(-1.0, min(1.0, consts[-1]))))}


def audit_numbers(dv, solver, audit_dir, design_deg=DESIGN_DEFAULT_DEG):
    """Seed 000's numbers, reproduced or refuted at the paper's design (`design_deg`)."""
    from .underactuated_wrist_audit import audit_numbers as run

    ks = kernels(dv)
    return run(dv, solver, audit_dir, ks, extra_context(ks, design_deg)["default_constants"], DESIGN_CONSTANTS)


def casadi_functions(dv, ks) -> dict:
    from .wrist_casadi import casadi_functions as wrist_functions
    return wrist_functions(dv, ks)
