"""The 3-RSR wrist's verbs: its design, IK with every branch, FK, batches, pose matrices, Jacobians and workspace.

A wristkin runtime source: the wrist's generated module inlines it from the marker line on
(derive/runtime_files.py), after its constants, derived kernels and the 3-RSR core (rsr_legs.py); above the
marker, what it reads from them (rsr_stand_in.py: the catalogue's wrist), so that it is linted and tested as it
is (tests/test_rsr_runtime.py)."""

from __future__ import annotations

import math

import _runtime
import numpy as np
from rsr_legs import _leg_cond_inverse, _legs, _plane, _plane_of_set, _pose_of_plane, _workspace, _wrist_design_error
from rsr_stand_in import (
    _C_FK,
    _C_FK_BATCH,
    _C_IK,
    _C_IK_BATCH,
    _C_JACOBIAN,
    _FK_RESULT,
    _IK_RESULT,
    FK_AUX_NAMES,
    FLAG_DOUBLE_ROOT,
    FLAG_GIMBAL,
    FLAG_INDETERMINATE,
    FLAG_SINGULAR_DIRECT,
    FLAG_SINGULAR_INVERSE,
    GIMBAL_EPS,
    IK_AUX_NAMES,
    IK_VERIFY_TOL,
    MAX_FK,
    MAX_IK,
    POSE_TOL,
    SINGULAR_EPS,
    STATUS_INDETERMINATE,
    STATUS_NO_ASSEMBLY,
    STATUS_OK,
    STATUS_UNREACHABLE,
    BatchSolutions,
    Design,
    InvalidDesign,
    InvalidInput,
    Solutions,
    _c_design,
    _design_values,
    _k_fk_pose,
    _k_geometric_jacobian,
    _k_jacobians,
    _rows,
    _stack,
    _vector,
    _wrap,
)


# wristkin: inlined from here
def make_design(params=None) -> Design:
    """Validate (L, phi_min, phi_max, lbw_min, lbw_max): metres and radians; the limits bound the workspace."""
    if isinstance(params, Design):
        return params
    vals = _design_values(params)
    err = _wrist_design_error(vals)
    if err:
        raise InvalidDesign(err)
    return Design(vals, _c_design(vals))


_DEFAULT_DESIGN = make_design()
_VEC3 = ((3,),)


def _design(design):
    if design is None:
        return _DEFAULT_DESIGN
    return design if isinstance(design, Design) else make_design(design)


def _pose(pose):
    alpha, beta, lbw = _vector(pose, 3, "pose (alpha, beta, l_bw)")
    if not 0.0 <= beta <= math.pi:
        raise InvalidInput(f"beta must be in [0, pi], got {beta!r}")
    return (_wrap(alpha), beta, lbw)  # exactly: the kernels add the legs' angles to alpha


# ---------------------------------------------------------------------------- kinematics
def ik(pose, design=None) -> Solutions:
    """All 8 joint sets (2 roots per leg) for the pose (alpha, beta, l_bw).

    aux = (residual, cond_inverse, cond_direct); a double root is reported once, flagged."""
    d = _design(design)
    if d.native is not None:
        sol = _C_IK(pose, d.native, _IK_RESULT)
        if sol.__class__ is not Solutions or sol.status != STATUS_OK:  # a conversion, or words
            sol = _runtime.c_explained(sol, _C_IK, pose, _VEC3, (d.native, _IK_RESULT),
                                       _ik_numpy, (pose, d), worded=(STATUS_OK,))
        if sol is not None:
            return sol
    return _ik_numpy(pose, d)


def _ik_numpy(pose, d):
    """ik on the numpy path (also what words the reason of an answer from C that needs one)."""
    p = _pose(pose)
    values = np.full((MAX_IK, 3), np.nan)
    aux = np.full((MAX_IK, 3), np.nan)
    valid = np.zeros(MAX_IK, dtype=bool)
    flags = np.zeros(MAX_IK, dtype=np.int64)
    roots, lflags, conds, reason = _legs(p, d.params)
    if any(r is None for r in roots):
        return Solutions(values, valid, flags, aux, STATUS_UNREACHABLE, "pose not reachable: " + reason)
    f0 = lflags[0] | lflags[1] | lflags[2]
    for k in range(MAX_IK):
        if any(lflags[i] & (FLAG_DOUBLE_ROOT | FLAG_INDETERMINATE) and (k >> i) & 1 for i in range(3)):
            continue  # a double root, or a free leg's representative, is reported once, on the + branch
        legs = [roots[i][(k >> i) & 1] for i in range(3)]
        res = max(leg[3] for leg in legs)
        if res > IK_VERIFY_TOL:
            continue
        plane = _plane_of_set(legs, d.params)
        cd = 0.0 if plane is None else plane[1]
        values[k], aux[k], valid[k] = (legs[0][0], legs[1][0], legs[2][0]), (res, min(conds), cd), True
        flags[k] = f0 | (FLAG_SINGULAR_DIRECT if cd <= SINGULAR_EPS else 0)
    status = STATUS_INDETERMINATE if np.any(flags & FLAG_INDETERMINATE) else STATUS_OK
    return Solutions(values, valid, flags, aux, status, f"{int(valid.sum())} solution(s)")


def fk(joints, design=None) -> Solutions:
    """The symmetric assembly mode (one solution): values = (alpha, beta, l_bw); aux = [R_W | p_W] + conditioning."""
    d = _design(design)
    if d.native is not None:
        sol = _C_FK(joints, d.native, _FK_RESULT)
        if sol.__class__ is not Solutions:  # a conversion, or words
            sol = _runtime.c_explained(sol, _C_FK, joints, _VEC3, (d.native, _FK_RESULT),
                                       _fk_numpy, (joints, d))
        if sol is not None:
            return sol
    return _fk_numpy(joints, d)


def _fk_numpy(joints, d):
    """fk on the numpy path (also what words the reason of an answer from C that needs one)."""
    q = _vector(joints, 3, "joints")
    values = np.full((1, 3), np.nan)
    aux = np.full((1, len(FK_AUX_NAMES)), np.nan)
    plane = _plane(q, d.params)
    if plane is None:
        return Solutions(values, np.zeros(1, bool), np.zeros(1, np.int64), aux, STATUS_NO_ASSEMBLY,
                         "S1, S2, S3 are collinear: the mirror plane is undefined (direct singularity)")
    n, cd = plane
    pose, gimbal, tw = _pose_of_plane(n)
    ci = _leg_cond_inverse(q, pose, d.params)
    f = (FLAG_GIMBAL if gimbal else 0) | (FLAG_SINGULAR_DIRECT if cd <= SINGULAR_EPS else 0) | (
        FLAG_SINGULAR_INVERSE if ci <= SINGULAR_EPS else 0)
    values[0], aux[0] = pose, (*tw, ci, cd)
    return Solutions(values, np.ones(1, bool), np.array([f], np.int64), aux, STATUS_OK, "1 assembly mode")


def _c_batch(fn, rows, d, max_n, n_aux):
    """A batch through the C loop, or None (then the scalar verbs run row by row and explain any error)."""
    a = _runtime.c_floats(rows)
    if d.native is None or a is None or a.ndim != 2 or a.shape[1] != 3:
        return None
    n = a.shape[0]
    out = (np.empty((n, max_n, 3)), np.empty((n, max_n), bool), np.empty((n, max_n), np.int64),
           np.empty((n, max_n, n_aux)), np.empty(n, np.int64))
    return BatchSolutions(*out) if fn(a, d.native, *out, 3) >= 0 else None


def ik_batch(poses, design=None) -> BatchSolutions:
    d = _design(design)
    if d.native is not None:
        out = _c_batch(_C_IK_BATCH, poses, d, MAX_IK, len(IK_AUX_NAMES))
        if out is not None:
            return out
    return _stack([ik(p, d) for p in _rows(poses, 3, "poses")], MAX_IK, 3, len(IK_AUX_NAMES))


def fk_batch(joints, design=None) -> BatchSolutions:
    d = _design(design)
    if d.native is not None:
        out = _c_batch(_C_FK_BATCH, joints, d, MAX_FK, len(FK_AUX_NAMES))
        if out is not None:
            return out
    return _stack([fk(q, d) for q in _rows(joints, 3, "joints")], MAX_FK, 3, len(FK_AUX_NAMES))


def pose_matrix(pose) -> np.ndarray:
    """The platform frame as a 4x4: [Rz(alpha) Ry(beta) Rz(-alpha) | l_bw n(alpha, beta)]."""
    alpha, beta, lbw = _pose(pose)
    n = (math.sin(beta / 2) * math.cos(alpha), math.sin(beta / 2) * math.sin(alpha), math.cos(beta / 2))
    t = np.eye(4)
    t[:3] = np.array(_k_fk_pose((*n, lbw / 2))).reshape(3, 4)
    return t


def pose_from_matrix(matrix) -> tuple:
    """(alpha, beta, l_bw) of a platform frame; InvalidInput if it is not in the wrist's 3-DOF image (torsion or
    an off-axis centre beyond POSE_TOL)."""
    a = np.asarray(matrix, dtype=float)
    if a.shape not in ((3, 4), (4, 4)) or not np.all(np.isfinite(a)):
        raise InvalidInput("matrix: expected a finite 4x4 or 3x4 platform frame")
    r = a[:3, :3]
    z = r[:, 2]
    beta = math.atan2(math.hypot(z[0], z[1]), z[2])
    alpha = math.atan2(z[1], z[0]) if math.hypot(z[0], z[1]) > GIMBAL_EPS else 0.0
    n = np.array([math.sin(beta / 2) * math.cos(alpha), math.sin(beta / 2) * math.sin(alpha), math.cos(beta / 2)])
    lbw = float(n @ a[:3, 3])
    err = float(np.max(np.abs(pose_matrix((alpha, beta, lbw))[:3] - a[:3])))
    if err > POSE_TOL:
        raise InvalidInput(f"matrix is not a pose of this wrist (zero torsion, centre on the mirror normal): "
                           f"deviation {err:.3g} > {POSE_TOL}")
    return (alpha, beta, lbw)


def jacobians(joints, pose, design=None):
    """(jq (3,), jx (3, 3)) with jq * phi_dot = jx @ (alpha, beta, l_bw)_dot."""
    d = _design(design)
    out = _k_jacobians(_vector(joints, 3, "joints"), _pose(pose), d.params)
    return np.array(out[:3]), np.array(out[3:]).reshape(3, 3)


def workspace(alpha, beta, design=None):
    """(l_bw_min, l_bw_max) reachable at attitude (alpha, beta) within the design's limits, or None."""
    d = _design(design)
    alpha, beta = _vector((alpha, beta), 2, "(alpha, beta)")
    return _workspace(alpha, beta, d.params)


def middle_lbw(alpha, beta, design=None):
    """The seed's 'middle curve': the mean of the reachable centre distances at (alpha, beta); None if none."""
    span = workspace(alpha, beta, design)
    return None if span is None else 0.5 * (span[0] + span[1])


def jacobian(joints, design=None) -> np.ndarray:
    """Geometric Jacobian (6 x 3): platform-centre velocity rows, then angular velocity, per phi_dot (base frame)."""
    d = _design(design)
    if d.native is not None:
        jac = _runtime.c_call(_C_JACOBIAN, joints, _VEC3, d.native)
        if jac.__class__ is np.ndarray:  # else a status (no pose there) or an error: the numpy path explains
            return jac
    q = _vector(joints, 3, "joints")
    if _plane(q, d.params) is None:
        raise InvalidInput("S1, S2, S3 are collinear: the mirror plane (and the platform) is undefined")
    return np.array(_k_geometric_jacobian(q, d.params)).reshape(6, 3)
