"""A serial chain's product of exponentials as SymPy expressions with its constants folded: exp(S_1 q_1) ...
exp(S_n q_n) M, each screw written with the joint's axis and point as numbers (an exact 0 or +-1 entry stays exact,
so the terms it zeroes vanish), over the joint values and the cosines and sines of the revolute ones; and its
geometric Jacobian's columns. What a family emits as a robot's FK and Jacobian kernels (the chain family's true
chain, the serial family's calibrated robot)."""

from __future__ import annotations

import numpy as np
import sympy as sp

from ..identities.frames import rodrigues

# entries this close to an exact 0 or +-1 are that value: a URDF's rpy of pi/2 leaves ~6e-17 where the axis has a
# zero; the ideal chain's relations are made exact elsewhere, the true chain keeps every other digit
_EXACT_TOL = 1e-15


def number(v: float) -> sp.Expr:
    v = float(v)
    for exact in (0, 1, -1):
        if abs(v - exact) <= _EXACT_TOL:
            return sp.Integer(exact)
    return sp.Float(v, 17)


def vec(v) -> sp.Matrix:
    return sp.Matrix([number(x) for x in v])


def screw(kind: str, h: sp.Matrix, r: sp.Matrix, q: sp.Symbol, c: sp.Symbol, s: sp.Symbol):
    """exp(S q) as (R, t): a slide q along h, or a turn about the axis through r along h by the angle whose cosine and
    sine are c, s (Rodrigues)."""
    if kind == "P":
        return sp.eye(3), h * q
    rot = rodrigues(h, c, s)
    return rot, r - rot * r


def joint_symbols(n: int) -> tuple[tuple[sp.Symbol, ...], ...]:
    """(q, c, s): the joint values and the cosines and sines of the revolute ones (the kernels read each joint's
    slide from q, its turn from c and s: the caller takes cos and sin once for every kernel)."""
    return tuple(tuple(sp.Symbol(f"{v}{i}", real=True) for i in range(n)) for v in ("q", "c", "s"))


def symbolic_chain(chain, joints):
    """(R, t, columns) of the chain's end frame (no base / tool) over the n joint symbols `joints` and their cos and
    sin: the product of the screws times the home frame, and the geometric Jacobian's columns (w x (p - o), w) or
    (w, 0), linear rows first. Built over cos q and sin q directly (symbols for them substituted afterwards gave the
    same expressions and took seconds of xreplace on a 7-joint chain)."""
    qs, cs, ss = tuple(joints), tuple(sp.cos(q) for q in joints), tuple(sp.sin(q) for q in joints)
    rot, t = sp.eye(3), sp.zeros(3, 1)
    axes_points = []
    for kind, a, p, q, c, s in zip(chain.kinds, chain.axes, chain.points, qs, cs, ss, strict=True):
        h, r = vec(a), vec(p)
        axes_points.append((kind, rot * h, rot * r + t))
        e_rot, e_t = screw(kind, h, r, q, c, s)
        rot, t = rot * e_rot, rot * e_t + t
    home = np.asarray(chain.home, dtype=float)
    m_rot = sp.Matrix(3, 3, [number(x) for x in home[:3, :3].ravel()])
    end_rot, end = rot * m_rot, rot * vec(home[:3, 3]) + t
    cols = []
    for kind, w, o in axes_points:
        cols.append([*w, 0, 0, 0] if kind == "P" else [*w.cross(end - o), *w])
    return end_rot, end, cols
