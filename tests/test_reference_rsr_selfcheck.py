"""Trust checks for the independent numeric reference of the 3-RSR wrist and the SCARA + 3-RSR robot.

The reference (tests/reference/rsr.py) is what generated solvers are tested against, so it is
itself checked here: IK legs against the raw loop equations and against FK, the leg root count
against the amplitude of the distance sinusoid, the analytic constraint Jacobian against finite
differences, and the hybrid IK against the joints that generated the target. Seeded, fast (< 20 s).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from reference.rsr import (
    DEFAULT_L,
    HybridDesign,
    base_axis,
    constraint_jacobian,
    constraint_residual,
    constraint_singularity_measure,
    expm_so3,
    fk_all,
    fk_contains,
    fk_symmetric,
    hybrid_fk_all,
    hybrid_fk_with_wrist,
    hybrid_ik_all,
    hybrid_ik_contains,
    ik_all,
    ik_leg,
    is_assembly,
    is_mirror_symmetric,
    leg_point,
    mount_transform,
    params_from_pose,
    pose_from_params,
    scara_fk,
)
from seeding import case_rng

DEG = math.pi / 180.0
L = DEFAULT_L


def _random_params(n: int, seed: int) -> list[tuple[float, float, float]]:
    """(alpha, beta, l_bw) with alpha, beta in (0, 60 deg) and l_bw in (0.04, 0.1) m."""
    rng = case_rng(seed)
    return [(rng.uniform(0.0, 60.0) * DEG, rng.uniform(0.0, 60.0) * DEG, rng.uniform(0.04, 0.1)) for _ in range(n)]


def _expected_leg_root_count(i: int, p: np.ndarray) -> int:
    """|S_i(phi) - p|^2 - L^2 = |p|^2 - 2 L (cos phi (v_i . p) + sin phi p_z) with v_i = Rz(a_i) e_y:
    a sinusoid, so 2 roots if its amplitude exceeds |p|^2, 0 if below (1 only at equality)."""
    v = np.cross(np.array([0.0, 0.0, 1.0]), base_axis(i))
    amp = 2.0 * L * math.hypot(v @ p, p[2])
    return 2 if amp > p @ p else 0


@pytest.mark.parametrize("params", _random_params(12, seed=101))
def test_ik_legs_close_the_loops_and_counts(params):
    R, p = pose_from_params(*params)
    for i in (1, 2, 3):
        leg = ik_leg(i, R, p, L)
        assert len(leg.roots) in (0, 1, 2)
        assert len(leg.roots) == _expected_leg_root_count(i, p)
    triples = ik_all(R, p, L)
    assert len(triples) == 8
    for phis in triples:
        assert np.max(np.abs(constraint_residual(R, p, phis, L))) < 1e-14
        assert is_assembly(R, p, phis, L, tol=1e-12)


@pytest.mark.parametrize("params", _random_params(4, seed=202))
def test_fk_all_contains_posed_platform(params):
    R, p = pose_from_params(*params)
    triples = ik_all(R, p, L)
    phis = triples[len(triples) // 2]
    modes = fk_all(phis, L)
    assert fk_contains(phis, L, R, p, tol=1e-8, modes=modes)
    for Rm, pm in modes:
        assert np.max(np.abs(constraint_residual(Rm, pm, phis, L))) < 1e-12
        assert np.max(np.abs(Rm.T @ Rm - np.eye(3))) < 1e-12
    # the mirror-symmetric mode is found numerically and is exactly the posed one
    sym = [m for m in modes if is_mirror_symmetric(*m)]
    assert len(sym) == 1
    assert np.max(np.abs(sym[0][0] - R)) < 1e-9 and np.max(np.abs(sym[0][1] - p)) < 1e-9


def test_fk_modes_distinct_sorted_and_deterministic():
    phis = (0.4, 1.1, -0.3)
    a = fk_all(phis, L, seed=3)
    b = fk_all(phis, L, seed=3)
    assert len(a) == len(b) and len(a) >= 2
    for (Ra, pa), (Rb, pb) in zip(a, b, strict=True):
        assert np.array_equal(Ra, Rb) and np.array_equal(pa, pb)
    for k, (Rk, pk) in enumerate(a):
        for Rj, pj in a[:k]:
            assert max(np.max(np.abs(Rk - Rj)), np.max(np.abs(pk - pj)) / L) > 1e-6
    # the coincident pose (I, 0) always closes the loops (S_i . u_i = 0, |S_i| = L)
    assert is_assembly(np.eye(3), np.zeros(3), phis, L, tol=1e-15)
    assert fk_contains(phis, L, np.eye(3), np.zeros(3), modes=a)
    far = fk_all(phis, L, n_starts=500, include_coincident=False)
    assert far and all(np.linalg.norm(m[1]) > 1e-6 * L for m in far)


def test_fk_symmetric_round_trip_from_actuated_angles():
    phis = (0.5, 0.8, 0.2)
    (R, p), = fk_symmetric(phis, L)
    alpha, beta, l_bw = params_from_pose(R, p)
    R2, p2 = pose_from_params(alpha, beta, l_bw)
    assert np.max(np.abs(R2 - R)) < 1e-12 and np.max(np.abs(p2 - p)) < 1e-12
    assert any(np.max(np.abs(np.array(t) - phis)) < 1e-9 for t in ik_all(R, p, L))


def test_params_round_trip():
    for params in _random_params(20, seed=7):
        got = params_from_pose(*pose_from_params(*params))
        assert np.allclose(got, params, atol=1e-12)


def test_residual_zero_on_family():
    for params in _random_params(20, seed=8):
        R, p = pose_from_params(*params)
        for phis in ik_all(R, p, L):
            assert np.max(np.abs(constraint_residual(R, p, phis, L))) < 1e-14
        # S_i are on the base link circle: |S_i| = L, S_i . u_i = 0
        for i, phi in zip((1, 2, 3), ik_all(R, p, L)[0], strict=True):
            s = leg_point(i, phi, L)
            assert abs(np.linalg.norm(s) - L) < 1e-15 and abs(s @ base_axis(i)) < 1e-15


def test_ik_unreachable_is_empty():
    R, p = pose_from_params(0.3, 0.4, 2.5 * L)  # |p| > 2L: no leg can reach
    assert ik_all(R, p, L) == []
    R, p = pose_from_params(0.3, 0.4, 0.07)
    assert ik_all(expm_so3([0.0, 0.0, 0.3]) @ R, p, L) == []  # rotated off the family


def test_constraint_jacobian_matches_finite_differences():
    R, p = pose_from_params(0.4, 0.6, 0.07)
    phis = ik_all(R, p, L)[0]
    J = constraint_jacobian(R, p, phis, L)
    h = 1e-6
    Jn = np.zeros((6, 6))
    for k in range(6):
        e = np.zeros(6)
        e[k] = h
        plus = constraint_residual(expm_so3(e[:3]) @ R, p + e[3:], phis, L)
        minus = constraint_residual(expm_so3(-e[:3]) @ R, p - e[3:], phis, L)
        Jn[:, k] = (plus - minus) / (2.0 * h)
    assert np.max(np.abs(J - Jn)) < 1e-8
    assert 0.0 < constraint_singularity_measure(R, p, phis, L) <= 1.0


def test_scara_modified_dh_against_hand_formula():
    ds = HybridDesign(d=0.1)
    t1, t2, d3, t4 = 0.3, -0.7, 0.05, 1.1
    T = scara_fk((t1, t2, d3, t4), ds)
    x = ds.L1 * math.cos(t1) + ds.L2 * math.cos(t1 + t2)
    y = ds.L1 * math.sin(t1) + ds.L2 * math.sin(t1 + t2)
    c, s = math.cos(t1 + t2 + t4), math.sin(t1 + t2 + t4)
    assert np.allclose(T[:3, 3], [x, y, ds.d - d3], atol=1e-15)
    assert np.allclose(T[:3, :3], [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]], atol=1e-15)


def _random_hybrid_joints(n: int, seed: int, ds: HybridDesign):
    """q from random SCARA joints and a random posed wrist (legs from ik_all), with T and l_bw."""
    rng = case_rng(seed)
    out = []
    for alpha, beta, l_bw in _random_params(n, seed + 1):
        R, p = pose_from_params(alpha, beta, l_bw)
        triples = ik_all(R, p, ds.L)
        phis = triples[int(rng.integers(len(triples)))]
        qs = [rng.uniform(-math.pi, math.pi), rng.uniform(-math.pi, math.pi), rng.uniform(-0.1, 0.2),
              rng.uniform(-math.pi, math.pi)]
        q = np.array(qs + list(phis))
        out.append((q, hybrid_fk_with_wrist(q[:4], R, p, ds), l_bw))
    return out


@pytest.mark.parametrize("case", range(4))
def test_hybrid_ik_recovers_generating_joints(case):
    ds = HybridDesign()
    q, T, l_bw = _random_hybrid_joints(4, seed=303, ds=ds)[case]
    sols = hybrid_ik_all(T, l_bw, ds)
    assert hybrid_ik_contains(sols, q)
    assert len(sols) == 16  # 2 SCARA elbows x 2^3 leg roots
    for s in sols:
        R, p = pose_from_params(*params_from_pose(np.eye(3), _wrist_position(s, T, ds)))
        assert np.max(np.abs(hybrid_fk_with_wrist(s[:4], R, p, ds) - T)) < 1e-10
        assert is_assembly(R, p, s[4:], ds.L, tol=1e-9)


def _wrist_position(q: np.ndarray, T: np.ndarray, ds: HybridDesign) -> np.ndarray:
    """p_w = (T_s T_c)^-1 applied to the target origin."""
    M = scara_fk(q[:4], ds) @ mount_transform(ds)
    return np.linalg.solve(M, T[:, 3])[:3]


def test_hybrid_fk_all_contains_generating_pose():
    ds = HybridDesign()
    q, T, _ = _random_hybrid_joints(1, seed=404, ds=ds)[0]
    assert any(np.max(np.abs(Tm - T)) < 1e-9 for Tm in hybrid_fk_all(q, ds))


def test_ik_leg_tangential_double_root():
    # |p| = 2L in the plane of leg 1: the leg is fully stretched, one double root at S_1 = p / 2
    p = 2.0 * L * np.array([0.0, math.cos(0.7), math.sin(0.7)])
    leg = ik_leg(1, np.eye(3), p, L)
    assert len(leg.distance_roots) == 1
    assert abs(leg.distance_roots[0] - 0.7) < 1e-6
