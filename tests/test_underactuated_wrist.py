"""Generated Python and C solvers of the underactuated wrist vs the independent numpy reference.

The reference (tests/reference/underactuated_wrist.py) is built from rotation matrices, a geometric
cone-intersection sweep and numeric root finding: no A/B/C, D/E/F or K polynomial.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from reference import underactuated_wrist as ref
from seeding import case_rng

D = np.radians
HERE = Path(__file__).resolve().parent


def rot_of(values):
    return ref.rotation_from_euler(*values)


def same_rotation_sets(a, b, tol=1e-8):
    if len(a) != len(b):
        return False
    return all(min(np.max(np.abs(x - y)) for y in b) < tol for x in a)


def py_rotations(sol):
    return [sol.aux[k, :9].reshape(3, 3) for k in np.flatnonzero(sol.valid)]


# ------------------------------------------------------------------------------------------- FK
@pytest.mark.parametrize("seed", range(6))
def test_fk_matches_reference_on_random_joints(uw, uw_c, seed):
    rng = case_rng(100 + seed)
    for _ in range(10):
        q = rng.uniform(0.0, 2 * math.pi, 3)
        expected = ref.fk_reference(q).rotations
        py = uw.fk(q)
        c = uw_c.fk(q)
        assert py.count == len(expected) == c.count, (q, py.count, len(expected), c.count)
        assert same_rotation_sets(py_rotations(py), expected)
        assert same_rotation_sets([c.aux[k, :9].reshape(3, 3) for k in np.flatnonzero(c.valid)], expected)
        for k in np.flatnonzero(py.valid):  # the pose angles describe the same rotation
            assert np.max(np.abs(rot_of(py.values[k]) - py.aux[k, :9].reshape(3, 3))) < 1e-12


def test_fk_solution_counts_0_to_8_all_exercised(uw, uw_c):
    cases = json.loads((HERE / "reference" / "fk_count_cases.json").read_text())
    seen = set()
    for case in cases["cases"]:
        q = np.array(case["joints"])
        expected = ref.fk_reference(q).rotations
        assert len(expected) == case["count"]
        py, c = uw.fk(q), uw_c.fk(q)
        assert py.count == c.count == case["count"], (q, py.count, c.count, case["count"])
        assert same_rotation_sets(py_rotations(py), expected)
        seen.add(py.count)
    assert seen >= {0, 2, 4, 6, 8}


def test_fk_no_assembly_is_empty_with_reason(uw, uw_c):
    cases = json.loads((HERE / "reference" / "fk_count_cases.json").read_text())
    q = next(np.array(c["joints"]) for c in cases["cases"] if c["count"] == 0)
    py, c = uw.fk(q), uw_c.fk(q)
    assert py.count == 0 and py.status == uw.STATUS_NO_ASSEMBLY and "no real assembly" in py.reason
    assert c.rc == 0 and c.count == 0 and c.status == uw.STATUS_NO_ASSEMBLY
    assert np.all(np.isnan(py.values))


def test_fk_across_a_count_transition_none_missed_none_spurious(uw, uw_c):
    """March along a joint-space line through the 2 -> 4 transition, finely near the double root."""
    cases = json.loads((HERE / "reference" / "fk_count_cases.json").read_text())
    q2 = np.array(next(c["joints"] for c in cases["cases"] if c["count"] == 2))
    q4 = np.array(next(c["joints"] for c in cases["cases"] if c["count"] == 4))
    lo, hi = 0.0, 1.0
    for _ in range(40):  # bisect the transition with the reference only
        mid = 0.5 * (lo + hi)
        if ref.fk_reference(q2 + mid * (q4 - q2)).count <= 2:
            lo = mid
        else:
            hi = mid
    for s in [lo - 1e-3, lo - 1e-6, lo, hi + 1e-6, hi + 1e-3]:
        q = q2 + s * (q4 - q2)
        expected = ref.fk_reference(q).rotations
        for sol in (uw.fk(q), uw_c.fk(q)):
            rots = [sol.aux[k, :9].reshape(3, 3) for k in np.flatnonzero(sol.valid)]
            for r in rots:  # none spurious
                assert np.max(np.abs(ref.loop_residuals(q, r))) < 1e-9
            for r in expected:  # none missed (near-double modes may be merged within 1e-4)
                assert min((np.max(np.abs(r - x)) for x in rots), default=1.0) < 1e-4


def test_fk_contains_pose_of_every_ik_solution(uw, uw_c):
    rng = case_rng(7)
    n_checked = 0
    for _ in range(80):
        pose = np.array([rng.uniform(-math.pi, math.pi), rng.uniform(0.0, 0.3), rng.uniform(-math.pi, math.pi)])
        sets = uw.ik(pose)
        R = rot_of(pose)
        for k in np.flatnonzero(sets.valid):
            for solver in (uw.fk, uw_c.fk):
                fk = solver(sets.values[k])
                rots = [fk.aux[j, :9].reshape(3, 3) for j in np.flatnonzero(fk.valid)]
                assert min(np.max(np.abs(R - x)) for x in rots) < 1e-9
            n_checked += 1
    assert n_checked >= 64  # 8 sets per reachable pose


# ------------------------------------------------------------------------------------------- IK
def test_ik_matches_reference(uw, uw_c):
    rng = case_rng(11)
    reach = 0
    for _ in range(60):
        pose = np.array([rng.uniform(-math.pi, math.pi), rng.uniform(0.0, math.pi), rng.uniform(-math.pi, math.pi)])
        expected = ref.ik_reference(rot_of(pose))
        py, c = uw.ik(pose), uw_c.ik(pose)
        assert py.count == len(expected.triples) == c.count
        if py.count:
            reach += 1
            got = sorted(tuple(np.round(v, 9)) for v in py.values)
            want = sorted(tuple(np.round(np.mod(t, 2 * math.pi), 9)) for t in expected.triples)
            assert np.max(np.abs(np.array(got) - np.array(want))) < 1e-8
            assert np.max(np.abs(py.values - c.values)) < 1e-12
            for v in py.values:
                assert np.max(np.abs(ref.loop_residuals(v, rot_of(pose)))) < 1e-12
        else:
            assert py.status == uw.STATUS_UNREACHABLE == c.status and "unreachable" in py.reason
    assert 10 < reach < 60


def test_ik_motor_angles_and_home(uw):
    sol = uw.ik([0.0, 0.0, 0.0])
    assert sol.count == 8
    # set 0 takes the +acos root everywhere: the home assembly theta0 = 140.1479636 deg (reference home_angle)
    theta0 = ref.home_angle()
    home = [k for k in range(8) if np.allclose(sol.values[k], theta0, atol=1e-12)]
    assert len(home) == 1
    assert np.allclose(sol.aux[home[0], :3], 0.0, atol=1e-12)
    assert math.degrees(theta0) == pytest.approx(140.1479636, abs=1e-6)


def test_ik_near_reachability_boundary(uw, uw_c):
    """Bisect the nutation to the edge of branch reachability: tangent roots inside, empty set outside."""
    base = np.array([0.4, 0.0, -0.3])

    def reachable(t):
        return uw.ik(base + [0.0, t, 0.0]).count > 0
    grid = np.linspace(0.0, math.pi, 400)
    first_out = next(t for t in grid if not reachable(t))
    lo, hi = first_out - grid[1], first_out
    assert reachable(lo) and not reachable(hi)
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if reachable(mid) else (lo, mid)
    inside, outside = base + [0.0, lo, 0.0], base + [0.0, hi + 1e-6, 0.0]
    sol = uw.ik(inside)
    assert sol.count == 8 and np.all(sol.flags & uw.FLAG_SINGULAR_INVERSE)
    for v in sol:
        assert np.max(np.abs(ref.loop_residuals(v, rot_of(inside)))) < 1e-10
    assert uw.ik(outside).status == uw.STATUS_UNREACHABLE and uw_c.ik(outside).count == 0
    assert len(ref.ik_reference(rot_of(outside)).triples) == 0


# ------------------------------------------------------------------------------------------- paper
TABLE2 = [  # seed 000 Table 2 as printed (theta1..3 inputs; psi, theta, phi): t = 1, 2, 3, 5 s reproduce
    ((137.92, 138.44, 137.82), (-36.01, 0.26, 38.95)),
    ((132.96, 134.72, 132.13), (-42.23, 1.00, 52.36)),
    ((127.04, 130.28, 123.56), (-51.45, 2.36, 72.37)),
    ((120.00, 125.00, 111.29), (-53.74, 3.97, 94.82)),
]


@pytest.mark.parametrize("inputs, printed", TABLE2)
def test_table2_rows_reproduce_within_input_rounding(uw, inputs, printed):
    sol = uw.fk(D(inputs))
    k = uw.select(sol, previous=None)
    near = min(np.flatnonzero(sol.valid), key=lambda j: abs(math.degrees(sol.values[j, 1]) - printed[1])
               + abs(math.degrees(sol.values[j, 0]) - printed[0]))
    got = np.degrees(sol.values[near])
    # inputs are printed to 0.01 deg; psi and phi move by up to ~0.1 deg per 0.01 deg of input near theta ~ 0
    assert abs(got[1] - printed[1]) < 0.02
    assert abs(got[0] - printed[0]) < 0.1 and abs(got[2] - printed[2]) < 0.1
    assert k >= 0


def test_table2_t4_row_does_not_reproduce(uw):
    sol = uw.fk(D((122.08, 126.56, 105.68)))
    printed = np.array([-63.43, 5.82, 111.85])
    # the two assembly modes are (-64.01, 5.81, 111.80) and (-63.39, 4.79, 118.85): psi fits neither
    for v in np.degrees(sol.values[sol.valid]):
        assert np.max(np.abs(v - printed)) > 0.5


# ------------------------------------------------------------------------------------------- bad input
@pytest.mark.parametrize("bad", [[math.nan, 0, 0], [0, math.inf, 0], [0, 0, -math.inf]])
def test_non_finite_input(uw, uw_c, bad):
    with pytest.raises(uw.InvalidInput):
        uw.ik(bad)
    with pytest.raises(uw.InvalidInput):
        uw.fk(bad)
    assert uw_c.ik(bad).rc == -2 and uw_c.fk(bad).rc == -2
    assert uw_c.ik(bad).count == 0


@pytest.mark.parametrize("shape", [[1, 2], [1, 2, 3, 4], "abc", [[1, 2, 3]]])
def test_wrong_shape(uw, shape):
    with pytest.raises(uw.InvalidInput):
        uw.ik(shape)


@pytest.mark.parametrize("params", [
    (0.0, 1.0, 0.5, 0.5), (1.0, math.pi, 0.5, 0.5), (1.0, 1.0, -0.1, 0.5), (1.0, 1.0, 0.5, 0.0),
    (1.0, 1.0, 0.5, 2.0), (math.nan, 1, 1, 1),
    (0.2, 0.2, 1.5, 0.1),  # no spherical closure: |cos theta0| > 1
    (1.0, 1.0, math.pi / 2, math.pi / 2),  # beta1 + beta2 = pi: the home loop fixes no theta0 (every one closes it)
])
def test_bad_design(uw, uw_c, params):
    with pytest.raises(uw.InvalidDesign):
        uw.make_design(params)
    assert uw_c.design(params)[0] in (-2, -3)


def test_design_dict_and_unknown_key(uw):
    d = uw.make_design({"beta2": math.radians(43.89)})
    assert d.params == uw.DESIGN_DEFAULT
    with pytest.raises(uw.InvalidDesign):
        uw.make_design({"gamma": 1.0})


def test_other_designs_match_reference(uw, uw_c):
    rng = case_rng(5)
    done = 0
    while done < 6:
        params = (rng.uniform(0.5, 1.5), rng.uniform(0.5, 1.5), rng.uniform(0.1, 1.2), rng.uniform(0.3, 1.2))
        try:
            d = uw.make_design(params)
        except uw.InvalidDesign:
            continue
        rc, dc = uw_c.design(params)
        assert rc == 0
        design = dict(zip(("alpha1", "alpha2", "beta1", "beta2"), params, strict=True))
        q = rng.uniform(0, 2 * math.pi, 3)
        expected = ref.fk_reference(q, design).rotations
        assert uw.fk(q, d).count == len(expected) == uw_c.fk(q, dc).count
        assert same_rotation_sets(py_rotations(uw.fk(q, d)), expected)
        done += 1


# ------------------------------------------------------------------------------------------- batch, select
def test_batch_equals_scalar(uw, uw_c):
    rng = case_rng(3)
    poses = np.column_stack([rng.uniform(-3, 3, 50), rng.uniform(0, 3, 50), rng.uniform(-3, 3, 50)])
    b = uw.ik_batch(poses)
    for i, p in enumerate(poses):
        s = uw.ik(p)
        assert np.array_equal(b.valid[i], s.valid) and b.status[i] == s.status
        np.testing.assert_allclose(b.values[i], s.values, atol=1e-12, equal_nan=True)
        np.testing.assert_allclose(b.aux[i], s.aux, atol=1e-9, equal_nan=True)
        assert np.array_equal(b.flags[i], s.flags)
    cases = json.loads((HERE / "reference" / "fk_count_cases.json").read_text())["cases"]
    joints = np.vstack([rng.uniform(0, 2 * math.pi, (300, 3)), [c["joints"] for c in cases]])
    fb = uw.fk_batch(joints)  # vectorised: eigenvalues + vectorised polish, a different path from fk
    rc, outs = uw_c.batch("fk", joints)
    assert rc == 0
    for i, q in enumerate(joints):
        s = uw.fk(q)
        assert fb.count[i] == s.count == outs[i].count and fb.status[i] == s.status
        assert np.array_equal(fb.flags[i], s.flags)
        np.testing.assert_allclose(fb.aux[i], s.aux, atol=1e-9, equal_nan=True)
    with pytest.raises(uw.InvalidInput):
        uw.fk_batch([[0.0, math.nan, 0.0]])
    assert uw.fk_batch(np.empty((0, 3))).values.shape == (0, uw.MAX_FK, 3)


def test_select_is_continuous_along_a_motion(uw, uw_c):
    """Poses from FK along a joint path (Table 2 inputs); IK + select(previous) must give back the path."""
    q_start, q_end = D(np.array([137.92, 138.44, 137.82])), D(np.array([120.0, 125.0, 111.29]))
    R_prev = uw.fk(q_start).aux[uw.select(uw.fk(q_start)), :9].reshape(3, 3)
    prev_q = q_start
    for t in np.linspace(0.0, 1.0, 60):
        q = q_start + t * (q_end - q_start)
        fk = uw.fk(q)
        k = min(np.flatnonzero(fk.valid), key=lambda j: np.max(np.abs(fk.aux[j, :9].reshape(3, 3) - R_prev)))
        R_prev = fk.aux[k, :9].reshape(3, 3)
        ik = uw.ik(fk.values[k])
        j = uw.select(ik, previous=prev_q)
        assert j >= 0
        np.testing.assert_allclose(ik.values[j], q, atol=1e-8)
        prev_q = ik.values[j]
    sol = uw.ik(uw.fk(q_start).values[0])
    assert uw.select(sol, lower=np.zeros(3), upper=np.full(3, 2 * math.pi)) >= 0
    assert uw.select(sol, lower=np.zeros(3), upper=np.full(3, 1e-9)) == -1


# ------------------------------------------------------------------------------------------- rates
def _log_so3(R):
    c = (np.trace(R) - 1) / 2
    th = math.acos(max(-1.0, min(1.0, c)))
    w = np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]])
    return w * (0.5 if th < 1e-12 else th / (2 * math.sin(th)))


def test_angular_velocity_and_acceleration_vs_finite_differences(uw, uw_c):
    q0, qd, qdd = D(np.array([132.96, 134.72, 132.13])), np.array([0.3, -0.2, 0.5]), np.array([0.1, 0.4, -0.3])

    def rot_at(t, near):
        sol = uw.fk(q0 + qd * t + 0.5 * qdd * t * t)
        rots = py_rotations(sol)
        return min(rots, key=lambda r: np.max(np.abs(r - near)))
    sol0 = uw.fk(q0)
    k = 0
    R0 = sol0.aux[k, :9].reshape(3, 3)
    h = 1e-4
    Rp, Rm = rot_at(h, R0), rot_at(-h, R0)
    w_fd = _log_so3(Rp @ Rm.T) / (2 * h)
    w = uw.angular_velocity(q0, sol0.values[k], qd)
    np.testing.assert_allclose(w, w_fd, atol=1e-6)
    w_c = np.zeros(3)
    _, pp = uw_c._arr(sol0.values[k])
    import ctypes
    a, qp = uw_c._arr(q0)
    b, qdp = uw_c._arr(qd)
    out = (ctypes.c_double * 3)()
    assert uw_c.lib.wk_underactuated_wrist_angular_velocity(qp, pp, qdp, None, out) == 0
    w_c = np.array(out[:])
    np.testing.assert_allclose(w_c, w, atol=1e-12)
    # acceleration: central difference of w along the motion
    wp = uw.angular_velocity(q0 + qd * h + 0.5 * qdd * h * h, uw.pose_from_rotation(Rp)[0], qd + qdd * h)
    wm = uw.angular_velocity(q0 - qd * h + 0.5 * qdd * h * h, uw.pose_from_rotation(Rm)[0], qd - qdd * h)
    wdot = uw.angular_acceleration(q0, sol0.values[k], qd, qdd)
    np.testing.assert_allclose(wdot, (wp - wm) / (2 * h), atol=1e-5)
    # inverse relations
    np.testing.assert_allclose(uw.joint_rates(q0, sol0.values[k], w), qd, atol=1e-10)
    np.testing.assert_allclose(uw.joint_accelerations(q0, sol0.values[k], w, wdot), qdd, atol=1e-8)
    # Euler rates round trip
    er = uw.euler_rates(sol0.values[k], w)
    np.testing.assert_allclose(uw.omega_from_euler_rates(sol0.values[k], er), w, atol=1e-12)


def test_fk_exactly_at_a_double_root(uw, uw_c):
    """At the fold itself (bisected to 1e-12 with the reference) the merging mode is reported once, flagged."""
    cases = json.loads((HERE / "reference" / "fk_count_cases.json").read_text())
    q2 = np.array(next(c["joints"] for c in cases["cases"] if c["count"] == 2))
    q4 = np.array(next(c["joints"] for c in cases["cases"] if c["count"] == 4))
    lo, hi = 0.0, 1.0
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if ref.fk_reference(q2 + mid * (q4 - q2)).count <= 2 else (lo, mid)
    for s in (lo, hi):
        q = q2 + s * (q4 - q2)
        expected = ref.fk_reference(q).rotations
        fb = uw.fk_batch(q[None, :])
        batch_row = uw.Solutions(fb.values[0], fb.valid[0], fb.flags[0], fb.aux[0], int(fb.status[0]), "")
        for sol in (uw.fk(q), uw_c.fk(q), batch_row):
            rots = [sol.aux[k, :9].reshape(3, 3) for k in np.flatnonzero(sol.valid)]
            for r in expected:  # none missed
                assert min(np.max(np.abs(r - x)) for x in rots) < 1e-4
            for k in np.flatnonzero(sol.valid):  # extra modes only inside the fold band, and flagged
                res = np.max(np.abs(ref.loop_residuals(q, sol.aux[k, :9].reshape(3, 3))))
                assert res <= uw.FK_FOLD_TOL
                if res > uw.FK_RESIDUAL_TOL:
                    assert sol.flags[k] & uw.FLAG_DOUBLE_ROOT and sol.flags[k] & uw.FLAG_SINGULAR_DIRECT
            assert sol.count == 3


def test_select_weights_every_mechanism_takes_the_same_keyword(uw):
    """select(..., weights=...) is part of the shared API: a zero weight ignores that joint's distance."""
    import math

    import numpy as np

    sol = uw.ik([math.radians(a) for a in (-35.99, 0.26, 38.93)])
    ks = np.flatnonzero(sol.valid)
    target = sol.values[ks[-1]].copy()
    prev = target.copy()
    prev[1:] += 1.0  # far in joints 2 and 3, exact in joint 1
    assert uw.select(sol, previous=prev, weights=(1.0, 0.0, 0.0)) in [
        k for k in ks if abs(math.remainder(sol.values[k, 0] - target[0], 2 * math.pi)) < 1e-12]


def test_close_roots_of_the_eliminant_keep_both_modes(uw, uw_c):
    """Two roots of the degree-8 eliminant 1.4e-7 apart belong to two well-conditioned modes that share eta (the
    loop equations are nearly proportional there): both are returned (scalar, batch and C), unflagged, and IK of
    each gives the joints back. A merge is confirmed, never assumed."""
    q = np.array([1.3787517671176137, 0.7898908212231482, 5.308687386977519])
    expected = ref.fk_reference(q).rotations
    assert len(expected) == 6
    fb = uw.fk_batch(q[None, :])
    batch_row = uw.Solutions(fb.values[0], fb.valid[0], fb.flags[0], fb.aux[0], int(fb.status[0]), "")
    for sol in (uw.fk(q), uw_c.fk(q), batch_row):
        assert sol.count == 6
        rots = [sol.aux[k, :9].reshape(3, 3) for k in np.flatnonzero(sol.valid)]
        for r in expected:  # each mode is found; well conditioned, so to ~eps / cond_direct
            assert min(np.max(np.abs(r - x)) for x in rots) < 1e-9
    for pose in uw.fk(q):
        ik = uw.ik(pose)
        assert min(np.max(np.abs(np.remainder(v - q + np.pi, 2 * np.pi) - np.pi)) for v in ik) < 1e-9


@pytest.mark.parametrize("design,q,count", [
    # fuzz seed 20: the eliminant's isolator stopped short of two roots (fixed in the root search)
    ((1.1495084542024554, 1.0520892737782648, 0.4747603510932728, 0.70165869691749816),
     (2.771736820857104, 6.122370955265905, 1.234660381773652), 6),
    # fuzz seed 917: two modes 2e-5 apart whose eliminant roots (4e-8 apart) are within its rounding: one touching
    # root, polished into the fold band from between them; split along the loop equations' near-null direction
    ((1.0471975511965976, 1.0471975511965976, 0.5235987755982988, 0.7660250087003112),
     (1.0764849551776707, 3.126192783918335, 5.636405366707507), 4),
])
def test_modes_the_eliminant_cannot_tell_apart_are_found_on_the_loop_equations(uw, uw_c, design, q, count):
    """Every assembly mode of the independent sweep (fk_reference) is returned, by the module and by the C library,
    each to 1e-8 (at seed 917 two are 2e-5 apart: well inside what the joints determine)."""
    expected = ref.fk_reference(q, dict(zip(("alpha1", "alpha2", "beta1", "beta2"), design, strict=True))).rotations
    assert len(expected) == count
    rc, dc = uw_c.design(design)
    assert rc == 0
    for sol in (uw.fk(q, uw.make_design(design)), uw_c.fk(q, dc)):
        assert sol.count == count
        rots = py_rotations(sol)
        for r in expected:
            assert min(np.max(np.abs(r - x)) for x in rots) < 1e-8


def test_euler_angles_next_to_the_gimbal_reproduce_their_rotation(uw, uw_c):
    """Just above GIMBAL_EPS psi and phi are individually ill-determined (~eps / sin theta) but the returned
    angles must reproduce the mode's own rotation matrix to rounding (phi is taken after psi)."""
    q = (3.1415926537790035, 3.1415926521088884, 3.141592647950821)
    for sol in (uw.fk(q), uw_c.fk(q)):
        assert sol.count >= 1
        for k in np.flatnonzero(sol.valid):
            r = uw.rotation_from_pose(sol.values[k])
            assert np.max(np.abs(r - sol.aux[k, :9].reshape(3, 3))) < 1e-14  # a few ulps of unit entries


def test_degenerate_designs_are_invalid_in_python_and_c(uw, uw_c):
    for bad in ([5e-324, 1.0, 0.5, 5e-324], [1e-4, 1.0, 0.5, 0.7], [1.0, np.pi - 1e-5, 0.5, 0.7], [1.0, 1.0, 0.5, 0.0]):
        with pytest.raises(uw.InvalidDesign):
            uw.make_design(bad)
        assert uw_c.design(bad)[0] == -3  # WK_ERR_DESIGN
