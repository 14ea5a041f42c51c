"""A serial arm's checks of an IK set on its FK: the pose error, the damped Gauss-Newton polish and refit, a
calibrated arm's search along its near-singular direction, and the member of the wrist's singular family nearest a
previous set.

A wristkin runtime source: every serial arm's generated module (the catalogue's DH chains, the finite-screw chains'
serial view) inlines it from the marker line on (derive/runtime_files.py), after its constants, derived kernels
and stage functions; above the marker, what it reads from them and from the other sources (serial_stand_in.py:
the PUMA-560), so that it is linted and tested as it is (tests/test_serial_runtime.py)."""

from __future__ import annotations

import math

import _runtime
import numpy as np
from serial_input import _REVOLUTE
from serial_stand_in import (
    _HELD,
    _WRIST_JOINTS,
    IK_VERIFY_TOL,
    JOINT_KINDS,
    N_JOINTS,
    POLISH_STEPS,
    _k_fk,
    _k_jacobian,
    _wrap,
)


# wristkin: inlined from here
def _pose_error(q, pose, dp):
    """(max |FK(q) - pose| over [R | p], 6-vector twist error: position, then 1/2 sum of column crosses)."""
    t = _k_fk(q, dp)
    err = max(abs(x - y) for x, y in zip(t, pose, strict=True))
    r, rt = np.array(t).reshape(3, 4), np.array(pose).reshape(3, 4)
    w = 0.5 * sum(np.cross(r[:, i], rt[:, i]) for i in range(3))
    return err, np.concatenate([rt[:, 3] - r[:, 3], w])


def _gn_step(q, e, err, pose, dp, max_step=math.inf, hold=-1):
    """One damped Gauss-Newton step from q (pose error e, residual err), no longer than max_step in any joint, joint
    `hold` fixed unless -1: (q, e, err) moved, or as given when the step is refused (singular, too long) or does not
    help."""
    j = np.array(_k_jacobian(q, dp), dtype=float).reshape(6, N_JOINTS)
    for fixed in (_HELD, hold):  # the held joint keeps its value, and `hold` (the damping then leaves their steps 0)
        if fixed >= 0:
            j[:, fixed] = 0.0
    # a regular square J: its LU (the normal equations square its conditioning); near singular (a pivot at or below
    # 1e-6 of its largest entry, where the damping 1e-12 on J^T J starts to matter) or a zeroed column: damped
    step = _runtime.solve_square(j, e, 1e-6) if N_JOINTS == 6 else None
    if step is None:
        try:
            step = np.linalg.solve(j.T @ j + 1e-12 * np.eye(N_JOINTS), j.T @ e)
        except np.linalg.LinAlgError:
            return q, e, err
    if not np.all(np.abs(step) <= max_step):
        return q, e, err
    trial = [x + dx for x, dx in zip(q, step, strict=True)]
    err2, e2 = _pose_error(trial, pose, dp)
    return (trial, e2, err2) if err2 < err else (q, e, err)


def _polish(q, pose, dp, iters=POLISH_STEPS, target=IK_VERIFY_TOL):
    """Damped Gauss-Newton on the pose error until it is at most `target`: removes the sqrt(eps) error a tangent
    root passes downstream (and a double root's, to rounding)."""
    q = list(q)
    err, e = _pose_error(q, pose, dp)
    for _ in range(iters):
        if err <= target:
            break
        q, e, err2 = _gn_step(q, e, err, pose, dp)
        if not err2 < err:
            break
        err = err2
    return [_wrap(x) if k == "R" else x for x, k in zip(q, JOINT_KINDS, strict=True)], err


# a calibrated arm's search along its near-null direction (_along_null): steps of the held-joint fit, the held
# joint's Newton steps, the longest of those (rad, or length for a slide), and the halvings of a step that does not
# help before the search ends
HELD_FIT_STEPS = 8
NULL_SEARCH_STEPS = 20
NULL_SEARCH_MAX_STEP = 0.5
NULL_SEARCH_HALVINGS = 6


def _held_fit(q, pose, dp, hold):
    """Damped Gauss-Newton on the other joints with joint `hold` fixed, until a step no longer helps: (q, e, err)."""
    q = list(q)
    err, e = _pose_error(q, pose, dp)
    for _ in range(HELD_FIT_STEPS):
        q, e, err2 = _gn_step(q, e, err, pose, dp, hold=hold)
        if not err2 < err:
            break
        err = err2
    return q, e, err


def _along_null(q, pose, dp, target):
    """A calibrated arm's set that Gauss-Newton could not bring onto the pose: near a singularity of the ideal
    geometry the true chain's solution lies along the near-null direction n of J, up to 1e-7 / sigma_min away (a
    shoulder's q1 by radians), where Gauss-Newton's steps overshoot. The joint carrying most of n is held and the
    others fitted (well conditioned): what is left of the residual e lies along J n, and the held joint's Newton step
    is (J n) . e n_j / |J n|^2 (n and J n read again at each point), taken along n, at most NULL_SEARCH_MAX_STEP
    in the held joint, while it helps and
    the residual is above `target` (the plain polish cannot finish: its damping holds a step along n still below
    sigma_min ~ 1e-6); a step that does not help is halved, NULL_SEARCH_HALVINGS times at most (along a wrist's
    broken self-motion the residual is no linear function of the held joint: the Newton step from a set 0.39 rad off
    was 1.02, clamped to 0.5 it missed, its half helped); then polished: (q, residual)."""
    def null(qq):
        jac = np.array(_k_jacobian(qq, dp), dtype=float).reshape(6, N_JOINTS)
        if _HELD >= 0:
            jac[:, _HELD] = 0.0
        n = np.linalg.eigh(jac.T @ jac)[1][:, 0]
        return n, jac @ n

    n, _ = null(q)
    if _HELD >= 0:
        n[_HELD] = 0.0
    hold = int(np.argmax(np.abs(n)))
    q, e, err = _held_fit(q, pose, dp, hold)
    for _ in range(NULL_SEARCH_STEPS):
        if err <= target:
            break
        n, jn = null(q)
        s2 = float(jn @ jn)
        step = float(jn @ e) * n[hold] / s2 if s2 > 0.0 else 0.0
        step = min(max(step, -NULL_SEARCH_MAX_STEP), NULL_SEARCH_MAX_STEP)
        if not step != 0.0:
            break
        for _ in range(NULL_SEARCH_HALVINGS + 1):
            # along n (the held fit then corrects a second-order error only: one or two steps, not five)
            trial = [x + step * v / n[hold] for x, v in zip(q, n, strict=True)]
            trial, e2, err2 = _held_fit(trial, pose, dp, hold)
            if err2 < err:
                break
            step *= 0.5
        if not err2 < err:
            break
        q, e, err = trial, e2, err2
    return _polish(q, pose, dp, target=target)


# a calibrated arm's wrist family scan (_family_scan): points of q4 round the circle, each fitted with q4 held
FAMILY_SCAN_POINTS = 36
# the probe either side of a root from which the scan estimates a fold's other root (_family_scan): the residual
# there, ~1e-3 |s'|, must stand above rounding (s' ~ 1e-10 at 1e-10 from singular: 1e-13), and the quadratic model
# hold to the other root
FAMILY_PARTNER_PROBE = 1e-3


def _family_scan(q, pose, dp, target, hold):
    """The true chain's solutions along a calibrated arm's family through set q, parametrised by joint `hold`: near a
    self-motion of its ideal geometry (the wrist's at theta5 = 0 or pi, q4 and q6 turning together: hold q4; the
    shoulder's with the wrist centre on axis 1, q1 and the wrist turning together: hold q1) the calibration breaks
    the family into isolated solutions, up to four of them (the bench's sweep: four at one wrist 1e-8 from singular,
    a fold's pair among them, where the ideal stages' two sets reached one; two 0.08 rad apart at a shoulder 1e-8
    from singular, the stages' set on the far one). Joint `hold` is set to FAMILY_SCAN_POINTS points round the
    circle from q's, the other joints fitted with it held (each from the fit before: the family moves them little);
    where the fit's residual has a local minimum along the circle the set is searched along the near-null direction
    to `target` (_along_null), and from the fold's other root estimated about the solution it finds. Returns [(set,
    residual)], each verified (IK_VERIFY_TOL) and distinct (_runtime.same_set), FAMILY_SCAN_POINTS at most."""
    x, pts = list(q), []
    for i in range(FAMILY_SCAN_POINTS):
        x[hold] = _wrap(q[hold] + 2.0 * math.pi * i / FAMILY_SCAN_POINTS)
        x, _, err = _held_fit(x, pose, dp, hold)
        pts.append((err, list(x)))
    out = []

    def keep(start):
        xq, e = _along_null(start, pose, dp, target)
        if e <= IK_VERIFY_TOL and not any(_runtime.same_set(xq, o, _REVOLUTE) for o, _ in out):
            out.append((xq, e))
            return xq
        return None

    spacing = 2.0 * math.pi / FAMILY_SCAN_POINTS
    for i, (err, x) in enumerate(pts):
        if len(out) >= FAMILY_SCAN_POINTS:  # as many as C keeps
            break
        if not (err <= pts[i - 1][0] and err <= pts[(i + 1) % FAMILY_SCAN_POINTS][0]):
            continue
        root = keep(x)
        if root is None:
            continue
        # near a fold the family's solutions come in pairs closer than the points (0.05, 5e-3 and 5.6e-4 rad apart
        # at 1e-8, 1e-9 and 1e-10 from singular): one minimum between them, the search reaching one. Along the
        # family the fit's residual is |s(t)|, s ~ s'(t - t1) + s''(t - t1)^2 / 2 about the root t1 found, so its
        # values a probe h either side, a and b, give the other root t2 = t1 - 2 s' / s'' = t1 - h (a + b) / (a - b),
        # searched from there when it is within a spacing (a farther one has a minimum of its own)
        if len(out) >= FAMILY_SCAN_POINTS:
            break
        a, b = (_held_fit([v + side if k == hold else v for k, v in enumerate(root)], pose, dp, hold)[2]
                for side in (FAMILY_PARTNER_PROBE, -FAMILY_PARTNER_PROBE))
        if a != b:
            step = -FAMILY_PARTNER_PROBE * (a + b) / (a - b)
            if abs(step) <= spacing:
                y = list(root)
                y[hold] = _wrap(root[hold] + step)
                keep(_held_fit(y, pose, dp, hold)[0])
    return out


def _indistinct(x, ex, y, ey, pose, dp, floor):
    """Whether two verified sets (residuals ex, ey) are one solution as merge_indistinct decides
    (_runtime.pair_indistinct, refitted on the pose)."""
    return _runtime.pair_indistinct(x, ex, y, ey, _REVOLUTE,
                                    lambda mid, step, accept: _refit(mid, pose, dp, step, accept), floor) is not None


def _refit(q, pose, dp, max_step, accept):
    """The residual after at most one damped Gauss-Newton step no longer than max_step in any joint (q updated in
    place when it helps), none when it is at most `accept` already: the runtime's merge_indistinct asks whether a
    point between two sets fits the pose."""
    err, e = _pose_error(q, pose, dp)
    if err <= accept:
        return err
    moved, _, err2 = _gn_step(q, e, err, pose, dp, max_step)
    if err2 < err:
        q[:] = [_wrap(x) if k == "R" else x for x, k in zip(moved, JOINT_KINDS, strict=True)]
    return err2


def _nearest_member(q, prev, dp):
    """At the wrist singularity the family is q4 + t, q6 - sigma t (the two axes coincide; sigma = +1 when they
    point the same way): the member whose q4 is prev's q4."""
    j = np.array(_k_jacobian(q, dp), dtype=float).reshape(6, N_JOINTS)
    j4, j6 = _WRIST_JOINTS
    sigma = 1.0 if float(np.dot(j[3:, j4], j[3:, j6])) >= 0.0 else -1.0
    t = _wrap(_wrap(prev[j4]) - q[j4])
    q = list(q)
    q[j4], q[j6] = _wrap(q[j4] + t), _wrap(q[j6] - sigma * t)
    return q
