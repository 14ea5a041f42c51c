"""A spatial 3R's stage: three revolute axes in general position placing a point (spatial3.py, inlined before it),
on the lines, the point and its target its derived kernel gives. The candidates are computed once per prefix of the
set index above the stage's bits and kept in the call's scratch `ws`; set k takes candidate (k >> shift) & 3. A
candidate found twice (a double root's two isolations) is kept once; at most four are (Pieper's bound: more only
where the pose is on a family, whose first four stand for it). A point on the first axis leaves that joint
undetermined: previous's value, else 0 (flagged indeterminate). The FK check after the stages verifies each set.
The C twin: runtime/c/serial/sr_spatial3.c.

A wristkin runtime source: a serial arm's generated module with a spatial3 stage inlines it from the marker line on
(derive/runtime_files.py), after its constants, derived kernels, stage functions and the sources before it; above the
marker, what it reads from them (serial_stand_in.py: the PUMA-560 stands in for the names), so that it is linted and
tested as it is (tests/test_derived_robot.py)."""

from __future__ import annotations

import math

import _runtime
from serial_stages import _ws_take
from serial_stand_in import DEGENERATE_EPS, FLAG_INDETERMINATE, ON_AXIS_TOL
from spatial3 import _spatial3_lines

# wristkin: inlined from here
S3_KEEP = 4  # Pieper's bound on a 3R's positions


def _s3_candidates(out):
    """The candidates [(q_a, q_b, q_c), flags] of the stage's outputs (3 axes, 3 points, x, y): distinct, at most
    S3_KEEP."""
    h = [tuple(out[3 * i:3 * i + 3]) for i in range(3)]
    r = [tuple(out[9 + 3 * i:12 + 3 * i]) for i in range(3)]
    scale = max(1.0, *(abs(v) for v in out[9:24]))  # the points', the point's and its target's largest coordinate
    kept = []
    for q, f in _spatial3_lines(h, r, tuple(out[18:21]), tuple(out[21:24]), scale, DEGENERATE_EPS,
                                ON_AXIS_TOL):
        if len(kept) == S3_KEEP:
            break
        if any(_runtime.same_set(q, other) for other, _ in kept):  # a solution's identity, as the general 6R's
            continue
        kept.append((q, f))
    return kept


def _spatial3_stage(kernel, parent, idx, joints, q, c, s, pose, dp, prev, ws):
    """Set k's candidate (ok, flags): `kernel` the stage's (axes, points, x, y), `parent` the set index's prefix above
    the stage's bits (the candidates are recomputed when it changes), `idx` the candidate."""
    cand = _ws_take(ws, parent, lambda: _s3_candidates(kernel(pose, q, c, s, dp)), idx, joints, q, c, s)
    if cand is None:
        return False, 0
    if cand[1] & FLAG_INDETERMINATE and prev is not None:  # the first joint's family: previous's member
        v = prev[joints[0]]
        q[joints[0]], c[joints[0]], s[joints[0]] = v, math.cos(v), math.sin(v)
    return True, cand[1]
