"""Printers for the generated targets, fixing what SymPy's defaults get wrong for us.

C: integer powers become products (pow(x, 2) is slow and noisy), M_PI is never
emitted (undeclared under -std=c99), floats carry 17 significant digits.
Python: math functions for scalar code, numpy (as `np`) for vectorised code.
"""

from __future__ import annotations

import sympy as sp
from sympy.printing.c import C99CodePrinter
from sympy.printing.numpy import NumPyPrinter
from sympy.printing.pycode import PythonCodePrinter


def _int_power(printer, expr) -> str | None:
    b, e = expr.as_base_exp()
    if e.is_Integer and 1 < abs(int(e)) <= 4:
        base = printer.parenthesize(b, sp.printing.precedence.PRECEDENCE["Mul"] + 1)
        # Parenthesised: a power binds tighter than * and /, so `2/x**2` must not print as `2/x*x`.
        prod = "(" + "*".join([base] * abs(int(e))) + ")"
        return prod if e > 0 else f"1.0/{prod}"
    if e == -1:
        return f"1.0/{printer.parenthesize(b, sp.printing.precedence.PRECEDENCE['Mul'] + 1)}"
    return None


class CPrinter(C99CodePrinter):
    def __init__(self):
        super().__init__()

    def _print_Pow(self, expr):
        return _int_power(self, expr) or super()._print_Pow(expr)

    def _print_Float(self, expr):
        return repr(float(expr)) if "e" not in repr(float(expr)) else f"{float(expr):.17g}"

    def _print_Pi(self, expr):
        return "3.14159265358979323846"


class PyMathPrinter(PythonCodePrinter):
    def _print_Pow(self, expr, rational=False):
        return _int_power(self, expr) or super()._print_Pow(expr, rational=rational)

    def _print_Float(self, expr):
        return repr(float(expr))


class NumpyPrinter(NumPyPrinter):
    def __init__(self):
        super().__init__({"fully_qualified_modules": True})

    def _print_Pow(self, expr, rational=False):
        return _int_power(self, expr) or super()._print_Pow(expr, rational=rational)

    def _print_Float(self, expr):
        return repr(float(expr))

    def doprint(self, expr, assign_to=None):
        return super().doprint(expr, assign_to).replace("numpy.", "np.")
