"""The forms a pose is given in (a matrix, 12 / 16 numbers, xyz + rpy, xyz + quaternion) as one 4x4 matrix.

A wristkin runtime source: every serial arm's and user robot's generated module inlines it from the marker line on
(derive/runtime_files.py), after its constants; above the marker, what it reads from them (serial_stand_in.py: the
PUMA-560), so that it is linted and tested as it is (tests/test_serial_runtime.py, tests/test_shared_runtime.py)."""

from __future__ import annotations

import math

import numpy as np
from serial_stand_in import ROTATION_TOL, InvalidInput, _array


# wristkin: inlined from here
def _quat_matrix(x, y, z, w):
    """A unit quaternion's rotation; within ROTATION_TOL of unit norm it is normalised (as a matrix within
    that band is projected), beyond it refused: a quaternion rounded to a few digits is not taken as exact."""
    n = math.sqrt(x * x + y * y + z * z + w * w)
    if not abs(n - 1.0) <= ROTATION_TOL:
        raise InvalidInput(f"pose: the quaternion's norm is {n:.9g}: a unit quaternion is expected (accepted within "
                           f"{ROTATION_TOL:g} of 1, then normalised); normalise it or pass it with more "
                           "digits")
    x, y, z, w = x / n, y / n, z / n, w / n
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def _rpy_matrix(r, p, y):
    """URDF's roll, pitch, yaw: R = Rz(y) Ry(p) Rx(r), its entries written out."""
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return np.array([[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                     [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                     [-sp, cp * sr, cp * cr]])


def pose_matrix(pose) -> np.ndarray:
    """A pose as a 4x4 matrix: from a 4x4 / 3x4 matrix, 12 / 16 numbers (row-major), xyz + rpy (6 numbers, R =
    Rz(y) Ry(p) Rx(r)) or xyz + quaternion x, y, z, w (7 numbers). Not validated beyond its shape and finiteness
    (ik checks the last row and the rotation)."""
    a = _array(pose, "pose")
    if not np.all(np.isfinite(a)):
        raise InvalidInput("pose: values must be finite")
    if a.ndim == 1 and a.size in (6, 7):
        out = np.eye(4)
        out[:3, 3] = a[:3]
        out[:3, :3] = _rpy_matrix(*a[3:]) if a.size == 6 else _quat_matrix(*a[3:])
        return out
    if a.ndim == 1 and a.size in (12, 16):
        a = a.reshape(-1, 4)
    if a.shape not in ((3, 4), (4, 4)):
        raise InvalidInput(f"pose: expected a 4x4 or 3x4 matrix, 12 / 16 numbers, xyz + rpy (6) or xyz + "
                           f"quaternion (7), got shape {a.shape}")
    out = np.eye(4)
    out[:a.shape[0]] = a
    return out
