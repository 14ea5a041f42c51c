"""The serial chains' CasADi functions (DH and finite-screw chains): FK, geometric Jacobian and AD checks."""

from __future__ import annotations

import casadi as ca

from ..casadi_export import _elems, _kernel_sx


def serial_functions(name: str, kernels) -> dict[str, ca.Function]:
    """A DH chain's FK (3x4 [R | p]) and geometric Jacobian (6 x n) from its kernels, plus the Jacobian of
    the position by CasADi's AD, which must equal the linear rows of the geometric one (tested)."""
    K = {k.name: k for k in kernels}
    n = len(K["fk"].inputs[0][1])
    q = ca.SX.sym("q", n)
    p = ca.SX.sym("p", len(K["fk"].inputs[1][1]))
    groups = {"q": _elems(q), "dp": _elems(p)}
    fk = _kernel_sx(K["fk"], groups)
    T = ca.reshape(ca.vertcat(*[fk[k] for k, _ in K["fk"].outputs]), 4, 3).T
    jo = _kernel_sx(K["jacobian"], groups)
    J = ca.reshape(ca.vertcat(*[jo[k] for k, _ in K["jacobian"].outputs]), n, 6).T
    return {
        f"{name}_fk": ca.Function(f"{name}_fk", [q, p], [ca.densify(T)], ["q", "p"], ["T"]),
        f"{name}_jacobian": ca.Function(f"{name}_jacobian", [q, p], [ca.densify(J)], ["q", "p"], ["J"]),
        f"{name}_position_jacobian_ad": ca.Function(f"{name}_position_jacobian_ad", [q, p],
                                                    [ca.densify(ca.jacobian(T[:, 3], q))], ["q", "p"], ["Jp"]),
    }
