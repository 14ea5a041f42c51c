"""Three revolute axes in general position: the interpreted plan's spatial3 op, on spatial3.py (inlined before it).

A wristkin runtime source: every user robot's generated module inlines it from the marker line on
(derive/runtime_files.py), after the robot's constants; above the marker, what it reads from them and from the
other sources (chain_stand_in.py: a stand-in robot), so that it is linted and tested as it is
(tests/test_chain_runtime.py)."""

from __future__ import annotations

from chain_stages import _OP_STAGES
from chain_stand_in import DEGENERATE_EPS, ON_AXIS_TOL, SCALE
from spatial3 import _spatial3_lines

# wristkin: inlined from here


def _spatial3(ch, ja, jb, jc, x, y):
    """(q_a, q_b, q_c, flags) with e_a e_b e_c x = y for three revolute axes in general position (spatial3.py)."""
    js = (ja, jb, jc)
    return [(*q, f) for q, f in _spatial3_lines([ch.axes[j] for j in js], [ch.points[j] for j in js], x, y, SCALE,
                                                DEGENERATE_EPS, ON_AXIS_TOL)]


def _spatial3_stage(ch, g, prev, op, x, y, q, count, go_on, family, params=()):
    """The op ("spatial3", a, b, c): every real root of the polynomial."""
    _, ja, jb, jc = op
    for qa, qb, qc, f in _spatial3(ch, ja, jb, jc, x, y):
        q[ja], q[jb], q[jc] = qa, qb, qc
        go_on(f)


_OP_STAGES["spatial3"] = _spatial3_stage
