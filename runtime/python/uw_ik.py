"""The underactuated wrist's inverse kinematics: every one of the 8 sets, one pose (ik) or many (ik_batch).

A wristkin runtime source: the underactuated wrist's generated module inlines it from the marker line on
(derive/runtime_files.py), after its constants and derived kernels; above the marker, what it reads from them
and from the other sources (uw_stand_in.py: the catalogue's wrist), so that it is linted and tested as it is
(tests/test_uw_runtime.py)."""

from __future__ import annotations

import math

import _runtime
import numpy as np
from uw_design import _VEC3, _design, _matrix, _wrap_2pi, _wrap_pi
from uw_orientation import _cond_rows, _cross, _rotation_columns, rotation_from_pose
from uw_stand_in import (
    _C_IK,
    _C_IK_BATCH,
    _IK_RESULT,
    _TWO_PI,
    FLAG_DOUBLE_ROOT,
    FLAG_INDETERMINATE,
    FLAG_SINGULAR_DIRECT,
    FLAG_SINGULAR_INVERSE,
    IK_AUX_NAMES,
    MAX_IK,
    SINGULAR_EPS,
    STATUS_INDETERMINATE,
    STATUS_OK,
    STATUS_UNREACHABLE,
    TANGENT_TOL,
    BatchSolutions,
    InvalidInput,
    Solutions,
    _k_ik_abc,
    _k_middle_axes,
    _k_platform_axes,
    _kv_ik_abc,
    _kv_middle_axes,
    _kv_platform_axes,
    _vector,
    _wrap_all,
)


# wristkin: inlined from here
# ---------------------------------------------------------------------------- inverse kinematics
def ik(pose, design=None) -> Solutions:
    """All 8 IK solution sets: set k takes the +acos root on branch i when bit i of k is 0."""
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
    p = _vector(pose, 3, "pose")
    rot = tuple(rotation_from_pose(p).ravel())
    abc = _k_ik_abc(rot, d.constants)
    sa1 = d.constants[1]
    values = np.full((MAX_IK, 3), np.nan)
    aux = np.full((MAX_IK, len(IK_AUX_NAMES)), np.nan)
    valid = np.zeros(MAX_IK, dtype=bool)
    flags = np.zeros(MAX_IK, dtype=np.int64)
    roots, cs, bflag, cond_inv = [], [], [], []
    status, reasons = STATUS_OK, []
    for i in range(3):
        a, b, c = abc[3 * i:3 * i + 3]
        r = math.hypot(a, b)
        scale = max(r, abs(c), 1e-300)
        if r <= 1e-13 * max(scale, 1.0):
            if abs(c) <= 1e-13:
                # Branch i is satisfied for every theta_i: report the home angle as its representative.
                status = STATUS_INDETERMINATE
                reasons.append(f"branch {i + 1} indeterminate (A = B = C = 0): any theta{i + 1} closes the loop")
                t = d.theta0
                roots.append((t, t))
                cs.append(((math.cos(t), math.sin(t)), (math.cos(t), math.sin(t))))
                bflag.append(FLAG_INDETERMINATE | FLAG_SINGULAR_INVERSE)
                cond_inv.append(0.0)
                continue
            status = STATUS_UNREACHABLE
            reasons.append(f"branch {i + 1} unreachable: A = B = 0, C = {c:.3g}")
            break
        u = -c / r
        if abs(u) > 1.0 + TANGENT_TOL:
            status = STATUS_UNREACHABLE
            reasons.append(f"branch {i + 1} unreachable: |C|/sqrt(A^2+B^2) = {abs(u):.9g} > 1")
            break
        f = 0
        u = max(-1.0, min(1.0, u))
        sg = math.sqrt(max(0.0, 1.0 - u * u))
        if sg <= TANGENT_TOL:
            f |= FLAG_DOUBLE_ROOT
        ci = r * sg / sa1
        if ci <= SINGULAR_EPS:
            f |= FLAG_SINGULAR_INVERSE
        base, g = math.atan2(b, a), math.acos(u)
        roots.append((_wrap_2pi(base + g), _wrap_2pi(base - g)))
        ca, sa_ = a / r, b / r
        cs.append(((ca * u - sa_ * sg, sa_ * u + ca * sg), (ca * u + sa_ * sg, sa_ * u - ca * sg)))
        bflag.append(f)
        cond_inv.append(ci)
    if status == STATUS_UNREACHABLE:
        return Solutions(values, valid, flags, aux, status, "; ".join(reasons))
    # rows Zi2 x Zi3 of jx per (branch, root), computed once; the 8 sets only combine them
    z3 = _k_platform_axes(rot, d.constants)
    z2 = [_k_middle_axes([cs[i][b][0] for i in range(3)], [cs[i][b][1] for i in range(3)], d.constants)
          for b in (0, 1)]
    rows = [[_cross(z2[b][3 * i:3 * i + 3], z3[3 * i:3 * i + 3]) for b in (0, 1)] for i in range(3)]
    for k in range(MAX_IK):
        sel = [(k >> i) & 1 for i in range(3)]
        q = [roots[i][sel[i]] for i in range(3)]
        cd = _cond_rows([rows[i][sel[i]] for i in range(3)])
        f = bflag[0] | bflag[1] | bflag[2]
        if cd <= SINGULAR_EPS:
            f |= FLAG_SINGULAR_DIRECT
        values[k] = q
        aux[k] = [*(_wrap_pi(t - d.theta0) for t in q), min(cond_inv), cd]
        valid[k] = True
        flags[k] = f
    return Solutions(values, valid, flags, aux, status, "; ".join(reasons) or "8 solution sets")


def ik_batch(poses, design=None) -> BatchSolutions:
    """Vectorised IK over rows of an (N, 3) array of poses (same layout as ik)."""
    d = _design(design)
    if d.native is not None:
        p = _runtime.c_floats(poses)
        if p is not None and p.ndim == 2 and p.shape[1] == 3:
            n = p.shape[0]
            out = (np.empty((n, MAX_IK, 3)), np.empty((n, MAX_IK), bool), np.empty((n, MAX_IK), np.int64),
                   np.empty((n, MAX_IK, len(IK_AUX_NAMES))), np.empty(n, np.int64))
            if _C_IK_BATCH(p, d.native, *out, 3) >= 0:
                return BatchSolutions(*out)
    p = _matrix(poses, 3, "poses")
    n = p.shape[0]
    finite = np.all(np.isfinite(p), axis=1)
    pz = np.where(finite[:, None], p, 0.0)
    rot = [np.broadcast_to(x, (n,)) for x in _rotation_columns(pz)]
    abc = np.broadcast_arrays(*_kv_ik_abc(tuple(rot), d.constants))
    a, b, c = (np.stack(abc[j::3], axis=1) for j in range(3))  # (N, 3) each
    r = np.hypot(a, b)
    with np.errstate(divide="ignore", invalid="ignore"):
        u = np.where(r > 0.0, -c / r, np.inf)
    reach = (np.abs(u) <= 1.0 + TANGENT_TOL) & finite[:, None]
    indet = (r <= 1e-13) & (np.abs(c) <= 1e-13) & finite[:, None]
    uc = np.clip(np.nan_to_num(u, nan=0.0, posinf=1.0, neginf=-1.0), -1.0, 1.0)
    sg = np.sqrt(np.maximum(0.0, 1.0 - uc * uc))
    base, g = np.arctan2(b, a), np.arccos(uc)
    roots = np.stack([np.mod(base + g, _TWO_PI), np.mod(base - g, _TWO_PI)], axis=2)  # (N, 3, 2)
    roots = np.where(indet[:, :, None], d.theta0, roots)
    bits = (np.arange(MAX_IK)[:, None] >> np.arange(3)[None, :]) & 1  # (8, 3)
    vals = roots[:, np.arange(3)[None, :], bits]  # (N, 8, 3)
    ok = np.all(reach | indet, axis=1)
    valid = np.repeat(ok[:, None], MAX_IK, axis=1)
    cond_inv = np.min(np.where(indet, 0.0, r * sg / d.constants[1]), axis=1)
    f = np.zeros((n, 3), dtype=np.int64)
    f |= np.where(sg <= TANGENT_TOL, FLAG_DOUBLE_ROOT, 0)
    f |= np.where(r * sg / d.constants[1] <= SINGULAR_EPS, FLAG_SINGULAR_INVERSE, 0)
    f |= np.where(indet, FLAG_INDETERMINATE | FLAG_SINGULAR_INVERSE, 0)
    flags = np.repeat((f[:, 0] | f[:, 1] | f[:, 2])[:, None], MAX_IK, axis=1)
    # direct-singularity measure per set, vectorised through the axes kernel
    cq, sq = np.cos(vals), np.sin(vals)
    a2 = np.broadcast_arrays(*_kv_middle_axes(tuple(np.moveaxis(cq, 2, 0)), tuple(np.moveaxis(sq, 2, 0)),
                                              d.constants))
    a3 = np.broadcast_arrays(*_kv_platform_axes(tuple(x[:, None] for x in rot), d.constants))
    z2 = np.stack([np.stack(a2[3 * i:3 * i + 3], axis=-1) for i in range(3)], axis=-2)  # (N, 8, 3, 3)
    z3 = np.broadcast_to(np.stack([np.stack(a3[3 * i:3 * i + 3], axis=-1) for i in range(3)], axis=-2), z2.shape)
    rows = np.cross(z2, z3)
    norm = np.prod(np.linalg.norm(rows, axis=-1), axis=-1)
    with np.errstate(divide="ignore", invalid="ignore"):
        cd = np.where(norm > 0.0, np.abs(np.linalg.det(rows)) / norm, 0.0)
    flags = flags | np.where(cd <= SINGULAR_EPS, FLAG_SINGULAR_DIRECT, 0)
    motor = _wrap_all(vals - d.theta0)  # as the scalar path's _wrap_pi, bit for bit
    aux = np.concatenate([motor, np.repeat(cond_inv[:, None, None], MAX_IK, axis=1), cd[:, :, None]], axis=2)
    status = np.where(ok, np.where(np.any(indet, axis=1), STATUS_INDETERMINATE, STATUS_OK), STATUS_UNREACHABLE)
    vals = np.where(valid[:, :, None], vals, np.nan)
    aux = np.where(valid[:, :, None], aux, np.nan)
    flags = np.where(valid, flags, 0)
    if not np.all(finite):
        raise InvalidInput(f"poses: rows {np.flatnonzero(~finite).tolist()} are not finite")
    return BatchSolutions(vals, valid, flags, aux, status)
