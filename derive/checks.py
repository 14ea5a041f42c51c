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


def symbolic_identity(lhs, rhs, claim: str, simplifier: Callable = sp.simplify) -> Check:
    """Prove lhs == rhs by simplifying the difference to zero."""
    diff = _as_matrix(lhs) - _as_matrix(rhs)
    ok = all(simplifier(sp.expand_trig(d)) == 0 for d in diff)
    return Check("symbolic", claim, bool(ok))


def numeric_identity(lhs, rhs, claim: str, ranges: dict[sp.Symbol, tuple[float, float]],
                     samples: int = 200, tol: float = 1e-11) -> Check:
    """Evaluate lhs - rhs at seeded random points of `ranges`; pass if max |diff| <= tol."""
    syms = sorted(ranges, key=lambda s: s.name)
    f = sp.lambdify(syms, _as_matrix(lhs) - _as_matrix(rhs), "numpy")
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
