"""Checks of the plain-numpy DH reference (tests/reference/dh.py) against the slides' printed matrices.

Every expected matrix below is typed in from the printed closed forms, not computed by the reference.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from reference.dh import (
    MECHANISMS,
    finite_difference_jacobian,
    fk,
    frames,
    geometric_jacobian,
    ik_reference,
    jacobian_fd_error,
    joint_distance,
    link_matrices,
    pose_error,
    random_joints,
    wrap_angle,
    wrap_joints,
)
from seeding import case_rng

c, s = math.cos, math.sin
N_RANDOM = 10


def _rng(tag: int) -> np.random.Generator:
    return case_rng(20240 + tag)


def _homog(top: list[list[float]]) -> np.ndarray:
    return np.vstack([np.array(top, dtype=float), [0.0, 0.0, 0.0, 1.0]])


# --------------------------------------------------------------------------------------------
# Printed matrices
# --------------------------------------------------------------------------------------------


@pytest.mark.parametrize("k", range(N_RANDOM))
def test_spherical_wrist_links_and_T63(k):
    rng = _rng(k)
    d6 = 0.1 + 0.2 * rng.random()
    t4, t5, t6 = rng.uniform(-math.pi, math.pi, 3)
    A4, A5, A6 = link_matrices("spherical_wrist", [t4, t5, t6], {"d6": d6})
    np.testing.assert_allclose(A4, _homog([[c(t4), 0, -s(t4), 0], [s(t4), 0, c(t4), 0], [0, -1, 0, 0]]), atol=1e-15)
    np.testing.assert_allclose(A5, _homog([[c(t5), 0, s(t5), 0], [s(t5), 0, -c(t5), 0], [0, 1, 0, 0]]), atol=1e-15)
    np.testing.assert_allclose(A6, _homog([[c(t6), -s(t6), 0, 0], [s(t6), c(t6), 0, 0], [0, 0, 1, d6]]), atol=1e-15)
    c4, s4, c5, s5, c6, s6 = c(t4), s(t4), c(t5), s(t5), c(t6), s(t6)
    T63 = _homog([
        [c4 * c5 * c6 - s4 * s6, -c4 * c5 * s6 - s4 * c6, c4 * s5, c4 * s5 * d6],
        [s4 * c5 * c6 + c4 * s6, -s4 * c5 * s6 + c4 * c6, s4 * s5, s4 * s5 * d6],
        [-s5 * c6, s5 * s6, c5, c5 * d6],
    ])
    np.testing.assert_allclose(fk("spherical_wrist", [t4, t5, t6], {"d6": d6}), T63, atol=1e-14)


@pytest.mark.parametrize("k", range(N_RANDOM))
def test_rpp_T30(k):
    rng = _rng(100 + k)
    d1 = 0.5 + 0.3 * rng.random()
    t1 = rng.uniform(-math.pi, math.pi)
    d2, d3 = rng.uniform(-1.0, 1.0, 2)
    T30 = frames("rpp_wrist", [t1, d2, d3, 0.3, -0.2, 0.1], {"d1": d1})[2]
    expected = _homog([[c(t1), 0, -s(t1), -s(t1) * d3], [s(t1), 0, c(t1), c(t1) * d3], [0, -1, 0, d1 + d2]])
    np.testing.assert_allclose(T30, expected, atol=1e-14)


@pytest.mark.parametrize("k", range(N_RANDOM))
def test_rpp_full_is_T30_times_wrist(k):
    rng = _rng(150 + k)
    q = random_joints("rpp_wrist", rng)
    T30 = frames("rpp_wrist", q)[2]
    np.testing.assert_allclose(fk("rpp_wrist", q), T30 @ fk("spherical_wrist", q[3:]), atol=1e-14)


@pytest.mark.parametrize("k", range(N_RANDOM))
def test_scara_T40(k):
    rng = _rng(200 + k)
    a1, a2, d4 = 0.4 + 0.1 * rng.random(), 0.3 + 0.1 * rng.random(), 0.1 + 0.1 * rng.random()
    t1, t2, t4 = rng.uniform(-math.pi, math.pi, 3)
    d3 = rng.uniform(-0.5, 0.5)
    c12, s12, c4, s4 = c(t1 + t2), s(t1 + t2), c(t4), s(t4)
    expected = _homog([
        [c12 * c4 + s12 * s4, -c12 * s4 + s12 * c4, 0, a1 * c(t1) + a2 * c12],
        [s12 * c4 - c12 * s4, -s12 * s4 - c12 * c4, 0, a1 * s(t1) + a2 * s12],
        [0, 0, -1, -d3 - d4],
    ])
    T = fk("scara_wrist", [t1, t2, d3, t4], {"a1": a1, "a2": a2, "d4": d4})
    np.testing.assert_allclose(T, expected, atol=1e-14)


def test_wrist_1dof():
    for t in np.linspace(-3, 3, 7):
        expected = _homog([[c(t), -s(t), 0, 0], [s(t), c(t), 0, 0], [0, 0, 1, 0.1]])
        np.testing.assert_allclose(fk("wrist_1dof", [t]), expected, atol=1e-15)


def test_puma_zero_pose_printed():
    # No sourced numeric value is asserted here; the zero pose is printed for the record (pytest -s).
    T = fk("puma560", np.zeros(6))
    print("PUMA-560 (Corke standard DH) T_6^0 at q = 0:\n", np.array2string(T, precision=6, suppress_small=True))
    np.testing.assert_allclose(T[:3, :3] @ T[:3, :3].T, np.eye(3), atol=1e-15)
    np.testing.assert_allclose(T[3], [0, 0, 0, 1])


# --------------------------------------------------------------------------------------------
# Jacobian
# --------------------------------------------------------------------------------------------


@pytest.mark.parametrize("name", list(MECHANISMS))
def test_jacobian_vs_finite_differences(name):
    rng = _rng(300)
    for _ in range(N_RANDOM):
        q = random_joints(name, rng)
        J = geometric_jacobian(name, q)
        assert J.shape == (6, len(MECHANISMS[name]["joints"]))
        assert jacobian_fd_error(name, q) < 1e-8
    np.testing.assert_allclose(finite_difference_jacobian(name, q), J, atol=1e-8)


def test_wrap():
    assert wrap_angle(math.pi) == pytest.approx(math.pi)
    assert wrap_angle(-math.pi) == pytest.approx(math.pi)
    assert wrap_angle(3 * math.pi / 2) == pytest.approx(-math.pi / 2)
    np.testing.assert_allclose(wrap_joints("rpp_wrist", [7.0, 7.0, -7.0, 7.0, 0, 0]),
                               [7.0 - 2 * math.pi, 7.0, -7.0, 7.0 - 2 * math.pi, 0, 0])
    assert joint_distance("wrist_1dof", [math.pi - 1e-3], [-math.pi + 1e-3]) == pytest.approx(2e-3)


# --------------------------------------------------------------------------------------------
# IK reference
# --------------------------------------------------------------------------------------------

EXPECTED_COUNTS = {"puma560": 8, "rpp_wrist": 4, "scara_wrist": 2, "spherical_wrist": 2, "wrist_1dof": 1}
IK_TRIALS = {"puma560": 10, "rpp_wrist": 10, "scara_wrist": 20, "spherical_wrist": 20, "wrist_1dof": 20}


@pytest.mark.parametrize("name", list(EXPECTED_COUNTS))
def test_ik_reference_round_trip_and_count(name):
    rng = _rng(400 + list(EXPECTED_COUNTS).index(name))
    for _ in range(IK_TRIALS[name]):
        q = random_joints(name, rng)
        T = fk(name, q)
        sols = ik_reference(name, T)
        assert len(sols) == EXPECTED_COUNTS[name], (q, sols)
        assert any(joint_distance(name, q, sol) < 1e-6 for sol in sols), (q, sols)
        for sol in sols:
            assert pose_error(name, sol, T) <= 1e-9
            np.testing.assert_array_equal(sol, wrap_joints(name, sol))
        for i in range(len(sols)):
            for j in range(i):
                assert joint_distance(name, sols[i], sols[j]) > 1e-6


def test_ik_reference_deterministic():
    T = fk("puma560", random_joints("puma560", _rng(500)))
    a, b = ik_reference("puma560", T), ik_reference("puma560", T)
    assert len(a) == len(b) == 8
    for x, y in zip(a, b, strict=True):
        np.testing.assert_array_equal(x, y)


@pytest.mark.parametrize("name", ["wrist_1dof", "spherical_wrist", "scara_wrist"])
def test_ik_reference_unreachable_is_empty(name):
    rng = _rng(600)
    for _ in range(3):
        T = fk(name, random_joints(name, rng))
        T2 = T.copy()
        # tilt the orientation about the base x axis: no longer reachable for these < 6-DOF mechanisms
        a = 0.3
        Rx = np.array([[1, 0, 0], [0, c(a), -s(a)], [0, s(a), c(a)]])
        T2[:3, :3] = Rx @ T[:3, :3]
        T2[:3, 3] = T[:3, 3] + np.array([0.01, 0.02, 0.03])
        assert ik_reference(name, T2) == []


def test_ik_reference_design_override():
    design = {"a1": 0.55, "a2": 0.25, "d4": 0.05}
    q = np.array([0.3, 1.1, -0.2, -2.0])
    T = fk("scara_wrist", q, design)
    sols = ik_reference("scara_wrist", T, design=design)
    assert len(sols) == 2
    assert any(joint_distance("scara_wrist", q, sol) < 1e-6 for sol in sols)
    for sol in sols:
        assert pose_error("scara_wrist", sol, T, design) <= 1e-9
    T1 = fk("wrist_1dof", [0.7], {"dw": 0.25})
    assert ik_reference("wrist_1dof", T1) == []  # z = 0.25 is out of reach for the default dw = 0.1
    (sol,) = ik_reference("wrist_1dof", T1, design={"dw": 0.25})
    assert sol[0] == pytest.approx(0.7, abs=1e-9)
