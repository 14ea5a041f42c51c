"""The one timing loop every benchmark row uses (so rows measured side by side are measured alike)."""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence


def per_call(fn: Callable, rows: Sequence, repeats: int = 5, warmup: int | None = None) -> float:
    """Best-of-`repeats` seconds per call of fn(row) over rows, after a warm-up pass."""
    for row in rows[: warmup if warmup is not None else max(1, min(len(rows) // 10, 50))]:
        fn(row)
    best = math.inf
    for _ in range(repeats):
        t0 = time.perf_counter()
        for row in rows:
            fn(row)
        best = min(best, time.perf_counter() - t0)
    return best / len(rows)
