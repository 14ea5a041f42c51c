"""Measured numbers as generated files print them: the same bytes on every CPU and BLAS kernel.

A measured error (a residual, a round-trip error) changes in its last bits with the numeric kernels of the
machine (OpenBLAS's per-CPU kernels, numpy's AVX2/AVX-512 loops, FMA), and by more where it is amplified by
conditioning. Generated files must be byte-identical everywhere, so they state such a number as a decade
bound, and rounding-level values (below ROUNDING_FLOOR, about 450 ulps of 1) as one bucket. A quantity of
order one that is computed to full precision (a length, an angle, a miss distance) keeps three significant
digits, which no kernel changes.
"""

from __future__ import annotations

import math

ROUNDING_FLOOR = 1e-13  # rounding-level errors of order-one quantities vary by a few ulps per kernel
ORDER_ONE = 1e-4  # at or above this, a measured value keeps 3 significant digits


def error_bucket(x: float, floor: float = ROUNDING_FLOOR) -> str:
    """'0', '< 1e-13' (rounding level: below `floor`) or the decade bound '< 1e-k' of |x|; 'not finite' for
    NaN/inf."""
    if not math.isfinite(x):
        return "not finite"
    x = abs(float(x))
    if x == 0.0:
        return "0"
    if x < floor:
        return f"< {floor:.0e}"
    return f"< 1e{math.floor(math.log10(x)) + 1}"


def measured(x: float, unit: str = "") -> str:
    """A measured value: 3 significant digits where it is of order one, else its error bucket."""
    if math.isfinite(x) and abs(x) >= ORDER_ONE:
        text = f"{x:.3g}"
    else:
        text = error_bucket(x)
    return f"{text} {unit}".rstrip()


def against(x: float, tol: float) -> str:
    """An error with its tolerance: e.g. '< 1e-13, tolerance 1e-09'."""
    return f"{error_bucket(x)}, tolerance {tol:.0e}"
