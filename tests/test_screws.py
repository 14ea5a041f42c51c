"""Finite screws (seed 003): conversions, the triangle product (Sa triangle Sb = Sb first, T(Sa) @ T(Sb)), group
laws, the half-turn singularity and chain displacement versus the product of exponentials."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import sympy as sp
from seeding import case_rng

from derive.identities.screws import (
    JointAxis,
    ScrewSingularity,
    chain_displacement,
    finite_screw,
    joint_symbols,
    np_finite_screw,
    np_poe,
    np_screw_to_transform,
    np_transform_to_screw,
    np_triangle,
    random_chain,
    random_screw,
    random_unit,
    screw_axis,
    screw_to_transform,
    transform_to_screw,
    triangle,
)

ROOT = Path(__file__).resolve().parent.parent

TOL = 1e-9


def _np(m) -> np.ndarray:
    return np.array(sp.Matrix(m).evalf(), dtype=float)


def _pair(rng):
    while True:
        Sa, Sb = random_screw(rng), random_screw(rng)
        if abs(1 - Sa[:3] @ Sb[:3] / 4) > 0.05:
            return Sa, Sb


def test_round_trip_random_screws():
    rng = case_rng(3)
    for _ in range(200):
        S = random_screw(rng)
        T = np_screw_to_transform(S)
        assert np.allclose(T[:3, :3] @ T[:3, :3].T, np.eye(3), atol=TOL)
        assert np.allclose(np_transform_to_screw(T), S, atol=TOL)
    for _ in range(10):  # the SymPy functions agree with the numpy helpers
        S = random_screw(rng)
        T = screw_to_transform(S)
        assert np.allclose(_np(T), np_screw_to_transform(S), atol=TOL)
        assert np.allclose(_np(transform_to_screw(T)).ravel(), S, atol=TOL)


def test_axis_parameters_recovered():
    rng = case_rng(4)
    for _ in range(20):
        s, th, t = random_unit(rng), rng.uniform(0.1, 3.0), rng.uniform(-2, 2)
        r = rng.uniform(-2, 2, 3)
        foot = r - (r @ s) * s
        ax = screw_axis(np_finite_screw(s, r, th, t))
        assert math.isclose(float(ax.theta), th, abs_tol=TOL)
        assert np.allclose(_np(ax.s).ravel(), s, atol=TOL)
        assert np.allclose(_np(ax.r).ravel(), foot, atol=TOL)
        assert math.isclose(float(ax.t), t, abs_tol=TOL)
    ax = screw_axis((0, 0, 0, 0, 3, 4))  # pure translation
    assert ax.theta == 0 and ax.t == 5


def test_finite_screw_matches_chasles_transform():
    rng = case_rng(5)
    for _ in range(10):
        s, r, th, t = random_unit(rng), rng.uniform(-1, 1, 3), rng.uniform(-3, 3), rng.uniform(-1, 1)
        K = np.array([[0, -s[2], s[1]], [s[2], 0, -s[0]], [-s[1], s[0], 0]])
        R = np.eye(3) + np.sin(th) * K + (1 - np.cos(th)) * K @ K
        T = screw_to_transform(finite_screw(s, r, th, t))
        assert np.allclose(_np(T[:3, :3]), R, atol=TOL)
        assert np.allclose(_np(T[:3, 3]).ravel(), (np.eye(3) - R) @ r + t * s, atol=TOL)


def test_triangle_is_transform_product_right_factor_first():
    rng = case_rng(6)
    worst_swapped = np.inf
    for _ in range(300):
        Sa, Sb = _pair(rng)
        Ta, Tb = np_screw_to_transform(Sa), np_screw_to_transform(Sb)
        assert np.allclose(np_screw_to_transform(np_triangle(Sa, Sb)), Ta @ Tb, atol=TOL)
        worst_swapped = min(worst_swapped, np.abs(np_screw_to_transform(np_triangle(Sa, Sb)) - Tb @ Ta).max())
    assert worst_swapped > 1e-6  # not commutative: the order convention matters
    Sa, Sb = _pair(rng)
    assert np.allclose(_np(triangle(Sa, Sb)).ravel(), np_triangle(Sa, Sb), atol=TOL)


def test_identity_inverse_associativity():
    rng = case_rng(7)
    zero = np.zeros(6)
    for _ in range(100):
        S = random_screw(rng)
        assert np.allclose(np_triangle(zero, S), S, atol=TOL)
        assert np.allclose(np_triangle(S, zero), S, atol=TOL)
        assert np.allclose(np_triangle(S, -S), zero, atol=TOL)
        assert np.allclose(np_screw_to_transform(-S), np.linalg.inv(np_screw_to_transform(S)), atol=TOL)
        Sa, Sb, Sc = (random_screw(rng, max_angle=1.2) for _ in range(3))
        left, right = np_triangle(np_triangle(Sa, Sb), Sc), np_triangle(Sa, np_triangle(Sb, Sc))
        assert np.allclose(left, right, rtol=TOL, atol=TOL)


@pytest.mark.parametrize("theta", [math.pi, -math.pi, sp.pi, -sp.pi, 3 * sp.pi])
def test_half_turn_raises(theta):
    with pytest.raises(ScrewSingularity):
        finite_screw((0, 0, 1), (1, 0, 0), theta, 0.5)
    if isinstance(theta, float):
        with pytest.raises(ScrewSingularity):
            np_finite_screw((0, 0, 1), (1, 0, 0), theta, 0.5)


def test_half_turn_in_conversions_and_products():
    half = np.diag([1.0, -1.0, -1.0, 1.0])  # rotation by pi about x
    with pytest.raises(ScrewSingularity):
        np_transform_to_screw(half)
    with pytest.raises(ScrewSingularity):
        transform_to_screw(sp.Matrix(half.astype(int)))
    quarter = finite_screw((0, 0, 1), (0, 0, 0), sp.pi / 2)
    with pytest.raises(ScrewSingularity):
        triangle(quarter, quarter)
    with pytest.raises(ScrewSingularity):
        np_triangle(_np(quarter).ravel(), _np(quarter).ravel())
    assert isinstance(ScrewSingularity("x"), ValueError)


def test_chain_displacement_equals_poe_random_5_joint_chains():
    rng = case_rng(8)
    qs = joint_symbols(5)
    # a random R/P mix, all revolute and prismatic-first: the kinds of chain the induction covers (each chain is a
    # symbolic 5-joint product, ~5 s; two more random mixes added 10 s and no kind of chain)
    chains = [random_chain(rng, 5)] + [
        [JointAxis("R", tuple(random_unit(rng)), tuple(rng.uniform(-1, 1, 3))) for _ in range(5)],
        [JointAxis(k, tuple(random_unit(rng)), tuple(rng.uniform(-1, 1, 3))) for k in "PPPRR"]]
    for axes in chains:
        f = sp.lambdify(qs, chain_displacement(axes, qs), "numpy")
        checked = 0
        while checked < 5:
            vals = rng.uniform(-2, 2, 5)
            poe = np_poe(axes, vals)
            if 1 + np.trace(poe[:3, :3]) < 1e-3:  # total rotation near a half turn: no finite screw
                continue
            S = np.asarray(f(*vals), dtype=float).reshape(6)
            assert np.allclose(np_screw_to_transform(S), poe, atol=1e-8)
            checked += 1


def test_chain_is_symbolic_in_joint_variables():
    axes = [JointAxis("R", (0, 0, 1)), JointAxis("P", (1, 0, 0)), JointAxis("R", (0, 0, 1), (1, 0, 0))]
    S = chain_displacement(axes)
    assert S.free_symbols == set(joint_symbols(3))
    q1, q2, q3 = joint_symbols(3)
    Sq = S.subs({q1: 0, q3: 0})
    assert sp.simplify(Sq - sp.Matrix([0, 0, 0, q2, 0, 0])) == sp.zeros(6, 1)


def test_derivation_all_checks_pass():
    """The algebra's steps are part of both screw robots' derivations: their committed reports (fresh by the drift
    check) show every step and its checks, so reading them costs nothing (deriving again took 20 s)."""
    for robot in ("p1p2p3rarb", "rarararbrb"):
        text = (ROOT / "generated" / "audit" / f"{robot}.md").read_text()
        for step in ("triangle_product", "group_laws", "first_order", "chain_displacement"):
            assert step in text, (robot, step)
        assert "FAILED" not in text and "symbolic identity: proven" in text and "numeric, " in text
