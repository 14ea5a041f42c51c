"""The subproblems' formulas, proven once with SymPy for symbolic unit axes and vectors (every chain's IK is
built from these; each robot's instance is then checked numerically on its own axes).

Unit length (|k|^2 = 1) and cos^2 + sin^2 = 1 enter as substitutions after expanding, so every claim is a
polynomial identity that expands to zero.
"""

from __future__ import annotations

from functools import lru_cache

import sympy as sp

from ..identities.frames import rodrigues
from ..model import Check


def _vec(name):
    return sp.Matrix(sp.symbols(f"{name}x {name}y {name}z", real=True))


def _reduce(expr, units, c, s):
    """The remainder of expr after dividing by |k|^2 - 1 (in kz, for each unit vector k) and by c^2 + s^2 - 1
    (in s): zero exactly when expr vanishes on unit vectors and on the unit circle."""
    e = sp.expand(expr)
    for k in units:
        e = sp.rem(e, k[0] ** 2 + k[1] ** 2 + k[2] ** 2 - 1, k[2])
    if s is not None:
        e = sp.rem(sp.expand(e), c ** 2 + s ** 2 - 1, s)
    return sp.expand(e)


def _zero(exprs, units, c=None, s=None) -> bool:
    return all(_reduce(e, units, c, s) == 0 for e in exprs)


def _cache_file():
    """Where the proofs' outcome is kept, keyed by this file's bytes and SymPy's version (a changed proof or SymPy
    proves again); None when no cache folder is writable."""
    import hashlib
    import os
    from pathlib import Path

    key = hashlib.sha256(Path(__file__).read_bytes() + sp.__version__.encode()).hexdigest()[:16]
    folder = Path(os.environ.get("WRISTKIN_CACHE") or Path.home() / ".cache" / "wristkin")
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError:
        return None
    return folder / f"subproblem-proofs-{key}.json"


@lru_cache(maxsize=1)
def subproblem_checks() -> tuple[tuple[str, str, Check], ...]:
    """(name, statement, check) for every formula the generated solvers evaluate: proven by `prove`, once per
    version of this file and of SymPy (the outcome is cached on disk; the claims are the same for every robot)."""
    import json
    import os

    path = _cache_file()
    if path is not None and path.is_file():
        try:
            rows = json.loads(path.read_text())
            return tuple((n, s, Check("symbolic", s, bool(ok))) for n, s, ok in rows)
        except (OSError, ValueError, TypeError):
            pass
    out = prove()
    if path is not None:
        try:
            tmp = path.with_suffix(f".{os.getpid()}.tmp")  # parallel workers write their own, then one wins
            tmp.write_text(json.dumps([[n, s, c.passed] for n, s, c in out]))
            tmp.replace(path)
        except OSError:
            pass
    return out


def prove() -> tuple[tuple[str, str, Check], ...]:
    """Run every proof (a few seconds of SymPy)."""
    k, h, p, p1, p2 = _vec("k"), _vec("h"), _vec("p"), _vec("a"), _vec("b")
    c, s, d = sp.symbols("c s d", real=True)
    R = rodrigues(k, c, s)
    out = []

    def add(name, statement, exprs, units, cs=True):
        ok = _zero(exprs, units, c if cs else None, s if cs else None)
        out.append((name, statement, Check("symbolic", statement, ok)))

    add("rotation", "R(k, t) = I + sin t [k]x + (1 - cos t) [k]x^2 is a rotation: R^T R = I, for |k| = 1",
        list(R.T * R - sp.eye(3)), [k])
    perp = p - k.dot(p) * k
    add("sp1_form", "R(k, t) p = (k.p) k + cos t (p - (k.p) k) + sin t (k x p)",
        list(R * p - (k.dot(p) * k + c * perp + s * k.cross(p))), [k])
    q = R * p
    qperp = q - k.dot(q) * k
    add("sp1_angle", "subproblem 1: for q = R(k, t) p, k.(p_perp x q_perp) = sin t |p_perp|^2 and "
        "p_perp.q_perp = cos t |p_perp|^2, so t = atan2 of the two",
        [k.dot(perp.cross(qperp)) - s * perp.dot(perp), perp.dot(qperp) - c * perp.dot(perp)], [k])
    a1perp = p1 - k.dot(p1) * k
    lhs = (R * p1 - p2).dot(R * p1 - p2) - d ** 2
    A, B = p2.dot(a1perp), p2.dot(k.cross(p1))
    C = sp.Rational(1, 2) * (p1.dot(p1) + p2.dot(p2) - d ** 2) - k.dot(p1) * k.dot(p2)
    add("sp3", "subproblem 3: |R(k, t) p1 - p2|^2 - d^2 = -2 (A cos t + B sin t - C) with A = p2.p1_perp, "
        "B = p2.(k x p1), C = (|p1|^2 + |p2|^2 - d^2)/2 - (k.p1)(k.p2)", [lhs + 2 * (A * c + B * s - C)], [k])
    add("sp4", "subproblem 4: h.R(k, t) p = (k.p)(h.k) + cos t h.p_perp + sin t h.(k x p)",
        [h.dot(R * p) - (k.dot(p) * h.dot(k) + c * h.dot(perp) + s * h.dot(k.cross(p)))], [k])
    k1, k2 = _vec("m"), _vec("n")
    a1, a2, g = sp.symbols("a1 a2 g", real=True)
    c12 = k1.dot(k2)
    den = 1 - c12 ** 2
    alpha, beta = (a1 - c12 * a2) / den, (a2 - c12 * a1) / den
    base = alpha * k1 + beta * k2
    w = base + g * k1.cross(k2)
    exprs = [sp.together(k1.dot(w) - a1).as_numer_denom()[0], sp.together(k2.dot(w) - a2).as_numer_denom()[0],
             sp.together(w.dot(w) - base.dot(base) - g ** 2 * den).as_numer_denom()[0]]
    add("sp2", "subproblem 2: w = alpha k1 + beta k2 + g (k1 x k2), alpha = (a1 - c a2)/(1 - c^2), beta = "
        "(a2 - c a1)/(1 - c^2), c = k1.k2, has k1.w = a1, k2.w = a2, |w|^2 = |alpha k1 + beta k2|^2 + g^2 (1 - c^2)",
        exprs, [k1, k2], cs=False)
    r, phi, wv = sp.symbols("r phi w", real=True)
    ok = all(sp.simplify(r * sp.cos(phi) * sp.cos(phi + sg * wv) + r * sp.sin(phi) * sp.sin(phi + sg * wv)
                         - r * sp.cos(wv)) == 0 for sg in (1, -1))
    out.append(("trig", "A cos t + B sin t = C: with A = r cos phi, B = r sin phi, t = phi +- acos(C / r) gives "
                "r cos(acos(C / r)) = C", Check("symbolic", "t = atan2(B, A) +- acos(C / r) solves A cos t + B sin t = "
                                                "C", ok)))
    return tuple(out)
