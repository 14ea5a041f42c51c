"""Exact, order-independent reductions: every partial result is an integer count, an integer fixed-point sum, a
minimum or a maximum, so merging chunks in any grouping or order gives the same bits (a float sum would not:
its rounding depends on the order). Values in [0, 1] are summed as round(v * 2^32) in int64: resolution 2.3e-10,
exact up to 2^31 values per design."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

FIXED = float(2**32)  # fixed-point scale of summed values in [0, 1]
SUM, MIN, MAX = "sum", "min", "max"


@dataclass(frozen=True)
class Partial:
    name: str
    op: str  # SUM (int64), MIN / MAX (float64)
    shape: tuple[int, ...] = ()  # per design

    @property
    def dtype(self):
        return np.int64 if self.op == SUM else np.float64

    @property
    def identity(self):
        return {SUM: 0, MIN: np.inf, MAX: -np.inf}[self.op]

    def empty(self, n_designs: int) -> np.ndarray:
        return np.full((n_designs, *self.shape), self.identity, dtype=self.dtype)


def fixed_sum(values: np.ndarray) -> int:
    """Sum of values in [0, 1] as an exact int64 fixed-point number."""
    return int(np.rint(np.asarray(values, dtype=float) * FIXED).astype(np.int64).sum())


def merge(spec: Partial, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    if spec.op == SUM:
        return a + b
    return np.minimum(a, b) if spec.op == MIN else np.maximum(a, b)


def reduce_axis(spec: Partial, stacked: np.ndarray, axis: int) -> np.ndarray:
    if spec.op == SUM:
        return stacked.sum(axis=axis, dtype=np.int64)
    return stacked.min(axis=axis) if spec.op == MIN else stacked.max(axis=axis)
