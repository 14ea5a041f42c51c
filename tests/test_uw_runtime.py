"""The underactuated wrist's hand-written numerics (runtime/python/uw_*.py, runtime/c/underactuated_wrist/uw_*.c)
tested as they are: imported (Python) and compiled strictly (C) on their own with the catalogue wrist's derived
kernels, on cases whose answer is known by construction (the generating pose or joints among the returned sets,
a constructed root of the loop equations), C and Python on the same inputs, and the generated files carrying them
verbatim."""

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
from derive.families.spherical_parallel import C_RUNTIME_FILES, PY_RUNTIME_FILES

ROOT = Path(__file__).resolve().parent.parent
GEN_C = ROOT / "generated" / "c"
UW_C = ROOT / "runtime" / "c" / "underactuated_wrist"
D = ctypes.POINTER(ctypes.c_double)
DEFAULT = (math.pi / 3, math.pi / 3, math.pi / 6, 0.7660250087003112)  # the catalogue's design (radians)


def _p(a):
    return np.ascontiguousarray(a, dtype=float).ctypes.data_as(D)


class _Design(ctypes.Structure):
    _fields_ = [("params", ctypes.c_double * 4), ("c", ctypes.c_double * 22), ("theta0", ctypes.c_double)]


def _solutions(n, width, naux):
    class S(ctypes.Structure):
        _fields_ = [("count", ctypes.c_int), ("status", ctypes.c_int), ("valid", ctypes.c_int * n),
                    ("flags", ctypes.c_uint * n), ("values", (ctypes.c_double * width) * n),
                    ("aux", (ctypes.c_double * naux) * n)]
    return S


IkSolutions, FkSolutions = _solutions(8, 3, 5), _solutions(8, 3, 13)


@pytest.fixture(scope="module")
def lib():
    """The harness with every source; the derived kernels cut from the generated C (between its 'generated
    kernels' and 'real roots' banners), the 22 design constants checked against its header."""
    text = (GEN_C / "underactuated_wrist.c").read_text()
    assert "#define WK_UNDERACTUATED_WRIST_N_CONSTANTS 22" in (GEN_C / "underactuated_wrist.h").read_text()
    kernels = text[re.search(r"/\* -+ generated kernels \*/", text).end():re.search(r"/\* -+ real roots", text).start()]
    assert kernels.count("static void uw_k_") >= 10
    inc = BUILD_DIR / "uw_runtime_kernels"
    inc.mkdir(parents=True, exist_ok=True)
    (inc / "uw_kernels.h").write_text(kernels)
    # the harness includes the sources: their bytes name the build (compile_shared hashes only what it is given)
    h = hashlib.sha256(b"".join(p.read_bytes() for p in sorted(UW_C.iterdir()))).hexdigest()[:16]
    so = compile_shared([ROOT / "tests" / "c" / "uw_runtime_harness.c", RUNTIME_C], [GEN_C, inc], "uw_runtime",
                        extra_flags=[f"-DWKT_SOURCES={h}"])
    L = load(so)
    for verb in ("ik", "fk"):
        getattr(L, f"wkt_uw_{verb}").argtypes = [D, ctypes.c_void_p, ctypes.c_void_p]
    L.wkt_uw_design_init.argtypes = [D, ctypes.c_void_p]
    L.wkt_uw_euler.argtypes = [D, D, D, ctypes.POINTER(ctypes.c_uint)]
    L.wkt_uw_polynomial.argtypes = [D, ctypes.c_double, ctypes.c_double, D]
    L.wkt_uw_polish.argtypes = [D, D, D]
    L.wkt_uw_polish.restype = ctypes.c_double
    return L


@pytest.fixture(scope="module")
def py():
    """The Python sources imported as they are (their imports above the inlining marker: each other and
    uw_stand_in, which takes the derived kernels from the generated module; no C extension)."""
    sys.path.insert(0, str(ROOT / "runtime" / "python"))
    try:
        import uw_design
        import uw_fk
        import uw_fk_batch
        import uw_fk_modes
        import uw_ik
        import uw_rates
        import uw_select
    finally:
        sys.path.remove(str(ROOT / "runtime" / "python"))
    return type("Sources", (), {"design": uw_design, "ik": uw_ik, "fk": uw_fk, "fk_batch": uw_fk_batch,
                                "modes": uw_fk_modes, "rates": uw_rates, "select": uw_select})


def _c_design(lib, params):
    d = _Design()
    assert lib.wkt_uw_design_init(_p(params), ctypes.byref(d)) == 0
    return d


def _designs(py, lib, rng, n):
    """The catalogue's design and random ones inside the ranges, away from their margins, that close at the home
    pose (Python and C reject the same others)."""
    out = [DEFAULT]
    while len(out) < n:
        params = (*rng.uniform(0.4, math.pi - 0.4, 2), *rng.uniform(0.05, 0.5 * math.pi - 0.05, 2))
        try:
            py.design.make_design(params)
        except py.design.InvalidDesign:
            assert lib.wkt_uw_design_init(_p(params), ctypes.byref(_Design())) == -3  # WK_ERR_DESIGN
            continue
        out.append(params)
    return out


def _rot_zxz(p):
    def rz(t):
        return np.array([[math.cos(t), -math.sin(t), 0], [math.sin(t), math.cos(t), 0], [0, 0, 1]])

    def rx(t):
        return np.array([[1, 0, 0], [0, math.cos(t), -math.sin(t)], [0, math.sin(t), math.cos(t)]])
    return rz(p[0]) @ rx(p[1]) @ rz(p[2])


def test_python_ik_then_fk_returns_the_pose_and_c_returns_the_same_sets(py, lib):
    """Every IK set of a random pose assembles (FK) back to that pose, in Python; C gives the same sets and modes
    (one algorithm in both, operation for operation: equal to rounding)."""
    rng = case_rng(2230)
    checked = usable = 0
    for params in _designs(py, lib, rng, 12):
        d = py.design.make_design(params)
        cd = _c_design(lib, params)
        assert abs(cd.theta0 - d.theta0) <= 1e-15 and np.allclose(list(cd.c), d.constants, rtol=0, atol=1e-15)
        reached, centre = 0, None
        for k in range(400):  # poses until 3 reachable ones (a design reaches a part of SO(3))
            if reached == 3:
                break
            # random poses (the unreachable ones compare statuses), every other one an assembled pose's: a design
            # whose reach is a sliver of SO(3) (seed 31415: 2 of 400 random poses; seed 111: 2 of 200 random joints
            # assemble) still gives its 3, joints drawn near the last that assembled
            pose = (rng.uniform(-math.pi, math.pi), rng.uniform(0.2, math.pi - 0.2), rng.uniform(-math.pi, math.pi))
            if k % 2:
                joints = rng.uniform(0.0, 2 * math.pi, 3) if centre is None or k % 4 == 1 else \
                    centre + rng.normal(0.0, 0.2, 3)
                f = py.fk.fk(joints, d)
                if not f.valid.any():
                    continue
                centre = joints
                r = np.array(f.aux[f.valid][0][:9]).reshape(3, 3)
                beta = math.acos(max(-1.0, min(1.0, r[2, 2])))
                if not 0.2 <= beta <= math.pi - 0.2:
                    continue
                pose = (math.atan2(r[0, 2], -r[1, 2]), beta, math.atan2(r[2, 0], r[2, 1]))  # R = Rz Rx Rz
            s = py.ik.ik(pose, d)
            out = IkSolutions()
            assert lib.wkt_uw_ik(_p(pose), ctypes.byref(cd), ctypes.byref(out)) == 0
            assert out.status == s.status
            if s.status != 0:
                continue
            reached += 1
            assert [bool(v) for v in out.valid] == list(s.valid)
            assert np.allclose(np.array(out.values), s.values, rtol=0, atol=1e-12)
            assert list(out.flags) == list(s.flags)
            r = _rot_zxz(pose)
            for q in s.values[s.valid]:
                f = py.fk.fk(q, d)
                rots = [np.array(a[:9]).reshape(3, 3) for a in f.aux[f.valid]]
                assert min(np.max(np.abs(x - r)) for x in rots) <= 1e-9, (params, pose, q)
                cf = FkSolutions()
                assert lib.wkt_uw_fk(_p(q), ctypes.byref(cd), ctypes.byref(cf)) == 0
                assert cf.count == int(np.sum(f.valid))
                assert np.allclose(np.array(cf.values)[:cf.count], f.values[f.valid], rtol=0, atol=1e-9)
                checked += 1
        if reached < 3:  # a design whose few assemblies all lie outside the tested beta range (seeds 111, 137)
            assert params != DEFAULT
            continue
        usable += 1
        if usable == 4:
            break
    assert usable == 4 and checked >= 4 * 3 * 8


def test_fk_batch_and_scalar_fk_agree(py):
    """The vectorised FK (companion-matrix roots, a vectorised polish) finds the scalar FK's modes."""
    rng = case_rng(2231)
    d = py.design.make_design(DEFAULT)
    q = rng.uniform(0.0, 2 * math.pi, (40, 3))
    b = py.fk_batch.fk_batch(q, d)
    for i in range(len(q)):
        s = py.fk.fk(q[i], d)
        assert int(np.sum(b.valid[i])) == int(np.sum(s.valid))
        assert np.allclose(b.aux[i][b.valid[i]][:, :9], s.aux[s.valid][:, :9], rtol=0, atol=1e-9)


def test_c_eliminant_is_the_identity_times_the_tangent_half_angle_factor(lib):
    """K(x) = (1 + x^2)^4 ((E1 F2 - E2 F1)^2 + (D2 F1 - D1 F2)^2 - (D1 E2 - D2 E1)^2) at x = tan((eta - eta_c)/2),
    computed here from that definition on random loop coefficients."""
    rng = case_rng(2232)
    for _ in range(20):
        trip = rng.normal(size=18)
        eta_c = rng.uniform(-math.pi, math.pi)
        kbuf = np.zeros(9)
        lib.wkt_uw_polynomial(_p(trip), math.cos(eta_c), math.sin(eta_c), kbuf.ctypes.data_as(D))
        for eta in rng.uniform(-3.0, 3.0, 5):
            x = math.tan((eta - eta_c) / 2)
            v = trip.reshape(6, 3) @ np.array([1.0, math.cos(eta), math.sin(eta)])
            d1, e1, f1, d2, e2, f2 = v
            ident = (e1 * f2 - e2 * f1) ** 2 + (d2 * f1 - d1 * f2) ** 2 - (d1 * e2 - d2 * e1) ** 2
            want = (1 + x * x) ** 4 * ident
            got = np.polyval(kbuf[::-1], x)
            assert abs(got - want) <= 1e-10 * (1 + x * x) ** 4 * np.sum(np.abs(trip)) ** 4


def test_c_polish_converges_to_a_constructed_root(lib):
    """Loop coefficients made to vanish at a drawn (zeta0, eta0): the damped Gauss-Newton from 1e-3 away reaches it
    (a regular root: its Jacobian's determinant well away from zero)."""
    rng = case_rng(2233)
    done = 0
    while done < 20:
        trip = rng.normal(size=(6, 3))
        z0, e0 = rng.uniform(-3.0, 3.0, 2)
        w = np.array([1.0, math.cos(e0), math.sin(e0)])
        for j in (0, 3):  # F_j's constant term closes equation j at (z0, e0)
            g = trip[j] @ w * math.cos(z0) + trip[j + 1] @ w * math.sin(z0) + trip[j + 2] @ w
            trip[j + 2, 0] -= g
        dw = np.array([0.0, -math.sin(e0), math.cos(e0)])
        jac = np.array([[-(trip[j] @ w) * math.sin(z0) + (trip[j + 1] @ w) * math.cos(z0),
                         (trip[j] @ dw) * math.cos(z0) + (trip[j + 1] @ dw) * math.sin(z0) + trip[j + 2] @ dw]
                        for j in (0, 3)])
        if abs(np.linalg.det(jac)) < 0.1:
            continue
        z, e = np.array([z0 + 1e-3]), np.array([e0 - 1e-3])
        err = lib.wkt_uw_polish(_p(trip.ravel()), z.ctypes.data_as(D), e.ctypes.data_as(D))
        assert err <= 1e-14 and abs(z[0] - z0) <= 1e-12 and abs(e[0] - e0) <= 1e-12
        done += 1


def test_c_euler_angles_reproduce_the_rotation(lib):
    rng = case_rng(2234)
    for theta in [*rng.uniform(0.0, math.pi, 20), 0.0, math.pi, 1e-12]:
        pose = np.array([rng.uniform(-math.pi, math.pi), theta, rng.uniform(-math.pi, math.pi)])
        r, back, flags = np.zeros(9), np.zeros(3), ctypes.c_uint()
        lib.wkt_uw_euler(_p(pose), r.ctypes.data_as(D), back.ctypes.data_as(D), ctypes.byref(flags))
        # at the gimbal (sin theta <= GIMBAL_EPS = 1e-10) phi is folded into psi: R is kept to that sine
        tol = 2e-10 if flags.value else 1e-14
        assert np.max(np.abs(_rot_zxz(back) - r.reshape(3, 3))) <= tol
        assert np.max(np.abs(_rot_zxz(pose) - r.reshape(3, 3))) <= 1e-15
        assert bool(flags.value) == (math.sin(theta) <= 1e-10)


def test_the_generated_files_carry_the_sources_verbatim():
    py = (ROOT / "generated" / "python" / "wristkin" / "underactuated_wrist.py").read_text()
    c = (GEN_C / "underactuated_wrist.c").read_text()
    for rel in PY_RUNTIME_FILES:
        assert runtime_files.inline(rel) in py, rel
    for rel in C_RUNTIME_FILES:
        assert runtime_files.inline(rel) in c, rel
    assert sorted(C_RUNTIME_FILES) == sorted(f"c/underactuated_wrist/{p.name}" for p in UW_C.glob("*.c"))
    assert sorted(PY_RUNTIME_FILES) == sorted(f"python/{p.name}" for p in (ROOT / "runtime" / "python").glob("uw_*.py")
                                              if p.name != "uw_stand_in.py")
    for template in ("c/underactuated_wrist.c.jinja", "python/underactuated_wrist.py.jinja"):
        text = (ROOT / "templates" / template).read_text()
        assert len(text.splitlines()) <= 400 and not re.search(r"\{%-?\s*(el)?if\b", text), template
