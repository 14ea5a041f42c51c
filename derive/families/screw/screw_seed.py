"""The seed's own IK routes for the two 3T2R robots, derived next to ours and compared (seed 003, section 4).

The seed's formulas were lost in extraction; each route is rebuilt from what its text says it does, and the
reconstruction is stated in the step. Everything here feeds the audit report only; the generated solvers use the
routes of `screw_robots` (atan2 / acos forms, defined at half turns).
"""

from __future__ import annotations

import math

import numpy as np
import sympy as sp

from ...checks import numeric_predicate, symbolic_identity
from ...identities import screws
from ...identities.polynomial import half_angle_quadratic
from ...model import Derivation, Finding, Step
from ...report_numbers import error_bucket, measured
from .screw_serial import ScrewSpec, numeric_axes, sample_design, sample_joints

N_AUDIT = 300  # seeded samples behind each number of the report


# ------------------------------------------------------------------------------------------ numpy helpers
def _rot(s, th) -> np.ndarray:
    return screws.np_twist_exp("R", s, (0.0, 0.0, 0.0), th)[:3, :3]


def _vecs(spec: ScrewSpec, dsn: dict, names: str) -> list[np.ndarray]:
    return [np.array([dsn[sp.Symbol(f"{n}{c}", real=True)] for c in "xyz"]) for n in names.split()]


def seed_orientation(a, b, R) -> tuple[float, float]:
    """Seed eq. (14)/(19) rebuilt on the finite screw of the pose: g = (g_a + g_b + g_a x g_b / 2) / D with
    g_a = 2 tan(phi_a/2) a, g_b = 2 tan(phi_b/2) b. In the basis (a, b, w = a x b), g = (G_a, G_b, G_w) gives
    tan(phi_a/2) = G_a / (2 + (a.b) G_w), tan(phi_b/2) = G_b / (2 + (a.b) G_w). Raises ScrewSingularity at a
    composite half turn (the pose has no finite screw)."""
    T = np.eye(4)
    T[:3, :3] = R
    g = screws.np_transform_to_screw(T)[:3]
    w = np.cross(a, b)
    G = np.linalg.solve(np.column_stack([a, b, w]), g)
    den = 2.0 + float(a @ b) * G[2]
    return 2.0 * math.atan(G[0] / den), 2.0 * math.atan(G[1] / den)


def atan2_orientation(a, b, R) -> tuple[float, float]:
    """The emitted route: R b = Rot(a, phi_a) b and R^T a = Rot(b, -phi_b) a, one atan2 each."""
    ab, w = float(a @ b), np.cross(a, b)
    Rb, Ra = R @ b, R.T @ a
    return math.atan2(Rb @ w, Rb @ b - ab * ab), math.atan2(Ra @ w, Ra @ a - ab * ab)


def _wrap(x: float) -> float:
    return abs(math.remainder(x, 2 * math.pi))


# ------------------------------------------------------------------------------------------ shared step
def _orientation_step(dv: Derivation, spec: ScrewSpec, dirs: str, phi) -> None:
    """The seed's orientation IK through the finite screw of the pose, checked and measured at half turns."""
    def err(rng):
        dsn = sample_design(spec, rng)
        a, b = _vecs(spec, dsn, dirs)
        while True:
            q = sample_joints(spec, rng, 2.5)
            R = screws.np_poe(numeric_axes(spec, dsn), list(q.values()))[:3, :3]
            if 1 + np.trace(R) > 1e-2:
                break
        pa, pb = phi(list(q.values()))
        sa, sb = seed_orientation(a, b, R)
        return max(_wrap(sa - pa), _wrap(sb - pb))
    dv.add(Step("seed_orientation_route", "Seed route for the two rotational parameters (eqs. 14, 19)",
                "finite screw of the pose g = 2 vee(R - R^T)/(1 + tr R); in the basis (a, b, a x b), "
                "g = (G_a, G_b, G_w) and tan(phi_a/2) = G_a/(2 + (a.b) G_w), tan(phi_b/2) = G_b/(2 + (a.b) G_w)",
                ("displacement_model", "screw_transform_to_screw"),
                {"tan(phi_a/2)": sp.Symbol("G_a") / (2 + sp.Symbol("c_ab") * sp.Symbol("G_w")),
                 "tan(phi_b/2)": sp.Symbol("G_b") / (2 + sp.Symbol("c_ab") * sp.Symbol("G_w")),
                 "image condition": sp.Eq(sp.Symbol("G_a") * sp.Symbol("G_b"),
                                          sp.Symbol("G_w") * (2 + sp.Symbol("c_ab") * sp.Symbol("G_w")))},
                (numeric_predicate(err, "equals the generating (phi_a, phi_b) off the half turns (1 + tr R > 1e-2), "
                                   "random robots", samples=100, tol=1e-9),),
                source="seed 003, eqs. (14) and (19) (formulas lost; rebuilt from 'solved in the similar way')",
                note="Undefined when the pose is a half turn (1 + tr R = 0); the emitted IK uses the atan2 form."))


SEED_ROUTE_TOL = 1e-9  # the solvers' IK verification tolerance: a route off by more is unusable there


def _half_turn_evidence(spec: ScrewSpec, dirs: str, half: list[int]) -> str:
    """Numbers for the orientation routes at and near a composite half turn."""
    rng = np.random.default_rng(31)
    dsn = sample_design(spec, rng)
    a, b = _vecs(spec, dsn, dirs)
    axes = numeric_axes(spec, dsn)
    parts = []
    # 1 + tr R ~ delta^2 and the seed route's error ~ eps / delta^2: each delta keeps both a factor >= 100 away
    # from the thresholds the report compares them with (SINGULAR_TOL = 1e-12 and SEED_ROUTE_TOL), so the
    # report's words hold on every CPU although the amplified rounding error itself varies with the kernels
    for delta in (1e-2, 1e-5, 1e-7, 0.0):
        q = [0.0] * len(axes)
        q[half[0]] = math.pi - delta  # a turn of pi - delta about a, nothing about b: 1 + tr R = O(delta^2)
        R = screws.np_poe(axes, q)[:3, :3]
        ea = max(_wrap(x - y) for x, y in zip(atan2_orientation(a, b, R), (math.pi - delta, 0.0), strict=True))
        try:
            es = max(_wrap(x - y) for x, y in zip(seed_orientation(a, b, R), (math.pi - delta, 0.0), strict=True))
            seed = f"< {SEED_ROUTE_TOL:g}" if es < SEED_ROUTE_TOL else f"> {SEED_ROUTE_TOL:g} (digits lost)"
        except (screws.ScrewSingularity, np.linalg.LinAlgError, ZeroDivisionError):
            seed = "no finite screw (ScrewSingularity)"
        at = f"pi - {delta:g}" if delta else "pi"
        parts.append(f"phi_a = {at}: seed route error {seed}, atan2 route {error_bucket(ea)}")
    return "; ".join(parts)


# ------------------------------------------------------------------------------------------ P1P2P3RaRb
def p_robot_steps(dv: Derivation, spec: ScrewSpec) -> None:
    _orientation_step(dv, spec, "a b", lambda q: (q[3], q[4]))

    def proj_err(rng, orthonormal=True):
        dsn = sample_design(spec, rng)
        if orthonormal:
            Q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
            for i, col in enumerate(Q.T):
                for c, x in zip("xyz", col, strict=True):
                    dsn[sp.Symbol(f"p{i + 1}{c}", real=True)] = float(x)
        p = _vecs(spec, dsn, "p1 p2 p3")
        t = rng.uniform(-1, 1, 3)
        d = t[0] * p[0] + t[1] * p[1] + t[2] * p[2]
        return float(np.max(np.abs(np.array([pi @ d for pi in p]) - t)))
    dv.add(Step("seed_projection_route", "Seed route for the prismatic parameters: projections (eq. 16)",
                "t_i = p_i . d (projection of the translation d = t1 p1 + t2 p2 + t3 p3 on each direction); exact "
                "only when [p1 p2 p3] is orthonormal, since p_i . d = sum_j (p_i . p_j) t_j", ("ik_stage5",),
                {"t_i (seed)": sp.Symbol("p_i") * sp.Symbol("d"), "t (general)": "[p1 p2 p3]^-1 d (Cramer)"},
                (numeric_predicate(proj_err, "projections recover t for orthonormal p1, p2, p3 (random frames)",
                                   samples=100, tol=1e-12),),
                source="seed 003, eq. (16)"))
    rng = np.random.default_rng(7)
    errs = [proj_err(rng, orthonormal=False) for _ in range(N_AUDIT)]
    dflt = dict(zip(spec.design, spec.design_default, strict=True))
    p = _vecs(spec, dflt, "p1 p2 p3")
    t = np.array([0.3, -0.2, 0.5])
    d = t @ np.array(p)
    dv.findings.append(Finding(
        "prismatic parameters (eq. 16)", "t_i = projection of the translation on p_i",
        "t = [p1 p2 p3]^-1 d (Cramer's rule); projections only for orthonormal directions", "wrong in seed",
        f"orthonormal random frames: max error {error_bucket(dv['seed_projection_route'].checks[0].max_error)} m; "
        "random unit "
        f"(non-orthogonal) directions, t uniform in [-1, 1]: median error {np.median(errs):.2f} m, max "
        f"{max(errs):.2f} m over {N_AUDIT} samples; default design, t = (0.3, -0.2, 0.5): projections give "
        f"({', '.join(f'{pi @ d:.3f}' for pi in p)})"))
    dv.findings.append(Finding(
        "rotational parameters (eq. 14) at half turns", "closed form from the finite screw of the pose",
        "phi_a = atan2((R b).(a x b), (R b).b - (a.b)^2), phi_b likewise from R^T a (emitted)", "clarified",
        _half_turn_evidence(spec, "a b", [3])))


# ------------------------------------------------------------------------------------------ RaRaRaRbRb
def _quartic_symbols():
    return sp.symbols("u_x u_y v_x v_y d_x d_y", real=True)


def seed_quartic_polys():
    """(P4, P2, t): the seed's quartic in t = tan(theta1/2) and the quadratic of the direct route.

    Plane normal to a, orthonormal frame (e1, a x e1): d = Rot(theta1) u + Rot(theta1 + theta2) v. Seed route
    (eqs. 24-26, rebuilt from the text): the two components are linear in (cos, sin)(theta1 + theta2); solve them,
    impose cos^2 + sin^2 = 1 and substitute the half tangent of theta1 without using cos^2 + sin^2 = 1 for
    theta1 -> quartic. Direct route: |d - Rot(theta1) u|^2 = |v|^2 is linear in (cos, sin) theta1 -> quadratic."""
    ux, uy, vx, vy, dx, dy = _quartic_symbols()
    c1, s1, t = sp.symbols("c1 s1 t", real=True)
    ex, ey = dx - (c1 * ux - s1 * uy), dy - (s1 * ux + c1 * uy)  # d - Rot(theta1) u
    vv = vx**2 + vy**2
    c12 = (vx * ex + vy * ey) / vv  # [vx -vy; vy vx] (c12, s12) = e
    s12 = (vx * ey - vy * ex) / vv
    circle = sp.expand((c12**2 + s12**2 - 1) * vv)  # = (|e|^2 - |v|^2), quadratic form in (c1, s1)
    half = {c1: (1 - t**2) / (1 + t**2), s1: 2 * t / (1 + t**2)}
    P4 = sp.expand(sp.cancel(circle.subs(half) * (1 + t**2) ** 2))
    A = sp.expand(-2 * (dx * ux + dy * uy))  # |d|^2 + |u|^2 - |v|^2 - 2 d.Rot(theta1) u = 0
    B = sp.expand(-2 * (dy * ux - dx * uy))
    C = sp.expand(dx**2 + dy**2 + ux**2 + uy**2 - vv)
    P2 = half_angle_quadratic(A, B, C, t)
    return P4, P2, t


def r_robot_steps(dv: Derivation, spec: ScrewSpec) -> None:
    _orientation_step(dv, spec, "a b", lambda q: (q[0] + q[1] + q[2], q[3] + q[4]))
    P4, P2, t = seed_quartic_polys()
    f4 = sp.lambdify(_quartic_symbols(), sp.Poly(P4, t).all_coeffs(), "math")

    def on_robot(rng):
        """The robot's own planar problem (plane normal to a): tan(theta1/2) of the generating joints is a root."""
        dsn = sample_design(spec, rng)
        a, r1, r2, r3 = _vecs(spec, dsn, "a r1 r2 r3")
        q = list(sample_joints(spec, rng, 2.5).values())
        e1 = np.cross(a, [1.0, 0.0, 0.0] if abs(a[0]) < 0.9 else [0.0, 1.0, 0.0])
        e1 /= np.linalg.norm(e1)
        e2 = np.cross(a, e1)
        u, v = r2 - r1, r3 - r2
        d = _rot(a, q[0]) @ u + _rot(a, q[0] + q[1]) @ v
        coeffs = f4(u @ e1, u @ e2, v @ e1, v @ e2, d @ e1, d @ e2)
        return abs(np.polyval(coeffs, math.tan(q[0] / 2))) / max(abs(c) for c in coeffs)
    dv.add(Step("seed_quartic", "Seed route for theta1, theta2: the quartic of eqs. (24)-(26), and the quadratic",
                "in-plane components of d = Rot(theta1) u + Rot(theta1 + theta2) v, solved linearly for "
                "(cos, sin)(theta1 + theta2), cos^2 + sin^2 = 1, half tangent t = tan(theta1/2): a quartic P4(t); "
                "the direct route |d - Rot(theta1) u|^2 = |v|^2 gives a quadratic P2(t), and the emitted route "
                "(law of cosines in theta2, then one rotation for theta1) has the same two roots",
                ("ik_stage3", "ik_stage4"),
                {"P4 (seed quartic)": sp.collect(P4, t), "P2 (quadratic)": sp.collect(P2, t),
                 "relation": sp.Eq(sp.Symbol("P4"), (1 + t**2) * sp.Symbol("P2"))},
                (symbolic_identity(P4, sp.expand((1 + t**2) * P2), "P4 = (1 + t^2) P2 identically: the quartic "
                                   "only adds t = +/- i", sp.expand),
                 numeric_predicate(on_robot, "on random robots, tan(theta1/2) of the generating joints is a root of "
                                   "P4 built from the robot's (r2 - r1, r3 - r2, d) in the plane normal to a "
                                   "(relative residual)", samples=100, tol=1e-9,
                                   # rounding level: Horner at |t| up to tan(1.25) ~ 3 sums terms 81x the largest
                                   # coefficient, so the residual reaches 1e-13 and its decade moves with the kernels
                                   floor=1e-12)),
                source="seed 003, eqs. (24)-(27) (formulas lost; rebuilt from the text)",
                note="The extra roots t = +/- i are the circular points (cos theta1, sin theta1) = (1, +/- i) x "
                     "infinity: never real, never a solution."))
    A, B, C = sp.symbols("A B C", real=True)
    tq = sp.Symbol("t", real=True)
    th = sp.Symbol("theta4", real=True)
    quad = half_angle_quadratic(A, B, C, tq)
    dv.add(Step("seed_half_tangent", "Seed route for theta4: the half-tangent formula (eq. 22)",
                "A cos theta4 + B sin theta4 + C = 0 with t = tan(theta4/2): (C - A) t^2 + 2 B t + (A + C) = 0",
                ("ik_stage1",), {"quadratic": sp.collect(quad, tq)},
                (symbolic_identity(quad.subs(tq, sp.tan(th / 2)) * sp.cos(th / 2) ** 2,
                                   A * sp.cos(th) + B * sp.sin(th) + C, "cos^2(theta/2) times the quadratic at "
                                   "t = tan(theta/2) is A cos + B sin + C"),),
                source="seed 003, eqs. (21)-(22)",
                note="At theta4 = pi the leading coefficient C - A vanishes and the root moves to t = infinity: the "
                     "half-tangent formula divides by zero there. The emitted stage uses atan2(B, A) +/- acos(-C/r), "
                     "which has no such point."))
    dv.findings.extend(_r_findings(spec))


def _r_findings(spec: ScrewSpec) -> list[Finding]:
    P4, P2, t = seed_quartic_polys()
    syms = _quartic_symbols()
    f4 = sp.lambdify(syms, sp.Poly(P4, t).all_coeffs(), "math")
    f2 = sp.lambdify(syms, sp.Poly(P2, t).all_coeffs(), "math")
    rng = np.random.default_rng(11)
    worst_i, real4, real2, extra_real, lost = 0.0, 0, 0, 0, 0
    for _ in range(N_AUDIT):
        u, v = rng.uniform(-1, 1, 2), rng.uniform(-1, 1, 2)
        if rng.uniform() < 0.7:  # reachable: d from random angles; else any d (often out of reach)
            t1, t12 = rng.uniform(-math.pi, math.pi, 2)
            d = _rot2(t1) @ u + _rot2(t12) @ v
        else:
            d = rng.uniform(-2, 2, 2)
        args = (*u, *v, *d)
        r4, r2 = np.roots(f4(*args)), np.roots(f2(*args))
        re4 = [x.real for x in r4 if abs(x.imag) <= 1e-7 * max(1.0, abs(x))]
        re2 = [x.real for x in r2 if abs(x.imag) <= 1e-7 * max(1.0, abs(x))]
        real4 += len(re4)
        real2 += len(re2)
        extra = sorted(r4, key=lambda x: min(abs(x - y) for y in r2) if len(r2) else 0.0)[len(r2):]
        worst_i = max([worst_i] + [min(abs(x - 1j), abs(x + 1j)) for x in extra])
        extra_real += sum(1 for x in re4 if not any(abs(x - y) <= 1e-6 * max(1.0, abs(x)) for y in re2))
        lost += sum(1 for x in re2 if not any(abs(x - y) <= 1e-6 * max(1.0, abs(x)) for y in re4))
    # theta4 = pi: the seed's half-tangent quadratic loses the root
    rng = np.random.default_rng(12)
    dsn = sample_design(spec, rng)
    q = list(sample_joints(spec, rng).values())
    q[3] = math.pi
    a, b, r4v, r5v = _vecs(spec, dsn, "a b r4 r5")
    T = screws.np_poe(numeric_axes(spec, dsn), q)
    w = r5v - r4v
    A_ = a @ (w - (b @ w) * b)
    C_ = (a @ b) * (b @ w) + a @ r4v - a @ (T[:3, :3] @ r5v) - a @ T[:3, 3]
    lead = C_ - A_
    return [
        Finding("theta1, theta2 (eqs. 24-26)", "a quartic in the half tangent of theta1, solved by the quartic "
                "formula", "P4 = (1 + t^2) P2: the quartic is the quadratic times 1 + t^2; the emitted route needs "
                "one law-of-cosines step (2 roots) and one rotation", "clarified",
                f"symbolic identity (step seed_quartic); {N_AUDIT} random planar problems (70% reachable): real roots "
                f"of P4 {real4}, of P2 {real2}; real roots of P4 that are not roots of P2: {extra_real}; roots of P2 "
                f"missing from P4: {lost}; the two extra roots of P4 lie within {error_bucket(worst_i)} of +/- i. "
                "The quartic "
                "adds only the complex pair t = +/- i and is never needed."),
        Finding("theta4 half-tangent formula (eq. 22) at theta4 = pi", "t = tan(theta4/2) from the quadratic",
                "atan2(B, A) +/- acos(-C / sqrt(A^2 + B^2)) (emitted)", "clarified",
                f"random robot with theta4 = pi: leading coefficient |C - A| {error_bucket(lead)} (vs A = {A_:.2f}): "
                "the root "
                "is at t = infinity, the quadratic formula divides by ~0; the generated IK returns theta4 = pi (tests "
                "test_half_turn_joint_values)"),
        Finding("rotational parameters (eq. 19) at half turns", "closed form from the finite screw of the pose",
                "phi_a = atan2((R b).(a x b), (R b).b - (a.b)^2), phi_b likewise from R^T a (emitted)", "clarified",
                _half_turn_evidence(spec, "a b", [0])),
    ]


def _rot2(t: float) -> np.ndarray:
    return np.array([[math.cos(t), -math.sin(t)], [math.sin(t), math.cos(t)]])


# ------------------------------------------------------------------------------------------ audit numbers
def _dist(kinds, x, y) -> float:
    d = np.asarray(x) - np.asarray(y)
    return float(np.max(np.abs([math.remainder(v, 2 * math.pi) if k == "R" else v
                                for v, k in zip(d, kinds, strict=True)])))


def audit_numbers(spec: ScrewSpec, dv: Derivation, solver) -> dict:
    """Round trips through the freshly generated solver on random robots (counts and thresholds only)."""
    rng = np.random.default_rng(2024)
    kinds = solver.JOINT_KINDS
    counts: dict[int, int] = {}
    found, all_ok, n = 0, True, N_AUDIT
    for _ in range(n):
        dsn = sample_design(spec, rng)
        design = solver.make_design(list(dsn.values()))
        q = list(sample_joints(spec, rng).values())
        T = screws.np_poe(numeric_axes(spec, dsn), q)
        sol = solver.ik(T, design)
        counts[sol.count] = counts.get(sol.count, 0) + 1
        all_ok &= all(float(np.max(np.abs(screws.np_poe(numeric_axes(spec, dsn), v) - T))) <= 1e-9 for v in sol)
        found += any(_dist(kinds, v, q) < 1e-6 for v in sol)
    unreach, m = 0, 100
    for _ in range(m):
        T = screws.np_screw_to_transform(screws.random_screw(rng))
        unreach += solver.ik(T).status == solver.STATUS_UNREACHABLE
    sing = _singular_numbers(spec, solver)
    findings = []
    if spec.structure == "RaRaRaRbRb":
        findings.append(Finding(
            "number of IK solutions", "two sets of joint parameters in the Matlab example (section 5.2)",
            "up to 4 = 2 (theta4: A cos + B sin + C = 0) x 2 (elbow: law of cosines); each stage is the lowest "
            "degree possible (a quadratic in the half tangent) since both of its roots occur", "clarified",
            f"{n} random robots and joints: solution counts {dict(sorted(counts.items()))}; 4 real solutions occur, "
            "so no route of lower total degree than 2 x 2 exists; the seed's quartic route has degree 2 x 4"))
    return {
        "findings": findings,
        "summary": [("joints", ", ".join(f"{q} ({'revolute' if k == 'R' else 'prismatic'})"
                                         for q, k in zip(spec.joints, spec.kinds, strict=True))),
                    ("design", f"{len(spec.design)} numbers: every axis direction (unit) and position at the "
                               "initial pose; default " + ", ".join(f"{d}={v:g}" for d, v in
                                                                    zip(spec.design, spec.design_default,
                                                                        strict=True))),
                    ("IK solution sets per pose (max)", str(solver.MAX_IK))],
        "sections": [
            {"title": "Round trips through the generated solver (random robots)",
             "body": f"{n} seeded random robots of the structure (unit directions uniform on the sphere, points in "
                     f"[-1, 1]^3) with random joints (angles in (-pi, pi], slides in [-1, 1]): IK solution counts "
                     f"{dict(sorted(counts.items()))}; the generating joints were among the solutions {found} of "
                     f"{n} times; every returned solution reproduced the pose (4x4 product of exponentials) to "
                     f"1e-9: {'yes' if all_ok else 'NO'}. {unreach} of {m} random rigid transforms were reported "
                     "unreachable (the image of a 5-DOF chain has measure zero). Branch-by-branch comparison with "
                     "the independent reference (multistart least squares): tests/test_screw_robots.py."},
            {"title": "Singular configurations", "body": sing},
        ],
    }


def _singular_numbers(spec: ScrewSpec, solver) -> str:
    rng = np.random.default_rng(77)
    if spec.structure == "P1P2P3RaRb":
        worst = math.inf
        for _ in range(N_AUDIT):
            dsn = sample_design(spec, rng, margin=0.1)
            q = list(sample_joints(spec, rng).values())
            jac = solver.jacobian(q, list(dsn.values()))
            worst = min(worst, float(np.linalg.svd(jac, compute_uv=False)[-1]))
        return ("None for an admissible design: the Jacobian has the independent columns p1, p2, p3 (linear) and "
                "a, Rot(a, theta_a) b (angular, never parallel since angle(a, b) is preserved), so rank 5 "
                f"everywhere. Smallest singular value of J over {N_AUDIT} random robots (design "
                f"conditions above 0.1) and joints: {measured(worst)}.")
    worst_sing, flagged, n = 0.0, 0, 60
    for i in range(n):
        dsn = sample_design(spec, rng, margin=0.1)
        a, b, r1, r2, r3, r4, r5 = _vecs(spec, dsn, "a b r1 r2 r3 r4 r5")
        q = list(sample_joints(spec, rng).values())
        if i % 2 == 0:  # theta4 at an extremum of a.Rot(b, theta4)(r5 - r4): no translation along a
            w = r5 - r4
            q[3] = math.atan2(a @ np.cross(b, w), a @ (w - (b @ w) * b))
        else:  # elbow stretched or folded: Rot(a, theta2) v parallel to u in the plane normal to a
            u, v = (r2 - r1) - ((r2 - r1) @ a) * a, (r3 - r2) - ((r3 - r2) @ a) * a
            q[1] = math.atan2(a @ np.cross(v, u), u @ v)
        design = list(dsn.values())
        worst_sing = max(worst_sing, float(np.linalg.svd(solver.jacobian(q, design), compute_uv=False)[-1]))
        T = screws.np_poe(numeric_axes(spec, dsn), q)
        sol = solver.ik(T, design)
        flagged += any(int(f) & solver.FLAG_DOUBLE_ROOT for f in sol.flags[sol.valid])
    return ("The orientation depends on phi_a = theta1 + theta2 + theta3 and phi_b = theta4 + theta5 only, so with "
            "the orientation fixed the translation comes from theta4 (along a) and the planar elbow theta1, theta2: "
            "J loses rank (a) where d(a.p)/d theta4 = 0, theta4 = atan2(B, A) mod pi (the theta4 stage has a double "
            "root), and (b) where the elbow is stretched or folded (the theta2 stage has a double root). Measured "
            f"on {n} random robots at such configurations (half each): largest smallest singular value of J "
            f"{error_bucket(worst_sing)}; IK sets flagged double_root + singular_inverse in {flagged} of {n}.")
