"""Elementary rotations and frame products (SymPy), the common language of every chain."""

from __future__ import annotations

import sympy as sp

E_X = sp.Matrix([1, 0, 0])
E_Y = sp.Matrix([0, 1, 0])
E_Z = sp.Matrix([0, 0, 1])


def rot_x(a) -> sp.Matrix:
    c, s = sp.cos(a), sp.sin(a)
    return sp.Matrix([[1, 0, 0], [0, c, -s], [0, s, c]])


def rot_z(a) -> sp.Matrix:
    c, s = sp.cos(a), sp.sin(a)
    return sp.Matrix([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def rot_zxz(psi, theta, phi) -> sp.Matrix:
    """ZXZ ('313') Euler rotation: precession psi, nutation theta, self-rotation phi."""
    return rot_z(psi) * rot_x(theta) * rot_z(phi)


def skew(v) -> sp.Matrix:
    return sp.Matrix([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])


def rodrigues(k, c, s) -> sp.Matrix:
    """Rotation about the unit axis k from the (cos, sin) of its angle: I + s [k]x + (1 - c) [k]x^2."""
    kx = skew(k)
    return sp.eye(3) + s * kx + (1 - c) * kx * kx


def zxz_rate_matrix(psi, theta) -> sp.Matrix:
    """E with omega = E * (psi_dot, theta_dot, phi_dot) for R = Rz(psi) Rx(theta) Rz(phi).

    Columns: the world-frame axes of the three elementary rotations.
    """
    col1 = E_Z
    col2 = rot_z(psi) * E_X
    col3 = rot_z(psi) * rot_x(theta) * E_Z
    return sp.Matrix.hstack(col1, col2, col3)
