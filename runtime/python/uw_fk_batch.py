"""The underactuated wrist's forward kinematics vectorised over rows (companion-matrix roots, a
vectorised polish; rows the vectorised path cannot decide fall back to the scalar fk).

A wristkin runtime source: the underactuated wrist's generated module inlines it from the marker line on
(derive/runtime_files.py), after its constants and derived kernels; above the marker, what it reads from them
and from the other sources (uw_stand_in.py: the catalogue's wrist), so that it is linted and tested as it is
(tests/test_uw_runtime.py)."""

from __future__ import annotations

import _runtime
import numpy as np
from uw_design import _design, _matrix
from uw_fk import fk
from uw_stand_in import (
    _C_FK_BATCH,
    _TWO_PI,
    FK_AUX_NAMES,
    FK_DUPLICATE_TOL,
    FK_FOLD_TOL,
    FK_RESIDUAL_TOL,
    FLAG_DOUBLE_ROOT,
    FLAG_GIMBAL,
    FLAG_SINGULAR_DIRECT,
    FLAG_SINGULAR_INVERSE,
    GIMBAL_EPS,
    MAX_FK,
    POLISH_ITERS,
    SINGULAR_EPS,
    STATUS_NO_ASSEMBLY,
    STATUS_OK,
    BatchSolutions,
    InvalidInput,
    _k_base_axes,
    _kv_fk_def,
    _kv_fk_rotation,
    _kv_middle_axes,
    _kv_platform_axes,
)

# wristkin: inlined from here
_RING = np.exp(2j * np.pi * np.arange(16) / 16)  # sampling ring for eta_c (cos + i sin)


def _vpoly_k(trip, ce, se):
    """Vectorised K0..K8 (N, 9) from trip (N, 6, 3) rotated by eta_c (cos ce, sin se per row)."""
    rc = trip[:, :, 1] * ce[:, None] + trip[:, :, 2] * se[:, None]
    rs = -trip[:, :, 1] * se[:, None] + trip[:, :, 2] * ce[:, None]
    q = np.stack([trip[:, :, 0] + rc, 2.0 * rs, trip[:, :, 0] - rc], axis=2)  # (N, 6, 3) ascending in x

    def mul(a, b):
        out = np.zeros(a.shape[:-1] + (a.shape[-1] + b.shape[-1] - 1,))
        for i in range(a.shape[-1]):
            out[..., i:i + b.shape[-1]] += a[..., i:i + 1] * b
        return out
    d1, e1, f1, d2, e2, f2 = (q[:, j] for j in range(6))
    t1, t2, t3 = mul(e1, f2) - mul(e2, f1), mul(d2, f1) - mul(d1, f2), mul(d1, e2) - mul(d2, e1)
    return mul(t1, t1) + mul(t2, t2) - mul(t3, t3)


def _vresidual(tr, z, e):
    """Loop residuals g (M, 2) and Jacobian (M, 2, 2) for candidate rows tr (M, 6, 3)."""
    ce, se, cz, sz = np.cos(e), np.sin(e), np.cos(z), np.sin(z)
    v = tr[:, :, 0] + tr[:, :, 1] * ce[:, None] + tr[:, :, 2] * se[:, None]
    dv = -tr[:, :, 1] * se[:, None] + tr[:, :, 2] * ce[:, None]
    g = np.stack([v[:, 0] * cz + v[:, 1] * sz + v[:, 2], v[:, 3] * cz + v[:, 4] * sz + v[:, 5]], axis=1)
    jac = np.stack([np.stack([-v[:, 0] * sz + v[:, 1] * cz, dv[:, 0] * cz + dv[:, 1] * sz + dv[:, 2]], axis=1),
                    np.stack([-v[:, 3] * sz + v[:, 4] * cz, dv[:, 3] * cz + dv[:, 4] * sz + dv[:, 5]], axis=1)],
                   axis=1)
    return g, jac


def fk_batch(joints, design=None) -> BatchSolutions:
    """Vectorised FK over rows of an (N, 3) array (same layout and tolerances as fk).

    Real roots come from the eigenvalues of the stacked companion matrices (candidates within a loose
    imaginary band), then a vectorised damped Gauss-Newton on the loop equations decides: a candidate
    is kept if its residual is within FK_RESIDUAL_TOL (FK_FOLD_TOL, flagged, if its root was not clearly
    real). Rows whose loop equations are proportional at a candidate fall back to the scalar fk.
    """
    d = _design(design)
    if d.native is not None:
        qc = _runtime.c_floats(joints)
        if qc is not None and qc.ndim == 2 and qc.shape[1] == 3:
            n = qc.shape[0]
            out = (np.empty((n, MAX_FK, 3)), np.empty((n, MAX_FK), bool), np.empty((n, MAX_FK), np.int64),
                   np.empty((n, MAX_FK, len(FK_AUX_NAMES))), np.empty(n, np.int64))
            if _C_FK_BATCH(qc, d.native, *out, 3) >= 0:
                return BatchSolutions(*out)
    q = _matrix(joints, 3, "joints")
    if not np.all(np.isfinite(q)):
        bad = np.flatnonzero(~np.all(np.isfinite(q), axis=1)).tolist()
        raise InvalidInput(f"joints: rows {bad} are not finite")
    n = q.shape[0]
    values = np.full((n, MAX_FK, 3), np.nan)
    aux = np.full((n, MAX_FK, len(FK_AUX_NAMES)), np.nan)
    valid = np.zeros((n, MAX_FK), dtype=bool)
    flags = np.zeros((n, MAX_FK), dtype=np.int64)
    status = np.full(n, STATUS_NO_ASSEMBLY, dtype=np.int64)
    if n == 0:
        return BatchSolutions(values, valid, flags, aux, status)
    cf = np.stack(np.broadcast_arrays(*_kv_fk_def(tuple(np.cos(q.T)), tuple(np.sin(q.T)), d.constants)),
                  axis=1)  # (N, 18)
    trip = cf.reshape(n, 6, 3)
    # eta_c per row: the ring sample with the largest |identity| goes to x = infinity
    v = (trip[:, None, :, 0] + trip[:, None, :, 1] * _RING.real[None, :, None]
         + trip[:, None, :, 2] * _RING.imag[None, :, None])  # (N, 16, 6)
    ident = ((v[..., 1] * v[..., 5] - v[..., 4] * v[..., 2]) ** 2 + (v[..., 3] * v[..., 2] - v[..., 0] * v[..., 5]) ** 2
             - (v[..., 0] * v[..., 4] - v[..., 3] * v[..., 1]) ** 2)
    kbest = np.argmax(np.abs(ident), axis=1)
    eta_c = 2.0 * np.pi * kbest / 16 - np.pi
    K = _vpoly_k(trip, np.cos(eta_c), np.sin(eta_c))  # (N, 9), |K8| is the largest sample
    scale = np.max(np.abs(K), axis=1)
    degenerate = np.abs(K[:, 8]) <= 1e-14 * scale  # identically zero or degree drop: scalar path decides
    lead = np.where(degenerate, 1.0, K[:, 8])
    comp = np.zeros((n, 8, 8))
    comp[:, 1:, :-1] = np.eye(7)
    comp[:, :, -1] = -K[:, :8] / lead[:, None]
    roots = np.linalg.eigvals(comp)  # (N, 8)
    cand = np.abs(roots.imag) <= 1e-3 * (1.0 + np.abs(roots.real))
    clear = np.abs(roots.imag) <= 1e-9 * (1.0 + np.abs(roots.real))
    rows, cols = np.nonzero(cand & ~degenerate[:, None])
    x = roots.real[rows, cols]
    eta = eta_c[rows] + 2.0 * np.arctan(x)
    tr = trip[rows]
    # zeta by Cramer's rule
    ce, se = np.cos(eta), np.sin(eta)
    vv = tr[:, :, 0] + tr[:, :, 1] * ce[:, None] + tr[:, :, 2] * se[:, None]
    den = vv[:, 0] * vv[:, 4] - vv[:, 3] * vv[:, 1]
    nc = vv[:, 1] * vv[:, 5] - vv[:, 4] * vv[:, 2]
    ns = vv[:, 3] * vv[:, 2] - vv[:, 0] * vv[:, 5]
    proportional = np.abs(den) <= 1e-8 * np.hypot(vv[:, 0], vv[:, 1]) * np.hypot(vv[:, 3], vv[:, 4])
    sgn = np.where(den >= 0.0, 1.0, -1.0)
    zeta = np.arctan2(sgn * ns, sgn * nc)
    g, jac = _vresidual(tr, zeta, eta)
    err = np.max(np.abs(g), axis=1)
    for _ in range(POLISH_ITERS):
        jtj = np.einsum("mki,mkj->mij", jac, jac)
        mu = 1e-14 * (jtj[:, 0, 0] + jtj[:, 1, 1]) + 1e-300
        rhs = -np.einsum("mki,mk->mi", jac, g)[..., None]
        step = np.linalg.solve(jtj + mu[:, None, None] * np.eye(2), rhs)[..., 0]
        g2, jac2 = _vresidual(tr, zeta + step[:, 0], eta + step[:, 1])
        err2 = np.max(np.abs(g2), axis=1)
        better = err2 < err
        zeta, eta = np.where(better, zeta + step[:, 0], zeta), np.where(better, eta + step[:, 1], eta)
        g, jac = np.where(better[:, None], g2, g), np.where(better[:, None, None], jac2, jac)
        err = np.minimum(err, err2)
        if not np.any(better & (err > 1e-16)):
            break
    touching = ~clear[rows, cols]
    keep = err <= np.where(touching, FK_FOLD_TOL, FK_RESIDUAL_TOL)
    fallback = np.zeros(n, dtype=bool)
    fallback[degenerate] = True
    fallback[rows[proportional]] = True
    keep &= ~fallback[rows]
    # a touching root that polishes to a regular residual is a regular mode (the merge is confirmed, not assumed)
    touching = touching & ~(err <= FK_RESIDUAL_TOL)
    rows, zeta, eta, touching = rows[keep], np.mod(zeta[keep], _TWO_PI), np.mod(eta[keep], _TWO_PI), touching[keep]
    # dedupe within a row (conjugate pairs and near-double roots polish to the same mode), stable order
    order = np.lexsort((zeta, eta, rows))
    rows, zeta, eta, touching = rows[order], zeta[order], eta[order], touching[order]

    def wrapped(a):
        return np.abs(np.remainder(a + np.pi, _TWO_PI) - np.pi)
    same = np.zeros(len(rows), dtype=bool)
    same[1:] = ((rows[1:] == rows[:-1]) & (wrapped(eta[1:] - eta[:-1]) < FK_DUPLICATE_TOL)
                & (wrapped(zeta[1:] - zeta[:-1]) < FK_DUPLICATE_TOL))
    mflag = np.where(touching, FLAG_DOUBLE_ROOT | FLAG_SINGULAR_DIRECT, 0)
    dup_into = np.flatnonzero(same) - 1
    np.bitwise_or.at(mflag, dup_into, FLAG_DOUBLE_ROOT | mflag[np.flatnonzero(same)])
    first = ~same
    rows, zeta, eta, mflag = rows[first], zeta[first], eta[first], mflag[first]
    start = np.searchsorted(rows, rows, side="left")
    slot = np.arange(len(rows)) - start
    ok = slot < MAX_FK
    rows, zeta, eta, mflag, slot = rows[ok], zeta[ok], eta[ok], mflag[ok], slot[ok]
    # rotation, Euler angles and conditioning, vectorised over the kept modes
    tze = (q[rows, 0], zeta, eta)
    rot = np.stack(np.broadcast_arrays(*_kv_fk_rotation(tuple(np.cos(tze)), tuple(np.sin(tze)), d.constants)),
                   axis=1)  # (M, 9)
    st = np.hypot(rot[:, 2], rot[:, 5])
    gimbal = st <= GIMBAL_EPS
    psi = np.where(gimbal, np.arctan2(rot[:, 3], rot[:, 0]), np.arctan2(rot[:, 2], -rot[:, 5]))
    cp, sp_ = np.cos(psi), np.sin(psi)  # phi from Rx(-theta) Rz(-psi) R, as in _euler
    phi = np.arctan2(rot[:, 8] * (-sp_ * rot[:, 0] + cp * rot[:, 3]) + st * rot[:, 6], cp * rot[:, 0] + sp_ * rot[:, 3])
    pose = np.stack([psi, np.arctan2(st, rot[:, 8]), np.where(gimbal, 0.0, phi)], axis=1)
    z1 = np.array(_k_base_axes(d.constants)).reshape(3, 3)
    z2 = np.stack(np.broadcast_arrays(*_kv_middle_axes(tuple(np.cos(q[rows].T)), tuple(np.sin(q[rows].T)),
                                                       d.constants)), axis=1).reshape(-1, 3, 3)
    z3 = np.stack(np.broadcast_arrays(*_kv_platform_axes(tuple(rot.T), d.constants)), axis=1).reshape(-1, 3, 3)
    ci = np.min(np.abs(np.einsum("mij,mij->mi", np.cross(z1[None], z2), z3)), axis=1) / d.constants[1]
    jrows = np.cross(z2, z3)
    norm = np.prod(np.linalg.norm(jrows, axis=2), axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        cd = np.where(norm > 0.0, np.abs(np.linalg.det(jrows)) / norm, 0.0)
    f = (mflag | np.where(gimbal, FLAG_GIMBAL, 0) | np.where(ci <= SINGULAR_EPS, FLAG_SINGULAR_INVERSE, 0)
         | np.where(cd <= SINGULAR_EPS, FLAG_SINGULAR_DIRECT, 0))
    values[rows, slot] = pose
    aux[rows, slot] = np.column_stack([rot, zeta, eta, ci, cd])
    valid[rows, slot] = True
    flags[rows, slot] = f
    status[np.unique(rows)] = STATUS_OK
    for r in np.flatnonzero(fallback):
        s = fk(q[r], d)
        values[r], valid[r], flags[r], aux[r], status[r] = s.values, s.valid, s.flags, s.aux, s.status
    return BatchSolutions(values, valid, flags, aux, status)
