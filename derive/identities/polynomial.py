"""Half-angle substitution and elimination steps for trigonometric loop equations."""

from __future__ import annotations

import sympy as sp


def half_angle_quadratic(a, b, c, t) -> sp.Expr:
    """a cos q + b sin q + c = 0 with t = tan(q/2), times (1 + t^2): (c - a) t^2 + 2 b t + (a + c)."""
    return sp.expand((c - a) * t**2 + 2 * b * t + (a + c))


def weierstrass(expr, cos_sym, sin_sym, x) -> sp.Expr:
    """(1 + x^2) * expr for expr affine in (cos, sin); result is a quadratic in x."""
    return sp.expand((1 + x**2) * expr.subs({cos_sym: (1 - x**2) / (1 + x**2),
                                            sin_sym: 2 * x / (1 + x**2)}))


def affine_cs_coefficients(expr, c, s) -> tuple[sp.Expr, sp.Expr, sp.Expr]:
    """Split expr = k0 + kc*c + ks*s (expr must be affine in the symbols c, s).

    Term by term on the expanded sum: the coefficients Poly(expr, c, s) gives, without building the polynomial
    ring of every other generator (trig functions of the joints and design angles), which cost 5x as much."""
    e = sp.expand(expr)
    parts: dict = {sp.S.One: [], c: [], s: []}
    for term in sp.Add.make_args(e) if e != 0 else ():
        k, monomial = term.as_independent(c, s, as_Add=False)
        if monomial not in parts:
            raise ValueError("expression is not affine in (cos, sin)")
        parts[monomial].append(k)
    return sp.Add(*parts[sp.S.One]), sp.Add(*parts[c]), sp.Add(*parts[s])


def cramer_cs(d1, e1, f1, d2, e2, f2):
    """Solve d_i cos z + e_i sin z + f_i = 0 (i = 1, 2) for (cos z, sin z) = (nc/den, ns/den)."""
    den = d1 * e2 - d2 * e1
    nc = e1 * f2 - e2 * f1
    ns = d2 * f1 - d1 * f2
    return nc, ns, den


def elimination_identity(d1, e1, f1, d2, e2, f2) -> sp.Expr:
    """cos^2 + sin^2 = 1 after Cramer, cleared of the denominator: must vanish at every solution."""
    nc, ns, den = cramer_cs(d1, e1, f1, d2, e2, f2)
    return nc**2 + ns**2 - den**2
