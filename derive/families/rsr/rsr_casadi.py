"""CasADi functions of the 3-RSR wrist and the SCARA + 3-RSR hybrid, built from their checked kernels.

Wrist: `rsr_wrist_fk` (phi, design) -> (alpha, beta, l_bw, T 3x4) through the mirror plane; `rsr_wrist_fk_jacobian`
d(alpha, beta, l_bw)/d phi by AD; `rsr_wrist_leg_residual` F(phi, x) = L (A_i cos phi_i + B sin phi_i) - l_bw/2
with its AD Jacobians `Jq`, `Jx` (inverse and direct singular sets: det Jq = 0, det Jx = 0); and
`rsr_wrist_constraint_jacobian`, the 6x6 Jacobian of the full closed-chain constraints (platform links
perpendicular to their axes and of length L) with respect to the platform twist, evaluated on the symmetric
mode: where it is singular the symmetric mode can bifurcate into a non-symmetric one (constraint singularity).
Hybrid: `scara_rsr_fk` (q, design) -> T 3x4 and `scara_rsr_jacobian` d vec(T)/dq (12 x 7) by AD.
"""

from __future__ import annotations

import casadi as ca

from ...casadi_export import _elems, _kernel_sx

_AXES = ((1.0, 0.0), (-0.5, 0.8660254037844386), (-0.5, -0.8660254037844386))  # u_i = Rz(a_i) e_x


def _wrist_fk_sx(K, q, w):
    plane = _kernel_sx(K["fk_plane"], {"q": _elems(q), "design": _elems(w)})
    nvec = ca.vertcat(plane["Nx"], plane["Ny"], plane["Nz"])
    s1 = ca.vertcat(plane["S1x"], plane["S1y"], plane["S1z"])
    # orientation n_z >= 0, as in the generated solvers (smooth away from n_z = 0)
    n = ca.sign(nvec[2]) * nvec / ca.norm_2(nvec)
    h = ca.dot(n, s1)
    pose = _kernel_sx(K["fk_pose"], {"plane": [n[0], n[1], n[2], h]})
    t = ca.reshape(ca.vertcat(*[pose[k] for k, _ in K["fk_pose"].outputs]), 4, 3).T
    x = ca.vertcat(ca.atan2(n[1], n[0]), 2 * ca.atan2(ca.sqrt(n[0] ** 2 + n[1] ** 2), n[2]), 2 * h)
    return x, t


def wrist_functions(kernels) -> dict[str, ca.Function]:
    K = {k.name: k for k in kernels}
    q, x, w = ca.SX.sym("phi", 3), ca.SX.sym("x", 3), ca.SX.sym("L", 1)
    xs, t = _wrist_fk_sx(K, q, w)
    co = _kernel_sx(K["ik_coeffs"], {"pose": _elems(x), "design": _elems(w)})
    f = ca.vertcat(*[w[0] * (co[f"A{i + 1}"] * ca.cos(q[i]) + co["B"] * ca.sin(q[i])) - x[2] / 2 for i in range(3)])
    # full closed chain on the symmetric mode: rows [w_i x d_i / L, -w_i] and [0, -d_i / L] (twist (omega L, v))
    rows = []
    for i, (cx, sy) in enumerate(_AXES):
        wi = ca.mtimes(t[:, :3], ca.vertcat(cx, sy, 0.0))
        si = ca.vertcat(-sy * w[0] * ca.cos(q[i]), cx * w[0] * ca.cos(q[i]), w[0] * ca.sin(q[i]))
        di = si - t[:, 3]
        rows.append(ca.horzcat(ca.cross(wi, di).T / w[0], -wi.T))
        rows.append(ca.horzcat(ca.SX.zeros(1, 3), -di.T / w[0]))
    jc = ca.vertcat(*rows)
    name = "rsr_wrist"
    return {
        f"{name}_fk": ca.Function(f"{name}_fk", [q, w], [xs, ca.densify(t)], ["phi", "L"], ["x", "T"]),
        f"{name}_fk_jacobian": ca.Function(f"{name}_fk_jacobian", [q, w], [ca.densify(ca.jacobian(xs, q))],
                                           ["phi", "L"], ["dx_dphi"]),
        f"{name}_leg_residual": ca.Function(f"{name}_leg_residual", [q, x, w],
                                            [f, ca.densify(ca.jacobian(f, q)), ca.densify(-ca.jacobian(f, x))],
                                            ["phi", "x", "L"], ["F", "Jq", "Jx"]),
        f"{name}_constraint_jacobian": ca.Function(f"{name}_constraint_jacobian", [q, w], [ca.densify(jc)],
                                                   ["phi", "L"], ["Jc"]),
    }


def hybrid_functions(kernels) -> dict[str, ca.Function]:
    K = {k.name: k for k in kernels}
    q, p = ca.SX.sym("q", 7), ca.SX.sym("p", 9)
    _, tw = _wrist_fk_sx(K, q[4:7], p[4:5])
    tw_rows = [tw[i, j] for i in range(3) for j in range(4)]
    comp = _kernel_sx(K["fk_compose"], {"qs": _elems(q[0:4]), "tw": tw_rows, "design": _elems(p[0:4])})
    t = ca.reshape(ca.vertcat(*[comp[k] for k, _ in K["fk_compose"].outputs]), 4, 3).T
    name = "scara_rsr"
    return {
        f"{name}_fk": ca.Function(f"{name}_fk", [q, p], [ca.densify(t)], ["q", "p"], ["T"]),
        f"{name}_jacobian": ca.Function(f"{name}_jacobian", [q, p], [ca.densify(ca.jacobian(ca.vec(t.T), q))],
                                        ["q", "p"], ["dT_dq"]),
    }
