"""Subproblem 6's stage (an offset wrist: two joints from the parallel group's invariants; sp6.py, inlined before
it), on the direction, axes, points and constants its derived kernel gives. The candidates are computed once per
prefix of the set index above the stage's bits and kept in the call's scratch `ws`; set k takes candidate
(k >> shift) & 3, at most four (the quartic's real roots; the core returns none twice: a near pair 3e-11 apart is two
roots, which a 1e-9 sameness band merged, losing the generating set). The stage sets
amp[k] to how much its q_k amplifies the input's rounding (near the wrist singularity, g = |h_l x R_k^T n| small:
eps / g from the quartic and Newton on its equations, eps from the split); the next stage, q_l about its axis, adds
its own 1 / g. The FK check after the stages verifies each set. The C twin: runtime/c/serial/sr_sp6.c.

A wristkin runtime source: a serial arm's generated module with an sp6 stage inlines it from the marker line on
(derive/runtime_files.py), after its constants, derived kernels, stage functions and the sources before it; above the
marker, what it reads from them (serial_stand_in.py: the PUMA-560 stands in for the names), so that it is linted and
tested as it is (tests/test_derived_robot.py)."""

from __future__ import annotations

from geom3 import _g3_cross, _g3_norm, _g3_turn_dir
from serial_stages import _ws_take
from serial_stand_in import DEGENERATE_EPS
from sp6 import _sp6_core

# wristkin: inlined from here
SP6_KEEP = 4  # the quartic's real roots
# the core's bands: a polynomial stage's roots carry ~1e-12 (the degree-4 eliminant's rounding), and subproblem 4's
# tangent band is the stages' (TANGENT_TOL)
SP6_DOUBLE_ROOT_TOL = 1e-12
SP6_ON_AXIS_TOL = 1e-12
SP6_TANGENT_TOL = 1e-9
# the wrist's family: the pose's axis on n within the rounding of unit vectors (64 eps, the spherical wrist's
# WRIST_FAMILY_TOL); above it the split's two roots (a band of 1e-12 missed the generating joints of poses 1e-13 ..
# 1e-12 rad from the singularity: 129 of 200 random ones at 1e-13)
SP6_FAMILY_TOL = 1.4210854715202004e-14


def _sp6_candidates(out):
    """The candidates [(q_j, q_k), flags, amp_k] of the stage's outputs (n, h_j, p_j, h_k, p_k, d_j, g, h_l), at
    most SP6_KEEP."""
    nv, h0, p0, h4, p4 = (tuple(out[i:i + 3]) for i in range(0, 15, 3))
    d0, g, h5 = out[15], tuple(out[16:19]), tuple(out[19:22])
    scale = max(1.0, *(abs(v) for v in out[6:9]), *(abs(v) for v in out[12:16]))  # the points' and the constant's
    tols = (scale, DEGENERATE_EPS, SP6_DOUBLE_ROOT_TOL, SP6_TANGENT_TOL, SP6_ON_AXIS_TOL, SP6_FAMILY_TOL)
    kept = []
    for q0, q4, f, order in _sp6_core(nv, h0, p0, h4, p4, d0, 0.0, g, h5, tols):
        if len(kept) == SP6_KEEP:
            break
        # g = |h_l x rot(h_k, q_k)^T n|: q_k carries eps / g from the quartic (order 2), ~eps from the split
        gap = _g3_norm(_g3_cross(h5, _g3_turn_dir(h4, -q4, nv)))
        kept.append(((q0, q4), f, max(1.0, 1.0 / max(gap, 1e-300)) if order == 2 else 1.0))
    return kept


def _sp6_stage(kernel, parent, idx, joints, q, c, s, pose, dp, amp, ws):
    """Set k's candidate (ok, flags): `kernel` the stage's outputs, `parent` the set index's prefix above the
    stage's bits (the candidates are recomputed when it changes), `idx` the candidate."""
    cand = _ws_take(ws, parent, lambda: _sp6_candidates(kernel(pose, q, c, s, dp)), idx, joints, q, c, s)
    if cand is None:
        return False, 0
    amp[joints[0]], amp[joints[1]] = 1.0, cand[2]
    return True, cand[1]
