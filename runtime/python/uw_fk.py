"""The underactuated wrist's forward kinematics for one joint triple: every real assembly mode as a pose.

A wristkin runtime source: the underactuated wrist's generated module inlines it from the marker line on
(derive/runtime_files.py), after its constants and derived kernels; above the marker, what it reads from them
and from the other sources (uw_stand_in.py: the catalogue's wrist), so that it is linted and tested as it is
(tests/test_uw_runtime.py)."""

from __future__ import annotations

import math

import _runtime
import numpy as np
from uw_design import _VEC3, _design
from uw_fk_modes import _fk_modes
from uw_orientation import _cond_rows, _cross, _euler
from uw_stand_in import (
    _C_FK,
    _FK_RESULT,
    FK_AUX_NAMES,
    FLAG_DOUBLE_ROOT,
    FLAG_SINGULAR_DIRECT,
    FLAG_SINGULAR_INVERSE,
    MAX_FK,
    SINGULAR_EPS,
    Solutions,
    _k_base_axes,
    _k_fk_rotation,
    _k_middle_axes,
    _k_platform_axes,
    _vector,
)


# wristkin: inlined from here
def fk(joints, design=None) -> Solutions:
    """Every real assembly mode (at most 8) for exterior joint angles (theta1, theta2, theta3)."""
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
    values = np.full((MAX_FK, 3), np.nan)
    aux = np.full((MAX_FK, len(FK_AUX_NAMES)), np.nan)
    valid = np.zeros(MAX_FK, dtype=bool)
    flags = np.zeros(MAX_FK, dtype=np.int64)
    cq, sq = [math.cos(t) for t in q], [math.sin(t) for t in q]
    modes, status, reason = _fk_modes(cq, sq, d)
    z1 = _k_base_axes(d.constants)
    z2 = _k_middle_axes(cq, sq, d.constants)
    for k, (z, e, _err, _jdet, f) in enumerate(modes[:MAX_FK]):
        rot = _k_fk_rotation((cq[0], math.cos(z), math.cos(e)), (sq[0], math.sin(z), math.sin(e)), d.constants)
        pose, fg = _euler(rot)
        z3 = _k_platform_axes(rot, d.constants)
        ax = [(z1[3 * i:3 * i + 3], z2[3 * i:3 * i + 3], z3[3 * i:3 * i + 3]) for i in range(3)]
        # jq_i = det[Zi1, Zi2, Zi3] (inverse singularity), rows Zi2 x Zi3 of jx (direct singularity)
        ci = min(abs(sum(x * y for x, y in zip(_cross(a, b), c, strict=True))) for a, b, c in ax) / d.constants[1]
        cd = _cond_rows([_cross(b, c) for _, b, c in ax])
        f |= fg
        if ci <= SINGULAR_EPS:
            f |= FLAG_SINGULAR_INVERSE
        if cd <= SINGULAR_EPS:
            f |= FLAG_SINGULAR_DIRECT | (f & FLAG_DOUBLE_ROOT)
        values[k] = pose
        aux[k] = [*rot, z, e, ci, cd]
        valid[k] = True
        flags[k] = f
    return Solutions(values, valid, flags, aux, status, reason)
