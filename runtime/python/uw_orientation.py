"""ZXZ Euler angles of the underactuated wrist's pose, its motor angles, and the direct-singularity
measure of three Jacobian rows.

A wristkin runtime source: the underactuated wrist's generated module inlines it from the marker line on
(derive/runtime_files.py), after its constants and derived kernels; above the marker, what it reads from them
and from the other sources (uw_stand_in.py: the catalogue's wrist), so that it is linted and tested as it is
(tests/test_uw_runtime.py)."""

from __future__ import annotations

import math

import numpy as np
from uw_design import _design, _wrap_2pi, _wrap_pi
from uw_stand_in import FLAG_GIMBAL, GIMBAL_EPS, InvalidInput, _vector


# wristkin: inlined from here
# ---------------------------------------------------------------------------- orientation helpers
def rotation_from_pose(pose) -> np.ndarray:
    """R = Rz(psi) Rx(theta) Rz(phi)."""
    psi, theta, phi = _vector(pose, 3, "pose")
    cp, sp_, ct, st, cf, sf = math.cos(psi), math.sin(psi), math.cos(theta), math.sin(theta), math.cos(phi), \
        math.sin(phi)
    return np.array([[cp * cf - sp_ * ct * sf, -cp * sf - sp_ * ct * cf, sp_ * st],
                     [sp_ * cf + cp * ct * sf, -sp_ * sf + cp * ct * cf, -cp * st],
                     [st * sf, st * cf, ct]])


def _euler(r):
    """ZXZ angles from a flat row-major rotation; theta in [0, pi]. Returns (pose, flags)."""
    st = math.hypot(r[2], r[5])
    theta = math.atan2(st, r[8])
    if st <= GIMBAL_EPS:
        # Only psi + phi (theta = 0) or psi - phi (theta = pi) is defined: put it all in psi.
        return (math.atan2(r[3], r[0]), theta, 0.0), FLAG_GIMBAL
    # psi from the third column (error ~ eps / sin(theta) near the gimbal); phi from Rz(phi) = Rx(-theta)
    # Rz(-psi) R, which takes that error back: the three angles reproduce R to rounding for every theta
    # (phi = atan2(r6, r7) alone would miss R by ~eps / sin(theta) next to the gimbal).
    psi = math.atan2(r[2], -r[5])
    cp, sp_ = math.cos(psi), math.sin(psi)
    m00, m10 = cp * r[0] + sp_ * r[3], r[8] * (-sp_ * r[0] + cp * r[3]) + st * r[6]
    return (psi, theta, math.atan2(m10, m00)), 0


def pose_from_rotation(rot):
    """(pose, flags): ZXZ Euler angles of a rotation matrix (FLAG_GIMBAL where only psi +/- phi is defined)."""
    a = np.asarray(rot, dtype=float)
    if a.shape != (3, 3) or not np.all(np.isfinite(a)):
        raise InvalidInput("rotation must be a finite 3x3 matrix")
    if np.max(np.abs(a.T @ a - np.eye(3))) > 1e-9 or np.linalg.det(a) < 0.0:
        raise InvalidInput("matrix is not a rotation (R^T R != I or det R < 0)")
    return _euler(tuple(a.ravel()))


def motor_angles(joints, design=None) -> np.ndarray:
    """Phi_i = theta_i - theta0, wrapped to (-pi, pi]."""
    d = _design(design)
    return np.array([_wrap_pi(_wrap_pi(t) - d.theta0) for t in _vector(joints, 3, "joints")])


def joints_from_motor_angles(motor, design=None) -> np.ndarray:
    d = _design(design)
    return np.array([_wrap_2pi(_wrap_pi(p) + d.theta0) for p in _vector(motor, 3, "motor angles")])


def _cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _cond_rows(rows):
    """|det[rows]| / prod |rows| in [0, 1]: the direct-singularity measure for rows Zi2 x Zi3."""
    r0, r1, r2 = rows
    det = (r0[0] * (r1[1] * r2[2] - r1[2] * r2[1]) - r0[1] * (r1[0] * r2[2] - r1[2] * r2[0])
           + r0[2] * (r1[0] * r2[1] - r1[1] * r2[0]))
    norm = math.prod(math.sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]) for r in rows)
    return abs(det) / norm if norm > 0.0 else 0.0


def _rotation_columns(p):
    """Row-major entries of R for an (N, 3) array of poses (vectorised)."""
    cp, sp_, ct, st, cf, sf = (np.cos(p[:, 0]), np.sin(p[:, 0]), np.cos(p[:, 1]), np.sin(p[:, 1]),
                               np.cos(p[:, 2]), np.sin(p[:, 2]))
    return (cp * cf - sp_ * ct * sf, -cp * sf - sp_ * ct * cf, sp_ * st,
            sp_ * cf + cp * ct * sf, -sp_ * sf + cp * ct * cf, -cp * st,
            st * sf, st * cf, ct)
