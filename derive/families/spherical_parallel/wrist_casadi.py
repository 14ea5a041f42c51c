"""The underactuated wrist's CasADi functions (seed 000), assembled only from the checked kernel expressions of
`underactuated_wrist.kernels` (the design constants kernel is composed in, so every function takes the design
parameters p = (alpha1, alpha2, beta1, beta2) as an explicit input). Outputs are densified.

Conventions (as in docs/API.md): angles in radians; e = (psi, theta, phi) are ZXZ Euler angles,
R = Rz(psi) Rx(theta) Rz(phi); q = (theta1, theta2, theta3) the exterior joint angles; loop i is
Zi2(theta_i) . (R p_i) - cos(alpha2) = A_i cos theta_i + B_i sin theta_i + C_i; jq * qdot = jx @ w.
"""

from __future__ import annotations

from collections.abc import Mapping

import casadi as ca

from ...casadi_export import _elems, _kernel_sx

DESIGN_NAMES = ("alpha1", "alpha2", "beta1", "beta2")


def _rot_x(a):
    c, s = ca.cos(a), ca.sin(a)
    return ca.vertcat(ca.horzcat(1, 0, 0), ca.horzcat(0, c, -s), ca.horzcat(0, s, c))


def _rot_z(a):
    c, s = ca.cos(a), ca.sin(a)
    return ca.vertcat(ca.horzcat(c, -s, 0), ca.horzcat(s, c, 0), ca.horzcat(0, 0, 1))


def rotation_zxz(e: ca.SX) -> ca.SX:
    """R = Rz(psi) Rx(theta) Rz(phi) for e = (psi, theta, phi) (docs/API.md)."""
    return ca.mtimes([_rot_z(e[0]), _rot_x(e[1]), _rot_z(e[2])])


def _mat3(out: Mapping[str, ca.SX], prefix: str) -> ca.SX:
    return ca.vertcat(*[ca.horzcat(*[out[f"{prefix}{i}{j}"] for j in range(3)]) for i in range(3)])


FUNCTION_DOCS = {
    "uw_loop": "g_i = A_i cos q_i + B_i sin q_i + C_i = Zi2(q_i) . (R(e) p_i) - cos(alpha2), i = 1..3.",
    "uw_ik_branch": "Closed-form IK per branch: q_i = atan2(B_i, A_i) + sigma_i acos(-C_i / "
                    "sqrt(A_i^2 + B_i^2)), sigma_i = +/-1; not wrapped (q_i in (-2 pi, 2 pi]); "
                    "NaN where branch i is unreachable.",
    "uw_fk_rotation": "R = Rx(pi - beta1) Rz(theta1) Rx(alpha1) Rz(zeta) Rx(alpha2) Rz(eta) G for "
                      "tze = (theta1, zeta, eta).",
    "uw_jacobians": "jq_i = det[Zi1, Zi2, Zi3], row i of jx = Zi2 x Zi3, with R = R(e): jq * qdot = jx @ w.",
    "uw_rates": "w = jx^-1 (jq * qd); wdot = jx^-1 (jq * qdd + jqdot * qd - jxdot w); ed = E^-1 w; "
                "edd = E^-1 (wdot - Edot ed) with w = E(e) ed (singular at sin theta = 0).",
    "uw_loop_jac": "dg/dq and dg/de of uw_loop (CasADi AD).",
    "uw_singularity": "det_jq = jq1 jq2 jq3 (inverse/serial singularity at 0), det_jx = det jx "
                      "(direct/parallel singularity at 0).",
}


def casadi_functions(dv=None, kernels=None) -> dict[str, ca.Function]:
    """The underactuated wrist's CasADi functions, built from the kernels' SymPy expressions.

    dv: the Derivation (`underactuated_wrist.derive()`); kernels: `underactuated_wrist.kernels(dv)`
    (computed from dv when None). Returns a dict name -> casadi.Function (insertion order fixed).
    """
    if kernels is None:
        raise ValueError("need the kernels (underactuated_wrist.kernels(dv))")
    if dv is not None and not dv.all_passed:
        raise AssertionError("derivation has failed steps")
    K = {k.name: k for k in kernels}
    missing = {"design_constants", "ik_abc", "fk_rotation", "jacobians", "jacobian_rates",
               "euler_rate_matrix"} - set(K)
    if missing:
        raise ValueError(f"missing kernels: {sorted(missing)}")
    (pname, psyms), = K["design_constants"].inputs
    if tuple(s.name for s in psyms) != DESIGN_NAMES:
        raise ValueError(f"design_constants takes {[s.name for s in psyms]}, expected {DESIGN_NAMES}")

    q = ca.SX.sym("q", 3)
    e = ca.SX.sym("e", 3)
    p = ca.SX.sym("p", 4)
    sigma = ca.SX.sym("sigma", 3)
    tze = ca.SX.sym("tze", 3)
    qd = ca.SX.sym("qd", 3)
    qdd = ca.SX.sym("qdd", 3)

    dc_out = _kernel_sx(K["design_constants"], {pname: _elems(p)})
    dc = [dc_out[name] for name, _ in K["design_constants"].outputs]

    # ik_abc takes the entries of R (row-major), built here from the ZXZ angles
    abc = _kernel_sx(K["ik_abc"], {"rot": _elems(rotation_zxz(e)), "dc": dc})
    A = [abc[f"A{i}"] for i in (1, 2, 3)]
    B = [abc[f"B{i}"] for i in (1, 2, 3)]
    C = [abc[f"C{i}"] for i in (1, 2, 3)]
    g = ca.vertcat(*[A[i] * ca.cos(q[i]) + B[i] * ca.sin(q[i]) + C[i] for i in range(3)])
    q_ik = ca.vertcat(*[ca.atan2(B[i], A[i]) + sigma[i] * ca.acos(-C[i] / ca.sqrt(A[i] ** 2 + B[i] ** 2))
                        for i in range(3)])

    R_fk = _mat3(_kernel_sx(K["fk_rotation"], {"c": [ca.cos(t) for t in _elems(tze)],
                                               "s": [ca.sin(t) for t in _elems(tze)], "dc": dc}), "r")

    R = rotation_zxz(e)
    jac = _kernel_sx(K["jacobians"], {"q": _elems(q), "rot": _elems(R), "dc": dc})
    jq = ca.vertcat(*[jac[f"jq{i}"] for i in (1, 2, 3)])
    jx = _mat3(jac, "jx")

    w = ca.solve(jx, jq * qd)
    rates = _kernel_sx(K["jacobian_rates"], {"q": _elems(q), "rot": _elems(R), "qd": _elems(qd),
                                            "w": _elems(w), "dc": dc})
    jqdot = ca.vertcat(*[rates[f"jqd{i}"] for i in (1, 2, 3)])
    jxdot = _mat3(rates, "jxd")
    wdot = ca.solve(jx, jq * qdd + jqdot * qd - ca.mtimes(jxdot, w))
    E = _mat3(_kernel_sx(K["euler_rate_matrix"], {"pose": _elems(e)}), "e")
    ed = ca.solve(E, w)
    Edot = ca.jtimes(E, e, ed)  # dE/dt along e' = ed
    edd = ca.solve(E, wdot - ca.mtimes(Edot, ed))

    d = ca.densify
    specs = [
        ("uw_loop", [q, e, p], [g], ["q", "e", "p"], ["g"]),
        ("uw_ik_branch", [e, p, sigma], [q_ik], ["e", "p", "sigma"], ["q"]),
        ("uw_fk_rotation", [tze, p], [R_fk], ["tze", "p"], ["R"]),
        ("uw_jacobians", [q, e, p], [jq, jx], ["q", "e", "p"], ["jq", "jx"]),
        ("uw_rates", [q, e, qd, qdd, p], [w, wdot, ed, edd], ["q", "e", "qd", "qdd", "p"],
         ["w", "wdot", "ed", "edd"]),
        ("uw_loop_jac", [q, e, p], [ca.jacobian(g, q), ca.jacobian(g, e)], ["q", "e", "p"],
         ["dg_dq", "dg_de"]),
        ("uw_singularity", [q, e, p], [jq[0] * jq[1] * jq[2], ca.det(jx)], ["q", "e", "p"],
         ["det_jq", "det_jx"]),
    ]
    return {name: ca.Function(name, ins, [d(o) for o in outs], nin, nout)
            for name, ins, outs, nin, nout in specs}


# ------------------------------------------------------------------------------ serialisation
