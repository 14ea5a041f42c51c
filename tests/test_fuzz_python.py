"""Fuzzing the generated Python modules (hypothesis), and the issue's reproducers as a seed corpus.

Every entry point of every mechanism gets hostile values (NaN, +-inf, +-0, denormals, +-1e308, strings,
complex numbers, wrong shapes) mixed into otherwise sensible input. Allowed outcomes: the module's typed
error (a `WristkinError`: InvalidInput / InvalidDesign), or a result whose valid rows are finite and whose
count matches; never a bare ValueError / IndexError / ZeroDivisionError / numpy error, never a silent NaN.
FK -> IK round trips on joints that include singular and near-singular values keep the joints, or a
flagged set (singular, double root, gimbal, indeterminate) stands in for them and reproduces the pose.
"""

from __future__ import annotations

import importlib
import math
import os
from pathlib import Path

import mpmath
import numpy as np
import pytest
import wristkin
from hypothesis import HealthCheck, given, seed, settings
from hypothesis import strategies as st
from seeding import TEST_SEED

ROOT = Path(__file__).resolve().parent.parent
NAMES = sorted(wristkin.MECHANISMS)
EXAMPLES = int(os.environ.get("WRISTKIN_FUZZ_EXAMPLES", "150"))  # per test and mechanism; `make fuzz` 3000

HOSTILE = [math.nan, math.inf, -math.inf, 0.0, -0.0, 5e-324, -5e-324, 2.2250738585072014e-308, 1e308, -1e308,
           1.7976931348623157e308, 1e300, -1e300, 1e16, 1e-7, math.pi, 1e6, 999999.9]  # 1e6: LENGTH_MAX
SPECIAL_ANGLES = [0.0, math.pi / 2, -math.pi / 2, math.pi, -math.pi, 1e-7, -1e-9, 1e-12]
FLAGGED = 1 | 2 | 4 | 8 | 16  # singular_inverse, singular_direct, gimbal, double_root, indeterminate
# An unflagged set has sigma_min/sigma_max above the singular threshold 1e-6, so its joints are accurate to
# about 1e6 * eps * scale ~ 2e-10 * scale; 1e-6 leaves three decades for the constant.
JOINT_TOL = 1e-6


def module(name):
    return importlib.import_module(f"wristkin.{name}")


def joint_kinds(mod) -> str:
    return "".join(getattr(mod, "JOINT_KINDS", "R" * len(mod.JOINT_NAMES)))


def joints_strategy(mod):
    kinds = joint_kinds(mod)
    angle = st.one_of(st.floats(-math.pi, math.pi), st.sampled_from(SPECIAL_ANGLES))
    slide = st.floats(-0.15, 0.15)
    return st.tuples(*[angle if k == "R" else slide for k in kinds]).map(np.array)


def hostile_strategy(n):
    """n numbers, a few of them hostile."""
    base = st.lists(st.floats(-3.0, 3.0), min_size=n, max_size=n)
    hits = st.lists(st.tuples(st.integers(0, n - 1), st.sampled_from(HOSTILE)), min_size=1, max_size=3)

    def mix(args):
        vals, hit = args
        vals = list(vals)
        for i, h in hit:
            vals[i] = h
        return vals

    return st.tuples(base, hits).map(mix)


def check_result(mod, res, inputs):
    assert np.all(np.isfinite(np.asarray(inputs, dtype=float))), "non-finite input accepted"
    valid = np.asarray(res.valid, dtype=bool)
    assert res.count == int(valid.sum())
    assert np.all(np.isfinite(res.values[valid])), "valid row with non-finite values"
    assert np.all(np.isfinite(res.aux[valid])), "valid row with non-finite aux"


def check_fk_accepts(mod, res, design=None):
    """IK returns only what FK accepts (docs/API.md, "Ranges"): fk of every valid row raises nothing."""
    for row in res.values[np.asarray(res.valid, dtype=bool)]:
        assert call(mod, mod.fk, row, design) is not None, f"fk rejects the IK row {row.tolist()}"


def call(mod, fn, *args):
    """fn(*args) -> result, or None when it raised the module's typed error."""
    try:
        return fn(*args)
    except mod.WristkinError:
        return None


def reduced(x):
    """x - 2 pi k in [-pi, pi]: math.remainder(x, fl(2 pi)) is |x| x 3.9e-17 off (4e-11 rad at 1e6); longer angles
    against 2 pi itself, to 2400 bits (mpmath: independent of the runtimes' reduction)."""
    if abs(x) <= 1e6:
        return math.remainder(x, 2 * math.pi)
    with mpmath.workprec(2400):
        v, two_pi = mpmath.mpf(x), 2 * mpmath.pi
        return float(v - mpmath.nint(v / two_pi) * two_pi)


def distance(kinds, a, b):
    """Max joint difference, angles wrapped (each side reduced first)."""
    out = 0.0
    for k, x, y in zip(kinds, a, b, strict=True):
        d = math.remainder(reduced(x) - reduced(y), 2 * math.pi) if k == "R" else x - y
        out = max(out, abs(d))
    return out


def pose_matrix(mod, row, aux):
    """The pose of an FK row as a matrix, whatever the mechanism's pose parameterisation."""
    if mod.NAME == "underactuated_wrist":
        return np.asarray(mod.rotation_from_pose(row), float).reshape(3, 3)
    if mod.NAME == "rsr_wrist":
        return np.asarray(aux[:12], float).reshape(3, 4)
    return np.asarray(row, float)


@pytest.mark.parametrize("name", NAMES)
def test_fk_and_ik_round_trips_keep_the_joints(name):
    mod = module(name)
    kinds = joint_kinds(mod)

    @seed(TEST_SEED)
    @settings(max_examples=EXAMPLES, suppress_health_check=list(HealthCheck))
    @given(joints_strategy(mod))
    def run(q):
        fk = call(mod, mod.fk, q)
        assert fk is not None, "FK rejected finite joints"
        check_result(mod, fk, q)
        for m in np.flatnonzero(fk.valid):
            ik = mod.ik(fk.values[m])
            check_result(mod, ik, fk.values[m])
            assert ik.count >= 1, f"IK of an FK pose is empty: joints {q.tolist()}"
            rows = np.flatnonzero(ik.valid)
            best = min(distance(kinds, ik.values[k], q) for k in rows)
            flagged = bool(fk.flags[m] & FLAGGED) or any(ik.flags[k] & FLAGGED for k in rows)
            assert best <= JOINT_TOL or flagged, f"FK -> IK lost joints {q.tolist()} (best {best:.3g})"
            target = pose_matrix(mod, fk.values[m], fk.aux[m])
            scale = max(1.0, float(np.max(np.abs(target))))
            for k in rows:  # every IK row reproduces the pose (solvers verify to 1e-9 * scale)
                back = mod.fk(ik.values[k])
                if ik.flags[k] & 2:  # direct singularity: FK amplifies rounding by 1 / cond_direct (or finds
                    continue  # no mode); the IK verified the row by its own equations
                err = min(float(np.max(np.abs(pose_matrix(mod, back.values[i], back.aux[i]) - target)))
                          for i in np.flatnonzero(back.valid))
                assert err <= 1e-8 * scale, f"IK row {ik.values[k].tolist()} misses the pose by {err:.3g}"

    run()


@pytest.mark.parametrize("name", NAMES)
def test_hostile_joints_poses_and_designs(name):
    mod = module(name)
    n_j, n_p, n_d = len(mod.JOINT_NAMES), len(mod.POSE_NAMES), len(mod.DESIGN_NAMES)

    @seed(TEST_SEED)
    @settings(max_examples=EXAMPLES, suppress_health_check=list(HealthCheck))
    @given(hostile_strategy(n_j), hostile_strategy(n_p), hostile_strategy(n_d), st.floats(0.8, 1.25))
    def run(q, pose, design, factor):
        res = call(mod, mod.fk, q)
        if res is not None:
            check_result(mod, res, q)
        res = call(mod, mod.ik, pose)
        if res is not None:
            check_result(mod, res, pose)
            check_fk_accepts(mod, res)
        for fn in ("jacobian",):
            if hasattr(mod, fn):
                out = call(mod, getattr(mod, fn), q)
                if out is not None:
                    assert np.all(np.isfinite(np.asarray(out, float))), f"{fn} returned non-finite values"
        d = call(mod, mod.make_design, design)
        if d is not None:
            assert np.all(np.isfinite(np.asarray(design, float)))
        scaled = [v * factor for v in mod.DESIGN_DEFAULT]
        d = call(mod, mod.make_design, scaled)
        if d is not None:  # an accepted design works: FK of a sensible configuration is typed or finite
            res = call(mod, mod.fk, [0.3] * n_j, d)
            if res is not None:
                check_result(mod, res, [0.3] * n_j)

    run()


@pytest.mark.parametrize("name", NAMES)
def test_strings_complex_shapes_and_empty_batches(name):
    mod = module(name)
    n_j = len(mod.JOINT_NAMES)
    pose_forms = {6, 7, 12, 16} if "pose_matrix" in dir(mod) else {12, 16}  # xyz + rpy / quaternion, a matrix
    for bad in (["a"] * n_j, [1 + 2j] * n_j, [0.1] * (n_j + 1), [[0.1] * n_j] * 2, None, "0.1", [], {"x": 1}):
        with pytest.raises(mod.WristkinError):
            mod.fk(bad)
        if isinstance(bad, list) and len(bad) in pose_forms and isinstance(bad[0], float):
            continue  # n_j + 1 numbers are a pose form for a 5-joint arm (xyz + rpy)
        with pytest.raises(mod.WristkinError):
            mod.ik(bad)
    with pytest.raises(mod.WristkinError):
        mod.make_design(["x"] * len(mod.DESIGN_NAMES))
    with pytest.raises(mod.WristkinError):
        mod.make_design([1 + 1j] * len(mod.DESIGN_NAMES))
    fb = mod.fk_batch(np.empty((0, n_j)))
    assert fb.values.shape[0] == 0 and fb.valid.shape[0] == 0
    ib = mod.ik_batch(np.empty((0, len(mod.POSE_NAMES))))
    assert ib.values.shape[0] == 0 and ib.valid.shape[0] == 0
    # what fk_batch returns, ik_batch takes
    q = np.full((2, n_j), 0.3)
    fb = mod.fk_batch(q)
    ib = mod.ik_batch(fb.values[:, 0, :])
    assert ib.values.shape[0] == 2


# The reproducers: each must give a typed error or a finite, complete answer (their exact
# expectations are tested where each mechanism is tested; here they seed the generic invariants).
CORPUS = [
    ("underactuated_wrist", "fk", [1.3787517671176137, 0.7898908212231482, 5.308687386977519]),
    ("underactuated_wrist", "fk", [3.1415926537790035, 3.1415926521088884, 3.141592647950821]),
    ("spherical_wrist", "fk", [0.3, 1e-7, 0.2]),
    ("rpp_wrist", "fk", [0.3, 0.2, 0.1, 0.3, 1e-7, 0.2]),
    ("rsr_wrist", "fk", [0.0, math.pi / 2, -math.pi / 2]),
    ("puma560", "fk", [0.0] * 6),
    ("puma560", "fk", [0.1, 0.2, 0.3, 0.4, 1e-7, 0.6]),
    ("puma560", "fk", [1e308] * 6),
    ("scara_wrist", "fk", [1e308, 1e308, 0.1, 1e308]),
    ("p1p2p3rarb", "fk", [1e308] * 5),
    ("scara_rsr", "fk", [1e308] * 7),
    # issue 21: long revolute angles (reduced against 2 pi itself), the folded scara_rsr family, a long stroke
    ("wrist_1dof", "fk", [1e16]),
    ("scara_rsr", "fk", [1e16, 0.5, 0.05, 1e9, 0.4, 0.5, 0.6]),
    ("scara_rsr", "fk", [0.3, math.pi, 0.05, 0.2, 0.4, 0.5, 0.6]),
    ("scara_wrist", "fk", [0.3, -1.78, 6.5e5, 0.2]),
]


def _rpp_pose_at_length_max():
    t = np.eye(4)
    t[:3, :3] = [[0.0, 0.0, -1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]]
    t[:3, 3] = [1e6, 0.0, 0.0]
    return t


def _scara_rsr_pose_at(pz):
    pose = module("scara_rsr").fk([0.3, 1.0, 0.05, 0.2, 0.4, 0.5, 0.6]).values[0].copy()
    pose[11] = pz
    return pose


# issue 21's IK reproducers: every set IK returns is one FK accepts (and reproduces the pose)
IK_CORPUS = [
    ("rsr_wrist", lambda: [1e16, 0.9, 0.05]),
    ("rpp_wrist", _rpp_pose_at_length_max),
    ("scara_rsr", lambda: _scara_rsr_pose_at(1e308)),
    ("scara_rsr", lambda: _scara_rsr_pose_at(2e6)),
]


@pytest.mark.parametrize("name,pose", IK_CORPUS, ids=[f"{n}-ik-{i}" for i, (n, _) in enumerate(IK_CORPUS)])
def test_seed_corpus_ik(name, pose):
    mod = module(name)
    p = pose()
    res = mod.ik(p)
    check_result(mod, res, p)
    check_fk_accepts(mod, res)


@pytest.mark.parametrize("name,verb,args", CORPUS, ids=[f"{n}-{v}-{i}" for i, (n, v, _) in enumerate(CORPUS)])
def test_seed_corpus(name, verb, args):
    mod = module(name)
    kinds = joint_kinds(mod)
    fk = call(mod, mod.fk, args)
    if fk is None:
        return
    check_result(mod, fk, args)
    for m in np.flatnonzero(fk.valid):
        ik = mod.ik(fk.values[m])
        check_result(mod, ik, fk.values[m])
        rows = np.flatnonzero(ik.valid)
        assert rows.size, f"IK of the FK pose of {args} is empty"
        best = min(distance(kinds, ik.values[k], args) for k in rows)
        flagged = bool(fk.flags[m] & FLAGGED) or any(ik.flags[k] & FLAGGED for k in rows)
        assert best <= JOINT_TOL or flagged, (name, args, best)
