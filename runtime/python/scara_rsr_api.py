"""The SCARA + 3-RSR hybrid's verbs: its design, FK, decoupled closed-form IK with every branch, batches, the
platform attitude as (alpha, beta, gamma).

A wristkin runtime source: the hybrid's generated module inlines it from the marker line on
(derive/runtime_files.py), after its constants, derived kernels and the 3-RSR core (rsr_legs.py); above the
marker, what it reads from them (scara_stand_in.py: the catalogue's hybrid), so that it is linted and tested as
it is (tests/test_rsr_runtime.py)."""

from __future__ import annotations

import math

import _runtime
import numpy as np
from rsr_legs import (
    LENGTH_MAX,
    _leg_cond_inverse,
    _legs,
    _plane,
    _plane_of_set,
    _pose_of_plane,
    _workspace,
    _wrist_design_error,
    azimuth_from_gamma,
)
from scara_stand_in import (
    _C_FK,
    _C_FK_BATCH,
    _C_FK_MATRIX,
    _C_IK,
    _C_IK_BATCH,
    _C_JACOBIAN,
    DEGENERATE_EPS,
    DESIGN_SCALE_MIN,
    FK_AUX_NAMES,
    FLAG_DOUBLE_ROOT,
    FLAG_GIMBAL,
    FLAG_INDETERMINATE,
    FLAG_PROJECTED,
    FLAG_SINGULAR_DIRECT,
    FLAG_SINGULAR_INVERSE,
    GIMBAL_EPS,
    IK_AUX_NAMES,
    IK_VERIFY_TOL,
    JOINT_KINDS,
    LINK_RATIO_MIN,
    MAX_FK,
    MAX_IK,
    N_JOINTS,
    ROTATION_TOL,
    SINGULAR_EPS,
    STATUS_INDETERMINATE,
    STATUS_NO_ASSEMBLY,
    STATUS_OK,
    STATUS_UNREACHABLE,
    TANGENT_TOL,
    BatchSolutions,
    Design,
    InvalidDesign,
    InvalidInput,
    Solutions,
    _as_rotation,
    _c_design,
    _design_values,
    _k_fk_compose,
    _k_jacobian,
    _k_wrist_offset,
    _projected_note,
    _rows,
    _stack,
    _vector,
    _wrap,
)


# wristkin: inlined from here
def make_design(params=None) -> Design:
    """Validate (L1, L2, d, d_f, L, phi_min, phi_max, lbw_min, lbw_max): metres and radians."""
    if isinstance(params, Design):
        return params
    vals = _design_values(params)
    if not (vals[0] > 0.0 and vals[1] > 0.0):
        raise InvalidDesign(f"link lengths L1, L2 must be > 0, got ({vals[0]!r}, {vals[1]!r})")
    if any(abs(v) > 1e6 for v in vals):
        raise InvalidDesign("design values must be below 1e6")
    short, long_ = sorted(vals[:2])
    if long_ < DESIGN_SCALE_MIN or short < LINK_RATIO_MIN * long_:
        raise InvalidDesign(f"link lengths L1, L2 = ({vals[0]!r}, {vals[1]!r}): the longer must be at least "
                            f"{DESIGN_SCALE_MIN:g} m and the shorter at least {LINK_RATIO_MIN:g} x the longer "
                            "(a vanishing link leaves an elbow joint that moves nothing: a singular design)")
    err = _wrist_design_error(vals[4:])
    if err:
        raise InvalidDesign(err)
    return Design(vals, _c_design(vals))


_DEFAULT_DESIGN = make_design()
_JOINT_SHAPE = ((N_JOINTS,),)


def _design(design):
    if design is None:
        return _DEFAULT_DESIGN
    return design if isinstance(design, Design) else make_design(design)


def _rotation12(a):
    """The 12 entries of [R | p] with R projected onto SO(3) (within ROTATION_PROJECT_TOL), and the deviation."""
    r, dev = _as_rotation(a[:3, :3])
    return tuple(float(x) for x in np.column_stack([r, a[:3, 3]]).ravel()), dev


def _pose(pose):
    """-> (12 entries of [R | p], l_bw or None = middle curve)."""
    try:
        a = np.asarray(pose, dtype=float)
    except (TypeError, ValueError) as exc:
        raise InvalidInput("pose: expected a 4x4 / 3x4 matrix, 12 numbers, or 13 numbers ([R | p], l_bw)") from exc
    if not np.all(np.isfinite(a)):
        raise InvalidInput("pose: values must be finite")
    if a.ndim == 1 and a.size == 13:
        return (*_rotation12(a[:12].reshape(3, 4)), float(a[12]))
    if a.ndim == 1 and a.size in (12, 16):
        a = a.reshape(-1, 4)
    if a.shape not in ((3, 4), (4, 4)):
        raise InvalidInput(f"pose: expected a 4x4 / 3x4 matrix, 12 or 13 numbers, got shape {a.shape}")
    if a.shape == (4, 4) and not np.max(np.abs(a[3] - (0.0, 0.0, 0.0, 1.0))) <= ROTATION_TOL:
        raise InvalidInput("pose: last row must be (0, 0, 0, 1)")
    return (*_rotation12(a), None)


GIMBAL_ALPHAS = tuple(k * math.pi / 6.0 for k in range(6))  # the family's members tried at beta = pi, 0 first


def _split_orientation(p):
    """(theta, alpha1, beta, gimbal) of R = Rz(theta) C Rz(alpha1) Ry(beta) Rz(-alpha1) (step orientation_split)."""
    ax, ay, az = p[2], p[6], p[10]
    sb = math.hypot(ax, ay)
    beta = math.atan2(sb, -az)
    if sb <= GIMBAL_EPS and az <= 0.0:  # beta = 0: the wrist does not depend on alpha1 (set 0); R = Rz(theta) C
        return math.atan2(p[4], -p[5]), 0.0, beta, True
    if sb <= GIMBAL_EPS:  # beta = pi: R = Rz(theta - 2 alpha1) C Ry(pi) = Rz(theta - 2 alpha1 + pi): alpha1 := 0
        return math.atan2(-p[4], -p[0]), 0.0, beta, True
    alpha = math.atan2(ay, ax)
    ca, sa = ax / sb, ay / sb
    alpha1 = math.atan2(-sa * p[0] + ca * p[4], sa * p[1] - ca * p[5])
    return _wrap(alpha + alpha1), alpha1, beta, False


def _joints(joints):
    """Angles wrapped exactly (_wrap reduces against 2 pi itself), the stroke d3 within LENGTH_MAX."""
    q = _vector(joints, N_JOINTS, "joints")
    if not abs(q[2]) <= LENGTH_MAX:
        raise InvalidInput(f"joints: the stroke d3 must be within {LENGTH_MAX:g} m, got {q[2]!r}")
    return tuple(v if k == "P" else _wrap(v) for v, k in zip(q, JOINT_KINDS, strict=True))


# ---------------------------------------------------------------------------- forward kinematics
def _fk(q, d):
    """(pose 13, aux, flags) or None when the wrist's mirror plane is undefined."""
    w, dp = d.params[4:], d.params[:4]
    plane = _plane(q[4:], w)
    if plane is None:
        return None
    n, cd = plane
    wpose, gimbal, tw = _pose_of_plane(n)
    t = _k_fk_compose(q[:4], tw, dp)
    ci = _leg_cond_inverse(q[4:], wpose, w)
    theta, alpha1, beta, _ = _split_orientation(t)
    alpha1 = 0.0 if gimbal else wpose[0]
    f = (FLAG_GIMBAL if gimbal else 0) | (FLAG_SINGULAR_DIRECT if cd <= SINGULAR_EPS else 0) | (
        FLAG_SINGULAR_INVERSE if ci <= SINGULAR_EPS else 0)
    gamma = math.atan2(math.sin(alpha1), math.cos(beta) * math.cos(alpha1))
    aux = (_wrap(theta - alpha1), beta, gamma, alpha1, ci, cd)
    return (*t, wpose[2]), aux, f


def fk(joints, design=None) -> Solutions:
    """The platform frame and l_bw (one solution); aux = (alpha, beta, gamma, alpha1, cond_inverse, cond_direct)."""
    d = _design(design)
    if d.native is not None:
        sol = _runtime.c_explained(_C_FK(joints, d.native), _C_FK, joints, _JOINT_SHAPE, (d.native,), _fk_numpy,
                                   (joints, d), "1 pose")
        if sol is not None:
            return sol
    return _fk_numpy(joints, d)


def _fk_numpy(joints, d):
    """fk on the numpy path (also what words the reason of an answer from C that needs one)."""
    q = _joints(joints)
    values = np.full((1, 13), np.nan)
    aux = np.full((1, len(FK_AUX_NAMES)), np.nan)
    out = _fk(q, d)
    if out is None:
        return Solutions(values, np.zeros(1, bool), np.zeros(1, np.int64), aux, STATUS_NO_ASSEMBLY,
                         "wrist S1, S2, S3 collinear: the mirror plane is undefined (direct singularity)")
    values[0], aux[0] = out[0], out[1]
    return Solutions(values, np.ones(1, bool), np.array([out[2]], np.int64), aux, STATUS_OK, "1 pose")


def fk_matrix(joints, design=None) -> np.ndarray:
    """The platform frame as a 4x4 (InvalidInput where the wrist's mirror plane is undefined)."""
    d = _design(design)
    if d.native is not None:
        t = _runtime.c_call(_C_FK_MATRIX, joints, _JOINT_SHAPE, d.native)
        if t.__class__ is np.ndarray:  # else a status (no pose there) or an error: the numpy path explains
            return t
    s = fk(joints, design)
    if not s.count:
        raise InvalidInput(s.reason)
    t = np.eye(4)
    t[:3] = s.values[0, :12].reshape(3, 4)
    return t


def jacobian(joints, design=None) -> np.ndarray:
    """Geometric Jacobian (6 x 7): platform-centre velocity rows, then angular velocity (base frame)."""
    d = _design(design)
    if d.native is not None:
        jac = _runtime.c_call(_C_JACOBIAN, joints, _JOINT_SHAPE, d.native)
        if jac.__class__ is np.ndarray:  # else a status (no pose there) or an error: the numpy path explains
            return jac
    q = _joints(joints)
    if _plane(q[4:], d.params[4:]) is None:
        raise InvalidInput("wrist S1, S2, S3 collinear: the mirror plane (and the platform) is undefined")
    return np.array(_k_jacobian(q, d.params)).reshape(6, N_JOINTS)


def fk_batch(joints, design=None) -> BatchSolutions:
    d = _design(design)
    q = _runtime.c_floats(joints) if d.native is not None else None
    if q is not None and q.ndim == 2 and q.shape[1] == N_JOINTS:
        n = q.shape[0]
        out = (np.empty((n, MAX_FK, 13)), np.empty((n, MAX_FK), bool), np.empty((n, MAX_FK), np.int64),
               np.empty((n, MAX_FK, len(FK_AUX_NAMES))), np.empty(n, np.int64))
        if _C_FK_BATCH(q, d.native, *out, N_JOINTS) >= 0:
            return BatchSolutions(*out)
    return _stack([fk(q, d) for q in _rows(joints, N_JOINTS, "joints")], MAX_FK, 13, len(FK_AUX_NAMES))


# ---------------------------------------------------------------------------- inverse kinematics
def _scara_roots(x, y, dp):
    """Both elbows of the planar two-link: [(theta1, theta2), ...], flags; [] if out of reach.

    1 + cos theta2 and 1 - cos theta2 come from factored differences of squares, so neither fold cancels:
    1 + c2 = (r - |L1 - L2|)(r + |L1 - L2|) / (2 L1 L2), 1 - c2 = (L1 + L2 - r)(L1 + L2 + r) / (2 L1 L2). With
    L1 = L2 and the flange nanometres from axis 1, c2 = (r^2 - L1^2 - L2^2) / (2 L1 L2) rounds to -1 and
    L1 + L2 c2 to 0, which turned theta1 by 90 degrees; L1 + L2 c2 = (L1 - L2) + L2 (1 + c2) keeps its digits."""
    l1, l2 = dp[0], dp[1]
    r = math.hypot(x, y)
    if not r <= 2.0 * (l1 + l2):  # far out of reach (the products below could overflow)
        return [], 0
    dl = abs(l1 - l2)
    opc = (r - dl) * (r + dl) / (2.0 * l1 * l2)
    omc = (l1 + l2 - r) * (l1 + l2 + r) / (2.0 * l1 * l2)
    # the tangent band scales with the rounding error of c2 (relative to its terms, >= 1 x TANGENT_TOL)
    tol = TANGENT_TOL * (x * x + y * y + l1 * l1 + l2 * l2) / (2.0 * l1 * l2)
    if opc < -tol or omc < -tol:
        return [], 0
    opc, omc = max(opc, 0.0), max(omc, 0.0)
    c2 = opc - 1.0 if opc <= omc else 1.0 - omc
    sg = math.sqrt(opc * omc)
    k = (l1 - l2) + l2 * opc  # L1 + L2 c2
    f = 0
    if sg <= math.sqrt(tol):
        f = FLAG_SINGULAR_INVERSE  # stretched or folded: the planar Jacobian L1 L2 sin theta2 vanishes
        if l2 * sg <= math.sqrt(tol) * abs(k):
            f |= FLAG_DOUBLE_ROOT  # the elbows coincide in theta1 too (tan of its offset within the band)
    if r <= DEGENERATE_EPS:  # L1 = L2 and the flange over joint 1: theta1 is free
        f |= FLAG_INDETERMINATE | FLAG_SINGULAR_INVERSE
    out = []
    for s2 in (sg, -sg):
        out.append((_wrap(math.atan2(y, x) - math.atan2(l2 * s2, k)), math.atan2(s2, c2)))
    return out, f


def ik(pose, design=None) -> Solutions:
    """Every joint set (2 elbows x 2^3 wrist legs) reaching the platform frame with the given l_bw (or the middle
    curve); each verified by FK. aux = (residual, alpha1, beta, gamma, cond_inverse, cond_direct)."""
    d = _design(design)
    if d.native is not None:  # C takes the 13 numbers ([R | p], l_bw); the middle curve is chosen here
        pc = _runtime.c_floats(pose, ((13,),))
        if pc is not None:
            sol = _runtime.c_explained(_C_IK(pc, d.native), _C_IK, pc, ((13,),), (d.native,), _ik_numpy, (pose, d),
                                       "{n} solution(s), l_bw = " f"{float(pc[12]):.6g} m", worded=(STATUS_OK,))
            if sol is not None:
                return sol
    return _ik_numpy(pose, d)


def _ik_numpy(pose, d):
    """ik on the numpy path (also what words the reason of an answer from C that needs one)."""
    p, dev, lbw = _pose(pose)
    dp, w = d.params[:4], d.params[4:]
    values = np.full((MAX_IK, N_JOINTS), np.nan)
    aux = np.full((MAX_IK, len(IK_AUX_NAMES)), np.nan)
    valid = np.zeros(MAX_IK, dtype=bool)
    flags = np.zeros(MAX_IK, dtype=np.int64)

    note = _projected_note(dev)

    def empty(reason):
        return Solutions(values, valid, flags, aux, STATUS_UNREACHABLE,
                         "pose not reachable: " + reason + (f"; {note}" if note else ""))

    theta, alpha1, beta, gimbal = _split_orientation(p)
    given = lbw
    # at beta = pi only theta - 2 alpha1 is fixed (a family): the split's member alpha1 = 0 puts leg i's coefficient
    # sin(alpha1 - a_i) at 0 for a leg at azimuth a_i = 0, which then cannot reach a centre distance near 0 (a
    # reachable pose was called unreachable); the family's other members are tried, each moving theta by 2 alpha1
    # (GIMBAL_ALPHAS: every 30 degrees in [0, pi), where the sines of the three legs' offsets stay apart)
    reason = f"no centre distance within the wrist limits at swing {math.degrees(beta):.4g} deg"
    for a1 in GIMBAL_ALPHAS if gimbal and beta > 0.5 * math.pi else (alpha1,):
        lbw = given
        if lbw is None:
            span = _workspace(a1, beta, w)
            if span is None:
                continue
            lbw = 0.5 * (span[0] + span[1])
        roots, lflags, conds, why = _legs((a1, beta, lbw), w)
        if all(r is not None for r in roots):
            theta, alpha1 = _wrap(theta + 2.0 * (a1 - alpha1)), a1
            break
        reason = "wrist " + why
    else:
        return empty(reason)
    ox, oy, oz = _k_wrist_offset((theta, alpha1, beta, lbw), dp)
    x4, y4, z4 = p[3] - ox, p[7] - oy, p[11] - oz
    elbows, eflag = _scara_roots(x4, y4, dp)
    if not elbows:
        return empty(f"flange point ({x4:.6g}, {y4:.6g}) outside the SCARA annulus")
    if not abs(dp[2] - z4) <= LENGTH_MAX:  # IK returns only sets that fk accepts
        return empty(f"the stroke d3 = {dp[2] - z4:.6g} m is beyond LENGTH_MAX = {LENGTH_MAX:g} m")
    gamma = math.atan2(math.sin(alpha1), math.cos(beta) * math.cos(alpha1))
    f0 = eflag | lflags[0] | lflags[1] | lflags[2] | (FLAG_GIMBAL if gimbal else 0)
    for legword in range(8):
        if any(lflags[i] & (FLAG_DOUBLE_ROOT | FLAG_INDETERMINATE) and (legword >> i) & 1 for i in range(3)):
            continue  # a double root, or a free leg's representative, is reported once, on the + branch
        legs = [roots[i][(legword >> i) & 1] for i in range(3)]
        plane = _plane_of_set(legs, w)
        if plane is None or plane[1] <= SINGULAR_EPS:
            # S1, S2, S3 (nearly) collinear (direct singularity): the legs do not fix the mirror plane (its rounding
            # error grows as 1 / cond_direct), the target does: the set is kept, flagged singular_direct (as
            # rsr_wrist does), with the target's plane
            sh = math.sin(0.5 * beta)
            plane = ((sh * math.cos(alpha1), sh * math.sin(alpha1), math.cos(0.5 * beta), 0.5 * lbw),
                     0.0 if plane is None else plane[1])
        n, cd = plane
        wp, _, tw = _pose_of_plane(n)
        for e in (0, 1):
            if e and eflag & (FLAG_DOUBLE_ROOT | FLAG_INDETERMINATE):
                # one elbow at full stretch / fold; with the flange on axis 1 (folded, L1 = L2) theta2 = +pi and -pi
                # are one angle and theta1 is free: the other elbow is a member of the same family
                continue
            t1, t2 = elbows[e]
            qs = (t1, t2, dp[2] - z4, _wrap(theta - t1 - t2))
            t = _k_fk_compose(qs, tw, dp)
            res = max(max(abs(x - y) for x, y in zip(t, p, strict=True)), abs(wp[2] - lbw))
            if res > IK_VERIFY_TOL:
                continue
            k = 8 * e + legword
            values[k], valid[k] = (*qs, legs[0][0], legs[1][0], legs[2][0]), True
            flags[k] = f0 | (FLAG_SINGULAR_DIRECT if cd <= SINGULAR_EPS else 0)
            aux[k] = (res, alpha1, beta, gamma, min(conds), cd)
    if not valid.any():
        return empty("no branch passes the FK check")
    status = STATUS_INDETERMINATE if np.any(flags & FLAG_INDETERMINATE) else STATUS_OK
    if dev:
        flags[valid] |= FLAG_PROJECTED
    return Solutions(values, valid, flags, aux, status, f"{int(valid.sum())} solution(s), l_bw = {lbw:.6g} m"
                     + (f"; {note}" if note else ""))


def ik_batch(poses, design=None) -> BatchSolutions:
    """IK over a stack: (N, 4, 4), (N, 3, 4), (N, 12) or (N, 13) rows."""
    d = _design(design)
    a = np.asarray(poses, dtype=float)
    if a.ndim not in (2, 3):
        raise InvalidInput("poses: expected an (N, 4, 4), (N, 3, 4), (N, 12) or (N, 13) array")
    if d.native is not None and a.ndim == 2 and a.shape[1] == 13:  # explicit l_bw: the C loop
        c, n = np.ascontiguousarray(a), a.shape[0]
        out = (np.empty((n, MAX_IK, N_JOINTS)), np.empty((n, MAX_IK), bool), np.empty((n, MAX_IK), np.int64),
               np.empty((n, MAX_IK, len(IK_AUX_NAMES))), np.empty(n, np.int64))
        if _C_IK_BATCH(c, d.native, *out, 13) >= 0:
            return BatchSolutions(*out)
    return _stack([ik(x, d) for x in a], MAX_IK, N_JOINTS, len(IK_AUX_NAMES))


# ---------------------------------------------------------------------------- attitude representation
def pose_from_abg(position, alpha, beta, gamma) -> np.ndarray:
    """4x4 platform frame from the seed's representation: approach azimuth alpha, swing beta, rotation gamma."""
    x, y, z = _vector(position, 3, "position")
    alpha, beta, gamma = _vector((alpha, beta, gamma), 3, "(alpha, beta, gamma)")
    if not 0.0 <= beta < 0.5 * math.pi:
        raise InvalidInput(f"beta must be in [0, pi/2), got {beta!r}")
    a1 = azimuth_from_gamma(gamma, beta)
    theta = alpha + a1

    def rz(a):
        return np.array([[math.cos(a), -math.sin(a), 0.0], [math.sin(a), math.cos(a), 0.0], [0.0, 0.0, 1.0]])

    ry = np.array([[math.cos(beta), 0.0, math.sin(beta)], [0.0, 1.0, 0.0], [-math.sin(beta), 0.0, math.cos(beta)]])
    t = np.eye(4)
    t[:3, :3] = rz(theta) @ np.diag([1.0, -1.0, -1.0]) @ rz(a1) @ ry @ rz(-a1)
    t[:3, 3] = (x, y, z)
    return t


def abg_from_pose(pose) -> tuple:
    """(alpha, beta, gamma) of a platform frame; at beta = 0 alpha is the SCARA rotation and gamma = 0 (GIMBAL)."""
    p, _, _ = _pose(pose)
    theta, alpha1, beta, _ = _split_orientation(p)
    return (_wrap(theta - alpha1), beta, math.atan2(math.sin(alpha1), math.cos(beta) * math.cos(alpha1)))
