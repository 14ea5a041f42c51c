"""The 3T2R structures of seed 003 (section 4) as ScrewSpecs of the generic finite-screw chain: a spec file names
the structure and gives its joints' axes at the initial pose (the default design).

Design = every axis direction and position at the initial pose, as symbols: one derivation covers every robot of
the structure (random robots in the tests are just other designs). Directions must be unit vectors.

Orientation (both robots): R = Rot(a, phi_a) Rot(b, phi_b). R b = Rot(a, phi_a) b and R^T a = Rot(b, -phi_b) a give
each angle by one atan2, with no half-tangent and no finite screw of the pose (defined at half turns too). The
image is a.(R b) = a.b.
"""

from __future__ import annotations

import sympy as sp

from ...identities.frames import rodrigues
from ...identities.screws import JointAxis
from ...serial_core.mechanism import SerialArm
from ...serial_core.stages import P_POSE, R_POSE, Stage
from . import screw_seed
from .screw_serial import DESIGN_NONZERO_TOL, DESIGN_UNIT_TOL, DesignCheck, ScrewSpec


def _vec(name: str) -> sp.Matrix:
    return sp.Matrix(sp.symbols(f"{name}x {name}y {name}z", real=True))


def _dot(u, v):
    return (u.T * v)[0]


def _angle_a(a, b):
    """phi_a from R b = Rot(a, phi_a) b: (R b).(a x b) = sin |a x b|^2, (R b).b - (a.b)^2 = cos |a x b|^2."""
    Rb = R_POSE * b
    return sp.atan2(_dot(Rb, a.cross(b)), _dot(Rb, b) - _dot(a, b) ** 2)


def _angle_b(a, b):
    """phi_b from R^T a = Rot(b, -phi_b) a: w.(a x b) = sin |a x b|^2, w.a - (a.b)^2 = cos |a x b|^2."""
    w = R_POSE.T * a
    return sp.atan2(_dot(w, a.cross(b)), _dot(w, a) - _dot(a, b) ** 2)


def _unit(name, v) -> DesignCheck:
    return DesignCheck(f"{name} is a unit vector (|{name}|^2 - 1)", _dot(v, v) - 1, "zero", DESIGN_UNIT_TOL)


def _apart(what, expr) -> DesignCheck:
    return DesignCheck(what, expr, "nonzero", DESIGN_NONZERO_TOL)


def _sq(v):
    return _dot(v, v)


# ------------------------------------------------------------------------------------- P1P2P3RaRb
def p1p2p3rarb(name: str, title: str, source: str, default: tuple[float, ...], seed: bool) -> ScrewSpec:
    """Three slides p1, p2, p3, then rotations about a (through ra) and b (through rb); default (p1, p2, p3, a, ra,
    b, rb)."""
    p1, p2, p3, a, ra, b, rb = (_vec(n) for n in ("p1", "p2", "p3", "a", "ra", "b", "rb"))
    t1, t2, t3 = sp.symbols("t1 t2 t3", real=True)
    tha, thb = sp.symbols("theta_a theta_b", real=True)
    joints = (t1, t2, t3, tha, thb)
    axes = (JointAxis("P", tuple(p1)), JointAxis("P", tuple(p2)), JointAxis("P", tuple(p3)),
            JointAxis("R", tuple(a), tuple(ra)), JointAxis("R", tuple(b), tuple(rb)))
    design = tuple(x for v in (p1, p2, p3, a, ra, b, rb) for x in v)
    Ra = rodrigues(a, sp.cos(tha), sp.sin(tha))
    # p = t1 p1 + t2 p2 + t3 p3 + (I - Ra) ra + Ra (I - Rb) rb and Ra Rb = R
    d = P_POSE - ra + Ra * ra - Ra * rb + R_POSE * rb
    det = _dot(p1, p2.cross(p3))
    stages = [
        Stage("value", (3,), (_angle_a(a, b),), "theta_a from the orientation",
              "R b = Rot(a, theta_a) b (Rot(b) fixes b): theta_a = atan2((R b).(a x b), (R b).b - (a.b)^2)"),
        Stage("value", (4,), (_angle_b(a, b),), "theta_b from the orientation",
              "R^T a = Rot(b, -theta_b) a: theta_b = atan2((R^T a).(a x b), (R^T a).a - (a.b)^2)"),
        Stage("value", (0,), (_dot(d, p2.cross(p3)) / det,), "t1 by Cramer's rule",
              "[p1 p2 p3] t = d, d = p - (I - R_a) ra - R_a rb + R rb: t1 = det[d p2 p3] / det[p1 p2 p3]"),
        Stage("value", (1,), (_dot(p1, d.cross(p3)) / det,), "t2 by Cramer's rule",
              "t2 = det[p1 d p3] / det[p1 p2 p3]"),
        Stage("value", (2,), (_dot(p1, p2.cross(d)) / det,), "t3 by Cramer's rule",
              "t3 = det[p1 p2 d] / det[p1 p2 p3]"),
    ]
    checks = (_unit("p1", p1), _unit("p2", p2), _unit("p3", p3), _unit("a", a), _unit("b", b),
              _apart("prismatic directions p1, p2, p3 independent (det[p1 p2 p3] != 0)", det),
              _apart("rotation axes not parallel (|a x b|^2 != 0)", _sq(a.cross(b))))
    image = (("a.(R b) - a.b (orientation reachable by Rot(a) Rot(b))", _dot(a, R_POSE * b) - _dot(a, b)),)
    return ScrewSpec(name, title, source, axes, joints, design, default,
                     (tuple(p1), tuple(p2), tuple(p3), tuple(a), tuple(b)), stages, checks, image,
                     extra_steps=screw_seed.p_robot_steps if seed else None, structure="P1P2P3RaRb")


# ------------------------------------------------------------------------------------- RaRaRaRbRb
def rarararbrb(name: str, title: str, source: str, default: tuple[float, ...], seed: bool) -> ScrewSpec:
    """Three rotations about parallel axes a (through r1, r2, r3), then two about parallel axes b (through r4, r5);
    default (a, r1, r2, r3, b, r4, r5)."""
    a, b = _vec("a"), _vec("b")
    r1, r2, r3, r4, r5 = (_vec(f"r{i}") for i in range(1, 6))
    th = sp.symbols("theta1:6", real=True)
    axes = tuple(JointAxis("R", tuple(s), tuple(r)) for s, r in ((a, r1), (a, r2), (a, r3), (b, r4), (b, r5)))
    design = tuple(x for v in (a, r1, r2, r3, b, r4, r5) for x in v)
    c4, s4, c5, s5 = sp.cos(th[3]), sp.sin(th[3]), sp.cos(th[4]), sp.sin(th[4])
    w45 = r5 - r4
    ab = _dot(a, b)
    # a.p = a.r4 - a.(R r5) + a.(Rot(b, theta4) (r5 - r4)): rotations about a keep the a-component
    A4 = _dot(a, w45 - _dot(b, w45) * b)
    B4 = _dot(a, b.cross(w45))
    C4 = ab * _dot(b, w45) + _dot(a, r4) - _dot(a, R_POSE * r5) - _dot(a, P_POSE)
    # d = Rot(a, theta1) (r2 - r1) + Rot(a, theta1 + theta2) (r3 - r2), from p with R_phi_a = R Rot(b, -phi_b)
    Rb5 = rodrigues(b, c5, -s5)  # Rot(b, -theta5)
    Rb45 = rodrigues(b, c4 * c5 - s4 * s5, -(s4 * c5 + c4 * s5))  # Rot(b, -(theta4 + theta5))
    d = P_POSE - r1 - R_POSE * Rb5 * w45 + R_POSE * r5 - R_POSE * Rb45 * (r4 - r3)
    u = (r2 - r1) - _dot(a, r2 - r1) * a
    v = (r3 - r2) - _dot(a, r3 - r2) * a
    c2, s2 = sp.cos(th[1]), sp.sin(th[1])
    w0 = u + c2 * v + s2 * a.cross(v)  # Rot(a, theta2) applied to the second link, in the plane normal to a
    stages = [
        Stage("trig_linear", (3,), (A4, B4, C4), "theta4 from the translation along a",
              "a.p = a.r4 - a.(R r5) + a.(Rot(b, theta4) (r5 - r4)) (the Ra joints move nothing along a): "
              "A cos theta4 + B sin theta4 + C = 0, two roots (seed eqs. 21-22, solved by atan2 +/- acos)"),
        Stage("value", (4,), (_angle_b(a, b) - th[3],), "theta5 = phi_b - theta4",
              "phi_b = theta4 + theta5 from R^T a = Rot(b, -phi_b) a (seed eq. 19)"),
        Stage("trig_linear", (1,), (2 * _dot(u, v), 2 * _dot(u, a.cross(v)),
                                    _sq(u) + _sq(v) - (_sq(d) - _dot(a, d) ** 2)), "theta2: planar elbow",
              "d = Rot(a, theta1) (r2 - r1) + Rot(a, theta1 + theta2) (r3 - r2); in the plane normal to a: "
              "|d_perp|^2 = |u|^2 + |v|^2 + 2 u.Rot(a, theta2) v (law of cosines), two roots"),
        Stage("rotation2d", (0,), (_dot(d, w0), _dot(d, a.cross(w0)), _sq(w0), 0), "theta1: planar shoulder",
              "Rot(a, theta1) w0 = d_perp, w0 = u + Rot(a, theta2) v: coordinates in the frame (w0, a x w0)"),
        Stage("value", (2,), (_angle_a(a, b) - th[0] - th[1],), "theta3 = phi_a - theta1 - theta2",
              "phi_a = theta1 + theta2 + theta3 from R b = Rot(a, phi_a) b (seed eq. 19)"),
    ]
    checks = (_unit("a", a), _unit("b", b),
              _apart("rotation axes not parallel (|a x b|^2 != 0)", _sq(a.cross(b))),
              _apart("Ra axes 1 and 2 distinct (|a x (r2 - r1)|^2 != 0)", _sq(a.cross(r2 - r1))),
              _apart("Ra axes 2 and 3 distinct (|a x (r3 - r2)|^2 != 0)", _sq(a.cross(r3 - r2))),
              _apart("Rb axes distinct (|b x (r5 - r4)|^2 != 0)", _sq(b.cross(w45))))
    image = (("a.(R b) - a.b (orientation reachable by Rot(a) Rot(b))", _dot(a, R_POSE * b) - ab),)
    return ScrewSpec(name, title, source, axes, th, design, default, (tuple(a), tuple(b)), stages, checks, image,
                     extra_steps=screw_seed.r_robot_steps if seed else None, structure="RaRaRaRbRb")


# structure -> (joint kinds, which joints share a direction, the builder)
STRUCTURES = {"P1P2P3RaRb": ("PPPRR", (), p1p2p3rarb), "RaRaRaRbRb": ("RRRRR", ((0, 1, 2), (3, 4)), rarararbrb)}


class ScrewMechanism(SerialArm):
    """A ScrewSpec rendered through the serial-chain templates (same API as the DH chains)."""

    DERIVE_SECONDS = 6
    DERIVE_GROUP = "screw"  # one process for every screw chain: the screw algebra they share is derived once

    def derive(self):
        from .screw_serial import derive_spec
        return derive_spec(self.spec)

    def kernels(self, dv):
        from .screw_serial import kernels_spec
        return kernels_spec(self.spec, dv)

    def extra_context(self, ks) -> dict:
        from .screw_serial import context_spec
        return context_spec(self.spec)

    def audit_numbers(self, dv, solver, audit_dir) -> dict:
        return screw_seed.audit_numbers(self.spec, dv, solver)

    def casadi_functions(self, dv, kernels) -> dict:
        """The serial chains' CasADi set (FK, geometric Jacobian, AD of the position) plus the whole 6 x n
        Jacobian by CasADi's AD: linear rows d p / d q, angular rows vee(d R / d q_k R^T) (tested equal)."""
        import casadi as ca

        from ...serial_core.casadi_functions import serial_functions

        name = self.NAME
        fns = serial_functions(name, kernels)
        n, m = len(self.spec.joints), len(self.spec.design)
        q, p = ca.SX.sym("q", n), ca.SX.sym("p", m)
        T = fns[f"{name}_fk"](q, p)
        R = T[:, :3]
        cols = []
        for k in range(n):
            W = ca.reshape(ca.jacobian(ca.vec(R), q[k]), 3, 3) @ R.T
            cols.append(ca.vertcat(W[2, 1], W[0, 2], W[1, 0]))
        J = ca.vertcat(ca.jacobian(T[:, 3], q), ca.horzcat(*cols))
        fns[f"{name}_jacobian_ad"] = ca.Function(f"{name}_jacobian_ad", [q, p], [ca.densify(J)], ["q", "p"], ["J"])
        return fns
