"""3-RSR wrist: generated Python and C against the independent numeric reference (tests/reference/rsr.py)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from reference import rsr as ref
from seeding import case_rng
from wristkin import rsr_wrist as w

L = w.DESIGN_DEFAULT[0]


def _wrapped_close(a, b, tol=1e-9):
    return float(np.max(np.abs(np.remainder(np.asarray(a) - np.asarray(b) + math.pi, 2 * math.pi) - math.pi))) < tol


def _random_pose(rng):
    """A reachable (alpha, beta, l_bw) with every leg reaching (about 1 in 2 draws)."""
    while True:
        pose = (rng.uniform(-math.pi, math.pi), rng.uniform(0.0, math.radians(80)), rng.uniform(0.01, 0.11))
        if w.ik(pose).count:
            return pose


@pytest.fixture(scope="module")
def wc():
    from c_solvers import RsrC
    return RsrC("rsr_wrist")


def test_ik_sets_equal_the_reference_sets():
    rng = case_rng(11)
    for _ in range(40):
        pose = _random_pose(rng)
        sol = w.ik(pose)
        r, p = ref.pose_from_params(*pose)
        expected = ref.ik_all(r, p, L)
        assert sol.count == len(expected) == 8
        got = list(sol)
        for q in expected:  # none missed ...
            assert any(_wrapped_close(q, g, 1e-8) for g in got), (pose, q)
        for g in got:  # ... none spurious: every returned set closes the full chain of the reference
            assert ref.is_assembly(r, p, g, L, tol=1e-10)


def test_fk_is_the_mirror_symmetric_assembly_mode_of_the_full_chain():
    rng = case_rng(5)
    for _ in range(6):
        q = rng.uniform(math.radians(25), math.radians(75), 3)
        sol = w.fk(q)
        assert sol.count == 1
        t = sol.aux[0, :12].reshape(3, 4)
        assert ref.is_assembly(t[:, :3], t[:, 3], q, L, tol=1e-12)
        assert ref.is_mirror_symmetric(t[:, :3], t[:, 3])
        modes = ref.fk_all(q, L, n_starts=600, include_coincident=False)
        assert ref.fk_contains(q, L, t[:, :3], t[:, 3], modes=modes)
        assert len(modes) in (4, 8)  # non-degenerate modes of the full closed chain (reference census)
        assert sum(ref.is_mirror_symmetric(*m) for m in modes) == 1  # the other modes are not symmetric
        assert np.allclose(ref.params_from_pose(t[:, :3], t[:, 3]), sol.values[0], atol=1e-12)


def test_round_trip_every_branch_and_generating_joints_found():
    rng = case_rng(3)
    for _ in range(300):
        q = rng.uniform(-math.pi, math.pi, 3)
        f = w.fk(q)
        if not f.count or f.flags[0] & w.FLAG_SINGULAR_DIRECT:
            continue
        sol = w.ik(f.values[0])
        assert any(_wrapped_close(q, g, 1e-7) for g in sol)
        for g, cd, fl in zip(sol.values[sol.valid], sol.aux[sol.valid, 2], sol.flags[sol.valid], strict=True):
            back = w.fk(g)
            if not back.count:
                # an exactly collinear set (cond_direct 0: the legs' S1, S2, S3 on one line) of the pose: IK returns
                # it flagged singular_direct and FK refuses its undefined mirror plane (WRISTKIN_TEST_SEED=367007)
                assert cd == 0.0 and fl & w.FLAG_SINGULAR_DIRECT and back.status != w.STATUS_OK, back.reason
                continue
            # another set of the pose can be nearly collinear (cond_direct -> 0, flagged singular_direct): its joints
            # fix the mirror plane only to ~eps / cond_direct (seed 1544: cond_direct 3.5e-12, pose off by 2.7e-9)
            assert np.max(np.abs(back.aux[0, :12] - f.aux[0, :12])) < 1e-9 + 1e-15 / max(cd, 1e-300)


def test_tangent_leg_gives_one_double_root_flagged():
    alpha, beta = 0.4, 0.7
    a = math.sin(beta / 2) * math.sin(alpha)  # leg 1
    rho = math.hypot(a, math.cos(beta / 2))
    lbw = 2 * L * rho * (1 - 1e-14)
    sol = w.ik((alpha, beta, lbw))
    r, p = ref.pose_from_params(alpha, beta, lbw)
    per_leg = [len(ref.ik_leg(i, r, p, L).roots) for i in (1, 2, 3)]
    assert per_leg[0] == 1
    assert sol.count == int(np.prod(per_leg)) == 4
    assert all(sol.flags[k] & w.FLAG_DOUBLE_ROOT for k in np.flatnonzero(sol.valid))


def test_near_free_leg_flags_every_set_singular(wc):
    """beta = pi with leg 1 in the swing plane, 1e-10 rad off: the leg's coefficient norm rho is ~1e-11, so its
    conditioning rho sin(acos u) is far below SINGULAR_EPS. FK flagged it; IK returned the sets unflagged (select()
    then preferred them as regular). Every IK set now carries singular_inverse, in Python and C."""
    q = [0.3, math.pi / 2 + 1e-10, -math.pi / 2 + 2e-10]
    f = w.fk(q)
    assert f.flags[0] & w.FLAG_SINGULAR_INVERSE
    for sol in (w.ik(f.values[0]), wc.ik(f.values[0])):
        assert sol.count >= 1
        assert all(sol.flags[k] & w.FLAG_SINGULAR_INVERSE for k in np.flatnonzero(sol.valid))


def test_unreachable_collinear_and_gimbal():
    s = w.ik((0.0, 0.3, 2.5 * L))
    assert s.count == 0 and s.status == w.STATUS_UNREACHABLE and "leg" in s.reason
    f = w.fk((math.pi / 2, math.pi / 2, math.pi / 2))  # all S_i at (0, 0, L): no plane
    assert f.count == 0 and f.status == w.STATUS_NO_ASSEMBLY and "collinear" in f.reason
    q = w.ik((0.0, 0.0, 0.08)).values[0]
    g = w.fk(q)
    assert g.flags[0] & w.FLAG_GIMBAL and g.values[0, 0] == 0.0 and abs(g.values[0, 1]) < 1e-12


@pytest.mark.parametrize("bad", [(math.nan, 0.1, 0.08), (0.0, math.inf, 0.08), (0.0, -0.1, 0.08), (0.0, 4.0, 0.08),
                                 (0.1, 0.2), "abc"])
def test_bad_pose_is_a_typed_error(bad):
    with pytest.raises(w.InvalidInput):
        w.ik(bad)


@pytest.mark.parametrize("design", [(0.0, 0.4, 1.3, 0.02, 0.1), (0.06, 1.3, 0.4, 0.02, 0.1),
                                    (0.06, 0.4, 1.3, 0.1, 0.02), (0.06, 0.4, 1.3, 0.02, 0.2),
                                    (0.06, math.nan, 1, 0, 1)])
def test_bad_design_is_a_typed_error(design):
    with pytest.raises(w.InvalidDesign):
        w.make_design(design)


def test_jacobians_match_casadi_and_finite_differences():
    from derive.families.rsr import rsr_wrist as mech
    from derive.families.rsr.rsr_casadi import wrist_functions

    fns = wrist_functions(mech.kernels(mech.derive_cached()))
    rng = case_rng(9)
    for _ in range(10):
        pose = _random_pose(rng)
        q = w.ik(pose).values[0]
        jq, jx = w.jacobians(q, pose)
        _, cq, cx = fns["rsr_wrist_leg_residual"](q, pose, L)
        assert np.allclose(np.diag(np.array(cq)), jq, atol=1e-12)
        assert np.allclose(np.array(cx), jx, atol=1e-12)
        # FK Jacobian by AD equals the inverse of the implicit relation: dx/dphi = Jx^-1 diag(jq)
        dx = np.array(fns["rsr_wrist_fk_jacobian"](q, L))
        if pose[1] > 0.05:
            assert np.allclose(dx, np.linalg.solve(jx, np.diag(jq)), atol=1e-8)


def test_gamma_conversions_are_exact_inverses():
    rng = case_rng(1)
    for _ in range(200):
        a1, beta = rng.uniform(-math.pi, math.pi), rng.uniform(0.0, math.radians(89))
        g = w.gamma_from_azimuth(a1, beta)
        assert abs(math.remainder(w.azimuth_from_gamma(g, beta) - a1, 2 * math.pi)) < 1e-12
    for a in (0.0, math.pi / 2, -math.pi / 2, math.pi):  # the seed's special positions: gamma = alpha
        assert abs(math.remainder(w.gamma_from_azimuth(a, 0.9) - a, 2 * math.pi)) < 1e-12
    with pytest.raises(w.InvalidInput):
        w.azimuth_from_gamma(0.3, math.pi / 2)


def test_workspace_interval_is_exact_against_a_dense_leg_scan():
    d = w.make_design()
    lo_lim, hi_lim = d.params[1], d.params[2]
    phis = np.linspace(lo_lim, hi_lim, 20001)
    rng = case_rng(4)
    for _ in range(20):
        alpha, beta = rng.uniform(-math.pi, math.pi), rng.uniform(0.0, 1.2)
        span = w.workspace(alpha, beta)
        # independent: n . S_i over the limited leg range from the reference's leg points
        n = np.array([math.sin(beta / 2) * math.cos(alpha), math.sin(beta / 2) * math.sin(alpha), math.cos(beta / 2)])
        lo, hi = d.params[3] / 2, d.params[4] / 2
        for i in (1, 2, 3):
            vals = np.array([n @ ref.leg_point(i, p, L) for p in phis])
            lo, hi = max(lo, vals.min()), min(hi, vals.max())
        if lo > hi + 1e-9:
            assert span is None
        else:
            assert span is not None and abs(span[0] - 2 * lo) < 1e-8 and abs(span[1] - 2 * hi) < 1e-8
            mid = w.middle_lbw(alpha, beta)
            k = w.select(w.ik((alpha, beta, mid)), lower=[lo_lim] * 3, upper=[hi_lim] * 3)
            assert k >= 0


def test_pose_matrix_round_trip_and_torsion_rejected():
    t = w.pose_matrix((0.7, 0.5, 0.08))
    assert np.allclose(w.pose_from_matrix(t), (0.7, 0.5, 0.08), atol=1e-12)
    twisted = t.copy()
    c, s = math.cos(0.01), math.sin(0.01)
    twisted[:3, :3] = twisted[:3, :3] @ np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
    with pytest.raises(w.InvalidInput):
        w.pose_from_matrix(twisted)


def test_c_matches_python(wc):
    rng = case_rng(21)
    for _ in range(200):
        pose = (rng.uniform(-4, 4), rng.uniform(0, math.pi), rng.uniform(-0.13, 0.13))
        py, c = w.ik(pose), wc.ik(pose)
        assert c.rc == 0 and c.count == py.count and c.status == py.status
        assert np.array_equal(c.valid, py.valid) and np.array_equal(c.flags, py.flags)
        if py.count:
            assert np.allclose(c.values[py.valid], py.values[py.valid], atol=1e-13)
            assert np.allclose(c.aux[py.valid], py.aux[py.valid], atol=1e-13)
        q = rng.uniform(-math.pi, math.pi, 3)
        pf, cf = w.fk(q), wc.fk(q)
        assert cf.count == pf.count and np.array_equal(cf.flags, pf.flags)
        if pf.count:
            assert np.allclose(cf.values[0], pf.values[0], atol=1e-13)
            assert np.allclose(cf.aux[0], pf.aux[0], atol=1e-13)


def test_c_bad_input_and_selection(wc):
    assert wc.ik((math.nan, 0.1, 0.08)).rc == -2
    assert wc.ik((0.0, -0.1, 0.08)).rc == -4
    assert wc.fk((0.1, math.inf, 0.2)).rc == -2
    assert wc.design((0.06, 1.3, 0.4, 0.02, 0.1))[0] == -3
    pose = (0.3, 0.4, 0.08)
    lo, hi = [w.DESIGN_DEFAULT[1]] * 3, [w.DESIGN_DEFAULT[2]] * 3
    assert wc.select(pose, lower=lo, upper=hi) == w.select(w.ik(pose), lower=lo, upper=hi)
    prev = w.ik(pose).values[5]
    assert wc.select(pose, previous=prev) == w.select(w.ik(pose), previous=prev) == 5


def test_geometric_jacobian_maps_leg_rates_to_the_platform_twist():
    rng = case_rng(16)
    for _ in range(20):
        q = rng.uniform(math.radians(25), math.radians(75), 3)
        jac = w.jacobian(q)
        eps = 1e-6
        t0 = w.pose_matrix(w.fk(q).values[0])
        for j in range(3):
            dq = np.zeros(3)
            dq[j] = eps
            tp, tm = w.pose_matrix(w.fk(q + dq).values[0]), w.pose_matrix(w.fk(q - dq).values[0])
            rot = (tp[:3, :3] - tm[:3, :3]) / (2 * eps) @ t0[:3, :3].T
            fd = np.r_[(tp[:3, 3] - tm[:3, 3]) / (2 * eps), rot[2, 1], rot[0, 2], rot[1, 0]]
            assert np.max(np.abs(fd - jac[:, j])) < 1e-7
    with pytest.raises(w.InvalidInput):
        w.jacobian((math.pi / 2, math.pi / 2, math.pi / 2))
