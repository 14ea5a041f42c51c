"""A serial arm's inverse kinematics: the stage tree run over every branch word, each candidate verified by FK
(polished where a tangent root left it sqrt(eps) off), families placed near `previous`, indistinct pairs
merged.

A wristkin runtime source: every serial arm's generated module (the catalogue's DH chains, the finite-screw chains'
serial view) inlines it from the marker line on (derive/runtime_files.py), after its constants, derived kernels
and stage functions; above the marker, what it reads from them and from the other sources (serial_stand_in.py:
the PUMA-560), so that it is linted and tested as it is (tests/test_serial_runtime.py)."""

from __future__ import annotations

import math

import _runtime
import numpy as np
from serial_frames import _as4, _rigid_inverse, _unframe
from serial_input import (
    _HAS_PRISMATIC,
    _JOINT_SHAPE,
    _POSE_SHAPES,
    _REVOLUTE,
    _design,
    _joints,
    _pose,
)
from serial_stages import _design_size
from serial_stand_in import (
    _C_IK,
    _C_IK_BATCH,
    _FAMILY_SCAN,
    _FK_IDEAL,
    _FOLD_MASKS,
    _IK_RESULT,
    _IMAGE_CHECK,
    _SHOULDER_FAMILY,
    _STAGE_SETS,
    _STAGES,
    _UNREACHABLE_NOTE,
    _WRIST_BEND,
    _WRIST_JOINTS,
    _WRIST_STAGE,
    CALIBRATED,
    DOUBLE_ROOT_POLISH_TOL,
    FLAG_DOUBLE_ROOT,
    FLAG_INDETERMINATE,
    FLAG_PROJECTED,
    FLAG_SINGULAR_INVERSE,
    IK_VERIFY_TOL,
    IMAGE_CHECKS,
    JOINT_KINDS,
    LENGTH_MAX,
    MAX_IK,
    N_JOINTS,
    SINGULAR_EPS,
    STATUS_INDETERMINATE,
    STATUS_OK,
    STATUS_UNREACHABLE,
    BatchSolutions,
    InvalidDesign,
    InvalidInput,
    Solutions,
    _array,
    _k_fk,
    _k_fk_cs,
    _projected_note,
    _stack,
)
from serial_verify import _along_null, _family_scan, _indistinct, _nearest_member, _polish, _refit

# wristkin: inlined from here
# a calibrated arm's set whose wrist bend has |sin q5| at most this, polished on the true chain, is searched along the
# near-null direction as a set the stages flag singular is: the polish stops at DOUBLE_ROOT_POLISH_TOL, which leaves
# it up to that over sigma_min from the solution, sigma_min ~ |sin q5|; at 1e-4 that is 1e-8 rad, below the
# conditioning allowance's 1e-6 with a margin for the wrist's geometry. The stages' flag is read on the ideal
# geometry, whose q5 differs from the true chain's by the deviation's share (a true q5 of 1e-12 not flagged: q4
# 1.2 rad off)
CALIBRATED_WRIST_SEARCH = 1e-4
# a calibrated arm whose first stage reads q1 from the wrist centre's (x, y) (_SHOULDER_FAMILY): where that point
# lies within this (times the design's size) of axis 1, as read on the ideal geometry, the shoulder's self-motion is
# near (q1 and the wrist turning together about a centre on the axis), and each family is scanned along q1: sigma_min
# of the true chain is ~ that distance, so a set polished to DOUBLE_ROOT_POLISH_TOL lies up to 1e-8 rad off at 1e-4,
# as CALIBRATED_WRIST_SEARCH's; the bench's shoulder 1e-8 from singular left its generating pair 0.08 rad from the
# stages' set, a bump of 1e-10 between them along q1
CALIBRATED_SHOULDER_SEARCH = 1e-4


def _shoulder_near(p, dp):
    """Whether the pose puts the ideal geometry's wrist centre within CALIBRATED_SHOULDER_SEARCH of axis 1 (the first
    stage's A, B: the centre's (y, x) in the base frame; it reads no joints)."""
    if _SHOULDER_FAMILY is None:
        return False
    zeros = [0.0] * N_JOINTS
    a, b = _SHOULDER_FAMILY[1](p, zeros, [1.0] * N_JOINTS, zeros, dp)[:2]
    return math.hypot(a, b) <= CALIBRATED_SHOULDER_SEARCH * _design_size(dp)


def _scan_families(values, valid, flags, aux, p, dp, rounding, projected):
    """A calibrated arm's families near a self-motion of its ideal geometry (the wrist's at theta5 = 0 or pi, the
    shoulder's with the wrist centre on axis 1): the calibration breaks each into up to four solutions, of which the
    ideal stages' two sets (a wrist's mirror pair, sets 2P and 2P + 1) reach at most two. Where one of them is within
    CALIBRATED_WRIST_SEARCH of the wrist's singularity, the family is scanned from it along q4, and where the pose is
    within CALIBRATED_SHOULDER_SEARCH of the shoulder's (_shoulder_near), from the first valid one along q1
    (_family_scan); each solution that is none of the sets kept (_indistinct: one solution where the pose cannot tell
    them apart; the merge ran before, so a pair searched onto one solution left a slot) takes the family's next free
    slot of 2P, 2P + 1, _STAGE_SETS + 2P and + 1 (MAX_IK is twice the stages' sets), flagged singular as the stages
    flag theirs (and `projected`); more than the family's four: the first ones."""
    floor = _runtime.fk_rounding(max(abs(p[3]), abs(p[7]), abs(p[11])))
    shoulder = _shoulder_near(p, dp)
    for fam in range(_STAGE_SETS // 2):
        own = (2 * fam, 2 * fam + 1)
        starts = [(k, _WRIST_JOINTS[0]) for k in own
                  if valid[k] and abs(math.sin(values[k][_WRIST_BEND])) <= CALIBRATED_WRIST_SEARCH][:1]
        if shoulder:
            starts += [(k, _SHOULDER_FAMILY[0]) for k in own if valid[k]][:1]
        slots = [k for k in (*own, _STAGE_SETS + 2 * fam, _STAGE_SETS + 2 * fam + 1) if not valid[k]]
        for start, hold in starts:
            for x, err in _family_scan(list(values[start]), p, dp, rounding, hold) if slots else ():
                if any(valid[k] and _indistinct(x, err, values[k], float(aux[k][0]), p, dp, floor)
                       for k in range(MAX_IK)):
                    continue
                k = slots.pop(0)
                values[k], aux[k][0], valid[k] = x, err, True
                flags[k] = (FLAG_SINGULAR_INVERSE if abs(math.sin(x[_WRIST_BEND])) <= SINGULAR_EPS else 0) | projected
                if not slots:
                    break


def ik(pose, design=None, previous=None) -> Solutions:
    """Every IK solution (at most MAX_IK), each verified by FK against the pose. A one-parameter family (the wrist
    at |sin theta5| <= WRIST_EXACT_TOL, or a stage whose equation vanishes) is returned once: its member nearest
    `previous` when given (previous's q4, or previous's value of that stage's joint), else the one at 0.
    `previous` changes nothing else: not the regular sets, not the status."""
    d = _design(design)
    if d.refused:
        raise InvalidDesign(d.refused)
    if d.native is not None:
        prev = None if previous is None else _runtime.c_floats(previous, _JOINT_SHAPE)
        if prev is not None or previous is None:
            sol = _C_IK(pose, d.native, prev, _IK_RESULT)
            if sol.__class__ is not Solutions:  # a conversion, or words
                sol = _runtime.c_explained(sol, _C_IK, pose, _POSE_SHAPES, (d.native, prev, _IK_RESULT),
                                           _ik_numpy, (pose, d, previous))
            if sol is not None:
                return sol
    return _ik_numpy(pose, d, previous)


def _ik_numpy(pose, d, previous):
    """ik on the numpy path (also what words the reason of an answer from C that needs one)."""
    p, dev = _pose(pose)
    if d.frames is not None:  # the design's base and tool frames: the pose the kernels answer
        p = _unframe(p, d.frames)
    prev = None if previous is None else _joints(previous, "previous")  # places a family's representative
    values = np.full((MAX_IK, N_JOINTS), np.nan)
    aux = np.full((MAX_IK, 1), np.nan)
    valid = np.zeros(MAX_IK, dtype=bool)
    flags = np.zeros(MAX_IK, dtype=np.int64)
    if _IMAGE_CHECK is not None:
        for e, what in zip(_IMAGE_CHECK(p, d.params), IMAGE_CHECKS, strict=True):
            if not abs(e) <= IK_VERIFY_TOL:  # a < 6-DOF chain reaches only its image
                return Solutions(values, valid, flags, aux, STATUS_UNREACHABLE,
                                 f"pose not reachable: outside the chain's image, {what} = {e:.3g} "
                                 f"(tolerance IK_VERIFY_TOL = {IK_VERIFY_TOL:g})")
    q, c, s = [0.0] * N_JOINTS, [1.0] * N_JOINTS, [0.0] * N_JOINTS
    amp = [1.0] * N_JOINTS  # each angle stage's amplification of the input's rounding (serial_stages)
    key = [-1] * len(_STAGES)
    state = [(False, 0)] * len(_STAGES)
    ws = {}  # the multi-candidate stages' scratch (the general 6R's candidates per prefix)
    unreachable = beyond = 0
    size = max(abs(p[3]), abs(p[7]), abs(p[11]))
    rounding = _runtime.fk_rounding(size)  # the FK's own rounding of this pose (the merge's floor)
    polish_double = DOUBLE_ROOT_POLISH_TOL * max(1.0, size)
    carried = [False] * MAX_IK  # sets the checks moved beyond CARRIED_MOVE (drop_carried)
    for k in range(_STAGE_SETS):  # the stages' sets (a calibrated arm's wrist family scan adds its own after them)
        f, alive = 0, True
        for i, (solve, shift) in enumerate(_STAGES):
            if k >> shift != key[i]:  # a stage is recomputed only when its branch prefix changes
                key[i] = k >> shift
                state[i] = solve(k, p, q, c, s, d.params, prev, amp, ws)
            alive, fl = state[i]
            f |= fl
            if not alive:
                break
        if not alive:
            unreachable += 1
            continue
        err = max(abs(x - y) for x, y in zip(_k_fk_cs(q, c, s, d.params), p, strict=True))
        qk, placed, searched = q, False, False
        if err > IK_VERIFY_TOL or ((f & FLAG_DOUBLE_ROOT or CALIBRATED) and err > polish_double):
            # a tangent root leaves a sqrt(eps) error downstream, and a double root's centre its stage's noise (a
            # UR's folded elbow behind a wrist 1e-5 from singular: the pose within 3e-12): polish a copy, a double
            # root's to rounding (DOUBLE_ROOT_POLISH_TOL says when); a calibrated robot's (the stages solve its ideal
            # geometry) every set to DOUBLE_ROOT_POLISH_TOL
            qk, err = _polish(qk, p, d.params, target=rounding if f & FLAG_DOUBLE_ROOT else (
                polish_double if CALIBRATED else IK_VERIFY_TOL))
        if not err <= IK_VERIFY_TOL and CALIBRATED:
            # the ideal stages' answer outside Gauss-Newton's basin on the true chain (near a singularity the ideal
            # geometry's 1e-7 moves it by 1e-7 / sigma_min): solved again for the compensated pose
            qc, err_c = _compensated(k, p, qk, d.params, prev, polish_double)
            if err_c < err:  # kept only where it helps (as C's sr_compensated)
                qk, err = qc, err_c
            if not err <= IK_VERIFY_TOL:
                # still off: the solution lies along the near-null direction, beyond Gauss-Newton's steps (a shoulder
                # 1e-10 from singular: 0 sets before). Searched there to the FK's rounding (the conditioning
                # allowance's residual: at sigma_min 1e-10 a residual of 1e-12 leaves the set 1e-2 off)
                qn, err_n = _along_null(qk, p, d.params, rounding)
                searched = True
                if err_n < err:
                    qk, err = qn, err_n
        if CALIBRATED and not searched and rounding < err <= IK_VERIFY_TOL and (
                err > polish_double or f & FLAG_SINGULAR_INVERSE or (
                _WRIST_BEND >= 0 and abs(math.sin(qk[_WRIST_BEND])) <= CALIBRATED_WRIST_SEARCH)):
            # near a singularity of the ideal geometry a set that passes the check may still lie residual / sigma_min
            # from the true chain's solution, along the near-null direction (a wrist 1e-12 from singular, sigma_min
            # 1e-13: a residual of 1.2e-13 left q4 0.55 rad off, outside the conditioning allowance; an elbow 1e-8
            # from stretched: the polish stalled at 4.9e-10, short of its target, on both sides of the solution,
            # 5e-3 from it). The calibration breaks the ideal wrist's self-motion, so the pose places the set:
            # searched there to the FK's rounding. So is a set the compensated re-solve brought within the check (an
            # elbow 1e-6 from folded: 6e-11 on the pose, 6.3e-4 rad from the solution, never searched before)
            qn, err_n = _along_null(qk, p, d.params, rounding)
            if err_n < err:
                qk, err = qn, err_n
            placed = err <= rounding  # the pose's own set: `previous` does not move it (below)
        if not err <= IK_VERIFY_TOL:
            continue
        carried[k] = qk is not q and any(  # only a polished or searched set (a new list) can be carried
            abs(math.remainder(a - b, 2.0 * math.pi) if rev else a - b) > _runtime.CARRIED_MOVE
            for a, b, rev in zip(qk, q, _REVOLUTE, strict=True))
        if carried[k] and err > rounding:  # to rounding: drop_carried then knows the solution it reached
            qk, err = _polish(qk, p, d.params, target=rounding)
        if _HAS_PRISMATIC and not all(abs(x) <= LENGTH_MAX
                                      for x, kind in zip(qk, JOINT_KINDS, strict=True) if kind == "P"):
            beyond += 1  # a set fk would reject: IK returns only what FK accepts
            continue
        if _WRIST_STAGE >= 0 and prev is not None and not placed and state[_WRIST_STAGE][1] & (
                FLAG_INDETERMINATE | _runtime.FLAG_READ_MEMBER) == FLAG_INDETERMINATE:
            # the wrist's own family (|sin theta5| <= WRIST_FAMILY_TOL), not another stage's: above that threshold
            # the pose places the wrist and `previous` must not move it (it moved theta4 by 3 rad at 1e-12)
            moved = _nearest_member(qk, prev, d.params)
            err_moved = max(abs(x - y) for x, y in zip(_k_fk(moved, d.params), p, strict=True))
            if err_moved <= IK_VERIFY_TOL:  # exact in theory; confirmed
                qk, err = moved, err_moved
        values[k], aux[k], valid[k], flags[k] = qk, err, True, (f & ~_runtime.FLAG_READ_MEMBER) | (
            FLAG_PROJECTED if dev else 0)
    # a set the polish carried to another branch's solution (a 5-joint arm's candidate that no orientation fits) is
    # that solution twice
    _runtime.drop_carried(values, valid, flags, aux, carried, _REVOLUTE)
    if _FOLD_MASKS:
        # a stage's pair that the pose cannot tell apart is one double root (the runtime says when); a calibrated
        # arm's every single-bit pair (its masks hold every bit of the set index), not only its stages' merge
        # candidates: the stages read the ideal geometry, the sets are polished or searched on the true chain
        _runtime.merge_indistinct(values, valid, flags, aux, _FOLD_MASKS, _REVOLUTE,
                                  lambda x, step, accept: _refit(x, p, d.params, step, accept), size,
                                  N_JOINTS >= 6 and not CALIBRATED)
    if _FAMILY_SCAN:  # after the merge: a mirror pair searched onto one solution leaves a slot for the scan
        _scan_families(values, valid, flags, aux, p, d.params, rounding, FLAG_PROJECTED if dev else 0)
    reasons = [f"{unreachable} of {MAX_IK} branch words have a stage with no real solution"] if unreachable else []
    if "why" in ws:  # a stage's own words for why it has no solution (the held elbow's reach)
        reasons.insert(0, ws["why"])
    if beyond:
        reasons.append(f"{beyond} set(s) need a prismatic joint beyond LENGTH_MAX = {LENGTH_MAX:g} m (fk rejects them)")
    note = _projected_note(dev)
    if valid.any():
        status = STATUS_INDETERMINATE if np.any(flags & FLAG_INDETERMINATE) else STATUS_OK
        return Solutions(values, valid, flags, aux, status, "; ".join([f"{int(valid.sum())} solution(s)"] +
                                                                      ([note] if note else [])))
    return Solutions(values, valid, flags, aux, STATUS_UNREACHABLE,
                     "pose not reachable: " + "; ".join((reasons or ["no branch passes the FK check"]) +
                                                        ([_UNREACHABLE_NOTE] if _UNREACHABLE_NOTE else []) +
                                                        ([note] if note else [])))


def _compensated(k, p, qk, dp, prev, target):
    """Set k solved again by the ideal stages for the pose the ideal chain must reach so that the true one reaches p,
    T_c = p true(q)^-1 ideal(q) at the failed candidate q, then polished on the true chain: (q, residual)."""
    c = [math.cos(v) if kind == "R" else 1.0 for v, kind in zip(qk, JOINT_KINDS, strict=True)]
    s = [math.sin(v) if kind == "R" else 0.0 for v, kind in zip(qk, JOINT_KINDS, strict=True)]
    ideal = _as4(_FK_IDEAL(qk, c, s, dp))
    true = _as4(_k_fk_cs(qk, c, s, dp))
    tc = tuple(float(x) for x in (_as4(p) @ _rigid_inverse(true) @ ideal)[:3].ravel())
    q, c, s, amp = [0.0] * N_JOINTS, [1.0] * N_JOINTS, [0.0] * N_JOINTS, [1.0] * N_JOINTS
    key, ws = [-1] * len(_STAGES), {}
    for word in (k - 1, k) if k & 1 else (k,):  # an odd set's wrist mirrors the even one's (its prefix first)
        for i, (solve, shift) in enumerate(_STAGES):
            if word >> shift != key[i]:
                key[i] = word >> shift
                if not solve(word, tc, q, c, s, dp, prev, amp, ws)[0]:
                    return qk, math.inf
    return _polish(q, p, dp, target=target)


def ik_batch(poses, design=None) -> BatchSolutions:
    """IK over a stack of poses: shape (N, 4, 4), (N, 3, 4), or (N, 12) / (N, 16) rows (what fk_batch returns)."""
    a = _array(poses, "poses")
    if not (a.ndim == 3 and a.shape[1:] in ((4, 4), (3, 4))) and not (a.ndim == 2 and a.shape[1] in (12, 16)):
        raise InvalidInput(f"poses: expected an (N, 4, 4), (N, 3, 4), (N, 12) or (N, 16) array, got shape {a.shape}")
    d = _design(design)
    if d.refused:
        raise InvalidDesign(d.refused)
    if d.native is not None:
        n, c = a.shape[0], np.ascontiguousarray(a)
        out = (np.empty((n, MAX_IK, N_JOINTS)), np.empty((n, MAX_IK), bool), np.empty((n, MAX_IK), np.int64),
               np.empty((n, MAX_IK, 1)), np.empty(n, np.int64))
        if _C_IK_BATCH(c, d.native, *out, c[0].size if n else 12) >= 0:
            return BatchSolutions(*out)
    return _stack([ik(x, d) for x in a], MAX_IK, N_JOINTS, 1)
