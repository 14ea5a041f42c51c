"""DH chains (seed 001 + PUMA-560): generated Python and C vs the independent numpy reference.

The reference (tests/reference/dh.py) multiplies numeric DH matrices and finds every IK branch by
multistart Levenberg-Marquardt; nothing in it comes from the derivation.
"""

from __future__ import annotations

import importlib
import math

import numpy as np
import pytest
from c_solvers import SerialC
from reference import dh as ref
from seeding import case_rng

NAMES = ["wrist_1dof", "spherical_wrist", "rpp_wrist", "scara_wrist", "puma560"]
IK_SAMPLES = {"wrist_1dof": 20, "spherical_wrist": 15, "rpp_wrist": 8, "scara_wrist": 15, "puma560": 5}


@pytest.fixture(scope="module", params=NAMES)
def mech(request):
    mod = importlib.import_module(f"wristkin.{request.param}")
    c = SerialC(request.param, mod.N_JOINTS, mod.MAX_IK, len(mod.DESIGN_NAMES))
    return request.param, mod, c


def _joints(mod, rng, special=False):
    vals = []
    for k in mod.JOINT_KINDS:
        if k == "P":
            vals.append(rng.uniform(-0.5, 0.5))
        elif special:
            vals.append(rng.choice([0.0, math.pi / 2, -math.pi / 2, math.pi]))
        else:
            vals.append(rng.uniform(-math.pi, math.pi))
    return np.array(vals)


def _dist(mod, a, b):
    diff = np.asarray(a) - np.asarray(b)
    rev = np.array([k == "R" for k in mod.JOINT_KINDS])
    return float(np.max(np.abs(np.where(rev, np.remainder(diff + math.pi, 2 * math.pi) - math.pi, diff))))


def test_fk_and_jacobian_match_reference(mech):
    name, mod, c = mech
    rng = case_rng(1)
    for _ in range(50):
        q = _joints(mod, rng)
        T = ref.fk(name, q)
        np.testing.assert_allclose(mod.fk_matrix(q), T, atol=1e-12)
        cr = c.fk(q)
        assert cr.rc == 0 and cr.count == 1
        np.testing.assert_allclose(cr.values[0], T[:3].ravel(), atol=1e-12)
        J = ref.geometric_jacobian(name, q)
        np.testing.assert_allclose(mod.jacobian(q), J, atol=1e-12)
        np.testing.assert_allclose(c.jacobian(q)[1], J, atol=1e-12)
        np.testing.assert_allclose(cr.aux[0, 0], mod.fk(q).aux[0, 0], atol=1e-9)


def test_ik_matches_reference_branch_for_branch(mech):
    name, mod, c = mech
    rng = case_rng(2)
    for _ in range(IK_SAMPLES[name]):
        q = _joints(mod, rng)
        T = ref.fk(name, q)
        expected = ref.ik_reference(name, T)
        py, cc = mod.ik(T), c.ik(T)
        assert py.count == len(expected) == cc.count, (name, q, py.count, len(expected), cc.count)
        for sol in expected:  # none missed
            assert min(_dist(mod, sol, v) for v in py) < 1e-6
        for v in py:  # none spurious
            assert ref.pose_error(name, v, T) < 1e-9
        np.testing.assert_allclose(cc.values[cc.valid], py.values[py.valid], atol=1e-12)
        assert np.array_equal(cc.valid, py.valid)


def test_round_trips_including_degenerate_joint_values(mech):
    name, mod, c = mech
    rng = case_rng(3)
    worst = 0.0
    for i in range(200):
        q = _joints(mod, rng, special=i % 2 == 1)
        T = ref.fk(name, q)
        py = mod.ik(T)
        assert py.count >= 1
        errs = [ref.pose_error(name, v, T) for v in py]
        worst = max(worst, max(errs))
        if not np.any(py.flags & mod.FLAG_INDETERMINATE):
            # The generating joints are among the branches, to the accuracy the conditioning allows: a stage
            # root carries ~1e-14 (regular) or ~sqrt(1e-14) ~ 1e-7 (tangent/double root) error, and the later
            # joints amplify it by at most 1 / (sigma_min / sigma_max) of J at q (the near-singular wrist makes
            # q4 and q6 individually ill-determined: the pose, checked above, is not).
            sv = np.linalg.svd(mod.jacobian(q), compute_uv=False)
            ratio = sv[-1] / sv[0]
            base = 1e-6 if np.any(py.flags & mod.FLAG_DOUBLE_ROOT) else 1e-7
            assert min(_dist(mod, q, v) for v in py) < base / max(ratio, 1e-300)
        cc = c.ik(T)
        assert cc.count == py.count and np.array_equal(cc.flags, py.flags)
    assert worst < 1e-9


@pytest.mark.parametrize("name", ["spherical_wrist", "rpp_wrist", "puma560"])
def test_wrist_singularity_is_flagged_with_representative(name):
    mod = importlib.import_module(f"wristkin.{name}")
    rng = case_rng(4)
    q = _joints(mod, rng)
    i5 = mod.JOINT_NAMES.index("theta5")
    q[i5] = 0.0
    T = ref.fk(name, q)
    sol = mod.ik(T)
    assert sol.status == mod.STATUS_INDETERMINATE
    i4 = mod.JOINT_NAMES.index("theta4")
    flagged = [k for k in np.flatnonzero(sol.valid) if sol.flags[k] & mod.FLAG_INDETERMINATE]
    assert flagged  # the generating arm branch has the wrist singularity; other arm branches need not
    for k in flagged:
        assert sol.flags[k] & mod.FLAG_SINGULAR_INVERSE
        assert sol.values[k, i4] == 0.0  # documented representative: theta4 := 0
    for k in np.flatnonzero(sol.valid):
        assert ref.pose_error(name, sol.values[k], T) < 1e-9


def test_unreachable_and_bad_input(mech):
    name, mod, c = mech
    far = np.eye(4)
    far[:3, 3] = (50.0, 0.0, 0.0)
    if name in ("wrist_1dof", "spherical_wrist"):
        far[:3, 3] = (0.0, 0.0, 5.0)
    if name == "rpp_wrist":  # unbounded prismatic joints reach every pose: the reference agrees
        assert mod.ik(far).count == len(ref.ik_reference(name, far)) == 4
    else:
        sol = mod.ik(far)
        assert sol.count == 0 and sol.status == mod.STATUS_UNREACHABLE and "not reachable" in sol.reason
        cc = c.ik(far)
        assert cc.rc == 0 and cc.count == 0 and cc.status == mod.STATUS_UNREACHABLE
        if name == "puma560":
            # an all-revolute chain reaches no farther than the sum of its link lengths (|a_i| + |d_i|): an
            # independent certificate, instead of a multistart search that needs 30 s to find nothing
            assert np.linalg.norm(far[:3, 3]) > sum(abs(v) for v in mod.DESIGN_DEFAULT)
        else:
            assert ref.ik_reference(name, far) == []
    bad = np.eye(4)
    bad[0, 0] = math.nan
    with pytest.raises(mod.InvalidInput):
        mod.ik(bad)
    assert c.ik(bad).rc == -2
    shear = np.eye(4)
    shear[0, 1] = 0.3
    with pytest.raises(mod.InvalidInput):
        mod.ik(shear)
    assert c.ik(shear).rc == -4
    with pytest.raises(mod.InvalidInput):
        mod.fk([math.inf] * mod.N_JOINTS)
    assert c.fk(np.full(mod.N_JOINTS, math.nan)).rc == -2
    with pytest.raises(mod.InvalidDesign):
        mod.make_design([math.nan] * len(mod.DESIGN_NAMES))


def test_select_limits_and_seed(mech):
    name, mod, c = mech
    rng = case_rng(5)
    q = _joints(mod, rng)
    T = ref.fk(name, q)
    sol = mod.ik(T)
    # previous q + offset picks the generating set when the offset is below half its distance to every other set:
    # near a singular elbow the twin can lie within 1e-3 (WRISTKIN_TEST_SEED=367007: scara_wrist's elbow 5.4e-5 from
    # straight, its twin 1.1e-4 away, picked by previous = q + 1e-3)
    others = [_dist(mod, v, q) for v in sol.values[sol.valid] if _dist(mod, v, q) >= 1e-7]
    previous = q + min(1e-3, 0.25 * min(others, default=1.0))
    k = mod.select(sol, previous=previous)
    assert _dist(mod, sol.values[k], q) < 1e-7
    assert mod.select(sol, lower=np.full(mod.N_JOINTS, 10.0)) == -1
    out = c.IK()
    a = np.ascontiguousarray(T[:3].ravel())
    getattr(c.lib, f"wk_{name}_ik")(c._ptr(a), None, out)
    assert c.select(out, previous=previous) == k


def test_other_design_matches_reference():
    mod = importlib.import_module("wristkin.scara_wrist")
    c = SerialC("scara_wrist", 4, mod.MAX_IK, 3)
    params = {"a1": 0.7, "a2": 0.25, "d4": 0.05}
    rc, d = c.design([params[n] for n in mod.DESIGN_NAMES])
    assert rc == 0
    q = np.array([0.3, -1.1, 0.2, 0.7])
    T = ref.fk("scara_wrist", q, params)
    sol = mod.ik(T, params)
    assert sol.count == 2 and min(_dist(mod, q, v) for v in sol) < 1e-9
    assert c.ik(T, d).count == 2


def test_fk_flags_exact_singularities_in_python_and_c():
    """sigma_min / sigma_max of J decides the FK flag: exact singularities (PUMA wrist theta5 = 0, stretched elbow)
    are flagged in both languages, a regular configuration is not."""
    mod = importlib.import_module("wristkin.puma560")
    c = SerialC("puma560", mod.N_JOINTS, mod.MAX_IK, len(mod.DESIGN_NAMES))
    q_wrist = np.array([0.3, -0.4, 0.5, 0.2, 0.0, 0.1])
    q_regular = np.array([0.3, -0.4, 0.5, 0.2, 0.7, 0.1])
    for q, singular in ((q_wrist, True), (q_regular, False)):
        assert bool(mod.fk(q).flags[0] & mod.FLAG_SINGULAR_INVERSE) == singular
        assert bool(c.fk(q).flags[0] & mod.FLAG_SINGULAR_INVERSE) == singular
        assert bool(mod.fk_batch(q[None, :]).flags[0, 0] & mod.FLAG_SINGULAR_INVERSE) == singular
        # manipulability: equal where regular; at the singularity both are rounding noise of sqrt(eps * |J|^2)
        assert abs(c.fk(q).aux[0, 0] - mod.fk(q).aux[0, 0]) < (1e-8 if singular else 1e-12)


@pytest.mark.parametrize("name", NAMES)
def test_ik_stays_complete_when_a_design_length_is_zero_or_one(name):
    """A stage must not lean on a design value being what the catalogue says: the PUMA's theta2 stage measured the
    distance to the base origin, which lies on axis 2 when d1 = 0, and 60 % of reachable poses were then reported
    unreachable. Each length at 0, 1 and -0.5 (where the design is valid): FK by the independent reference, the
    generating joints among the IK sets of Python and C (or, where the design makes two axes coincide, say the
    SCARA's a1 = 0, the family flagged indeterminate), every set a pose within IK_VERIFY_TOL."""
    mod = importlib.import_module(f"wristkin.{name}")
    c = SerialC(name, mod.N_JOINTS, mod.MAX_IK, len(mod.DESIGN_NAMES))
    rng = case_rng(11)
    for pname in mod.DESIGN_NAMES:
        for value in (0.0, 1.0, -0.5):
            params = dict(zip(mod.DESIGN_NAMES, mod.DESIGN_DEFAULT, strict=True))
            params[pname] = value
            try:
                mod.make_design(params)
            except mod.InvalidDesign:
                continue
            rc, d = c.design([params[n] for n in mod.DESIGN_NAMES])
            assert rc == 0, (name, pname, value)
            for _ in range(3):
                q = _joints(mod, rng)
                T = ref.fk(name, q, params)
                py, cc = mod.ik(T, params), c.ik(T, d)
                assert py.count >= 1, (name, pname, value, q)
                if py.status != mod.STATUS_INDETERMINATE:
                    assert min(_dist(mod, q, v) for v in py) < 1e-6, (name, pname, value, q)
                for v in py:
                    assert ref.pose_error(name, v, T, params) < 1e-9
                assert cc.count == py.count and np.array_equal(cc.valid, py.valid), (name, pname, value)


def test_a_stage_left_degenerate_by_an_upstream_double_root_returns_the_family():
    """PUMA with a3 = 0 and a2 = d4, theta3 = pi/2 + 1e-10: the arm folds the wrist centre onto the shoulder. theta3 is
    a double root, resolved to sqrt(eps), so theta3 lands on pi/2 and the theta2 stage's coefficients vanish to 3e-17,
    leaving |C| ~ 4e-11 where the family's is 0. That residue made the stage report no solution and the reachable pose
    unreachable, in Python and C. The stage now keeps its representative for |C| within sqrt(DOUBLE_ROOT_TOL), and the
    FK check (against the independent reference) confirms the sets, flagged indeterminate."""
    mod = importlib.import_module("wristkin.puma560")
    c = SerialC("puma560", mod.N_JOINTS, mod.MAX_IK, len(mod.DESIGN_NAMES))
    params = dict(zip(mod.DESIGN_NAMES, (0.6718, 0.4318, 0.15005, 0.0, 0.4318, 0.0), strict=True))
    rc, d = c.design([params[n] for n in mod.DESIGN_NAMES])
    assert rc == 0
    q = np.array([-2.801939007035828, 0.36585736624743825, math.pi / 2 + 1e-10, -3.048479771584668,
                  0.10281493379620077, -2.078294999943294])
    T = ref.fk("puma560", q, params)
    for sol in (mod.ik(T, params), c.ik(T, d)):
        assert sol.count >= 1 and sol.status == mod.STATUS_INDETERMINATE
        assert all(sol.flags[k] & mod.FLAG_INDETERMINATE for k in np.flatnonzero(sol.valid))
        for v in sol.values[sol.valid]:
            assert ref.pose_error("puma560", v, T, params) < 1e-9


@pytest.mark.parametrize("name, design, q", [
    # d3 = 0, wrist centre 2e-9 m from axis 1 (the shoulder singularity): fixed by the planner's preference for a
    # plane op (theta1 from the offset, linear in the wrist centre) over a second distance op (theta2 from the
    # distance to a point on axis 1, which sees that 2e-9 m squared and merged the shoulder's two branches)
    ("puma560", (0.6718, 0.4318, 0.0, 0.0203, 0.4318, 0.0),
     (-0.748030223045761, 0.22650626513655978, 1.1600232456541315, 2.514239547705726, 2.4031872962303913,
      1.0596606155137263)),
    # a1 = a2, folded to theta2 = pi + 1e-8: the elbow's distance stage read 1 - u^2 next to a1 a2 = 0.09 and lost
    # the wrist's 1e-17 m^2 from axis 1, merging both elbows (theta1 after them then a family); it now reads the
    # factors Dm Dp of its root gap, Dm = |w|^2 - (a1 - a2)^2 to its own relative precision (planned.py)
    ("scara_wrist", (0.3, 0.3, 0.1),
     (2.7311611234478006, 3.141592663589793, -0.08613585188632233, -0.8779139643328571)),
])
def test_near_singular_poses_of_degenerate_designs_stay_reachable(name, design, q):
    """The generating joints are among the sets (the pose determines them: 2e-9 m is 1e7 times the rounding of a
    metre-sized pose), in C and on numpy."""
    mod = importlib.import_module(f"wristkin.{name}")
    c = SerialC(name, mod.N_JOINTS, mod.MAX_IK, len(mod.DESIGN_NAMES))
    params = dict(zip(mod.DESIGN_NAMES, design, strict=True))
    rc, d = c.design([params[n] for n in mod.DESIGN_NAMES])
    assert rc == 0
    T = ref.fk(name, np.array(q), params)
    for sol in (mod._ik_numpy(T, mod.make_design(params), None), c.ik(T, d)):
        assert sol.count >= 1
        assert min(_dist(mod, q, v) for v in sol.values[sol.valid]) < 1e-6
        for v in sol.values[sol.valid]:
            assert ref.pose_error(name, v, T, params) < 1e-9
