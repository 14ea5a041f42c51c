"""SCARA + 3-RSR hybrid: generated Python and C against the independent reference (4x4 products, numeric IK)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from reference import rsr as ref
from seeding import case_rng
from wristkin import scara_rsr as h

P = h.DESIGN_DEFAULT
REF_DESIGN = ref.HybridDesign(L1=P[0], L2=P[1], d=P[2], d_f=P[3], L=P[4])
KINDS = np.array(h.JOINT_KINDS)


def _close(a, b, tol):
    diff = np.where(KINDS == "R", np.remainder(np.asarray(a) - b + math.pi, 2 * math.pi) - math.pi,
                    np.asarray(a) - b)
    return float(np.max(np.abs(diff))) < tol


def _random_q(rng):
    return np.array([rng.uniform(-3, 3), rng.uniform(-3, 3), rng.uniform(0.0, 0.3), rng.uniform(-3, 3),
                     *rng.uniform(math.radians(25), math.radians(75), 3)])


@pytest.fixture(scope="module")
def hc():
    from c_solvers import RsrC
    return RsrC("scara_rsr")


def test_fk_equals_the_reference_4x4_product_on_the_symmetric_mode():
    rng = case_rng(2)
    for _ in range(5):
        q = _random_q(rng)
        (r, p), = ref.fk_symmetric(q[4:], P[4])
        expected = ref.hybrid_fk_with_wrist(q[:4], r, p, REF_DESIGN)
        assert np.max(np.abs(h.fk_matrix(q) - expected)) < 1e-12
        assert abs(h.fk(q).values[0, 12] - np.linalg.norm(p)) < 1e-12


def test_ik_sets_equal_the_reference_numeric_ik():
    rng = case_rng(8)
    for _ in range(3):
        q = _random_q(rng)
        f = h.fk(q)
        sol = h.ik(f.values[0])
        expected = ref.hybrid_ik_all(h.fk_matrix(q), f.values[0, 12], REF_DESIGN)
        assert sol.count == len(expected) == 16
        got = list(sol)
        for e in expected:
            assert any(_close(e, g, 1e-7) for g in got)


def test_round_trip_every_branch():
    rng = case_rng(4)
    for _ in range(300):
        q = _random_q(rng)
        f = h.fk(q)
        sol = h.ik(f.values[0])
        assert any(_close(q, g, 1e-7) for g in sol)
        for g in sol:
            assert np.max(np.abs(h.fk(g).values[0] - f.values[0])) < 1e-9


def test_middle_curve_default_and_explicit_l_bw():
    q = np.array([0.3, 1.0, 0.1, 0.2, 0.8, 0.9, 1.0])
    t = h.fk_matrix(q)
    s12 = h.ik(t)
    assert s12.count == 16 and "l_bw" in s12.reason
    beta = h.abg_from_pose(t)[1]
    alpha1 = s12.aux[np.flatnonzero(s12.valid)[0], 1]
    from wristkin import rsr_wrist

    mid = rsr_wrist.middle_lbw(alpha1, beta, P[4:])
    assert all(abs(h.fk(g).values[0, 12] - mid) < 1e-12 for g in s12)


def test_elbow_stretched_double_root_and_gimbal():
    q = np.array([0.4, 0.0, 0.1, 0.3, 0.7, 0.7, 0.7])  # theta2 = 0: the two elbows coincide
    sol = h.ik(h.fk(q).values[0])
    assert sol.count == 8
    assert all(sol.flags[k] & h.FLAG_DOUBLE_ROOT for k in np.flatnonzero(sol.valid))
    qz = np.array([0.4, 1.0, 0.1, 0.3, 0.7, 0.7, 0.7])  # equal legs: beta = 0
    f = h.fk(qz)
    assert f.flags[0] & h.FLAG_GIMBAL
    sol = h.ik(f.values[0])
    assert sol.count == 16 and any(_close(qz, g, 1e-7) for g in sol)


@pytest.mark.parametrize("t2", [math.pi - 1e-8, -(math.pi - 1e-7), -(math.pi - 1e-9), math.pi - 1e-4])
def test_folded_elbow_with_equal_links_keeps_both_elbows(t2, hc):
    """L1 = L2 (the default) folded to within 1e-9 .. 1e-4 rad of theta2 = pi, the flange nanometres from axis 1.
    The plain law of cosines rounded cos theta2 to -1 and L1 + L2 cos theta2 to 0 there: a reachable pose came out
    unreachable, or one elbow was dropped as a 'double root' although the two differ by ~pi in theta1 and theta4.
    Both elbows x 8 leg words, the generating set among them (to the conditioning eps / (pi - |theta2|) of the fold,
    at most ~1e-7 here), flagged singular_inverse, not double; Python and C alike."""
    q = np.array([0.3, t2, 0.05, 0.2, 0.5, 0.6, 0.7])
    pose = h.fk(q).values[0]
    tol = max(1e-9, 1e-16 / (math.pi - abs(t2)))
    for sol in (h.ik(pose), hc.ik(pose)):
        assert sol.count == 16 and any(_close(q, g, tol) for g in sol.values[sol.valid]), (t2, sol.count)
        folded = abs(t2) > math.pi - 1e-5
        assert all(sol.flags[k] & h.FLAG_SINGULAR_INVERSE or not folded for k in np.flatnonzero(sol.valid))
        assert not np.any(sol.flags[sol.valid] & h.FLAG_DOUBLE_ROOT)


def test_set_next_to_a_direct_singularity_is_kept_flagged(hc):
    """S1, S2, S3 nearly collinear (cond_direct 3e-8): the plane built from the legs carries a rounding error of
    eps / cond_direct, more than the FK check allows, and the generating set was dropped. The target's plane is used
    there (as at exact collinearity), and the set comes back flagged singular_direct, as rsr_wrist keeps it."""
    q = np.array([0.3, 1.0, 0.05, 0.2, 1.5707963124910032, 1.5707964095437614, 0.200000038419825])
    pose = h.fk(q).values[0]
    for sol in (h.ik(pose), hc.ik(pose)):
        hits = [k for k in np.flatnonzero(sol.valid) if _close(q, sol.values[k], 1e-9)]
        assert hits and all(sol.flags[k] & h.FLAG_SINGULAR_DIRECT for k in hits)


def test_unreachable_and_bad_input():
    t = h.fk_matrix(np.array([0.3, 1.0, 0.1, 0.2, 0.8, 0.9, 1.0]))
    far = t.copy()
    far[0, 3] += 2.0
    s = h.ik(far)
    assert s.count == 0 and s.status == h.STATUS_UNREACHABLE and "annulus" in s.reason
    s = h.ik([*t[:3].ravel(), 0.5])
    assert s.count == 0 and "leg" in s.reason
    for bad in (np.full((4, 4), np.nan), np.eye(3), [1.0] * 13, "x"):
        with pytest.raises(h.InvalidInput):
            h.ik(bad)
    with pytest.raises(h.InvalidDesign):
        h.make_design((0.0, *P[1:]))
    with pytest.raises(h.InvalidInput):
        h.fk([0.0] * 6)
    with pytest.raises(h.InvalidInput):
        h.fk_matrix([0, 0, 0, 0, math.pi / 2, math.pi / 2, math.pi / 2])  # collinear wrist


def test_seed_representation_round_trip_and_arc_endpoints():
    rng = case_rng(6)
    for _ in range(100):
        a, b, g = rng.uniform(-math.pi, math.pi), rng.uniform(0.01, 1.2), rng.uniform(-math.pi, math.pi)
        t = h.pose_from_abg((0.3, 0.1, 0.0), a, b, g)
        back = h.abg_from_pose(t)
        assert abs(math.remainder(back[0] - a, 2 * math.pi)) < 1e-10 and abs(back[1] - b) < 1e-12
        assert abs(math.remainder(back[2] - g, 2 * math.pi)) < 1e-10
    from derive.families.rsr.rsr_audit import ARC_POINTS

    for x, y, z, a, b, g in ARC_POINTS:
        t = h.pose_from_abg((x / 1e3, y / 1e3, z / 1e3), math.radians(a), math.radians(b), math.radians(g))
        sol = h.ik(t)
        assert sol.count == 16
        lo = [-math.pi, -math.pi, 0.0, -math.pi] + [P[5]] * 3
        hi = [math.pi, math.pi, 0.5, math.pi] + [P[6]] * 3
        assert h.select(sol, lower=lo, upper=hi) >= 0


def test_energy_rule_selection_prefers_least_joint_1_motion():
    t = h.fk_matrix(np.array([0.3, 1.0, 0.1, 0.2, 0.8, 0.9, 1.0]))
    sol = h.ik(t)
    prev = np.zeros(7)
    k = h.select(sol, previous=prev, weights=(1, 0, 0, 0, 0, 0, 0))
    best = min(abs(math.remainder(sol.values[j, 0], 2 * math.pi)) for j in np.flatnonzero(sol.valid))
    assert abs(math.remainder(sol.values[k, 0], 2 * math.pi)) == best


def test_c_matches_python(hc):
    rng = case_rng(12)
    for _ in range(200):
        q = _random_q(rng) + rng.normal(0, 0.3, 7)
        pf, cf = h.fk(q), hc.fk(q)
        assert cf.rc == 0 and cf.count == pf.count and np.array_equal(cf.flags, pf.flags)
        if not pf.count:
            continue
        assert np.allclose(cf.values[0], pf.values[0], atol=1e-13)
        assert np.allclose(cf.aux[0], pf.aux[0], atol=1e-12)
        pose = pf.values[0] + np.r_[np.zeros(12), rng.normal(0, 0.01)]
        py, c = h.ik(pose), hc.ik(pose)
        assert c.rc == 0 and c.count == py.count and np.array_equal(c.valid, py.valid)
        assert np.array_equal(c.flags, py.flags)
        if py.count:
            assert np.allclose(c.values[py.valid], py.values[py.valid], atol=1e-11)
        prev = q
        assert hc.select(pose, previous=prev) == h.select(py, previous=prev)


def test_c_bad_input(hc):
    t = h.fk(np.array([0.3, 1.0, 0.1, 0.2, 0.8, 0.9, 1.0])).values[0]
    bad = t.copy()
    bad[0] = math.nan
    assert hc.ik(bad).rc == -2
    bad = t.copy()
    bad[0] += 0.1  # not a rotation
    assert hc.ik(bad).rc == -4
    assert hc.design((0.0, *P[1:]))[0] == -3
    assert hc.fk([0, 0, 0, 0, math.pi / 2, math.pi / 2, math.pi / 2]).status == h.STATUS_NO_ASSEMBLY


def test_casadi_fk_and_jacobian_from_the_generated_file():
    from derive.casadi_export import load_casadi

    fns = load_casadi(Path(__file__).resolve().parent.parent / "generated" / "casadi" / "scara_rsr.casadi")
    rng = case_rng(14)
    p = np.array(P)
    for _ in range(10):
        q = _random_q(rng)
        t = np.array(fns["scara_rsr_fk"](q, p))
        assert np.max(np.abs(t - h.fk_matrix(q)[:3])) < 1e-13
        jac = np.array(fns["scara_rsr_jacobian"](q, p))
        eps = 1e-6
        for j in range(7):
            dq = np.zeros(7)
            dq[j] = eps
            fd = (h.fk_matrix(q + dq)[:3] - h.fk_matrix(q - dq)[:3]).ravel() / (2 * eps)
            assert np.max(np.abs(jac[:, j] - fd)) < 1e-7


def test_geometric_jacobian_python_c_casadi(hc):
    import ctypes

    rng = case_rng(15)
    fn = hc.lib.wk_scara_rsr_jacobian
    dptr = ctypes.POINTER(ctypes.c_double)
    fn.argtypes = [dptr, ctypes.c_void_p, dptr]
    for _ in range(20):
        q = _random_q(rng)
        jac = h.jacobian(q)
        eps, t0 = 1e-6, h.fk_matrix(q)
        for j in range(7):
            dq = np.zeros(7)
            dq[j] = eps
            tp, tm = h.fk_matrix(q + dq), h.fk_matrix(q - dq)
            w = (tp[:3, :3] - tm[:3, :3]) / (2 * eps) @ t0[:3, :3].T
            fd = np.r_[(tp[:3, 3] - tm[:3, 3]) / (2 * eps), w[2, 1], w[0, 2], w[1, 0]]
            assert np.max(np.abs(fd - jac[:, j])) < 1e-7
        out = np.zeros(42)
        qa = np.ascontiguousarray(q)
        assert fn(qa.ctypes.data_as(dptr), None, out.ctypes.data_as(dptr)) == 0
        assert np.allclose(out.reshape(6, 7), jac, atol=1e-13)
    with pytest.raises(h.InvalidInput):
        h.jacobian([0, 0, 0, 0, math.pi / 2, math.pi / 2, math.pi / 2])


def test_near_beta_pi_with_a_leg_in_the_swing_plane_stays_reachable():
    """At beta = pi (and within the split's gimbal band of it) only theta - 2 alpha1 is fixed: a family. The split's
    member alpha1 = 0 puts the coefficient sin(alpha1 - a_i) of the leg at azimuth a_i = 0 at 0, and with the centre
    distance near 0 that leg cannot reach: a reachable pose was called unreachable (near beta = pi with the leg in
    the swing plane; at beta = pi exactly from joints (0, 0, 0, 0, 0, 0, 2 pi / 3), which Hypothesis found at
    WRISTKIN_TEST_SEED=766504). Now the family's other members are tried (every 30 degrees): sets returned, flagged
    gimbal, each one an assembly of the closed chain at the pose by the independent reference: the wrist platform
    its SCARA joints leave (the reference's own SCARA and mount transforms) meets the loop equations with its leg
    angles to IK_VERIFY_TOL (measured 2e-12 m; the module's FK cannot say it for the sets at the direct singularity,
    where the legs do not fix the platform). The generating joints are one member of the family: the pose does not
    single them out (1.7e-11 rad from beta = pi it fixes alpha1 only to eps / sin(beta) ~ 1e-5, and leg 1's angle
    swings by O(1) with it)."""
    for q in (np.array([0.3, 1.0, 0.05, 0.2, 0.2999999998301408, 1.570796326923454, -1.5707963266854634]),
              np.array([0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 2.0 * math.pi / 3.0])):
        pose = h.fk(q).values[0]
        target = np.vstack([pose[:12].reshape(3, 4), [0.0, 0.0, 0.0, 1.0]])
        for sol in (h.ik(pose), h._ik_numpy(pose, h._design(None))):
            assert sol.count >= 1, sol.reason
            for v, f in zip(sol.values[sol.valid], sol.flags[sol.valid], strict=True):
                assert f & h.FLAG_GIMBAL
                tw = np.linalg.inv(ref.scara_fk(v[:4], REF_DESIGN) @ ref.mount_transform(REF_DESIGN)) @ target
                assert np.max(np.abs(ref.constraint_residual(tw[:3, :3], tw[:3, 3], v[4:], P[4]))) <= h.IK_VERIFY_TOL
