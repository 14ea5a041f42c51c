"""The 3-RSR core shared by the 3-RSR wrist and the SCARA hybrid (runtime/python/rsr_legs.py,
runtime/c/rsr/rsr_legs.c) and the wrist's verbs (rsr_wrist_api.py / .c) tested as they are: the Python sources
imported with rsr_stand_in (the catalogue wrist's tolerances and derived kernels), the C sources compiled strictly
after the wrist's generated prelude, on cases whose answer is known by construction (leg roots that satisfy their
equations and contain the generating joints, the mirror plane of the generating joints, a workspace interval
holding the generating l_bw, IK of FK holding the joints), C and Python on the same inputs, and the generated
wrists carrying the sources verbatim."""

from __future__ import annotations

import ctypes
import hashlib
import math
import re
import sys
from pathlib import Path

import numpy as np
import pytest
from cbuild import BUILD_DIR, RUNTIME_C, compile_shared, load
from seeding import case_rng

from derive import runtime_files

ROOT = Path(__file__).resolve().parent.parent
GEN_C = ROOT / "generated" / "c"
D = ctypes.POINTER(ctypes.c_double)
U = ctypes.POINTER(ctypes.c_uint)
W = (0.06, 0.4363323129985824, 1.3089969389957472, 0.02, 0.11)  # the catalogue wrist's design (L, limits)


def _p(a):
    return np.ascontiguousarray(a, dtype=float).ctypes.data_as(D)


@pytest.fixture(scope="module")
def py():
    sys.path.insert(0, str(ROOT / "runtime" / "python"))
    try:
        import rsr_legs
        import rsr_wrist_api
    finally:
        sys.path.remove(str(ROOT / "runtime" / "python"))
    rsr_legs.api = rsr_wrist_api
    return rsr_legs


def _build(name, api_source, harness):
    """The harness of `name`'s sources: its generated C cut before the core (prelude) and between the core and the
    verbs (the default design), the prelude's kernels referenced by name."""
    text = (GEN_C / f"{name}.c").read_text()
    source, api = runtime_files.inline("c/rsr/rsr_legs.c"), runtime_files.inline(api_source)
    prelude = text[:text.index(source)]
    between = text[text.index(source) + len(source):text.index(api)]
    kernels = re.findall(r"static void (rsr_k_\w+)\(", prelude)
    assert len(kernels) >= 4
    inc = BUILD_DIR / f"rsr_runtime_{name}"
    inc.mkdir(parents=True, exist_ok=True)
    (inc / "rsr_prelude.h").write_text(prelude)
    (inc / "rsr_between.h").write_text(between)
    (inc / "rsr_kernels.h").write_text("void (*const wkt_rsr_kernels[])(void) = {\n" + ",\n".join(
        f"    (void (*)(void)){k}" for k in kernels) + "\n};\n")  # void (*)(void): the generic function type
    h = hashlib.sha256((source + api + prelude + between).encode()).hexdigest()[:16]
    return load(compile_shared([ROOT / "tests" / "c" / harness, RUNTIME_C], [inc, GEN_C], f"rsr_runtime_{name}",
                               extra_flags=[f"-DWKT_SOURCES={h}"]))


@pytest.fixture(scope="module")
def lib():
    L = _build("rsr_wrist", "c/rsr/rsr_wrist_api.c", "rsr_runtime_harness.c")
    L.wkt_rsr_legs.argtypes = [D, D, D, U, D]
    L.wkt_rsr_plane.argtypes = [D, D, D, D]
    L.wkt_rsr_pose_of_plane.argtypes = [D, D]
    L.wkt_rsr_workspace.argtypes = [ctypes.c_double, ctypes.c_double, D, D]
    L.wkt_rsr_leg_cond_inverse.argtypes = [D, D, D]
    L.wkt_rsr_leg_cond_inverse.restype = ctypes.c_double
    L.wkt_rsr_design_ok.argtypes = [D]
    for verb in ("ik", "fk"):
        getattr(L, f"wkt_rsr_{verb}").argtypes = [D, ctypes.c_void_p, ctypes.c_void_p]
    L.wkt_rsr_design_init.argtypes = [D, ctypes.c_void_p]
    return L


def _poses(py, rng, n):
    """(joints, pose) pairs: the pose of the mirror plane of random joints within the wrist's joint limits, whose
    l_bw is within its limits too (the workspace then holds it)."""
    out = []
    while len(out) < n:
        q = rng.uniform(W[1], W[2], 3)
        plane = py._plane(tuple(q), W)
        if plane is None:
            continue
        pose, _, _ = py._pose_of_plane(plane[0])
        if W[3] <= pose[2] <= W[4]:
            out.append((q, pose))
    return out


def test_python_legs_contain_the_generating_joints_and_c_agrees(py, lib):
    rng = case_rng(2250)
    for q, pose in _poses(py, rng, 40):
        roots, flags, conds, reason = py._legs(pose, W)
        assert all(r is not None for r in roots), reason
        a1, a2, a3, b, c = py._k_ik_coeffs(pose, W)
        for i, (a, pair) in enumerate(zip((a1, a2, a3), roots, strict=True)):
            for phi, cp, sp_, res in pair:
                assert abs(a * cp + b * sp_ - c) <= 1e-14 and res <= 1e-14
                assert abs(cp - math.cos(phi)) <= 1e-15 and abs(sp_ - math.sin(phi)) <= 1e-15
            assert min(abs(math.remainder(phi - q[i], 2 * math.pi)) for phi, *_ in pair) <= 1e-9
        leg, cflags, cond = np.zeros(24), np.zeros(3, np.uint32), ctypes.c_double()
        assert lib.wkt_rsr_legs(_p(pose), _p(W), leg.ctypes.data_as(D), cflags.ctypes.data_as(U), ctypes.byref(cond))
        assert np.allclose(leg.reshape(3, 2, 4), np.array(roots), rtol=0, atol=1e-14)
        assert list(cflags) == flags and abs(cond.value - min(conds)) <= 1e-15


def test_plane_pose_and_conditioning_in_python_and_c(py, lib):
    rng = case_rng(2251)
    for q, pose in _poses(py, rng, 30):
        plane, cond = py._plane(tuple(q), W)
        cplane, ccond = np.zeros(4), ctypes.c_double()
        assert lib.wkt_rsr_plane(_p(q), _p(W), cplane.ctypes.data_as(D), ctypes.byref(ccond)) == 1
        assert np.allclose(cplane, plane, rtol=0, atol=1e-15) and abs(ccond.value - cond) <= 1e-15
        cpose = np.zeros(3)
        lib.wkt_rsr_pose_of_plane(_p(plane), cpose.ctypes.data_as(D))
        assert np.allclose(cpose, pose, rtol=0, atol=1e-15)
        ci = py._leg_cond_inverse(tuple(q), pose, W)
        assert 0.0 <= ci <= 1.0 and abs(lib.wkt_rsr_leg_cond_inverse(_p(q), _p(pose), _p(W)) - ci) <= 1e-15
        span = py._workspace(pose[0], pose[1], W)
        assert span is not None and span[0] - 1e-12 <= pose[2] <= span[1] + 1e-12
        cspan = np.zeros(2)
        assert lib.wkt_rsr_workspace(pose[0], pose[1], _p(W), cspan.ctypes.data_as(D)) == 1
        assert np.allclose(cspan, span, rtol=0, atol=1e-15)


def test_design_rule_is_the_same_in_python_and_c(py, lib):
    for w in (W, (0.0, *W[1:]), (1e7, *W[1:]), (W[0], 1.0, 0.5, *W[3:]), (W[0], W[1], W[2], 0.05, 0.02),
              (W[0], W[1], W[2], 0.0, 3 * W[0])):
        assert (py._wrist_design_error(w) is None) == bool(lib.wkt_rsr_design_ok(_p(w))), w


def _solutions(n, width, naux):
    class S(ctypes.Structure):
        _fields_ = [("count", ctypes.c_int), ("status", ctypes.c_int), ("valid", ctypes.c_int * n),
                    ("flags", ctypes.c_uint * n), ("values", (ctypes.c_double * width) * n),
                    ("aux", (ctypes.c_double * naux) * n)]
    return S


def test_the_verbs_in_python_and_c_return_the_generating_joints_alike(py, lib):
    """The wrist's verbs (rsr_wrist_api): FK of random joints, then IK of that pose holds the joints; C gives
    Python's sets, flags, aux and status (one algorithm in both)."""
    api = py.api
    design = api.make_design(W)
    cd = ctypes.create_string_buffer(8 * 5)
    assert lib.wkt_rsr_design_init(_p(W), cd) == 0
    ik_s, fk_s = _solutions(api.MAX_IK, 3, len(api.IK_AUX_NAMES)), _solutions(1, 3, len(api.FK_AUX_NAMES))
    rng = case_rng(2252)
    for q, pose in _poses(py, rng, 30):
        f = api.fk(q, design)
        cf = fk_s()
        assert lib.wkt_rsr_fk(_p(q), cd, ctypes.byref(cf)) == 0 and cf.status == f.status
        assert np.allclose(np.array(cf.values)[0], f.values[0], rtol=0, atol=1e-15)
        assert np.allclose(np.array(cf.values)[0], pose, rtol=0, atol=1e-13)
        s = api.ik(pose, design)
        assert min(np.max(np.abs(np.remainder(v - q + math.pi, 2 * math.pi) - math.pi))
                   for v in s.values[s.valid]) <= 1e-9
        ci = ik_s()
        assert lib.wkt_rsr_ik(_p(pose), cd, ctypes.byref(ci)) == 0 and ci.status == s.status
        assert [bool(v) for v in ci.valid] == list(s.valid) and list(ci.flags) == list(s.flags)
        assert np.allclose(np.array(ci.values)[s.valid], s.values[s.valid], rtol=0, atol=1e-15)
        assert np.allclose(np.array(ci.aux)[s.valid], s.aux[s.valid], rtol=0, atol=1e-15)


def test_the_hybrid_in_python_and_c_returns_the_generating_joints_alike():
    """The SCARA + 3-RSR hybrid's verbs (scara_rsr_api, with scara_stand_in): IK of FK holds the generating joints;
    C (its source compiled strictly after the hybrid's generated prelude) equals Python on sets, flags and status."""
    sys.path.insert(0, str(ROOT / "runtime" / "python"))
    try:
        import scara_rsr_api as api
    finally:
        sys.path.remove(str(ROOT / "runtime" / "python"))
    L = _build("scara_rsr", "c/rsr/scara_rsr_api.c", "scara_runtime_harness.c")
    for verb in ("ik", "fk"):
        getattr(L, f"wkt_hy_{verb}").argtypes = [D, ctypes.c_void_p, ctypes.c_void_p]
    L.wkt_hy_design_init.argtypes = [D, ctypes.c_void_p]
    design = api.make_design(None)
    cd = ctypes.create_string_buffer(8 * len(design.params))
    assert L.wkt_hy_design_init(_p(design.params), cd) == 0
    ik_s, fk_s = _solutions(api.MAX_IK, api.N_JOINTS, len(api.IK_AUX_NAMES)), _solutions(1, 13, len(api.FK_AUX_NAMES))
    rng = case_rng(2253)
    lo, hi = design.params[5], design.params[6]
    kinds = np.array(api.JOINT_KINDS)
    for _ in range(30):
        q = np.array([*rng.uniform(-3, 3, 2), rng.uniform(-0.1, 0.1), rng.uniform(-3, 3), *rng.uniform(lo, hi, 3)])
        f = api.fk(q, design)
        cf = fk_s()
        assert L.wkt_hy_fk(_p(q), cd, ctypes.byref(cf)) == 0 and cf.status == f.status
        if f.status != 0:
            continue
        assert np.allclose(np.array(cf.values)[0], f.values[0], rtol=0, atol=1e-15)
        pose = f.values[0]
        s = api.ik(pose, design)
        gaps = [np.where(kinds == "R", np.remainder(v - q + math.pi, 2 * math.pi) - math.pi, v - q)
                for v in s.values[s.valid]]
        assert min(float(np.max(np.abs(g))) for g in gaps) <= 1e-9
        ci = ik_s()
        assert L.wkt_hy_ik(_p(pose), cd, ctypes.byref(ci)) == 0 and ci.status == s.status
        assert [bool(v) for v in ci.valid] == list(s.valid) and list(ci.flags) == list(s.flags)
        assert np.allclose(np.array(ci.values)[s.valid], s.values[s.valid], rtol=0, atol=1e-12)


def test_both_generated_wrists_carry_the_sources():
    for name in ("rsr_wrist", "scara_rsr"):
        assert runtime_files.inline("python/rsr_legs.py") in (ROOT / "generated" / "python" / "wristkin" /
                                                              f"{name}.py").read_text()
        assert runtime_files.inline("c/rsr/rsr_legs.c") in (GEN_C / f"{name}.c").read_text()
    assert runtime_files.inline("python/rsr_wrist_api.py") in (ROOT / "generated" / "python" / "wristkin" /
                                                             "rsr_wrist.py").read_text()
    assert runtime_files.inline("c/rsr/rsr_wrist_api.c") in (GEN_C / "rsr_wrist.c").read_text()
    assert runtime_files.inline("python/scara_rsr_api.py") in (ROOT / "generated" / "python" / "wristkin" /
                                                             "scara_rsr.py").read_text()
    assert runtime_files.inline("c/rsr/scara_rsr_api.c") in (GEN_C / "scara_rsr.c").read_text()
