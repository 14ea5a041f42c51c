"""An S-R-S arm's arm_angle stage (the shoulder's three joints and the elbow for the wrist centre's target and the
arm angle psi, the design's; arm_angle.py, inlined before it), or its held_elbow stage (the elbow held: the shoulder
at previous's arm angle), on the axes, centres and points its derived kernel gives. The sets are computed once per
prefix of the set index above the stage's bits and kept in the call's scratch `ws`; set k takes set (k >> shift) & 3
(two elbows x two shoulders; the held elbow's (k >> shift) & 1). The wrist's stage follows; the FK check verifies
each set. And the module's arm_angle(): the arm angle of joint values, read on the points its derived reader kernel
(_k_arm_angle_parts) places. The C twin: runtime/c/serial/sr_arm_angle.c.

A wristkin runtime source: a serial arm's generated module with an arm_angle stage inlines it from the marker line on
(derive/runtime_files.py), after its constants, derived kernels, stage functions and the sources before it; above the
marker, what it reads from them (serial_stand_in.py: the PUMA-560 stands in for the names), so that it is linted and
tested as it is (tests/test_arm_angle.py)."""

from __future__ import annotations

from arm_angle import AA_BANDS, _aa_angle_of, _arm_angle_core
from geom3 import _g3_axpy, _g3_norm
from serial_input import _design, _joints
from serial_stages import _ws_take
from serial_stand_in import DEGENERATE_EPS, SCALE, _k_arm_angle_parts

# wristkin: inlined from here
AA_TOLS = (SCALE, DEGENERATE_EPS, *AA_BANDS)  # the core's bands (arm_angle.py), on the robot's size


def _arm_angle_stage(kernel, parent, idx, joints, q, c, s, pose, dp, prev, ws):
    """Set k's set (ok, flags): `kernel` the stage's (h_a, h_b, h_c, s, h_e, p_e, x, y, psi), `parent` the set
    index's prefix above the stage's bits (the sets are recomputed when it changes), `idx` the set."""
    def sets():
        out = kernel(pose, q, c, s, dp)
        parts = [tuple(out[3 * i:3 * i + 3]) for i in range(8)]
        return _arm_angle_core(*parts, out[24], None if prev is None else prev[joints[0]], AA_TOLS)
    cand = _ws_take(ws, parent, sets, idx, joints, q, c, s)
    return (False, 0) if cand is None else (True, cand[1])


def _held_elbow_stage(kernel, parent, idx, joints, q, c, s, pose, dp, prev, ws):
    """Set k's set (ok, flags) of an S-R-S arm with its elbow held (a self-motion): `kernel` the stage's (h_a, h_b,
    h_c, s, h_e, p_e, x, y), x where the held elbow puts the wrist centre; the core with the elbow held at 0 about h_e
    (x has its turn): no set unless |y - s| = |x - s| within its tangent band, else the shoulder's sets at previous's
    arm angle (else 0), flagged indeterminate. `parent`, `idx` as _arm_angle_stage's."""
    def sets():
        out = kernel(pose, q, c, s, dp)
        parts = [tuple(out[3 * i:3 * i + 3]) for i in range(8)]
        psi = 0.0 if prev is None else _arm_angle_at(prev, dp)
        out = [(v[:3], f) for v, f in _arm_angle_core(*parts, psi, None if prev is None else prev[joints[0]], AA_TOLS,
                                                      held=0.0)]
        if not out:
            reach, target = (_g3_norm(_g3_axpy(parts[i], -1.0, parts[3])) for i in (6, 7))
            ws["why"] = (f"the wrist centre is {target:.9g} m from the shoulder centre, {target - reach:+.3g} m off "
                         f"the {reach:.9g} m the held elbow keeps (the other joints a self-motion: only poses at that "
                         "reach)")
        return out
    cand = _ws_take(ws, parent, sets, idx, joints, q, c, s)
    return (False, 0) if cand is None else (True, cand[1])


def _arm_angle_at(q, dp) -> float:
    """The arm angle of joint values q under the design's parameters dp, read on the points the reader kernel places."""
    out = _k_arm_angle_parts(list(q), dp)
    h1, s, e, w, axis = (tuple(out[3 * i:3 * i + 3]) for i in range(5))
    return _aa_angle_of(h1, s, e, w, axis, AA_TOLS)


def arm_angle(joints, design=None) -> float:
    """The arm angle of joint values: where they put the elbow on its circle about the shoulder-wrist line (0 in the
    plane of the first axis and that line, on the side the axis points to; positive about the line from the shoulder
    to the wrist). ik(fk_matrix(q), [arm_angle(q)]) returns q among its sets; with the elbow held, ik_near(pose,
    design, previous) returns the family's member at previous's arm angle."""
    return _arm_angle_at(_joints(joints), _design(design).params)
