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
    constant base transform, if any: frame 0 in the world)."""
    out, t = [], sp.eye(4) if base is None else base
    for row in rows:
        t = t * row.transform(convention)
        out.append(t)
    if tool is not None:
        out[-1] = out[-1] * tool
    return out
