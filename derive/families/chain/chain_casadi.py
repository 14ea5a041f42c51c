"""A chain's CasADi functions: FK (3x4 [R | p]) and the geometric Jacobian from the POE form, plus the
position Jacobian by CasADi's AD (must equal the geometric one's linear rows)."""

from __future__ import annotations

import casadi as ca
import numpy as np

from ...kinematics.poe import Chain


def _screw(kind, axis, point, q):
    if kind == "P":
        return ca.SX.eye(3), ca.SX(axis.tolist()) * q
    k = ca.SX(axis.tolist())
    kx = ca.skew(k)
    r = ca.SX.eye(3) + ca.sin(q) * kx + (1 - ca.cos(q)) * ca.mtimes(kx, kx)
    p = ca.SX(point.tolist())
    return r, p - ca.mtimes(r, p)


def chain_functions(name: str, c: Chain) -> dict:
    q = ca.SX.sym("q", c.n)
    p = ca.SX.sym("p", 1)  # no design parameters: a placeholder input keeps one signature (q, p)
    r, t = ca.SX(c.base[:3, :3].tolist()), ca.SX(c.base[:3, 3].tolist())
    cols = []
    for i, kind in enumerate(c.kinds):
        w = ca.mtimes(r, ca.SX(c.axes[i].tolist()))
        o = ca.mtimes(r, ca.SX(c.points[i].tolist())) + t
        cols.append((w, o, kind))
        ri, ti = _screw(kind, c.axes[i], c.points[i], q[i])
        r, t = ca.mtimes(r, ri), ca.mtimes(r, ti) + t
    end = np.asarray(c.home @ c.tool)
    re, te = ca.mtimes(r, ca.SX(end[:3, :3].tolist())), ca.mtimes(r, ca.SX(end[:3, 3].tolist())) + t
    T = ca.horzcat(re, te)
    J = ca.horzcat(*[ca.vertcat(w, ca.SX.zeros(3)) if kind == "P" else ca.vertcat(ca.cross(w, te - o), w)
                     for w, o, kind in cols])
    return {
        f"{name}_fk": ca.Function(f"{name}_fk", [q, p], [ca.densify(T)], ["q", "p"], ["T"]),
        f"{name}_jacobian": ca.Function(f"{name}_jacobian", [q, p], [ca.densify(J)], ["q", "p"], ["J"]),
        f"{name}_position_jacobian_ad": ca.Function(f"{name}_position_jacobian_ad", [q, p],
                                                    [ca.densify(ca.jacobian(te, q))], ["q", "p"], ["Jp"]),
    }
