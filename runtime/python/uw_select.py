"""Which of the underactuated wrist's solution sets to use (the seed's rule).

A wristkin runtime source: the underactuated wrist's generated module inlines it from the marker line on
(derive/runtime_files.py), after its constants and derived kernels; above the marker, what it reads from them
and from the other sources (uw_stand_in.py: the catalogue's wrist), so that it is linted and tested as it is
(tests/test_uw_runtime.py)."""

from __future__ import annotations

import numpy as np
from uw_stand_in import _TWO_PI, FLAG_SINGULAR_DIRECT, FLAG_SINGULAR_INVERSE, Solutions, _vector, _wrap_all


# wristkin: inlined from here
# ---------------------------------------------------------------------------- selection
def select(solutions: Solutions, previous=None, lower=None, upper=None, weights=None) -> int:
    """Index of the solution to use, or -1 (the seed's rule: in range, continuous, away from singularity).

    Candidates: valid rows with every value in [lower, upper] (angles compared wrapped to lower + [0, 2 pi)).
    With `previous`, the nearest candidate by weighted wrapped distance wins (per-joint `weights`, default 1;
    a singular flag is information, not a reason to jump to a farther set); without it, the best conditioned
    non-singular candidate (largest min(cond_inverse, cond_direct)), else the best conditioned one.
    """
    vals = solutions.values
    n = vals.shape[1]
    lo = None if lower is None else np.asarray(_vector(lower, n, "lower"))
    hi = None if upper is None else np.asarray(_vector(upper, n, "upper"))
    prev = None if previous is None else np.asarray(_vector(previous, n, "previous"))
    wts = np.ones(n) if weights is None else np.asarray(_vector(weights, n, "weights"))
    cand = []
    for k in np.flatnonzero(solutions.valid):
        v = vals[k]
        if lo is not None and hi is not None:
            off = np.mod(v - lo, _TWO_PI)
            if np.any(off > hi - lo):
                continue
        cand.append(int(k))
    if not cand:
        return -1
    regular = [k for k in cand if not solutions.flags[k] & (FLAG_SINGULAR_INVERSE | FLAG_SINGULAR_DIRECT)]
    pool = cand if prev is not None else (regular or cand)
    naux = solutions.aux.shape[1]
    if prev is not None:
        prev = _wrap_all(prev)
        return min(pool, key=lambda k: (float(np.sum(wts * np.abs(_wrap_all(vals[k] - prev)))), k))
    return max(pool, key=lambda k: (float(min(solutions.aux[k, naux - 2], solutions.aux[k, naux - 1])), -k))
