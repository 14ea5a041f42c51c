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


def fastest_of_rounds(measure: Callable[[], list[dict]], keys: Sequence[str], rounds: int = 2) -> list[dict]:
    """The rows `measure()` returns, measured `rounds` times, each of `keys` the fastest round's (None stays None).

    On the 2-core VM the first pass of Python rows after a long C-loop subprocess has run up to 1.6x slower than a
    second pass in the same process (the batch rows, which loop in C, too: the process, not the code), so a row's
    number depended on what ran before it. Every row, wristkin's and the peers', gets the same rounds."""
    best = measure()
    for _ in range(rounds - 1):
        for row, again in zip(best, measure(), strict=True):
            for k in keys:
                if row.get(k) is not None and again.get(k) is not None:
                    row[k] = min(row[k], again[k])
    return best
