"""Symbolic geometry of the symmetric 3-RSR (2R1T) parallel wrist of seed 002, shared by the wrist and the hybrid.

Base frame: origin O_B, z the base normal, x along the axis of base joint R1. Leg i (i = 1, 2, 3) has its base joint
axis u_i = Rz(a_i) e_x through O_B, a_i = 2 (i - 1) pi / 3, and its spherical-joint centre at
S_i = Rz(a_i) (0, L cos phi_i, L sin phi_i) (seed eq. 2): the base link O_B S_i is perpendicular to u_i.
The platform is the mirror image of the base about the plane S1 S2 S3 (seed eqs. 3-6).
Wrist pose parameters (seed eq. 9): azimuth alpha, swing beta, centre distance l_bw = |O_B O_W|, with the
mirror-plane normal n = (sin(beta/2) cos alpha, sin(beta/2) sin alpha, cos(beta/2)) and O_W = l_bw n.
"""

from __future__ import annotations

import math

import sympy as sp

from ...identities.frames import E_X, E_Z, rot_z

L = sp.Symbol("L", positive=True)
PHI = sp.symbols("phi1:4", real=True)
ALPHA, BETA, LBW = sp.symbols("alpha beta l_bw", real=True)
LEG_ANGLES = tuple(2 * sp.pi * i / 3 for i in range(3))


def rot_y(a) -> sp.Matrix:
    c, s = sp.cos(a), sp.sin(a)
    return sp.Matrix([[c, 0, s], [0, 1, 0], [-s, 0, c]])


def base_axis(i: int) -> sp.Matrix:
    return rot_z(LEG_ANGLES[i]) * E_X


def leg_point(i: int, phi=None, length=L) -> sp.Matrix:
    phi = PHI[i] if phi is None else phi
    return rot_z(LEG_ANGLES[i]) * sp.Matrix([0, length * sp.cos(phi), length * sp.sin(phi)])


def plane_normal_unnormalised(points) -> sp.Matrix:
    """N = S1S2 x S1S3 (seed eq. 3's construction; |N| = twice the area of the triangle S1 S2 S3)."""
    s1, s2, s3 = points
    return (s2 - s1).cross(s3 - s1)


def mirror_normal(alpha=ALPHA, beta=BETA) -> sp.Matrix:
    return sp.Matrix([sp.sin(beta / 2) * sp.cos(alpha), sp.sin(beta / 2) * sp.sin(alpha), sp.cos(beta / 2)])


def reflection(n: sp.Matrix) -> sp.Matrix:
    """Linear part of the reflection about a plane with unit normal n."""
    return sp.eye(3) - 2 * n * n.T


def platform_rotation_mirror(n: sp.Matrix) -> sp.Matrix:
    """Platform frame built as in seed eqs. 5-6 from mirrored axes: Wx = M u1, Wz = unit(M u1 x M u2), Wy = Wz x Wx.

    M is improper, so M u1 x M u2 = -M (u1 x u2) and the frame is M diag(1, 1, -1).
    """
    return reflection(n) * sp.diag(1, 1, -1)


def tilt_rotation(alpha=ALPHA, beta=BETA) -> sp.Matrix:
    """Zero-torsion tilt: rotation by beta about the horizontal axis (-sin alpha, cos alpha, 0)."""
    return rot_z(alpha) * rot_y(beta) * rot_z(-alpha)


def leg_equation_coefficients(i: int, alpha=ALPHA, beta=BETA):
    """n . S_i = L (A_i cos phi_i + B sin phi_i): A_i = sin(beta/2) sin(alpha - a_i), B = cos(beta/2)."""
    return sp.sin(beta / 2) * sp.sin(alpha - LEG_ANGLES[i]), sp.cos(beta / 2)


__all__ = ["ALPHA", "BETA", "E_Z", "L", "LBW", "LEG_ANGLES", "PHI", "base_axis", "leg_equation_coefficients",
           "leg_point", "mirror_normal", "plane_normal_unnormalised", "platform_rotation_mirror", "reflection",
           "rot_y", "tilt_rotation"]


def seed_fd(beta_deg: float) -> float:
    """The seed's fitted maximum (rotation - azimuth) difference f_d(beta), degrees."""
    k1, k2, k3, k4, k5, w = 54.02, -53.32, -12.04, -0.6695, 5.766, 0.01853
    b = beta_deg * w
    return k1 + k2 * math.cos(b) + k3 * math.sin(b) + k4 * math.cos(2 * b) + k5 * math.sin(2 * b)


def max_gamma_difference(beta: float) -> float:
    """max over alpha1 of gamma - alpha1 (degrees) for our gamma: asin(tan^2(beta/2)) in closed form."""
    return math.degrees(math.asin(math.tan(beta / 2) ** 2))
