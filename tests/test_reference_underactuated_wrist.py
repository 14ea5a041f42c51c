"""Trust checks for the independent numeric reference of the underactuated 3-DOF spherical wrist.

The reference (tests/reference/underactuated_wrist.py) is what generated solvers are tested
against, so it is itself checked here: against the loop equations, against a second FK built
a different way (multistart least squares), round trips, constructed degenerate configurations,
and the paper's Table 2.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from reference.underactuated_wrist import (
    PAPER_DESIGN,
    base_axes,
    euler_from_rotation,
    expm_so3,
    fk_count_census,
    fk_jacobian,
    fk_reference,
    fk_reference_multistart,
    home_angle,
    ik_branch_function,
    ik_reference,
    loop_residuals,
    middle_axes,
    middle_axis,
    platform_axes,
    rotation_from_euler,
)
from scipy.optimize import brentq
from seeding import case_rng

DEG = math.pi / 180.0
FIXTURES = Path(__file__).parent / "reference" / "fk_count_cases.json"


def _orientations(n: int, seed: int, max_nutation_deg: float = 25.0, max_twist_deg: float = 60.0):
    """Seeded orientations near the working range: small nutation, bounded psi + phi."""
    rng = case_rng(seed)
    out = []
    for _ in range(n):
        psi = rng.uniform(-math.pi, math.pi)
        twist = rng.uniform(-max_twist_deg, max_twist_deg) * DEG
        out.append(rotation_from_euler(psi, rng.uniform(0.0, max_nutation_deg) * DEG, twist - psi))
    return out


# test_fk_matches_multistart: a converged LM point's residual (the loop's rounding), and how far from a converged
# point a stalled one may lie: sqrt(res_tol = 1e-10) for a curvature of order 1
ROUNDING = 1e-14
STALL_SPREAD = 1e-5


def _min_dist(R: np.ndarray, mats: list[np.ndarray]) -> float:
    return min((float(np.linalg.norm(R - M)) for M in mats), default=math.inf)


def _rotation_taking(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """A proper rotation with R a = b (unit vectors)."""
    ax = np.cross(a, b)
    s = np.linalg.norm(ax)
    if s < 1e-15:
        perp = np.cross(a, [1.0, 0.0, 0.0] if abs(a[0]) < 0.9 else [0.0, 1.0, 0.0])
        return expm_so3(math.pi * perp / np.linalg.norm(perp)) if a @ b < 0 else np.eye(3)
    return expm_so3(ax / s * math.atan2(s, a @ b))


# ------------------------------------------------------------------------------------------
# Rotations and design
# ------------------------------------------------------------------------------------------


def test_euler_roundtrip():
    rng = case_rng(0)
    for _ in range(200):
        psi, phi = rng.uniform(-math.pi, math.pi, 2)
        th = rng.uniform(1e-3, math.pi - 1e-3)
        R = rotation_from_euler(psi, th, phi)
        assert np.allclose(R @ R.T, np.eye(3), atol=1e-14) and abs(np.linalg.det(R) - 1) < 1e-14
        p, t, f, degenerate = euler_from_rotation(R)
        assert not degenerate
        assert np.allclose([p, t, f], [psi, th, phi], atol=1e-10)


@pytest.mark.parametrize("theta", [0.0, math.pi])
def test_euler_degenerate_flag(theta):
    R = rotation_from_euler(0.7, theta, -0.2)
    psi, th, phi, degenerate = euler_from_rotation(R)
    assert degenerate and phi == 0.0 and abs(th - theta) < 1e-12
    assert np.allclose(rotation_from_euler(psi, th, phi), R, atol=1e-14)


def test_design_geometry():
    d = PAPER_DESIGN
    # alpha3 from the spherical law of cosines on the platform (axes 120 deg apart, beta2 off-axis).
    cos_a3 = math.cos(d.beta2) ** 2 + math.sin(d.beta2) ** 2 * math.cos(2 * math.pi / 3)
    assert abs(d.alpha3 - math.acos(cos_a3)) < 1e-14
    # Base axes: beta1 away from -z, azimuths 120 deg apart; middle axes alpha1 from their base axis.
    Z1 = base_axes()
    assert np.allclose(Z1[:, 2], -math.cos(d.beta1), atol=1e-15)
    cos_11 = math.cos(d.beta1) ** 2 + math.sin(d.beta1) ** 2 * math.cos(2 * math.pi / 3)
    assert np.allclose([Z1[i] @ Z1[j] for i, j in ((0, 1), (1, 2), (2, 0))], cos_11, atol=1e-15)
    for i in range(3):
        z2 = middle_axis(i, np.linspace(0, 2 * math.pi, 7))
        assert np.allclose(np.linalg.norm(z2, axis=-1), 1.0, atol=1e-15)
        assert np.allclose(z2 @ Z1[i], math.cos(d.alpha1), atol=1e-15)
    assert np.allclose(np.linalg.norm(platform_axes(), axis=1), 1.0, atol=1e-15)


# ------------------------------------------------------------------------------------------
# Inverse kinematics
# ------------------------------------------------------------------------------------------


def test_home_angle():
    theta0 = home_angle()
    assert abs(theta0 / DEG - 140.1479636) < 1e-6
    res = ik_reference(np.eye(3))
    assert res.flags == ("ok", "ok", "ok")
    for roots in res.roots:
        assert len(roots) == 2
        assert abs(roots[0] - theta0) < 1e-12
        assert abs(roots[1] / DEG - 219.8520364) < 1e-6
        assert abs(roots[0] + roots[1] - 2 * math.pi) < 1e-12
    assert np.max(np.abs(loop_residuals([theta0] * 3, np.eye(3)))) < 1e-15


def test_ik_roots_satisfy_loops():
    # at least 20 reachable orientations are checked whatever the test seed: a batch of 20 wide orientations is
    # added until they are there (19 of the 60 first ones were reachable at WRISTKIN_TEST_SEED=850437)
    Rs = _orientations(40, seed=1) + _orientations(20, seed=2, max_nutation_deg=90, max_twist_deg=180)
    n_reachable, extra = 0, 0
    while Rs:
        R = Rs.pop(0)
        res = ik_reference(R)
        for i, roots in enumerate(res.roots):
            assert all(0.0 <= t < 2 * math.pi for t in roots)
            assert len(roots) in (0, 2)  # generic orientations: two simple roots or none
            assert res.flags[i] == ("ok" if roots else "unreachable")
            if roots:
                assert np.max(np.abs(ik_branch_function(i, R)(np.array(roots)))) < 1e-12
        assert len(res.triples) == math.prod(len(r) for r in res.roots)
        n_reachable += bool(res.triples)
        for t in res.triples:
            assert np.max(np.abs(loop_residuals(t, R))) < 1e-12
        if not Rs and n_reachable < 20 and extra < 10:
            extra += 1
            Rs = _orientations(20, seed=100 + extra, max_nutation_deg=90, max_twist_deg=180)
    assert n_reachable >= 20


def test_ik_special_flags():
    P = platform_axes()
    Z11 = base_axes()[0]
    a1, a2 = PAPER_DESIGN.alpha1, PAPER_DESIGN.alpha2

    # Platform axis on the base axis: alpha1 == alpha2, so every theta_1 closes loop 1.
    res = ik_reference(_rotation_taking(P[0], Z11))
    assert res.flags[0] == "indeterminate" and res.roots[0] == [] and res.triples == []

    # Platform axis opposite the base axis: unreachable.
    res = ik_reference(_rotation_taking(P[0], -Z11))
    assert res.flags[0] == "unreachable" and res.triples == []

    # Platform axis exactly alpha1 + alpha2 from the base axis: one double root.
    perp = np.cross(Z11, [0.3, 0.4, 0.5])
    w = expm_so3((a1 + a2) * perp / np.linalg.norm(perp)) @ Z11
    R = _rotation_taking(P[0], w)
    res = ik_reference(R)
    assert res.flags[0] == "tangent" and len(res.roots[0]) == 1
    assert abs(ik_branch_function(0, R)(np.array(res.roots[0]))[0]) <= 1e-12
    assert len(res.triples) == len(res.roots[1]) * len(res.roots[2])
    # Slightly inside: two close simple roots; slightly outside: none.
    for ang, n in ((a1 + a2 - 1e-6, 2), (a1 + a2 + 1e-6, 0)):
        w = expm_so3(ang * perp / np.linalg.norm(perp)) @ Z11
        res = ik_reference(_rotation_taking(P[0], w))
        assert len(res.roots[0]) == n and res.flags[0] == ("ok" if n else "unreachable")


# ------------------------------------------------------------------------------------------
# Forward kinematics
# ------------------------------------------------------------------------------------------


def test_ik_then_fk_recovers_orientation():
    """At least 30 IK triples checked for any test seed: batches of 16 orientations are drawn until there (some
    draws hold unreachable orientations: 24 triples from the first 16 at WRISTKIN_TEST_SEED=125593)."""
    checked = 0
    batches = (_orientations(16, seed=3 + 1000 * k, max_nutation_deg=30, max_twist_deg=70) for k in range(12))
    for R in (R for batch in batches if checked < 30 for R in batch):
        for t in ik_reference(R).triples:
            fk = fk_reference(t)
            assert _min_dist(R, fk.rotations) < 1e-8
            assert fk.count % 2 == 0
            for M in fk.rotations:
                assert np.allclose(M @ M.T, np.eye(3), atol=1e-12) and abs(np.linalg.det(M) - 1) < 1e-12
            assert max(fk.residuals) < 1e-10
            checked += 1
    assert checked >= 30


def test_fk_home():
    fk = fk_reference([home_angle()] * 3)
    assert _min_dist(np.eye(3), fk.rotations) < 1e-12


def _crosscheck_triples():
    triples = []
    for R in _orientations(30, seed=4, max_nutation_deg=40, max_twist_deg=90):
        res = ik_reference(R)
        if res.triples:
            triples.append(res.triples[len(triples) % len(res.triples)])
        if len(triples) == 5:
            break
    cases = json.loads(FIXTURES.read_text())["cases"]
    for count in (0, 2, 4, 6, 8):
        triples.append(next(c["joints"] for c in cases if c["count"] == count))
    return triples


@pytest.mark.parametrize("thetas", _crosscheck_triples())
def test_fk_matches_multistart(thetas):
    fk = fk_reference(thetas)
    ms = fk_reference_multistart(thetas)
    # Between two close roots LM can stall with a residual below its res_tol (1e-10) but far above rounding, next to
    # a point that did converge (WRISTKIN_TEST_SEED=906809: two roots 3.8e-6 apart, both found by the scan and by LM
    # at 1e-16, and a third point 5.2e-7 from one of them at 3.8e-13). Such a stalled point is no root of its own.
    res = ms.residuals
    kept = [M for i, M in enumerate(ms.rotations)
            if not (res[i] > ROUNDING and any(res[k] <= ROUNDING and _min_dist(M, [N]) < STALL_SPREAD
                                              for k, N in enumerate(ms.rotations) if k != i))]
    assert fk.count == len(kept)
    for M in kept:
        assert _min_dist(M, fk.rotations) < 1e-8
    for M in fk.rotations:
        assert _min_dist(M, kept) < 1e-8


# Paper Table 2 (values printed to 0.01 deg), reproduced by the reference: joint angles theta_i
# (exterior angles, deg) -> one FK solution (psi, theta, phi) in deg. Inputs are themselves rounded
# to 0.01 deg, hence the 0.01 deg tolerance.
TABLE2 = [
    ((137.92, 138.44, 137.82), (-35.99, 0.26, 38.93)),
    ((132.96, 134.72, 132.13), (-42.22, 1.00, 52.34)),
    ((120.00, 125.00, 111.29), (-53.71, 3.96, 94.76)),
]


@pytest.mark.parametrize(("joints_deg", "euler_deg"), TABLE2)
def test_paper_table2(joints_deg, euler_deg):
    fk = fk_reference(np.array(joints_deg) * DEG)
    errs = [np.max(np.abs(np.array(e[:3]) / DEG - euler_deg)) for e in fk.euler()]
    assert min(errs) < 0.01
    # And backwards: IK of the printed orientation gives the printed joints (branch in [0, pi]).
    res = ik_reference(rotation_from_euler(*(np.array(euler_deg) * DEG)))
    got = [min(r, key=lambda t, j=j: abs(t / DEG - j)) / DEG
           for r, j in zip(res.roots, joints_deg, strict=True)]
    assert np.max(np.abs(np.array(got) - joints_deg)) < 0.01


def test_fk_root_at_branch_endpoint():
    """A solution whose Z23 is the tangency point of the two circles (mu = 0): the sweep's branch end."""
    P = platform_axes()
    R0 = rotation_from_euler(0.3, 0.25, -0.4)
    ax = np.array([0.3, -0.5, 0.8]) / np.linalg.norm([0.3, -0.5, 0.8])

    def config(lam):
        R = expm_so3(lam * ax) @ R0
        return R, np.array([r[0] for r in ik_reference(R).roots])

    def coplanar(lam):
        R, th = config(lam)
        return np.linalg.det(np.stack([middle_axes(th)[1], R @ P[0], R @ P[1]]))

    lam = brentq(coplanar, -0.17, -0.16, xtol=1e-15)
    R, th = config(lam)
    fk = fk_reference(th)
    assert _min_dist(R, fk.rotations) < 1e-12
    assert fk.count == fk_reference_multistart(th, starts=100).count


def test_fk_near_double_root():
    """Near an FK singularity two solutions merge; both must be found while they are ~1e-4 apart."""
    P = platform_axes()
    R0 = rotation_from_euler(0.3, 0.25, -0.4)
    ax = np.array([0.3, -0.5, 0.8]) / np.linalg.norm([0.3, -0.5, 0.8])

    def config(lam):
        R = expm_so3(lam * ax) @ R0
        roots = ik_reference(R).roots
        return R, np.array([roots[0][0], roots[1][1], roots[2][0]])

    def det_j(lam):
        R, th = config(lam)
        return np.linalg.det(fk_jacobian(th, R))

    lam = brentq(det_j, -0.17, -0.15, xtol=1e-15)
    R, th = config(lam)
    fk = fk_reference(th)
    assert _min_dist(R, fk.rotations) < 1e-6  # double root: only ~sqrt(res_tol) accurate
    # Move the joints across the fold (along the left null vector of the Jacobian).
    u = np.linalg.svd(fk_jacobian(th, R))[0][:, -1]
    h = 1e-7
    dr = np.array([(middle_axis(i, th[i] + h) - middle_axis(i, th[i] - h)) / (2 * h) @ (R @ P[i])
                   for i in range(3)])
    dth = u / dr / np.linalg.norm(u / dr)
    # At the fold itself the reference sees the double root once or, split by rounding into two modes about
    # sqrt(residual tolerance) apart, twice: the count there is 3 or 4. Off the fold by h the two merging
    # modes are about sqrt(h) apart (1e-4 at h = 1e-8), well resolved: 2 on one side, 4 on the other.
    assert fk.count in (3, 4)
    for eps in (1e-4, 1e-6, 1e-8):
        counts = sorted(fk_reference(th + s * eps * dth).count for s in (1.0, -1.0))
        assert counts == [2, 4]


# ------------------------------------------------------------------------------------------
# Solution-count census (fixtures)
# ------------------------------------------------------------------------------------------


def test_count_fixtures():
    doc = json.loads(FIXTURES.read_text())
    assert "fk_reference" in doc["note"]
    assert {c["count"] for c in doc["cases"]} == {0, 2, 4, 6, 8}
    for c in doc["cases"]:
        fk = fk_reference(c["joints"])
        assert fk.count == c["count"]
        for e in c["solutions_zxz_deg"]:
            assert _min_dist(rotation_from_euler(*(np.array(e) * DEG)), fk.rotations) < 1e-6


@pytest.mark.slow
def test_count_fixtures_regenerate():
    """The fixture file is what the reference's census gives: the census draws its samples in order and takes,
    per count, the first stable ones, so a census of the first 600 samples must give a prefix of the fixture's
    cases for every count (the full 3000-sample census, which adds only the distribution printed in the file
    and the README, takes 35 s and is rerun with tests/reference/underactuated_wrist.py when the file changes)."""
    doc = json.loads(FIXTURES.read_text())
    census = fk_count_census(n_samples=600, seed=doc["seed"], stability_step=doc["stability_step_rad"])
    assert census["cases"], "no case in the first 600 samples"
    for count in {c["count"] for c in census["cases"]}:
        got = [c["sample_index"] for c in census["cases"] if c["count"] == count]
        want = [c["sample_index"] for c in doc["cases"] if c["count"] == count]
        assert got == want[:len(got)], count
    assert sum(census["distribution"].values()) == 600
