"""The symbolic checks every derivation step relies on: the ideal-reduction prover must prove true trigonometric
identities, never a false one, and hand the cases it does not cover to the simplifier."""

import sympy as sp

from derive.checks import symbolic_identity, trig_polynomial_zero
from derive.identities.frames import rot_x, rot_z, rot_zxz

a, b, c, x, y = sp.symbols("a b c x y", real=True)


def test_proves_rotation_identities():
    R = rot_zxz(a, b, c)
    assert all(trig_polynomial_zero(e) for e in R.T * R - sp.eye(3))
    assert trig_polynomial_zero(R.det() - 1)
    # sums of angles are expanded first: Rz(a) Rz(b) = Rz(a + b)
    assert all(trig_polynomial_zero(e) for e in rot_z(a) * rot_z(b) - rot_z(a + b))


def test_proves_rational_and_tangent_identities():
    assert trig_polynomial_zero(sp.tan(a) * sp.cos(a) - sp.sin(a))
    assert trig_polynomial_zero((1 - sp.cos(a) ** 2) / sp.sin(a) - sp.sin(a))
    assert trig_polynomial_zero(sp.sin(2 * a) - 2 * sp.sin(a) * sp.cos(a))
    assert trig_polynomial_zero((x + y) ** 2 - x**2 - 2 * x * y - y**2)


def test_never_proves_a_false_identity():
    assert not trig_polynomial_zero(sp.sin(a) ** 2 - sp.cos(a) ** 2)
    assert not trig_polynomial_zero(sp.sin(a + b) - sp.sin(a) - sp.sin(b))
    assert not trig_polynomial_zero(rot_x(a)[1, 1] - sp.cos(2 * a))
    assert not trig_polynomial_zero(x * sp.cos(a) ** 2 + x * sp.sin(a) ** 2 - x - 1e-30)
    R = rot_zxz(a, b, c)
    assert not trig_polynomial_zero(R.det() + 1)


def test_leaves_related_arguments_and_roots_to_the_simplifier():
    # sin(a) and sin(a/2) are related: not a free pair of circles, so not decided here
    assert not trig_polynomial_zero(sp.sin(a) - 2 * sp.sin(a / 2) * sp.cos(a / 2))
    # roots and other functions of symbols are outside the polynomial ring: not decided here either
    assert not trig_polynomial_zero(sp.sqrt(x) * sp.sqrt(y) - sp.sqrt(x * y))
    assert not trig_polynomial_zero(sp.log(x * y) - sp.log(x) - sp.log(y))
    # ... and the check still proves them through the simplifier
    assert symbolic_identity(sp.sin(a), 2 * sp.sin(a / 2) * sp.cos(a / 2), "double angle").passed


def test_symbolic_identity_fails_a_wrong_formula():
    R = rot_zxz(a, b, c)
    assert symbolic_identity(R.T * R, sp.eye(3), "orthogonal").passed
    assert not symbolic_identity(R[0, 0], sp.cos(a) * sp.cos(c), "wrong entry").passed
