"""A serial arm's hand-written numerics (runtime/python/serial_*.py, runtime/c/serial/sr_*.c) tested as they are:
the Python sources imported on their own (serial_stand_in: the PUMA-560's constants and derived kernels), the C
sources compiled strictly with each catalogue serial robot's switches and derived kernels, on cases whose answer
is known by construction (a stage equation's generating root, the generating joints among the IK sets), C and
Python on the same poses, and the generated files carrying the sources verbatim."""

from __future__ import annotations

import ctypes
import hashlib
import importlib
import math
import re
import sys
from pathlib import Path

import numpy as np
import pytest
from cbuild import BUILD_DIR, RUNTIME_C, compile_shared, load
from seeding import case_rng

from derive import runtime_files
from derive.serial_core.views import (
    C_ARM_ANGLE_FILES,
    C_GENERAL6R_FILE,
    C_RUNTIME_AFTER_STAGES,
    C_RUNTIME_FILES,
    C_SP6_FILES,
    C_SPATIAL3_FILES,
    PY_RUNTIME_FILES,
)

ROOT = Path(__file__).resolve().parent.parent
GEN_C = ROOT / "generated" / "c"
SR_C = ROOT / "runtime" / "c" / "serial"
ROBOTS = ("puma560", "p1p2p3rarb", "rarararbrb", "rpp_wrist", "scara_wrist", "spherical_wrist", "wrist_1dof")
D = ctypes.POINTER(ctypes.c_double)
IP = ctypes.POINTER(ctypes.c_int)
U = ctypes.POINTER(ctypes.c_uint)
FLAG_SINGULAR_INVERSE, FLAG_DOUBLE_ROOT, FLAG_INDETERMINATE = 1, 8, 16
FLAG_MERGE_CANDIDATE = 0x10000  # internal (the runtime's): a pair within its stage's noise of a double root


def _p(a, t=D):
    return a.ctypes.data_as(t)


def _gap(a, b, kinds):
    d = np.asarray(a, float) - np.asarray(b, float)
    rev = np.array([k == "R" for k in kinds])
    d[rev] = np.remainder(d[rev] + math.pi, 2 * math.pi) - math.pi
    return float(np.max(np.abs(d)))


# ------------------------------------------------------------------------------------------------ Python sources
@pytest.fixture(scope="module")
def py():
    """The Python sources imported as they are (each other and serial_stand_in above their markers)."""
    sys.path.insert(0, str(ROOT / "runtime" / "python"))
    try:
        import serial_fk
        import serial_ik
        import serial_stages
    finally:
        sys.path.remove(str(ROOT / "runtime" / "python"))
    return type("Sources", (), {"stages": serial_stages, "ik": serial_ik, "fk": serial_fk})


def test_trig_linear_returns_the_generating_root_and_one_double_root_at_a_tangent(py):
    rng = case_rng(2240)
    st = py.stages
    for _ in range(50):
        a, b = rng.normal(size=2)
        q0 = rng.uniform(-math.pi, math.pi)
        cc = -(a * math.cos(q0) + b * math.sin(q0))
        roots = []
        for sgn in (1.0, -1.0):
            q, c, s = [0.0], [1.0], [0.0]
            ok, f = st._trig_linear((a, b, cc), 0, sgn, q, c, s, None, [1.0])
            assert ok and f == 0
            assert abs(a * c[0] + b * s[0] + cc) <= 1e-14 * (1 + abs(a) + abs(b))
            assert abs(c[0] - math.cos(q[0])) <= 1e-15 and abs(s[0] - math.sin(q[0])) <= 1e-15
            roots.append(q[0])
        assert min(abs(math.remainder(r - q0, 2 * math.pi)) for r in roots) <= 1e-12
        # tangent: C = -sqrt(A^2 + B^2) has the double root atan2(B, A), reported once (+ branch), flagged
        t = -math.hypot(a, b)
        q, c, s = [0.0], [1.0], [0.0]
        a1 = [1.0]
        assert st._trig_linear((a, b, t), 0, 1.0, q, c, s, None, a1) == (True, FLAG_DOUBLE_ROOT | FLAG_SINGULAR_INVERSE)
        assert a1[0] == 1.0 / math.sqrt(py.stages.ROOT_GAP_TOL)  # a double root: 1 / its band
        assert abs(math.remainder(q[0] - math.atan2(b, a), 2 * math.pi)) <= 1e-12
        assert st._trig_linear((a, b, t), 0, -1.0, q, c, s, None, [1.0]) == (False, 0)
    # a vanishing equation: the family's representative, previous's value when given
    q, c, s = [0.0], [1.0], [0.0]
    family = (True, FLAG_INDETERMINATE | FLAG_SINGULAR_INVERSE)
    assert st._trig_linear((0.0, 0.0, 0.0), 0, 1.0, q, c, s, [0.7], [1.0]) == family
    assert q == [0.7]


def test_a_distance_stage_keeps_both_roots_of_a_fold_onto_its_centre(py):
    """Two equal links L folded to pi -+ delta: |w|^2 = 2 L^2 (1 + cos q), so L^2 cos q + (L^2 - |w|^2 / 2) = 0. From
    u alone the roots merge below delta ~ sqrt(eps) (1 - u^2 = sin^2 delta is lost next to 1); from the factors
    Dm = |w|^2 - (L - L)^2, Dp = (L + L)^2 - |w|^2 they are the two generating roots to eps relative in delta, down
    to delta = 1e-12 (|w| is known to eps of itself, so delta is), marked a merge candidate (sin^2 delta within
    ROOT_GAP_TOL: an exact fold split by that noise would look the same; the merge asks the pose) but not a double
    root. A fold whose links differ keeps the old band."""
    st = py.stages
    for length in (0.3, 1.7):
        for delta in (1e-4, 1e-8, 1e-12):
            w = 2.0 * length * math.sin(delta / 2.0)
            out = (length * length, 0.0, length * length - w * w / 2.0, w * w, 4.0 * length * length - w * w,
                   w * w + 2.0 * w * w)
            got = []
            for sgn in (1.0, -1.0):
                q, c, s, amp = [0.0], [1.0], [0.0], [1.0]
                near = math.sin(delta) ** 2 <= st.ROOT_GAP_TOL
                assert st._trig_linear(out, 0, sgn, q, c, s, None, amp) == (True, FLAG_MERGE_CANDIDATE if near else 0)
                got.append(abs(math.remainder(q[0] - math.pi, 2 * math.pi)))
                assert amp[0] == pytest.approx(1.0 / math.sin(delta), rel=1e-9)
            assert got == pytest.approx([delta, delta], rel=1e-10, abs=1e-16)
            if delta < 1e-6:  # the same stage read from u alone: one double root
                q, c, s = [0.0], [1.0], [0.0]
                assert st._trig_linear(out[:3], 0, -1.0, q, c, s, None, [1.0]) == (False, 0)
    # unequal links folded to the tangent: the band is DOUBLE_ROOT_TOL's, one root at the centre, flagged
    a1, a2 = 0.4, 0.3
    w = a1 - a2
    out = (a1 * a2, 0.0, (a1 * a1 + a2 * a2 - w * w) / 2.0, w * w - (a1 - a2) ** 2, (a1 + a2) ** 2 - w * w,
           2 * w * w + 2 * (a1 - a2) ** 2)
    q, c, s = [0.0], [1.0], [0.0]
    assert st._trig_linear(out, 0, 1.0, q, c, s, None, [1.0]) == (True, FLAG_DOUBLE_ROOT | FLAG_SINGULAR_INVERSE)
    assert abs(math.remainder(q[0] - math.pi, 2 * math.pi)) <= 1e-7
    assert st._trig_linear(out, 0, -1.0, q, c, s, None, [1.0]) == (False, 0)


def test_a_wrist_gap_stage_separates_its_roots_down_to_the_wrists_rounding(py):
    """A UR-type wrist's angle from cos q = n.w (A = 1, B = 0, C = -cos delta) with its half-gap factored from
    |n x w| = sin delta: Dm = 2 sin^2 delta, Dp = 2, Em = 4 sin delta. With the wrist's band (WRIST_EXACT_TOL, as the
    DH wrist's family band on |sin theta5|: 2 WRIST_EXACT_TOL amp_before on |n x w|) the two generating roots come
    back at delta = 1e-10 behind an arm that amplifies the rounding 100-fold (the distance band, 4500 eps, merged
    them: a 60-degree wrist 1e-10 from straight lost its generating joints); |n x w| at the rounding of such an
    input (eps x amp_before) is one double root, flagged. Within WRIST_EXACT_TOL amp_before of it (sin^2 delta) the
    pair is a merge candidate: the merge asks the pose whether it tells them apart."""
    st = py.stages
    amp_before = 100.0
    for delta in (1e-4, 1e-8, 1e-10):
        out = (1.0, 0.0, -math.cos(delta), 2.0 * math.sin(delta) ** 2, 2.0, 4.0 * math.sin(delta))
        got = []
        for sgn in (1.0, -1.0):
            q, c, s, amp = [0.0], [1.0], [0.0], [1.0]
            near = math.sin(delta) ** 2 <= st.WRIST_EXACT_TOL * amp_before
            assert st._trig_linear(out, 0, sgn, q, c, s, None, amp, amp_before, st.WRIST_EXACT_TOL) == \
                (True, FLAG_MERGE_CANDIDATE if near else 0)
            got.append(q[0])
        assert got == pytest.approx([delta, -delta], rel=1e-12)
    noise = 4 * float(np.finfo(float).eps) * amp_before
    out = (1.0, 0.0, -math.cos(noise), 2.0 * noise ** 2, 2.0, 4.0 * noise)
    q, c, s = [0.0], [1.0], [0.0]
    flags = st._trig_linear(out, 0, 1.0, q, c, s, None, [1.0], amp_before, st.WRIST_EXACT_TOL)
    assert flags == (True, FLAG_DOUBLE_ROOT | FLAG_SINGULAR_INVERSE) and q == [0.0]
    assert st._trig_linear(out, 0, -1.0, q, c, s, None, [1.0], amp_before, st.WRIST_EXACT_TOL) == (False, 0)
    # the exact singularity with nothing left to round (|n x w| = 0: Dm = Em = 0, u one ulp past 1), as a UR at q5 = 0
    # gave it (seed 2): one double root and a finite amplification (it divided by a band of 0)
    out, amp = (1.0, 0.0, -1.0000000000000002, 0.0, 2.0, 0.0), [1.0]
    flags = st._trig_linear(out, 0, 1.0, q, c, s, None, amp, 1.02, st.WRIST_EXACT_TOL)
    assert flags == (True, FLAG_DOUBLE_ROOT | FLAG_SINGULAR_INVERSE) and q == [0.0] and math.isfinite(amp[0])



def test_a_wrist_gap_within_rounding_of_its_family_keeps_both_roots_flagged_indeterminate(py):
    """The same UR-type wrist stage with the family's floor (WRIST_FAMILY_TOL, the rounding measured at exact
    singularities with a margin): a half-gap |n x w| = sin delta above 2 WRIST_FAMILY_TOL amp_before but within
    2 WRIST_EXACT_TOL amp_before is the pose's own reading, both roots +-delta, flagged indeterminate and singular (a
    UR5e at q5 = 1e-12 read as one double root gave the family's member 2 rad from the generating joints); below the
    floor one double root, as before."""
    st = py.stages
    amp_before = 10.0
    delta = 1e-12  # 2 WRIST_FAMILY_TOL amp_before = 2.8e-13 < delta < 2 WRIST_EXACT_TOL amp_before = 2e-12
    out = (1.0, 0.0, -math.cos(delta), 2.0 * math.sin(delta) ** 2, 2.0, 4.0 * math.sin(delta))
    got = []
    for sgn in (1.0, -1.0):
        q, c, s, amp = [0.0], [1.0], [0.0], [1.0]
        assert st._trig_linear(out, 0, sgn, q, c, s, None, amp, amp_before, st.WRIST_EXACT_TOL, 1.0,
                               st.WRIST_FAMILY_TOL) == (True, FLAG_INDETERMINATE | FLAG_SINGULAR_INVERSE)
        got.append(q[0])
    assert got == pytest.approx([delta, -delta], rel=1e-12)
    noise = 4 * float(np.finfo(float).eps) * amp_before  # below the floor: one double root
    out = (1.0, 0.0, -math.cos(noise), 2.0 * noise ** 2, 2.0, 4.0 * noise)
    q, c, s = [0.0], [1.0], [0.0]
    assert st._trig_linear(out, 0, 1.0, q, c, s, None, [1.0], amp_before, st.WRIST_EXACT_TOL, 1.0,
                           st.WRIST_FAMILY_TOL) == (True, FLAG_DOUBLE_ROOT | FLAG_SINGULAR_INVERSE) and q == [0.0]

def test_rotation2d_is_the_angle_between_the_two_vectors(py):
    rng = case_rng(2241)
    for _ in range(30):
        t0, t = rng.uniform(-math.pi, math.pi, 2)
        r0, r = rng.uniform(0.1, 3.0, 2)
        q, c, s = [0.0], [1.0], [0.0]
        out = (r * math.cos(t0 + t), r * math.sin(t0 + t), r0 * math.cos(t0), r0 * math.sin(t0))
        assert py.stages._rotation2d(out, 0, q, c, s, None, [1.0]) == (True, 0)
        assert abs(math.remainder(q[0] - t, 2 * math.pi)) <= 1e-13


def test_python_ik_returns_the_generating_joints_and_the_wrist_family_near_previous(py):
    """PUMA-560 through the runtime sources: FK(q) -> IK contains q; at the wrist singularity (q5 = 0) one set of
    the family, moved to previous's q4 when given."""
    rng = case_rng(2242)
    kinds = py.ik.JOINT_KINDS
    for i in range(40):
        q = rng.uniform(-math.pi, math.pi, 6)
        pose = py.fk.fk_matrix(q)
        sol = py.ik.ik(pose)
        assert sol.status == 0
        assert min(_gap(v, q, kinds) for v in sol.values[sol.valid]) <= 1e-8, q
        assert all(np.max(np.abs(py.fk.fk_matrix(v) - pose)) <= 1e-9 for v in sol.values[sol.valid])
        if i < 10:
            q[4] = 0.0
            pose = py.fk.fk_matrix(q)
            sol = py.ik.ik(pose, previous=q)
            assert sol.status == py.ik.STATUS_INDETERMINATE  # the wrist family
            assert min(_gap(v, q, kinds) for v in sol.values[sol.valid]) <= 1e-8, q


# ------------------------------------------------------------------------------------------------ C sources
def _cut(name):
    """The generated C's robot-specific parts: before the first runtime source (constants, switches, types,
    kernels, data) and the stage functions between the stages banner and sr_ik.c."""
    text = (GEN_C / f"{name}.c").read_text()
    first = runtime_files.inline(C_RUNTIME_FILES[0])
    after = runtime_files.inline(C_RUNTIME_AFTER_STAGES[0])
    assert first in text and after in text
    stages = re.search(r"/\* -+ the IK stages", text).start()
    return text[:text.index(first)], text[stages:text.index(after)]


@pytest.fixture(scope="module", params=ROBOTS)
def clib(request):
    name = request.param
    prelude, stages = _cut(name)
    inc = BUILD_DIR / f"serial_runtime_{name}"
    inc.mkdir(parents=True, exist_ok=True)
    (inc / "serial_prelude.h").write_text(prelude)
    (inc / "serial_stages.h").write_text(stages)
    h = hashlib.sha256(b"".join(p.read_bytes() for p in sorted(SR_C.iterdir())) + prelude.encode()
                       + stages.encode()).hexdigest()[:16]
    so = compile_shared([ROOT / "tests" / "c" / "serial_runtime_harness.c", RUNTIME_C], [inc, GEN_C],
                        f"serial_runtime_{name}", extra_flags=[f"-DWKT_SOURCES={h}"])
    L = load(so)
    L.wkt_sr_ik.argtypes = [D, D, D, IP, U, D]
    L.wkt_sr_fk.argtypes = [D, D, D, D, U]
    L.wkt_sr_sizes.argtypes = [IP, IP]
    n, max_ik = ctypes.c_int(), ctypes.c_int()
    L.wkt_sr_sizes(ctypes.byref(n), ctypes.byref(max_ik))
    return name, L, n.value, max_ik.value


def _c_ik(L, n, max_ik, pose, previous=None):
    values, valid = np.zeros(max_ik * n), np.zeros(max_ik, np.int32)
    flags, aux = np.zeros(max_ik, np.uint32), np.zeros(max_ik)
    prev = None if previous is None else _p(np.ascontiguousarray(previous, float))
    status = L.wkt_sr_ik(_p(np.ascontiguousarray(pose, float)), prev, _p(values), _p(valid, IP), _p(flags, U),
                         _p(aux))
    return status, values.reshape(max_ik, n), valid.astype(bool), flags.astype(np.int64)


def test_c_sources_solve_every_catalogue_serial_robot_as_python_does(clib):
    """Each robot's switches compile the C sources strictly; FK(q) -> IK contains q on a generic pose, and the
    sets, flags and status equal the generated Python module's numpy path (one algorithm in both)."""
    name, L, n, max_ik = clib
    mod = importlib.import_module(f"wristkin.{name}")
    assert mod.N_JOINTS == n and mod.MAX_IK == max_ik
    design = mod.make_design()
    rng = case_rng(2243)
    kinds = mod.JOINT_KINDS
    for i in range(40):
        q = np.array([rng.uniform(-math.pi, math.pi) if k == "R" else rng.uniform(-0.4, 0.4) for k in kinds])
        if i < 8 and n >= 5:
            q[-2] = 0.0 if i < 4 else 1e-9  # a wrist at or next to its singularity
        pose, jac, man, fl = np.zeros(12), np.zeros(6 * n), ctypes.c_double(), ctypes.c_uint()
        assert L.wkt_sr_fk(_p(q), _p(pose), _p(jac), ctypes.byref(man), ctypes.byref(fl)) == 0
        assert np.max(np.abs(pose - mod.fk_matrix(q)[:3].ravel())) <= 1e-14
        assert np.max(np.abs(jac.reshape(6, n) - mod.jacobian(q))) <= 1e-14
        status, values, valid, flags = _c_ik(L, n, max_ik, pose, q if i % 2 else None)
        ref = mod._ik_numpy(pose, design, q if i % 2 else None)  # the numpy path: the Python sources
        assert status == ref.status and list(valid) == list(ref.valid), (name, q)
        if i >= 8:
            # one algorithm in both, rounding apart: each set agrees to its conditioning, a few eps of the pose over
            # sigma_min of J there (seed 3 under Haswell: the PUMA's sets 1.2e-12 apart at sigma_min 3.5e-4)
            for a, b in zip(values[valid], ref.values[ref.valid], strict=True):
                sigma_min = np.linalg.svd(mod.jacobian(b), compute_uv=False)[-1]
                tol = max(1e-12, 64 * np.finfo(float).eps * max(1.0, float(np.max(np.abs(pose)))) / sigma_min)
                assert np.max(np.abs(a - b)) <= tol, (name, q, np.max(np.abs(a - b)), tol)
        else:  # next to the wrist singularity q4 and q6 alone are fixed to eps / sin(q5) only: compare the poses
            assert all(np.max(np.abs(mod.fk_matrix(a) - mod.fk_matrix(b))) <= 1e-9
                       for a, b in zip(values[valid], ref.values[ref.valid], strict=True))
        assert list(flags[valid]) == list(ref.flags[ref.valid])
        if i >= 8:  # a generic pose (a singular family has its representative)
            assert min(_gap(v, q, kinds) for v in values[valid]) <= 1e-6, (name, q)


def _random_centre_jacobians(rng, count):
    """3 x 3 wrist-centre Jacobians U diag(sigma) V^T, sigma_min from 1 down to 1e-9 (a prefix near its own
    singularity), their sizes 0.1-2 m, and a wrist-centre position of 0.1-3 m."""
    for i in range(count):
        u, _ = np.linalg.qr(rng.normal(size=(3, 3)))
        v, _ = np.linalg.qr(rng.normal(size=(3, 3)))
        top = rng.uniform(0.1, 2.0)
        sigma = np.array([top, top * rng.uniform(0.05, 1.0), top * 10.0 ** -rng.uniform(0, 9 * (i % 4) / 3)])
        pose = np.zeros(12)
        pose[[3, 7, 11]] = rng.normal(size=3) * rng.uniform(0.1, 3.0)
        yield u @ np.diag(sigma) @ v.T, pose


def test_the_wrist_band_factor_reads_the_wrist_centre_kappa(py):
    """_wrist_amp against an independent reading: kappa_F = size ||J^-1||_F from numpy's inverse (size = max(1,
    |p|)), between size / sigma_min (the SVD) and sqrt(3) times that; the factor min(WRIST_KAPPA_SHARE kappa_F,
    WRIST_AMP_SHARE amp_before) to the cofactors' rounding relative to the inverse's (16 eps cond(J)); amp_before
    where there is no kernel, where |sin theta5| is beyond twice the widest band's reach (the kernel not read) and
    at det J = 0 exactly (the cap)."""
    st = py.stages
    rng = case_rng(2262)
    eps = float(np.finfo(float).eps)
    for jac, pose in _random_centre_jacobians(rng, 200):
        amp = 10.0 ** rng.uniform(0.0, 6.0)
        entries = tuple(jac.ravel())
        got = st._wrist_amp(0.0, amp, lambda *_, m=entries: m, pose, None, None, None, None)
        size = max(1.0, float(np.max(np.abs(pose[[3, 7, 11]]))))
        sv = np.linalg.svd(jac, compute_uv=False)
        kappa_f = size * float(np.linalg.norm(np.linalg.inv(jac)))
        assert size / sv[-1] * (1 - 1e-6) <= kappa_f <= math.sqrt(3.0) * size / sv[-1] * (1 + 1e-6)
        want = min(st.WRIST_KAPPA_SHARE * kappa_f, st.WRIST_AMP_SHARE * amp)
        assert abs(got - want) <= 16 * eps * sv[0] / sv[-1] * want, (got, want, sv)
    seen = []

    def kernel(*_):
        seen.append(1)
        return (1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0)
    far = 2.0 * st.WRIST_EXACT_TOL * st.WRIST_AMP_SHARE * 3.0 * 1.01
    assert st._wrist_amp(far, 3.0, kernel, np.zeros(12), None, None, None, None) == 3.0 and not seen
    assert st._wrist_amp(0.0, 3.0, None, np.zeros(12), None, None, None, None) == 3.0
    flat = (1.0, 2.0, 3.0, 2.0, 4.0, 6.0, 0.0, 1.0, 0.0)  # two rows parallel: det 0 exactly
    assert st._wrist_amp(0.0, 3.0, lambda *_: flat, np.zeros(12), None, None, None, None) == st.WRIST_AMP_SHARE * 3.0


KERNEL = ctypes.CFUNCTYPE(None, D, D, D, D, D, D)


def test_c_wrist_band_factor_is_pythons_to_the_bit(clib, py):
    """sr_wrist_amp and _wrist_amp read the same kernel output with the same operations: the same double, on the
    random Jacobians above, a singular one and beyond the gate."""
    name, L, _, _ = clib
    L.wkt_sr_has_wrist.restype = ctypes.c_int
    if not L.wkt_sr_has_wrist():
        pytest.skip(f"{name} has no spherical wrist stage")
    L.wkt_sr_wrist_amp.restype = ctypes.c_double
    L.wkt_sr_wrist_amp.argtypes = [ctypes.c_double, ctypes.c_double, KERNEL, D]
    st = py.stages
    rng = case_rng(2263)
    cases = list(_random_centre_jacobians(rng, 60))
    cases.append((np.array([[1.0, 2.0, 3.0], [2.0, 4.0, 6.0], [0.0, 1.0, 0.0]]), np.zeros(12)))
    for jac, pose in cases:
        m = tuple(jac.ravel())

        def fill(_pose, _q, _c, _s, _dp, out, m=m):
            for i, v in enumerate(m):
                out[i] = v
        cb = KERNEL(fill)
        for s5 in (0.0, 1e-12, 1.0):
            amp = 10.0 ** rng.uniform(0.0, 4.0)
            want = st._wrist_amp(s5, amp, lambda *_, m=m: m, pose, None, None, None, None)
            assert L.wkt_sr_wrist_amp(s5, amp, cb, _p(np.ascontiguousarray(pose))) == want, (name, jac, s5)


def test_c_design_init_rejects_what_python_rejects(clib):
    name, L, n, _ = clib
    mod = importlib.import_module(f"wristkin.{name}")
    L.wkt_sr_design_init.argtypes = [D, ctypes.c_void_p]
    buf = ctypes.create_string_buffer(L.wkt_sr_sizes(ctypes.byref(ctypes.c_int()), ctypes.byref(ctypes.c_int())))
    for scale in (1.0, 1e-6, 1e7):
        params = np.array(mod.DESIGN_DEFAULT, float) * scale
        try:
            mod.make_design(params)
            want = 0
        except mod.InvalidDesign:
            want = -3  # WK_ERR_DESIGN
        assert L.wkt_sr_design_init(_p(params), buf) == want, (name, scale)


def test_the_generated_files_carry_the_sources_verbatim():
    for name in ROBOTS:
        py = (ROOT / "generated" / "python" / "wristkin" / f"{name}.py").read_text()
        c = (GEN_C / f"{name}.c").read_text()
        assert all(runtime_files.inline(rel) in py for rel in PY_RUNTIME_FILES), name
        assert all(runtime_files.inline(rel) in c for rel in C_RUNTIME_FILES + C_RUNTIME_AFTER_STAGES), name
    # every serial C source is one of them, or the general 6R's, the spatial 3R's, subproblem 6's or the arm angle's
    # stage (a chain with such a stage carries it: test_derived_robot's multi-candidate stage tests, test_arm_angle)
    staged = tuple(f for f in C_SPATIAL3_FILES + C_SP6_FILES + C_ARM_ANGLE_FILES if f.startswith("c/serial/"))
    assert sorted(C_RUNTIME_FILES + C_RUNTIME_AFTER_STAGES + (C_GENERAL6R_FILE,) + staged) == sorted(
        f"c/serial/{p.name}" for p in SR_C.glob("*.c"))
    for template in ("c/serial.c.jinja", "python/serial.py.jinja"):
        text = (ROOT / "templates" / template).read_text()
        assert len(text.splitlines()) <= 400 and not re.search(r"\{%-?\s*(el)?if\b", text), template
