"""Printer regression: integer powers are printed as products and must keep their binding inside quotients."""

from __future__ import annotations

import math

import sympy as sp

from derive.lower import Kernel, lower


def test_integer_powers_in_denominators_keep_their_grouping():
    x, y = sp.symbols("x y", real=True)
    exprs = (2 / x**2, y / (x + y) ** 3, x**2 / y**4, 1 / (x * y) ** 2)
    k = Kernel("k", "powers", (("v", (x, y)),), tuple((f"o{i}", e) for i, e in enumerate(exprs)))
    for target, env in (("python", {"math": math}), ("c", {})):
        low = lower(k, target)
        scope = dict(env, x=1.7, y=0.3)
        for name, code in low.temps:
            scope[name] = eval(code, scope)  # the C expressions here are valid Python too
        for (_, code), e in zip(low.outputs, exprs, strict=True):
            assert math.isclose(eval(code, scope), float(e.subs({x: 1.7, y: 0.3})), rel_tol=1e-14), (target, code)
