"""Python runs the generated C (wristkin._native) and falls back to numpy: both must give the same solution sets.

`make test` runs the suite with the extension (the default where it is built), `make test-portable` runs the
numerically sensitive tests again with WRISTKIN_BACKEND=numpy, and this file compares the two backends call by
call: a Design made without its C counterpart (`Design(params)`) takes the numpy path in the same process.
"""

from __future__ import annotations

import importlib
import inspect
import math
import os
import pickle
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import wristkin
from reference import chain as ref
from reference import dh as dh_ref
from reference import screws as screw_ref
from seeding import case_rng

ROOT = Path(__file__).resolve().parent.parent
FORCED_NUMPY = os.environ.get("WRISTKIN_BACKEND", "").strip().lower() == "numpy"
NAMES = sorted(wristkin.MECHANISMS)
# the mechanisms whose verbs run in C (all, where the extension is built): the serial chains (pose matrices, ik
# with `previous`), the underactuated wrist (Euler angles, several assembly modes) and the 3-RSR wrist and hybrid
NATIVE = [n for n in NAMES if "ik" in importlib.import_module(f"wristkin.{n}").NATIVE_VERBS]
SERIAL = [n for n in NATIVE if "previous" in inspect.signature(importlib.import_module(f"wristkin.{n}").ik).parameters]
RSR = [n for n in NATIVE if n not in SERIAL and n != "underactuated_wrist"]
# Away from singularities both backends evaluate the same formulas: rounding-level agreement, with room for the
# few operations they order differently (each O(eps) relative, lengths of order 1 m).
REGULAR_TOL = 1e-12
# At special joint values (0, +-pi/2, pi, 1e-7) a set may sit next to a singularity, where a joint is only
# accurate to eps / sigma_min ~ 1e-16 / 1e-7 = 1e-9 (and a polished tangent root to sqrt(eps) ~ 1e-8).
SPECIAL_TOL = 1e-7
# Where singularities compound (a wrist 1e-7 from straight on an arm 5e-4 from its elbow boundary: sigma_min of
# the Jacobian 4e-11), a set is determined only to eps / sigma_min along the near-null direction, whatever the
# backend: both sets then reproduce the pose to rounding and may differ by up to CONDITIONED x eps / sigma_min.
# At sigma_min below rounding the set is a family representative chosen by convention, compared at SPECIAL_TOL.
CONDITIONED = 16.0
EPS = float(np.finfo(float).eps)
SPECIAL = [0.0, math.pi / 2, -math.pi / 2, math.pi, 1e-7, -1e-7]


def module(name):
    return importlib.import_module(f"wristkin.{name}")


@pytest.mark.skipif(FORCED_NUMPY, reason="WRISTKIN_BACKEND=numpy: the fallback pass")
def test_the_extension_is_built_from_these_generated_files_and_runs():
    native = importlib.import_module("wristkin._native")
    for name in NAMES:
        mod = module(name)
        assert native.INPUTS_HASH == mod.INPUTS_HASH, "stale extension: run `make native`"
        assert mod.BACKEND == ("c" if mod.NATIVE_VERBS else "numpy"), name
    assert len(SERIAL) == 7 and sorted(RSR) == ["rsr_wrist", "scara_rsr"] and NATIVE == NAMES


def test_backend_can_be_forced_to_numpy():
    code = "import wristkin; print(wristkin.puma560.BACKEND, wristkin.puma560.make_design().native)"
    run = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=120,
                         env={**os.environ, "WRISTKIN_BACKEND": "numpy"})
    assert run.returncode == 0 and run.stdout.split() == ["numpy", "None"], run.stderr


def _diff(a, b, revolute):
    """a - b with revolute entries wrapped to (-pi, pi]: pi and -pi are one angle (both lie in [-pi, pi])."""
    d = a - b
    return np.where(revolute, np.remainder(d + math.pi, 2 * math.pi) - math.pi, d) if revolute is not None else d


def _same(a, b, tol, what, revolute=None):
    """tol: one tolerance, or one per valid set (`_conditioned`)."""
    assert a.status == b.status, what
    assert np.array_equal(a.valid, b.valid), what
    assert np.array_equal(a.flags, b.flags), what
    d = _diff(a.values[a.valid], b.values[b.valid], revolute)
    over = np.abs(d) > np.reshape(tol, (-1, 1) if np.ndim(tol) else ())
    assert not np.any(over), f"{what}: {d} (tolerance {tol})"
    assert np.all(np.isnan(a.values[~a.valid])) and np.all(np.isnan(b.values[~b.valid])), what


def _same_batch(a, b, tol, what, revolute=None):
    """Two BatchSolutions: the same valid sets, flags and statuses, values within tol (angles wrapped; tol: one, or
    one per valid set in the batch's row-major order)."""
    for f in ("valid", "flags", "status"):
        assert np.array_equal(getattr(a, f), getattr(b, f)), (what, f)
    d = _diff(a.values[a.valid], b.values[b.valid], revolute)
    assert not np.any(np.abs(d) > np.reshape(tol, (-1, 1) if np.ndim(tol) else ())), what


def _conditioned(mod, design, sets, floor=SPECIAL_TOL):
    """Per set: `floor`, or CONDITIONED x eps / sigma_min of the Jacobian there where that is larger and the set is not
    singular to rounding (lengths are O(1 m), so the mixed units do not move sigma_min's order). The floor: SPECIAL_TOL
    at special joints; REGULAR_TOL x 10 at random ones (seed 4242 drew a framed PUMA 1.4e-6 from singular whose C and
    numpy sets differed by 2.6e-10, both on the pose to rounding)."""
    sigma = np.array([np.linalg.svd(mod.jacobian(q, design), compute_uv=False)[-1] for q in sets])
    regular = sigma > CONDITIONED * EPS
    return np.where(regular, np.maximum(floor, CONDITIONED * EPS / np.where(regular, sigma, 1.0)), floor)


def _joints(mod, rng, special: bool):
    q = np.where(np.array(mod.JOINT_KINDS) == "R", rng.uniform(-math.pi, math.pi, mod.N_JOINTS),
                 rng.uniform(-0.4, 0.4, mod.N_JOINTS))
    if special:
        for i in range(mod.N_JOINTS):
            if mod.JOINT_KINDS[i] == "R" and rng.random() < 0.5:
                q[i] = SPECIAL[rng.integers(len(SPECIAL))]
    return q


@pytest.mark.skipif(FORCED_NUMPY, reason="WRISTKIN_BACKEND=numpy: the fallback pass")
@pytest.mark.parametrize("name", SERIAL)
def test_serial_c_and_numpy_give_the_same_solution_sets(name):
    mod = module(name)
    c_design = mod.make_design()
    py_design = mod.Design(c_design.params)
    assert c_design.native is not None and py_design.native is None
    rng = case_rng(71)
    rev = np.array(mod.JOINT_KINDS) == "R"
    poses = []
    for k in range(120):
        special = k % 2 == 1
        tol = SPECIAL_TOL if special else REGULAR_TOL
        q = _joints(mod, rng, special)
        _same(mod.fk(q, c_design), mod.fk(q, py_design), tol, f"{name} fk {q.tolist()}")
        np.testing.assert_allclose(mod.jacobian(q, c_design), mod.jacobian(q, py_design), atol=tol, rtol=0)
        T = mod.fk_matrix(q, py_design)
        np.testing.assert_allclose(mod.fk_matrix(q, c_design), T, atol=tol, rtol=0)
        py_ik = mod.ik(T, py_design)
        # a random pose can also sit near a singularity (seed 222631 under Haswell: a PUMA with sigma_min 4e-6, its
        # C and numpy sets 5e-12 apart, both on the pose to 2e-15): the conditioning's bound above the floor
        sets_tol = _conditioned(mod, py_design, py_ik.values[py_ik.valid], floor=tol)
        _same(mod.ik(T, c_design), py_ik, sets_tol, f"{name} ik of fk({q.tolist()})", rev)
        prev = _joints(mod, rng, False)
        py_near = mod.ik(T, py_design, previous=prev)
        near_tol = _conditioned(mod, py_design, py_near.values[py_near.valid], floor=tol)
        _same(mod.ik(T, c_design, previous=prev), py_near, near_tol, f"{name} ik near {prev.tolist()}", rev)
        poses.append(T)
    # poses the chain cannot reach, and rotations a little off SO(3) (projected, reported): C answers, the numpy
    # path words the reason when it is read, so the result is the same either way
    off = poses[0].copy()
    off[:3, :3] *= 1.0 + 1e-8
    far = poses[1].copy()
    far[:3, 3] += 50.0
    for T in (off, far):
        a, b = mod.ik(T, c_design), mod.ik(T, py_design)
        _same(a, b, REGULAR_TOL, f"{name} ik of an odd pose", rev)
        assert a.reason == b.reason
    batch = np.array(poses)
    py_batch = mod.ik_batch(batch, py_design)
    _same_batch(mod.ik_batch(batch, c_design), py_batch, _conditioned(mod, py_design, py_batch.values[py_batch.valid]),
                f"{name} ik_batch", rev)
    qs = np.array([_joints(mod, rng, False) for _ in range(20)])
    cf, pf = mod.fk_batch(qs, c_design), mod.fk_batch(qs, py_design)
    np.testing.assert_allclose(cf.values, pf.values, atol=REGULAR_TOL, rtol=0)
    assert np.array_equal(cf.flags, pf.flags) and np.array_equal(cf.status, pf.status)


@pytest.mark.parametrize("name", sorted(set(SERIAL) | {"puma560"}))
def test_bad_input_raises_the_same_typed_error_on_both_paths(name):
    """The C path rejects, then the numpy path explains: one InvalidInput with the detailed message."""
    mod = module(name)
    T = mod.fk_matrix(np.zeros(mod.N_JOINTS))
    # numeric strings and complex values: refused on both paths (the C path once converted the strings)
    for bad in (np.full((4, 4), np.nan), T * 2.0, np.zeros(5), [[1, 2], [3, 4]], "pose", T.astype(str),
                T.astype(complex)):
        for design in (mod.make_design(), mod.Design(mod.make_design().params)):
            with pytest.raises(wristkin.InvalidInput):
                mod.ik(bad, design)
    with pytest.raises(wristkin.InvalidInput):
        mod.fk(np.full(mod.N_JOINTS, np.inf))
    with pytest.raises(wristkin.InvalidInput):
        mod.ik_batch(np.array([T, np.full((4, 4), np.nan)]))
    with pytest.raises(wristkin.InvalidInput):
        mod.fk_batch(np.full((3, mod.N_JOINTS), np.nan))


def _match_modes(a, b, tol, what):
    """FK assembly modes as sets: the two backends may find the roots in another order."""
    assert a.status == b.status and a.count == b.count, what
    rest = list(np.flatnonzero(b.valid))
    for k in np.flatnonzero(a.valid):
        d = [float(np.max(np.abs(_diff(a.values[k], b.values[j], np.ones(3, bool))))) for j in rest]
        j = rest.pop(int(np.argmin(d)))
        assert min(d) <= tol and a.flags[k] == b.flags[j], f"{what}: mode {a.values[k]} ({min(d):.2e})"


@pytest.mark.skipif(FORCED_NUMPY, reason="WRISTKIN_BACKEND=numpy: the fallback pass")
def test_underactuated_wrist_c_and_numpy_give_the_same_solution_sets():
    mod = module("underactuated_wrist")
    c_design = mod.make_design()
    py_design = mod.Design(c_design.params, c_design.constants, c_design.theta0)
    assert c_design.native is not None and py_design.native is None
    rng = case_rng(72)
    # FK modes are polished to rounding level (cond_direct >= 1e-6 away from folds): 1e-9 leaves room for the
    # modes near a fold, where a root is only accurate to sqrt(eps) ~ 1e-8 (flagged)
    fold_tol = 1e-7
    qs = rng.uniform(0.0, 2 * math.pi, (150, 3))
    for q in qs:
        a, b = mod.fk(q, c_design), mod.fk(q, py_design)
        _match_modes(a, b, fold_tol, f"fk {q.tolist()}")
        for pose in b:
            ia, ib = mod.ik(pose, c_design), mod.ik(pose, py_design)
            _same(ia, ib, REGULAR_TOL * 100, f"ik {pose.tolist()}", np.ones(3, bool))
    fa, fb = mod.fk_batch(qs[:40], c_design), mod.fk_batch(qs[:40], py_design)
    assert np.array_equal(fa.count, fb.count) and np.array_equal(fa.status, fb.status)
    poses = rng.uniform(-math.pi, math.pi, (60, 3))
    _same_batch(mod.ik_batch(poses, c_design), mod.ik_batch(poses, py_design), 1e-9, "wrist ik_batch",
                np.ones(3, bool))


@pytest.mark.skipif(FORCED_NUMPY, reason="WRISTKIN_BACKEND=numpy: the fallback pass")
@pytest.mark.parametrize("name", RSR)
def test_rsr_c_and_numpy_give_the_same_solution_sets(name):
    """FK values are the IK input ((alpha, beta, l_bw), or [R | p] and l_bw): the round trip runs both paths."""
    mod = module(name)
    c_design = mod.make_design()
    py_design = mod.Design(c_design.params)
    rev = np.array(mod.JOINT_KINDS) == "R"
    rng = case_rng(73)
    qs, poses = [], []
    for _ in range(100):
        q = np.where(rev, rng.uniform(-math.pi, math.pi, mod.N_JOINTS), rng.uniform(-0.1, 0.1, mod.N_JOINTS))
        q[-3:] = rng.uniform(math.radians(20), math.radians(80), 3)  # the legs where the wrist assembles
        a, b = mod.fk(q, c_design), mod.fk(q, py_design)
        _same(a, b, REGULAR_TOL, f"{name} fk {q.tolist()}")
        np.testing.assert_allclose(mod.jacobian(q, c_design), mod.jacobian(q, py_design), atol=REGULAR_TOL, rtol=0)
        _same(mod.ik(b.values[0], c_design), mod.ik(b.values[0], py_design), 1e-9, f"{name} ik", rev)
        qs.append(q)
        poses.append(b.values[0])
    for verb, rows in (("fk_batch", qs), ("ik_batch", poses)):
        _same_batch(getattr(mod, verb)(np.array(rows), c_design), getattr(mod, verb)(np.array(rows), py_design),
                    1e-9, f"{name} {verb}", rev if verb == "ik_batch" else None)


@pytest.mark.skipif(FORCED_NUMPY, reason="WRISTKIN_BACKEND=numpy: the fallback pass")
@pytest.mark.parametrize("name", [n for n in NATIVE if hasattr(module(n), "_IK_RESULT")])
def test_the_extension_hands_back_the_same_solutions_object_python_would_make(name):
    """The Solutions the extension makes (ik, fk) is the frozen dataclass, with the fields and reason the Python
    conversion of the same call gives (an outcome that needs the numpy path's words: see the test below)."""
    import dataclasses

    from wristkin import _runtime

    mod = module(name)
    rng = case_rng(31)
    kinds = np.array(list(getattr(mod, "JOINT_KINDS", "RRR")))
    # joints that have a pose: the underactuated wrist's two motors and sensed branch assemble only on part of the
    # cube (test seed 679837 drew joints with no FK solution, whose NaN row then went to ik as a pose)
    for _ in range(100):
        q = np.where(kinds == "R", rng.uniform(-math.pi, math.pi, kinds.size), 0.1)
        if mod.fk(q).count:
            break
    if name == "rsr_wrist":  # its joints are leg angles: take them from a reachable pose instead
        q = mod.ik(mod.fk(np.full(3, 0.3)).values[0]).values[0]
    assert mod.fk(q).count, name
    x = mod.fk(q).values[mod.fk(q).valid][0]
    pose = mod.fk_matrix(q) if name in SERIAL else x
    d = mod.make_design()
    for verb, arg, made in (("ik", pose, mod.ik(pose)), ("fk", q, mod.fk(q))):
        fn = getattr(mod, f"_C_{verb.upper()}")
        extra = (None,) if verb == "ik" and name in SERIAL else ()
        plain = fn(np.asarray(arg, float), d.native, *extra)  # without the result spec: the tuple
        assert type(made) is _runtime.Solutions and type(plain) is tuple, (name, verb)
        with pytest.raises(dataclasses.FrozenInstanceError):
            made.status = 1
        spec = getattr(mod, f"_{verb.upper()}_RESULT")
        assert made.reason == spec[1][made.count] and made.status == plain[0] & 255, (name, verb)
        for field, value in zip(("values", "valid", "flags", "aux"), plain[1:], strict=True):
            np.testing.assert_array_equal(getattr(made, field), value, err_msg=f"{name} {verb} {field}")


def _numpy_design(mod, name):
    """The default design without its C counterpart: its verbs take the numpy path."""
    c = mod.make_design()
    return mod.Design(c.params, c.constants, c.theta0) if name == "underactuated_wrist" else mod.Design(c.params)


def _unworded_inputs(mod, name, rng):
    """IK inputs whose outcome C finds but cannot word: unreachable poses, and rotations a little off SO(3)
    (projected: the reason reports the deviation)."""
    if name == "underactuated_wrist":  # Euler angles where a branch has |C| > sqrt(A^2 + B^2)
        design = _numpy_design(mod, name)
        poses = (rng.uniform(-math.pi, math.pi, 3) for _ in range(400))
        return [p for p in poses if mod.ik(p, design).status == mod.STATUS_UNREACHABLE][:3]
    if name == "rsr_wrist":  # (alpha, beta, l_bw): the legs cannot span a bottom-to-wrist length 10x theirs
        pose = mod.fk(np.full(3, 0.3)).values[0]
        return [pose + np.array([0.0, 0.0, 10.0 * abs(pose[2]) + 1.0])]
    q = _joints(mod, rng, False)
    if name == "scara_rsr":  # [R | p] and l_bw
        off = mod.fk(q).values[0].copy()
        off[[0, 1, 2, 4, 5, 6, 8, 9, 10]] *= 1.0 + 1e-8
        return [off]
    T = mod.fk_matrix(q)
    off, far = T.copy(), T.copy()
    off[:3, :3] *= 1.0 + 1e-8
    far[:3, 3] += 50.0
    return [off, far]


@pytest.mark.skipif(FORCED_NUMPY, reason="WRISTKIN_BACKEND=numpy: the fallback pass")
@pytest.mark.parametrize("name", NATIVE)
def test_an_outcome_c_cannot_word_comes_from_c_and_is_worded_only_when_read(name, monkeypatch):
    """An unreachable pose, a projected one, the wrist's unreachable branch: ik answers from C and runs the numpy
    path once, when the reason is first read (it ran it on every such call, 30-700x the C call's time). The result
    equals the numpy path's, reason included, also after the caller changed the input array in place, and a
    pickled result carries the worded reason."""
    mod = module(name)
    c_design, py_design = mod.make_design(), _numpy_design(mod, name)
    rev = np.array(getattr(mod, "JOINT_KINDS", "RRR")) == "R"
    expected = [(x, mod.ik(x, py_design)) for x in _unworded_inputs(mod, name, case_rng(37))]
    # (a prismatic chain reaches the far pose: its count is the whole reason)
    expected = [(x, b) for x, b in expected if b.status != mod.STATUS_OK or np.any(b.flags & mod.FLAG_PROJECTED)]
    calls = []
    numpy_ik = mod._ik_numpy
    monkeypatch.setattr(mod, "_ik_numpy", lambda *args: calls.append(args) or numpy_ik(*args))
    worded_later = 0
    for x, b in expected:
        calls.clear()
        arg = np.array(x, dtype=float)
        a = mod.ik(arg, c_design)
        assert calls == [], f"{name}: the numpy path ran before the reason was read"
        worded_later += "reason" not in a.__dict__
        arg += 1.0  # the reason describes the call, not the array's later contents
        _same(a, b, SPECIAL_TOL, f"{name} ik of {x.tolist()}", rev)
        assert a.reason == b.reason and len(calls) == 1, name
        second_read = a.reason
        assert second_read == b.reason and len(calls) == 1, "the reason is worded once"
        again = pickle.loads(pickle.dumps(mod.ik(x, c_design)))
        assert type(again) is type(a) and again.reason == b.reason and "_explain" not in again.__dict__
    assert worded_later == len(expected) and worded_later >= 1, name


@pytest.mark.skipif(FORCED_NUMPY, reason="WRISTKIN_BACKEND=numpy: the fallback pass")
def test_joints_with_no_assembly_come_back_from_c_as_numpy_words_them():
    """The wrist's fk where no assembly mode is real: the extension finishes the Solutions with the fixed reason the
    numpy path gives (it had taken the numpy path, ~100x slower), equal field by field."""
    mod = module("underactuated_wrist")
    c_design = mod.make_design()
    fallback = mod.Design(c_design.params, c_design.constants, c_design.theta0)  # no C design: the numpy path
    rng = case_rng(33)
    seen = 0
    while seen < 5:
        q = rng.uniform(0.0, 2 * math.pi, 3)
        c = mod.fk(q)
        if c.status != mod.STATUS_NO_ASSEMBLY:
            continue
        seen += 1
        n = mod.fk(q, fallback)
        assert (c.status, c.reason, c.count) == (n.status, n.reason, 0)
        assert np.array_equal(c.valid, n.valid) and np.array_equal(c.flags, n.flags)
        assert np.all(np.isnan(c.values)) and np.all(np.isnan(c.aux))


def _rigid(rng, reach=0.5):
    """A random rigid 4x4 (tests/reference's xyz + rpy)."""
    return ref.xyz_rpy(rng.uniform(-reach, reach, 3), rng.uniform(-math.pi, math.pi, 3))


@pytest.mark.parametrize("name", SERIAL)
def test_a_serial_arm_takes_base_and_tool_frames_on_both_paths(name):
    """make_design(base=B, tool=T): the pose is the tool's in the base's frame, B T0(q) T with T0 the independent
    reference's (tests/reference dh / screws; the catalogue's own frames are the identity), on C and numpy alike
    (1e-12); IK returns the generating joints of such a pose; the Jacobian is that framed pose's derivative (central
    differences of the reference, h = 1e-6: error O(h^2) ~ 1e-12 plus rounding eps / h ~ 2e-10); a design keeps its
    frames when its parameters change; a frame that is no rigid transform is refused on both paths."""
    mod = module(name)
    rng = case_rng(73)
    rev = np.array(mod.JOINT_KINDS) == "R"
    if name in dh_ref.MECHANISMS:  # the independent references: numeric DH matrices, or exponentials of the screws
        def own(q):
            return dh_ref.fk(name, q)
    else:
        robot = screw_ref.axes(name, mod.DESIGN_DEFAULT)

        def own(q):
            return screw_ref.fk(robot, q)
    for _ in range(5):
        base, tool = _rigid(rng), _rigid(rng, 0.2)
        c_design = mod.make_design(base=base, tool=tool)
        py_design = mod.Design(c_design.params, None, c_design.base, c_design.tool, c_design.frames)
        assert FORCED_NUMPY or c_design.native is not None
        for _ in range(6):
            q = _joints(mod, rng, False)
            want = base @ own(q) @ tool
            for d in (c_design, py_design):
                np.testing.assert_allclose(mod.fk_matrix(q, d), want, atol=1e-12, rtol=0)
                np.testing.assert_allclose(mod.fk(q, d).values[0], want[:3].ravel(), atol=1e-12, rtol=0)
            np.testing.assert_allclose(mod.fk_batch(np.array([q, q]), c_design).values[:, 0],
                                       np.array([want[:3].ravel()] * 2), atol=1e-12, rtol=0)
            a, b = mod.ik(want, c_design), mod.ik(want, py_design)
            _same(a, b, _conditioned(mod, c_design, a.values[a.valid], REGULAR_TOL * 10), f"{name} framed ik", rev)
            assert min(float(np.max(np.abs(_diff(v, q, rev)))) for v in a.values[a.valid]) <= 1e-9
            jac = mod.jacobian(q, c_design)
            np.testing.assert_allclose(jac, mod.jacobian(q, py_design), atol=1e-12, rtol=0)
            h = 1e-6
            for j in range(mod.N_JOINTS):
                dq = np.zeros(mod.N_JOINTS)
                dq[j] = h
                tp, tm = base @ own(q + dq) @ tool, base @ own(q - dq) @ tool
                lin = (tp[:3, 3] - tm[:3, 3]) / (2 * h)
                skew = (tp[:3, :3] - tm[:3, :3]) / (2 * h) @ want[:3, :3].T
                ang = np.array([skew[2, 1], skew[0, 2], skew[1, 0]])
                np.testing.assert_allclose(jac[:, j], np.concatenate([lin, ang]), atol=1e-8, rtol=0)
    moved = mod.make_design(c_design, base=np.eye(4))
    assert moved.tool == c_design.tool and moved.base == tuple(map(tuple, np.eye(4)))
    assert mod.make_design(moved) is moved
    bad = np.eye(4)
    bad[0, 0] = 1.5
    with pytest.raises(mod.WristkinError):
        mod.make_design(base=bad)
    with pytest.raises(mod.WristkinError):
        mod.make_design(tool=np.full((4, 4), np.nan))
