"""Verification and Gauss-Newton polish of a candidate on the true chain; the Jacobian.

A wristkin runtime source: every user robot's generated module inlines it from the marker line on
(derive/runtime_files.py), after the robot's constants; above the marker, what it reads from them and from the
other sources (chain_stand_in.py: a stand-in robot), so that it is linted and tested as it is
(tests/test_chain_runtime.py)."""

from __future__ import annotations

import _runtime
import numpy as np
from chain_poe import _fk_chain
from chain_rigid import _ID, _apply, _compose, _cross, _mv, _screw, _sub
from chain_stand_in import POLISH_STEPS, POLISH_TOL


# wristkin: inlined from here
# ---------------------------------------------------------------------------- verification on the true chain
def _frame_error(t, target):
    """max |t - target| over the entries of [R | p]."""
    return max(max(abs(t[0][i][j] - target[0][i][j]) for i in range(3) for j in range(3)),
               max(abs(t[1][i] - target[1][i]) for i in range(3)))


def _pose_error(ch, q, target):
    t = _fk_chain(ch, q)
    return _frame_error(t, target), t


def _twist_error(t, target):
    """6-vector (position error, 1/2 sum of column crosses) from t to target."""
    w = [0.0, 0.0, 0.0]
    for i in range(3):
        c = _cross((t[0][0][i], t[0][1][i], t[0][2][i]), (target[0][0][i], target[0][1][i], target[0][2][i]))
        w = [w[0] + 0.5 * c[0], w[1] + 0.5 * c[1], w[2] + 0.5 * c[2]]
    return np.array([*_sub(target[1], t[1]), *w])


def _jacobian_chain(ch, q):
    """Geometric Jacobian of the chain's end frame (no base / tool), 6 x n."""
    n = len(ch.kinds)
    t = _ID
    cols = []
    for j in range(n):
        cols.append((_mv(t[0], ch.axes[j]), _apply(t, ch.points[j]), ch.kinds[j]))
        t = _compose(t, _screw(ch.kinds[j], ch.axes[j], ch.points[j], q[j]))
    end = _compose(t, ch.home)[1]
    out = np.zeros((6, n))
    for j, (w, o, kind) in enumerate(cols):
        out[:, j] = (*w, 0.0, 0.0, 0.0) if kind == "P" else (*_cross(w, _sub(end, o)), *w)
    return out


def _polish_read(fk, jacobian, n, q, target):
    """Gauss-Newton on a chain read through fk(q) -> frame and jacobian(q) -> 6 x n (the derived kernels, or a
    chain's table): a square step by elimination, else least squares (the C runtime's ck_polish_read)."""
    q = list(q)
    t = fk(q)
    err = _frame_error(t, target)
    for _ in range(POLISH_STEPS):
        if err <= POLISH_TOL:
            break
        jac, e = jacobian(q), _twist_error(t, target)
        step = _runtime.solve_square(jac, e, 1e-8) if n == 6 else None
        if step is None:
            step = np.linalg.lstsq(np.asarray(jac, dtype=float), e, rcond=None)[0]
        trial = [v + float(dq) for v, dq in zip(q, step, strict=True)]
        t2 = fk(trial)
        err2 = _frame_error(t2, target)
        if not err2 < err:
            break
        q, err, t = trial, err2, t2
    return q, err


def _polish(ch, q, target):
    """Gauss-Newton on the true chain's table (a free joint is not in it: held): removes the error of the ideal
    geometry and of a tangent root."""
    return _polish_read(lambda x: _fk_chain(ch, x), lambda x: _jacobian_chain(ch, x), len(ch.kinds), q, target)


def _ratio_of(jac):
    """sigma_min / sigma_max of a Jacobian (6 x n): conditioning of the configuration."""
    s = np.linalg.svd(jac, compute_uv=False)
    return float(s[-1] / s[0]) if s[0] > 0.0 else 0.0


def _ratio(ch, q):
    """sigma_min / sigma_max of the chain's Jacobian at q."""
    return _ratio_of(_jacobian_chain(ch, q))


