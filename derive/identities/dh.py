"""Denavit-Hartenberg link transforms (standard and modified/Craig), symbolic."""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from .frames import rot_x, rot_z


def _homogeneous(rot: sp.Matrix, p) -> sp.Matrix:
    m = sp.eye(4)
    m[:3, :3] = rot
    m[:3, 3] = sp.Matrix(p)
    return m


def trans(x, y, z) -> sp.Matrix:
    return _homogeneous(sp.eye(3), (x, y, z))


def hrot_x(a) -> sp.Matrix:
    return _homogeneous(rot_x(a), (0, 0, 0))


def hrot_z(a) -> sp.Matrix:
    return _homogeneous(rot_z(a), (0, 0, 0))


def dh_standard(a, alpha, d, theta) -> sp.Matrix:
    """A_i = Rz(theta) Tz(d) Tx(a) Rx(alpha) (Spong / the seed's slides)."""
    return hrot_z(theta) * trans(0, 0, d) * trans(a, 0, 0) * hrot_x(alpha)


def dh_modified(a_prev, alpha_prev, d, theta) -> sp.Matrix:
    """A_i = Rx(alpha_{i-1}) Tx(a_{i-1}) Rz(theta) Tz(d) (Craig; seed 002's Table I)."""
    return hrot_x(alpha_prev) * trans(a_prev, 0, 0) * hrot_z(theta) * trans(0, 0, d)


def dh_standard_explicit(a, alpha, d, theta) -> sp.Matrix:
    """The textbook closed form of the standard A_i, used to check the product form."""
    ct, st, ca, sa = sp.cos(theta), sp.sin(theta), sp.cos(alpha), sp.sin(alpha)
    return sp.Matrix([[ct, -st * ca, st * sa, a * ct], [st, ct * ca, -ct * sa, a * st], [0, sa, ca, d], [0, 0, 0, 1]])


def dh_modified_explicit(a_prev, alpha_prev, d, theta) -> sp.Matrix:
    """Craig's closed form of the modified A_i, used to check the product form."""
    ct, st, ca, sa = sp.cos(theta), sp.sin(theta), sp.cos(alpha_prev), sp.sin(alpha_prev)
    return sp.Matrix([[ct, -st, 0, a_prev], [st * ca, ct * ca, -sa, -sa * d], [st * sa, ct * sa, ca, ca * d],
                      [0, 0, 0, 1]])


def explicit(row, convention: str) -> sp.Matrix:
    fn = dh_standard_explicit if convention == "standard" else dh_modified_explicit
    return fn(row.a, row.alpha, row.d, row.theta)


@dataclass(frozen=True)
class DHRow:
    """One link: a, alpha, d, theta may be numbers, design symbols or the joint variable."""

    a: sp.Expr
    alpha: sp.Expr
    d: sp.Expr
    theta: sp.Expr
    joint: sp.Symbol | None  # the variable of this row (None for a fixed row)
    kind: str = "R"  # "R" revolute (theta varies) or "P" prismatic (d varies)

    def transform(self, convention: str = "standard") -> sp.Matrix:
        if convention == "standard":
            return dh_standard(self.a, self.alpha, self.d, self.theta)
        if convention == "modified":
            return dh_modified(self.a, self.alpha, self.d, self.theta)
        raise ValueError(f"unknown DH convention {convention!r}")


def chain(rows, convention: str = "standard", tool: sp.Matrix | None = None,
          base: sp.Matrix | None = None) -> list[sp.Matrix]:
    """Cumulative transforms T_1^0 .. T_n^0 (the last one times the constant tool transform, if any; each after the
    constant base transform, if any: frame 0 in the world), each in the compact form of _Folded: a run of parallel
    axes turns through the sum of its angles (cos(q2 + q3 + q4), as simplify writes it, without its cost: 5 s of a
    UR's 12 s derivation)."""
    out, run = [], _Folded(sp.eye(4) if base is None else base)
    for row in rows:
        for op, value in _elementary(row, convention):
            run.apply(op, value)
        out.append(run.matrix())
    if tool is not None:
        out[-1] = out[-1] * tool
    return out


def _elementary(row, convention: str):
    """The row's transform as elementary operations, in order."""
    if convention == "standard":
        return (("rz", row.theta), ("tz", row.d), ("tx", row.a), ("rx", row.alpha))
    if convention == "modified":
        return (("rx", row.alpha), ("tx", row.a), ("rz", row.theta), ("tz", row.d))
    raise ValueError(f"unknown DH convention {convention!r}")


class _Folded:
    """A product M Rz(phi) F^k Trans(p) of elementary transforms, F = Rx(pi): a turn about z adds its angle to phi
    (F Rz(t) = Rz(-t) F: with sign s = (-1)^k), a shift along x or z adds to p in the run's frame (Rz(phi) F^k
    applied, so each link's offset reads cos and sin of its run's partial sum), a twist of 0 or pi keeps the run
    (pi flips s), any other twist closes it into M. The result is the plain product's, written with the sums."""

    def __init__(self, start: sp.Matrix):
        self.closed = start
        self.phi, self.sign, self.p = sp.Integer(0), 1, sp.zeros(3, 1)

    def apply(self, op: str, value) -> None:
        value = sp.sympify(value)
        if op == "rz":
            self.phi += self.sign * value
        elif op == "tz":
            self.p += sp.Matrix([0, 0, self.sign * value])
        elif op == "tx":
            self.p += value * sp.Matrix([sp.cos(self.phi), sp.sin(self.phi), 0])
        elif value == 0:
            pass
        elif value == sp.pi or value == -sp.pi:
            self.sign = -self.sign
        else:
            self.closed = self.matrix() * _homogeneous(rot_x(value), (0, 0, 0))
            self.phi, self.sign, self.p = sp.Integer(0), 1, sp.zeros(3, 1)

    def matrix(self) -> sp.Matrix:
        turn = rot_z(self.phi) * sp.diag(1, self.sign, self.sign)
        return self.closed * _homogeneous(turn, self.p)  # unexpanded: the products' nesting is what CSE shares
