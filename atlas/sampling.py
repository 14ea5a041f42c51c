"""The seeded workspace sample: unit-cube points in fixed blocks of BLOCK samples, the same for every design
(common random numbers: differences between designs are not sampling noise), each block from its own
SeedSequence((seed, stream, block)), so a block's numbers never depend on how blocks are grouped into chunks or
which worker draws them. A mechanism maps the unit cube into its joint or pose space (mechanisms.py)."""

from __future__ import annotations

import math

import numpy as np

BLOCK = 1024  # samples per block: the unit of evaluation (every numpy call sees one whole block)
POSE_STREAM, JOINT_STREAM = 0, 1


def grid_side(samples: int, dim: int) -> int:
    """Points per axis of a grid of about `samples` points in `dim` dimensions."""
    return max(1, round(samples ** (1.0 / dim)))


def sample_count(samples: int, dim: int, grid: bool) -> int:
    return grid_side(samples, dim) ** dim if grid else samples


def blocks(samples: int, dim: int, grid: bool) -> int:
    return math.ceil(sample_count(samples, dim, grid) / BLOCK)


def unit_block(seed: int, stream: int, block: int, samples: int, dim: int, grid: bool) -> np.ndarray:
    """(n, dim) points in [0, 1) of block `block` (n = BLOCK, fewer in the last block).

    Random: uniform, seeded per (seed, stream, block). Grid: cell centres (k + 1/2) / side of a regular lattice,
    first coordinate slowest."""
    total = sample_count(samples, dim, grid)
    lo, hi = block * BLOCK, min(total, (block + 1) * BLOCK)
    if hi <= lo:
        return np.empty((0, dim))
    if grid:
        side = grid_side(samples, dim)
        idx = np.arange(lo, hi)
        digits = [(idx // side ** (dim - 1 - k)) % side for k in range(dim)]
        return (np.stack(digits, axis=1) + 0.5) / side
    rng = np.random.default_rng(np.random.SeedSequence([seed, stream, block]))
    full = rng.random((BLOCK, dim))  # always a whole block: the last block is a prefix of the same numbers
    return full[: hi - lo]
