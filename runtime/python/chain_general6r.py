"""The general 6R's stage (no decomposition: every joint by elimination, runtime/python/general6r.py), registered
in chain_stages._OP_STAGES, which _solve runs by the op's kind.

A wristkin runtime source: every user robot's generated module inlines it from the marker line on
(derive/runtime_files.py), after the robot's constants; above the marker, what it reads from them and from the
other sources, so that it is linted and tested as it is (tests/test_general6r.py)."""

from __future__ import annotations

import numpy as np
from chain_rigid import _to_matrix
from chain_stages import _OP_STAGES
from general6r import g6_frames_of, g6_solve


# wristkin: inlined from here
def _general6r_stage(ch, g, prev, op, x, y, q, count, go_on, family, params=()):
    """Every candidate of the elimination for the product of exponentials g (the home frame removed): the loop read
    from joint op[1], backwards when op[2], op[3] the hidden angle. Each goes on to the verification."""
    _, shift, reverse, hidden = op
    for cand in g6_solve(g6_frames_of(ch.axes, ch.points), np.eye(4), _to_matrix(g), shift, reverse, hidden):
        q[:6] = cand
        go_on(0)


_OP_STAGES["general6r"] = _general6r_stage
