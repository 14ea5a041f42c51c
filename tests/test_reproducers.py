"""The reproducers of the portable-suite issue, each in Python and C: near-singular wrists, selection at the
wrist singularity, near-rotations, scaled designs, the 3-RSR degenerate configuration. (Generic invariants on
random and hostile input live in test_fuzz.py / test_fuzz_python.py; these pin the exact cases.)"""

from __future__ import annotations

import importlib
import math

import numpy as np
import pytest
from c_solvers import RsrC, SerialC, UnderactuatedWristC

FLAG_SINGULAR_INVERSE, FLAG_PROJECTED = 1, 32


def serial(name):
    mod = importlib.import_module(f"wristkin.{name}")
    return mod, SerialC(name, mod.N_JOINTS, mod.MAX_IK, len(mod.DESIGN_NAMES))


def wrapped(a, b):
    return float(np.max(np.abs(np.remainder(np.asarray(a) - np.asarray(b) + math.pi, 2 * math.pi) - math.pi)))


@pytest.mark.parametrize("name,i5", [("spherical_wrist", 1), ("rpp_wrist", 4), ("puma560", 4)])
@pytest.mark.parametrize("t5", [1e-5, 1e-6, 1e-7, 1e-9, 1e-12, -1e-9, math.pi - 1e-9])
def test_poses_next_to_the_wrist_singularity_are_reachable(name, i5, t5):
    """Within 1e-12 ... 1e-5 rad of a straight wrist every set is found (was: unreachable 74-99.8 %), each
    reproduces the pose to 1e-9, and C agrees with Python set for set."""
    mod, c = serial(name)
    q = np.array([0.3, 0.2, 0.1, 0.3, 0.5, 0.2][: mod.N_JOINTS])
    q[i5] = t5
    T = mod.fk(q).values[0]
    py, cc = mod.ik(T), c.ik(T)
    assert py.count == mod.MAX_IK and cc.count == py.count
    assert np.array_equal(py.valid, cc.valid) and np.array_equal(py.flags, cc.flags)
    assert np.max(py.aux[py.valid]) <= mod.IK_VERIFY_TOL
    # the joints: exact up to the conditioning, ~1e-16 / |sin theta5| in q4 and q6 (and flagged below 1e-6)
    sv = np.linalg.svd(mod.jacobian(q), compute_uv=False)
    assert min(wrapped(v, q) for v in py) < 1e-13 / (sv[-1] / sv[0])
    for v, f in zip(py.values[py.valid], py.flags[py.valid], strict=True):  # flagged where the wrist is near straight
        if abs(math.sin(v[i5])) <= 0.5 * mod.SINGULAR_EPS:
            assert f & FLAG_SINGULAR_INVERSE


def test_selection_at_the_wrist_singularity_follows_previous():
    """PUMA at its zero pose (theta5 = 0): select(ik(fk(qz)), previous=qz) stays (was: a set 3.05 rad away); with
    previous passed to IK, the singular family's member is the one at previous's theta4; C agrees."""
    mod, c = serial("puma560")
    qz = np.zeros(6)
    sol = mod.ik(mod.fk(qz).values[0])
    assert wrapped(sol.values[mod.select(sol, previous=qz)], qz) < 1e-12
    qprev = np.array([0.1, 0.2, 0.3, 1.1, 0.0, 0.6])
    T = mod.fk(qprev).values[0]
    sol = mod.ik(T, previous=qprev)
    k = mod.select(sol, previous=qprev)
    assert wrapped(sol.values[k], qprev) < 1e-9 and sol.flags[k] & mod.FLAG_INDETERMINATE
    res, raw = c.ik_near(T, qprev)
    assert wrapped(res.values[c.select(raw, qprev)], qprev) < 1e-9


# (not the 5-DOF screw robots: a float32 pose lies ~1e-8 off their 5-dimensional image, beyond IK_VERIFY_TOL,
# and is reported unreachable with that residual, as any pose off the image)
@pytest.mark.parametrize("name", ["puma560", "scara_wrist"])
def test_near_rotations_are_projected_and_far_ones_rejected_with_the_deviation(name):
    mod, c = serial(name)
    q = np.full(mod.N_JOINTS, 0.3)
    T = mod.fk_matrix(q)
    for near in (T.astype(np.float32), np.round(T, 8)):
        py, cc = mod.ik(near), c.ik(near)
        assert py.count >= 1 and cc.count == py.count
        assert np.all(py.flags[py.valid] & FLAG_PROJECTED) and np.all(cc.flags[cc.valid] & FLAG_PROJECTED)
        assert "projected onto SO(3)" in py.reason
        assert min(wrapped(v, q) for v in py) < 1e-5  # float32 pose: ~6e-8 per entry, amplified by the chain
    far = T.copy()
    far[0, 0] += 1e-4
    with pytest.raises(mod.InvalidInput, match=r"max\|R\^T R - I\| = [0-9.e-]+ \(accepted up to 1e-06"):
        mod.ik(far)
    assert c.ik(far).rc == -4  # WK_ERR_RANGE


@pytest.mark.parametrize("name", ["puma560", "scara_wrist"])
def test_designs_below_a_millimetre_are_rejected_in_python_and_c(name):
    mod, c = serial(name)
    tiny = np.array(mod.DESIGN_DEFAULT) * 1e-6
    with pytest.raises(mod.InvalidDesign, match="smaller units"):
        mod.make_design(tiny)
    assert c.design(tiny)[0] == -3  # WK_ERR_DESIGN
    assert c.design(np.array(mod.DESIGN_DEFAULT) * 1e-2)[0] == 0  # a centimetre-scale robot is fine


def test_rsr_wrist_at_beta_pi_is_flagged_and_sets_are_not_duplicated():
    """rsr_wrist.fk([0, pi/2, -pi/2]): beta = pi, l_bw = 0, leg 1 turns freely: FK flags singular_inverse, IK
    returns each set once (was: flags 0 and every set twice); the hybrid reaches the same platform pose."""
    mod = importlib.import_module("wristkin.rsr_wrist")
    c = RsrC("rsr_wrist")
    q = [0.0, math.pi / 2, -math.pi / 2]
    for fk in (mod.fk(q), c.fk(q)):
        assert fk.count == 1 and fk.flags[0] & FLAG_SINGULAR_INVERSE
    for ik in (mod.ik(mod.fk(q).values[0]), c.ik(mod.fk(q).values[0])):
        rows = [tuple(np.round(v, 12)) for v in ik.values[ik.valid]]
        assert ik.count == 4 and len(set(rows)) == 4
    hy = importlib.import_module("wristkin.scara_rsr")
    qh = [1e-12, 1e-12, -0.0098300311131065965, 2.0299772569726562, 1e-12, math.pi / 2, -math.pi / 2]
    sol = hy.ik(hy.fk(qh).values[0])
    assert sol.count >= 1 and sol.status != hy.STATUS_UNREACHABLE
    assert RsrC("scara_rsr").ik(hy.fk(qh).values[0]).count == sol.count


def test_rsr_designs_python_and_c_agree():
    mod = importlib.import_module("wristkin.rsr_wrist")
    c = RsrC("rsr_wrist")
    big = list(mod.DESIGN_DEFAULT)
    big[0] = 1e200
    with pytest.raises(mod.InvalidDesign):
        mod.make_design(big)
    assert c.design(big)[0] == -3


def test_rsr_centre_distance_is_signed_and_round_trips():
    """l_bw is the signed distance along the platform normal (docs/API.md): FK returns negative values for about
    half of random joints, and FK -> IK closes for both signs."""
    mod = importlib.import_module("wristkin.rsr_wrist")
    rng = np.random.default_rng(5)
    signs = set()
    for _ in range(40):
        q = rng.uniform(-math.pi, math.pi, 3)
        fk = mod.fk(q)
        if not fk.count or fk.flags[0] & 3:
            continue
        signs.add(bool(fk.values[0][2] > 0))
        assert min(wrapped(v, q) for v in mod.ik(fk.values[0])) < 1e-9
    assert signs == {True, False}


def _euler_distance(a, b):
    """ZXZ pose distance through the rotation matrices (Euler angles are not unique at a gimbal)."""
    def rot(e):
        c, s = np.cos(e), np.sin(e)
        rz = lambda i: np.array([[c[i], -s[i], 0], [s[i], c[i], 0], [0, 0, 1.0]])  # noqa: E731
        rx = np.array([[1.0, 0, 0], [0, c[1], -s[1]], [0, s[1], c[1]]])
        return rz(0) @ rx @ rz(2)
    return float(np.max(np.abs(rot(np.asarray(a)) - rot(np.asarray(b)))))


def test_wrist_fk_resolves_two_modes_a_fold_apart_python_and_c():
    """make fuzz, case 33675 of 1e6: joints whose pose is 1 of 2 real assembly modes 1e-7 apart in the eliminant's
    x (cond_direct 6.7e-6). FK stopped polishing after 8 Gauss-Newton steps, 1.3e-5 from either mode, so IK -> FK
    did not close. Both modes polish to rounding level now; each IK set's FK holds its pose to ~eps / cond_direct."""
    uw = importlib.import_module("wristkin.underactuated_wrist")
    c = UnderactuatedWristC()
    q = [-1.4413949531617787, 0.8592568522758901, -0.018014722277741146]
    for fk in (uw.fk, c.fk):
        for pose in fk(q).values[fk(q).valid]:
            sets = uw.ik(pose)
            assert sets.count == 8
            for k in np.flatnonzero(sets.valid):
                cond = max(float(sets.aux[k, -1]), uw.SINGULAR_EPS)
                tol = 1e-9 + 1e-13 / cond  # rounding of the joints (1e-16 ... 1e-13) amplified by 1 / cond_direct
                for fk2 in (uw.fk, c.fk):
                    back = fk2(sets.values[k])
                    best = min(_euler_distance(p, pose) for p in back.values[back.valid])
                    assert best <= tol, (k, best, tol)


def test_dh_designs_with_a_vanishing_nonzero_length_are_rejected_python_and_c():
    """make fuzz, scara_wrist: links of 1e-7 m made every stage coefficient (a product of two lengths) fall below
    DEGENERATE_EPS and the IK of FK poses came back empty; such designs are InvalidDesign (exactly 0 is another
    structure and stays accepted), a centimetre-scale robot stays fine."""
    mod, c = serial("scara_wrist")
    for bad in ([-1e-7, -1e-7, -math.pi], [0.4, 3e-6, 0.1]):
        with pytest.raises(mod.InvalidDesign, match="DH lengths must be 0 or at least"):
            mod.make_design(bad)
        assert c.design(np.array(bad))[0] == -3  # WK_ERR_DESIGN
    for good in ([0.4, 0.3, 0.0], [0.004, 0.003, 0.001], [2e-5, 0.3, 0.1]):
        mod.make_design(good)
        assert c.design(np.array(good))[0] == 0


def test_rsr_select_ranks_flagged_sets_by_distance_in_c_as_in_python():
    """The C selection of the 3-RSR wrist skipped singular sets whenever a regular one existed, while Python (and
    docs/API.md) rank every valid set by distance to `previous`: both now use the runtime's one rule."""
    mod = importlib.import_module("wristkin.rsr_wrist")
    c = RsrC("rsr_wrist")
    q = [0.3047357643748719, 0.6733437539769431, 1.5653269596422297]  # FK mode 0: IK set 4 flagged, others not
    pose = mod.fk(q).values[0]
    sol = mod.ik(pose)
    flagged = [k for k in np.flatnonzero(sol.valid) if sol.flags[k] & (FLAG_SINGULAR_INVERSE | 2)]
    assert flagged and len(flagged) < sol.count
    for k in np.flatnonzero(sol.valid):
        prev = sol.values[k] + 1e-6
        assert mod.select(sol, previous=prev) == k
        assert c.select(pose, previous=prev) == k
    assert mod.select(sol) == c.select(pose) and not sol.flags[mod.select(sol)] & 3


def test_previous_moves_only_a_family_never_a_regular_wrist():
    """rpp_wrist with d3 = 0 (the wrist centre on axis 1: theta1 is a one-parameter family) and |sin theta5| = 1e-12,
    above WRIST_EXACT_TOL (1e-13): the wrist sets are regular, so `previous` must not move theta4 (it moved from
    -2.6e-6 to previous's -3.12: the wrist's nearest-member move ran on theta1's indeterminate flag), and theta1's
    family is represented by previous's theta1 (it stayed 0). Python and C."""
    mod, c = serial("rpp_wrist")
    q = np.array([0.0, 0.2, 0.0, -2.6e-6, 1e-12, 0.5])
    T = mod.fk(q).values[0]
    prev = q.copy()
    prev[3] = -3.12

    def numpy_ik(pose, previous=None):
        return mod._ik_numpy(pose, mod._design(None), previous)

    for ik in (mod.ik, numpy_ik):
        a, b = ik(T), ik(T, previous=prev)
        assert a.count == b.count >= 1 and a.status == b.status == mod.STATUS_INDETERMINATE
        np.testing.assert_allclose(a.values[a.valid], b.values[b.valid], atol=1e-3)  # theta4 to ~eps / 1e-12
        assert min(wrapped(v, q) for v in b) < 1e-3
        moved = prev.copy()
        moved[0] = 0.4  # the family's member nearest previous
        s = ik(T, previous=moved)
        assert s.count >= 1 and all(abs(v[0] - 0.4) < 1e-12 for v in s)
        assert np.max(s.aux[s.valid]) <= mod.IK_VERIFY_TOL
    res, _ = c.ik_near(T, moved)
    assert res.count >= 1 and all(abs(v[0] - 0.4) < 1e-12 for v in res.values[res.valid])


def test_an_exact_wrist_singularity_behind_a_near_double_shoulder_root_is_the_family():
    """PUMA-560 at theta5 = 0 exactly, theta1's two roots 0.0044 apart (the shoulder near its double root: sin w =
    2.2e-3). The stages before the wrist amplify the pose's rounding by 1 / sin w = 450, so |sin theta5| came out
    1.3e-13, above WRIST_EXACT_TOL, and the exact singularity was returned as 8 "regular" sets (status ok, the family
    lost: make test-portable at WRISTKIN_TEST_SEED=627229). Now the wrist's band grows by the stages' amplification:
    the family, in Python and C."""
    mod, _ = serial("puma560")
    q = np.array([2.6698769939804583, -3.1086951870997592, 1.5431024612111823, 2.1108314795488496, 0.0,
                  3.135144430130416])
    pose = mod.fk_matrix(q)

    def numpy_ik(p, previous=None):
        return mod._ik_numpy(p, mod._design(None), previous)

    for ik in (mod.ik, numpy_ik):
        s = ik(pose, previous=q)
        assert s.status == mod.STATUS_INDETERMINATE, s.reason
        assert min(wrapped(v, q) for v in s) < 1e-8


def test_an_exact_wrist_singularity_behind_amplifying_position_stages_is_the_family():
    """PUMA-560 at theta5 = 0 exactly, the elbow's two roots 0.05 apart and the shoulder's amplifying by 32: the
    stages' errors compound (40 x 32 x 6.7 over theta3, theta2, theta1), leaving |sin theta5| = 5.1e-12, where the
    largest single amplification (40) kept the band at 4e-12 and the singularity came back as two "regular" sets
    whose theta4 the pose fixes only to 1e-5 (C and numpy 1.1e-5 apart; make test-haswell at
    WRISTKIN_TEST_SEED=507497). The band grows by the product: the family, in Python and C."""
    mod, _ = serial("puma560")
    q = np.array([-2.606073908150718, -1e-07, 1.642858033204953, -math.pi / 2, 0.0, 0.7009509987521931])
    pose = mod.fk_matrix(q)

    def numpy_ik(p, previous=None):
        return mod._ik_numpy(p, mod._design(None), previous)

    for ik in (mod.ik, numpy_ik):
        s = ik(pose)
        assert s.status == mod.STATUS_INDETERMINATE, s.reason
        s = ik(pose, previous=q)
        assert min(wrapped(v, q) for v in s) < 1e-8
