"""Spherical-geometry identities for mechanisms whose joint axes meet at one point.

Notation follows Crane & Duffy (Kinematic Analysis of Robot Manipulators): a
spherical polygon is walked vertex to vertex; s_ij, c_ij are the sine and cosine
of the side (twist) between axes i and j, s_j, c_j those of the exterior angle at
vertex j. The direction cosines of a vertex, expressed in the frame of the first
vertex, are the product of elementary rotations Rx(side) Rz(angle); the sine,
sine-cosine and cosine laws are the rows of that product.
"""

from __future__ import annotations

import sympy as sp

from .frames import E_Z, rot_x, rot_z


def polygon_vertex(sides, exterior_angles) -> sp.Matrix:
    """Direction of the last vertex of an open spherical polygon.

    sides[k] is the arc from vertex k to k+1, exterior_angles[k] the exterior angle at
    vertex k+1 (one fewer angle than sides). Vertex 0 is e_z of the reference frame and
    the first side lies in the y-z plane (X axis = Z x Z_1 convention).
    """
    if len(exterior_angles) != len(sides) - 1:
        raise ValueError("need exactly one exterior angle between consecutive sides")
    m = rot_x(sides[0])
    for side, angle in zip(sides[1:], exterior_angles, strict=True):
        m = m * rot_z(angle) * rot_x(side)
    return m * E_Z


def triangle_direction_cosines(s12, c12, s23, c23, s2, c2) -> sp.Matrix:
    """Crane-Duffy direction cosines of vertex 3 of a spherical triangle (in frame of vertex 1).

    X2 = s23 s2 (sine law), Y2 = -(s12 c23 + c12 s23 c2) (sine-cosine law),
    Z2 = c12 c23 - s12 s23 c2 (cosine law).
    """
    return sp.Matrix([s23 * s2, -(s12 * c23 + c12 * s23 * c2), c12 * c23 - s12 * s23 * c2])


def cos_angle_between_cone_axes(half_angle) -> sp.Expr:
    """Cosine of the angle between two of three axes 120 deg apart on a cone of given half-angle."""
    return 1 - sp.Rational(3, 2) * sp.sin(half_angle) ** 2


def equilateral_interior_angle_cos(side) -> sp.Expr:
    """cos of the interior angle of an equilateral spherical triangle (law of cosines for sides)."""
    return sp.cos(side) / (1 + sp.cos(side))
