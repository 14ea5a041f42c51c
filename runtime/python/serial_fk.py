"""A serial arm's forward kinematics, Jacobian and conditioning (one joint vector or many).

A wristkin runtime source: every serial arm's generated module (the catalogue's DH chains, the finite-screw chains'
serial view) inlines it from the marker line on (derive/runtime_files.py), after its constants, derived kernels
and stage functions; above the marker, what it reads from them and from the other sources (serial_stand_in.py:
the PUMA-560), so that it is linted and tested as it is (tests/test_serial_runtime.py)."""

from __future__ import annotations

import math

import _runtime
import numpy as np
from serial_frames import _reframe, _reframe_jacobian
from serial_input import _JOINT_SHAPE, _design, _joints
from serial_stand_in import (
    _C_FK,
    _C_FK_BATCH,
    _C_FK_MATRIX,
    _C_JACOBIAN,
    _FK_RESULT,
    FLAG_SINGULAR_INVERSE,
    N_JOINTS,
    SINGULAR_EPS,
    STATUS_OK,
    BatchSolutions,
    InvalidInput,
    Solutions,
    _k_fk,
    _k_jacobian,
    _kv_fk,
    _rows,
    _stack,
)


# wristkin: inlined from here
# ---------------------------------------------------------------------------- forward kinematics
def _jacobian_in_frames(q, d, v0=None):
    """The geometric Jacobian (6 x n) in the design's base and tool frames; v0: the kernels' end pose at q when the
    caller has it."""
    j = np.array(_k_jacobian(q, d.params), dtype=float).reshape(6, N_JOINTS)
    return j if d.frames is None else _reframe_jacobian(j, _k_fk(q, d.params) if v0 is None else v0, d.frames)


def _conditioning(q, d, v0=None):
    """(manipulability sqrt(det J^T J) (J J^T for more than 6 joints), sigma_min / sigma_max of J), both from its
    eigenvalues."""
    return _spectrum(_jacobian_in_frames(q, d, v0))


def _spectrum(j):
    """(manipulability, sigma_min / sigma_max) of a 6 x n Jacobian from its eigenvalues: the FK's conditioning and
    the general 6R stage's singular flag. A redundant arm (a held joint's 7 joints): J J^T, whose eigenvalues are J's
    nonzero sigma^2 (the arm's conditioning, whichever joint its IK holds)."""
    lam = np.maximum(np.linalg.eigvalsh(j.T @ j if j.shape[1] <= 6 else j @ j.T), 0.0)
    return math.sqrt(float(np.prod(lam))), (math.sqrt(lam[0] / lam[-1]) if lam[-1] > 0.0 else 0.0)


def _fk_flag(ratio):
    return FLAG_SINGULAR_INVERSE if ratio <= SINGULAR_EPS else 0


def fk(joints, design=None) -> Solutions:
    """The end pose (one solution; values = entries of [R | p]); aux = manipulability sqrt(det J^T J) (J J^T past 6
    joints); flagged singular when sigma_min / sigma_max of J is at or below SINGULAR_EPS."""
    d = _design(design)
    if d.native is not None:
        sol = _C_FK(joints, d.native, _FK_RESULT)
        if sol.__class__ is not Solutions:  # a conversion, or words
            sol = _runtime.c_explained(sol, _C_FK, joints, _JOINT_SHAPE, (d.native, _FK_RESULT),
                                       _fk_numpy, (joints, d))
        if sol is not None:
            return sol
    return _fk_numpy(joints, d)


def _fk_numpy(joints, d):
    """fk on the numpy path (also what words the reason of an answer from C that needs one)."""
    q = _joints(joints)
    v = _k_fk(q, d.params)
    values = np.array([v if d.frames is None else _reframe(v, d.frames)], dtype=float)
    man, ratio = _conditioning(q, d, v)
    flags = np.array([_fk_flag(ratio)], dtype=np.int64)
    return Solutions(values, np.array([True]), flags, np.array([[man]]), STATUS_OK, "1 pose")


def fk_matrix(joints, design=None) -> np.ndarray:
    """The end pose as a 4x4 homogeneous matrix."""
    d = _design(design)
    if d.native is not None:
        t = _C_FK_MATRIX(joints, d.native)
        if t.__class__ is not np.ndarray:
            t = _runtime.c_retry(t, _C_FK_MATRIX, joints, _JOINT_SHAPE, d.native)
        if t.__class__ is np.ndarray:  # else an error: the numpy path explains
            return t
    t = np.eye(4)
    t[:3] = fk(joints, design).values[0].reshape(3, 4)
    return t


def fk_batch(joints, design=None) -> BatchSolutions:
    """Vectorised FK over rows of an (N, n) array."""
    d = _design(design)
    if d.native is not None:
        q = _runtime.c_floats(joints, None)
        if q is not None and q.ndim == 2 and q.shape[1] == N_JOINTS:
            n = q.shape[0]
            out = (np.empty((n, 1, 12)), np.empty((n, 1), bool), np.empty((n, 1), np.int64), np.empty((n, 1, 1)),
                   np.empty(n, np.int64))
            if _C_FK_BATCH(q, d.native, *out, N_JOINTS) >= 0:
                return BatchSolutions(*out)
    q = _rows(joints, N_JOINTS, "joints")
    if not np.all(np.isfinite(q)):
        raise InvalidInput(f"joints: expected a finite (N, {N_JOINTS}) array")
    if q.shape[0] == 0:
        return _stack([], 1, 12, 1)
    q = np.array([_joints(row) for row in q])
    raw = np.stack(np.broadcast_arrays(*_kv_fk(tuple(q.T), d.params)), axis=1)
    vals = (raw if d.frames is None else np.array([_reframe(v, d.frames) for v in raw]))[:, None, :]
    cond = [_conditioning(tuple(row), d, v) for row, v in zip(q, raw, strict=True)]
    man = np.array([[c[0]] for c in cond])
    n = q.shape[0]
    return BatchSolutions(vals, np.ones((n, 1), dtype=bool), np.array([[_fk_flag(c[1])] for c in cond], np.int64),
                          man[:, :, None], np.zeros(n, dtype=np.int64))


def jacobian(joints, design=None) -> np.ndarray:
    """Geometric Jacobian (6 x n): linear velocity rows first, base frame."""
    d = _design(design)
    if d.native is not None:
        jac = _C_JACOBIAN(joints, d.native)
        if jac.__class__ is not np.ndarray:
            jac = _runtime.c_retry(jac, _C_JACOBIAN, joints, _JOINT_SHAPE, d.native)
        if jac.__class__ is np.ndarray:  # else an error: the numpy path explains
            return jac
    return _jacobian_in_frames(_joints(joints), d)
