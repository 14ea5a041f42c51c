"""Run the checks that back each derivation step.

Symbolic first (an identity SymPy can prove); a seeded numeric sample when the
symbolic route is too slow or SymPy cannot decide, with the tolerance stated.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import sympy as sp

from .model import Check

SEED = 20240615  # fixed so every regeneration draws the same samples


def _as_matrix(e) -> sp.Matrix:
    return e if isinstance(e, sp.MatrixBase) else sp.Matrix([e])


def trig_polynomial_zero(expr) -> bool:
    """True when `expr` is proven identically zero by ideal reduction; False means "not proven here".

    After expand_trig every trigonometric atom is sin, cos or tan of an argument that is no sum; each argument x
    becomes a pair (s_x, c_x) on its circle s_x^2 + c_x^2 = 1, and the numerator of the expression a polynomial
    in the pairs and the other symbols. The circles' equations form a Groebner basis (their leading terms s_x^2
    share no variable), so the numerator vanishes on every circle point iff its remainder on division by them is
    the zero polynomial: an exact proof, far cheaper than trigsimp. Arguments in a fixed relation (x and x/2,
    x and x + 1) or any other function or root of a symbol make it answer False: the caller then simplifies.
    """
    e = sp.expand_trig(sp.sympify(expr))
    atoms = e.atoms(sp.sin, sp.cos, sp.tan)
    args = sorted({f.args[0] for f in atoms}, key=sp.default_sort_key)
    for i, a in enumerate(args):
        if any((a / b).is_Rational or (a - b).is_number for b in args[i + 1:]):
            return False
    pairs = {a: (sp.Dummy(f"s{i}"), sp.Dummy(f"c{i}")) for i, a in enumerate(args)}
    rep = {f: {sp.sin: pairs[f.args[0]][0], sp.cos: pairs[f.args[0]][1],
               sp.tan: pairs[f.args[0]][0] / pairs[f.args[0]][1]}[f.func] for f in atoms}
    num = sp.expand(sp.fraction(sp.together(e.xreplace(rep)))[0])
    if num.atoms(sp.Function) or any(not p.exp.is_Integer and not p.base.is_number for p in num.atoms(sp.Pow)):
        return False
    if num == 0 or not args:
        return num == 0
    gens = [v for a in args for v in pairs[a]]
    gens += sorted(num.free_symbols - set(gens), key=lambda x: x.name)
    _, rem = sp.reduced(num, [s**2 + c**2 - 1 for s, c in pairs.values()], *gens, order="lex")
    return sp.expand(rem) == 0


def symbolic_identity(lhs, rhs, claim: str, simplifier: Callable = sp.simplify) -> Check:
    """Prove lhs == rhs: each entry of the difference by ideal reduction (trig_polynomial_zero), else by
    simplifying it to zero with `simplifier`."""
    diff = _as_matrix(lhs) - _as_matrix(rhs)
    ok = all(trig_polynomial_zero(d) or simplifier(sp.expand_trig(d)) == 0 for d in diff)
    return Check("symbolic", claim, bool(ok))


def sampler(args, expr, modules="numpy") -> Callable:
    """lambdify(args, expr) for sampling an expression in a check, its common subexpressions computed once.

    CSE in sympy's own order (order="none"): the canonical order and lambdify's implemented-function lookup each
    walk the expression as a tree, and products of transforms share subtrees so deeply that those walks took
    seconds where the CSE itself takes milliseconds. wristkin defines no implemented functions."""
    shared, reduced = sp.cse(expr, list=False, order="none")
    return sp.lambdify(args, reduced, modules, cse=lambda e: (shared, e), use_imps=False)


def numeric_identity(lhs, rhs, claim: str, ranges: dict[sp.Symbol, tuple[float, float]],
                     samples: int = 200, tol: float = 1e-11) -> Check:
    """Evaluate lhs - rhs at seeded random points of `ranges`; pass if max |diff| <= tol."""
    syms = sorted(ranges, key=lambda s: s.name)
    f = sampler(syms, _as_matrix(lhs) - _as_matrix(rhs))
    rng = np.random.default_rng(SEED)
    worst = 0.0
    for _ in range(samples):
        vals = [rng.uniform(*ranges[s]) for s in syms]
        worst = max(worst, float(np.max(np.abs(np.asarray(f(*vals), dtype=float)))))
    return Check("numeric", claim, worst <= tol, worst, tol, samples)


def numeric_predicate(fn: Callable[[np.random.Generator], float], claim: str,
                      samples: int = 200, tol: float = 1e-11, floor: float | None = None) -> Check:
    """Generic sampled check: fn(rng) returns an error for one random sample. `floor`: the rounding level of an
    extended-precision fn (default: double precision's, report_numbers.ROUNDING_FLOOR)."""
    rng = np.random.default_rng(SEED)
    worst = max(float(fn(rng)) for _ in range(samples))
    extra = {} if floor is None else {"floor": floor}
    return Check("numeric", claim, worst <= tol, worst, tol, samples, **extra)


def identity(lhs, rhs, claim: str, ranges: dict[sp.Symbol, tuple[float, float]],
             try_symbolic: bool = True, samples: int = 200, tol: float = 1e-11) -> tuple[Check, ...]:
    """Both checks where the symbolic one is feasible: a proof plus a numeric sanity sample."""
    checks: list[Check] = []
    if try_symbolic:
        checks.append(symbolic_identity(lhs, rhs, claim))
    checks.append(numeric_identity(lhs, rhs, claim, ranges, samples, tol))
    return tuple(checks)


def jacobian_fd_error(fk: Callable, jac: np.ndarray, q: np.ndarray, h: float = 1e-6) -> float:
    """The largest difference between a geometric Jacobian `jac` (6 x n, linear velocity of the end frame's origin
    first, then angular velocity) at q and central differences of the end frame fk (q -> 4 x 4): the origin's
    velocity, and the angular velocity read from dR/dq R^T (skew)."""
    q = np.asarray(q, dtype=float)
    t0, out = np.asarray(fk(q), dtype=float), 0.0
    for k in range(q.size):
        dq = np.zeros(q.size)
        dq[k] = h
        tp, tm = np.asarray(fk(q + dq), dtype=float), np.asarray(fk(q - dq), dtype=float)
        v = (tp[:3, 3] - tm[:3, 3]) / (2 * h)
        w = (tp[:3, :3] - tm[:3, :3]) / (2 * h) @ t0[:3, :3].T
        out = max(out, float(np.max(np.abs(np.concatenate([v, [w[2, 1], w[0, 2], w[1, 0]]]) - jac[:, k]))))
    return out
