"""The shared runtime's hand-written numerics that the derived stages inline, tested as they are: the dense steps
of runtime/c/wristkin_runtime.c (the polish's square solve and its LU, the conditioning bound, the Jacobi smallest
eigenpair) against numpy and their Python twin runtime/python/_runtime.py; the cores of subproblem 6 and the spatial
3R (runtime/c/wk_sp6.c, wk_spatial3.c), compiled strictly as they are inlined (tests/c/shared_runtime_harness.c),
with runtime/python/sp6.py beside them, on random instances whose answer is known by construction (numpy here,
never the generated code); and a user robot's own Python sources (chain_rigid.py, chain_poe.py, serial_own.py,
own_api.py) imported as they are on their stand-in robot. The spatial 3R's core against its Python twin:
tests/test_spatial3_runtime.py."""

from __future__ import annotations

import ctypes
import hashlib
import math
import re
import sys
from pathlib import Path

import numpy as np
import pytest
from cbuild import RUNTIME_C, compile_shared, load
from seeding import case_rng

ROOT = Path(__file__).resolve().parent.parent
RUNTIME_PY = ROOT / "runtime" / "python"
HARNESS = ROOT / "tests" / "c" / "shared_runtime_harness.c"
D = ctypes.POINTER(ctypes.c_double)
IP = ctypes.POINTER(ctypes.c_int)
U = ctypes.POINTER(ctypes.c_uint)
SP6_MAX, S3_MAX = 17, 12  # WK_SP6_MAX, WK_S3_MAX
# the serial sp6 stage's tolerances at scale 1, as the harness hands them to wk_sp6: (scale, degenerate,
# double_root, tangent, on_axis)
SP6_TOLS = (1.0, 1e-12, 1e-12, 1e-9, 1e-12, 1.4210854715202004e-14)


def _rot(k, t):
    k = np.asarray(k, float)
    kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + math.sin(t) * kx + (1 - math.cos(t)) * kx @ kx


def _unit(rng):
    v = rng.normal(size=3)
    return v / np.linalg.norm(v)


def _p(a):
    return np.ascontiguousarray(a, dtype=float).ctypes.data_as(D)


def _angle_gap(a, b):
    return abs(math.remainder(a - b, 2 * math.pi))


@pytest.fixture(scope="module")
def lib():
    # the harness includes the sources: their bytes name the build (compile_shared hashes only what it is given)
    shared = [ROOT / "runtime" / "c" / n
              for n in ("poly_real_roots.c", "wk_poly_ops.c", "wk_geom3.c", "wk_spatial3.c", "wk_sp6.c")]
    h = hashlib.sha256(b"".join(p.read_bytes() for p in shared)).hexdigest()[:16]
    so = compile_shared([HARNESS, RUNTIME_C], [ROOT / "runtime" / "c"], "shared_runtime",
                        extra_flags=[f"-DWKT_SOURCES={h}"])
    L = load(so)
    L.wkt_solve_square.argtypes = [D, ctypes.c_int, D, D]
    L.wkt_lu_solve_many.argtypes = [D, ctypes.c_int, D, ctypes.c_int, D]
    L.wkt_sp6.argtypes = [D, D, D, D, D, ctypes.c_double, D, D, D, D, U, IP]
    L.wkt_sp6_split.argtypes = [D, D, D, D, D, ctypes.c_double, D, D, ctypes.c_double, ctypes.c_double, D, D]
    L.wkt_spatial3.argtypes = [D, D, D, D, D, D, D, U]
    L.wk_jacobi_smallest.argtypes = [D, ctypes.c_int, D]
    L.wk_jacobi_smallest.restype = ctypes.c_double
    return L


@pytest.fixture(scope="module")
def py():
    """The Python sources imported as they are (their imports above the inlining marker: each other)."""
    sys.path.insert(0, str(RUNTIME_PY))
    try:
        import _runtime
        import sp6
    finally:
        sys.path.remove(str(RUNTIME_PY))
    return type("Sources", (), {"runtime": _runtime, "sp6": sp6})


def test_the_harness_tolerances_are_the_serial_stage_s():
    """The harness hands the cores the tolerances the serial stages do (sr_sp6.c's SR_SP6_*, serial_sp6.py's SP6_*,
    the derived DEGENERATE_EPS), and the Python calls here the same ones: not other ones."""
    from derive.tolerances import TOLERANCES

    text = HARNESS.read_text()
    c_stage = (ROOT / "runtime" / "c" / "serial" / "sr_sp6.c").read_text()
    py_stage = (RUNTIME_PY / "serial_sp6.py").read_text()
    assert f"#define WKT_DEGENERATE_EPS {TOLERANCES['degenerate']}\n" in text
    assert float(TOLERANCES["degenerate"]) == SP6_TOLS[1]
    for key, value in (("DOUBLE_ROOT_TOL", SP6_TOLS[2]), ("TANGENT_TOL", SP6_TOLS[3]), ("ON_AXIS_TOL", SP6_TOLS[4]),
                       ("FAMILY_TOL", SP6_TOLS[5])):
        for source, pattern in ((text, rf"#define WKT_SP6_{key} (\S+)\n"), (c_stage, rf"#define SR_SP6_{key} (\S+)\n"),
                                (py_stage, rf"\nSP6_{key} = (\S+)\n")):
            assert float(re.search(pattern, source).group(1)) == value, (key, pattern)


# ------------------------------------------------------------------------------------------------ set identity
REFIT = ctypes.CFUNCTYPE(ctypes.c_double, D, ctypes.c_double, ctypes.c_double, ctypes.c_void_p)


def _set_lib(lib):
    lib.wk_set_gap.argtypes = [ctypes.c_int, IP, D, D, ctypes.c_double]
    lib.wk_set_gap.restype = ctypes.c_double
    lib.wk_same_set.argtypes = [ctypes.c_int, IP, D, D]
    lib.wk_pair_indistinct.argtypes = [ctypes.c_int, IP, D, ctypes.c_double, D, ctypes.c_double, REFIT,
                                       ctypes.c_void_p, ctypes.c_double, D]
    lib.wk_pair_indistinct.restype = ctypes.c_double
    lib.wk_merge_indistinct.argtypes = [ctypes.c_int, ctypes.c_int, IP, U, ctypes.c_int, D, IP, U, D, ctypes.c_int,
                                        REFIT, ctypes.c_void_p, ctypes.c_double, ctypes.c_int]
    return lib


def _c_refit(refit, n):
    """The Python refit as C's wk_refit_fn on n joints (the pointer's joints copied in and written back)."""
    def call(q, step, accept, _ctx):
        x = [q[i] for i in range(n)]
        err = refit(x, step, accept)
        for i in range(n):
            q[i] = x[i]
        return err

    return REFIT(call)


def _ints(a, kind=ctypes.c_int):
    return (kind * len(a))(*[int(v) for v in a])


def test_the_set_gap_is_the_wrapped_max_norm_in_both_languages(py, lib):
    """wk_set_gap / set_gap: the largest joint difference, revolute ones wrapped (a numpy reference: remainder by
    2 pi), prismatic ones not, every joint revolute without a mask; the scan stops at the first joint beyond `stop`
    and returns that joint's gap; C and Python equal to the bit; wk_same_set / same_set at SAME_SET (1e-9)."""
    _set_lib(lib)
    rng = case_rng(2231)
    for _ in range(300):
        n = int(rng.integers(1, 8))
        x = rng.uniform(-4.0, 4.0, n)
        y = x + rng.choice([1e-12, 1e-9, 2e-9, 1e-4, 3.0], n) * rng.choice([-1, 1], n) \
            + rng.choice([0.0, 2 * math.pi, -2 * math.pi], n)
        rev = rng.integers(0, 2, n)
        d = y - x
        ref = np.abs(np.where(rev == 1, np.remainder(d + math.pi, 2 * math.pi) - math.pi, d))
        for mask, want in ((rev, ref), (None, np.abs(np.remainder(d + math.pi, 2 * math.pi) - math.pi))):
            c_mask = None if mask is None else _ints(mask)
            gap = lib.wk_set_gap(n, c_mask, _p(x), _p(y), math.inf)
            assert gap == py.runtime.set_gap(x, y, None if mask is None else [bool(v) for v in mask])
            assert abs(gap - np.max(want)) <= 1e-15 * 8
            stop = 1e-6
            first = next((i for i in range(n) if want[i] > stop), None)
            short = lib.wk_set_gap(n, c_mask, _p(x), _p(y), stop)
            assert short == py.runtime.set_gap(x, y, None if mask is None else list(mask), stop)
            if first is not None:  # the first joint beyond stop, not the largest
                assert abs(short - max(want[: first + 1])) <= 1e-14
            same = lib.wk_same_set(n, c_mask, _p(x), _p(y))
            assert bool(same) == py.runtime.same_set(x, y, None if mask is None else list(mask)) == (gap <= 1e-9)
    nan = np.array([0.0, math.nan])
    assert not py.runtime.same_set(nan, nan) and not lib.wk_same_set(2, None, _p(nan), _p(nan))


def _fold_refit(roots, curvature, bend=0.0):
    """A pose with a fold in joint 0 (residual curvature |(q0 - a)(q0 - b)| at the nearest pair of roots) and the
    other joints placed at 0.5 + bend (q0 - c)^2 (c: that pair's centre; the sets on the pose, their midpoint off it
    by bend (span / 2)^2): the refit takes one step of at most max_step on the other joints only (as a Gauss-Newton
    step does along a regular direction) and reports the residual, q updated when it helps."""
    def residual(q):
        a, b = min(roots, key=lambda r: abs((q[0] - r[0]) * (q[0] - r[1])))
        target = 0.5 + bend * (q[0] - 0.5 * (a + b)) ** 2
        return curvature * abs((q[0] - a) * (q[0] - b)) + sum(abs(v - target) for v in q[1:]), target

    def refit(q, max_step, accept, _ctx=None):
        err, target = residual(q)
        if err <= accept:
            return err
        moved = [q[0]] + [v + max(-max_step, min(max_step, target - v)) for v in q[1:]]
        err2 = residual(moved)[0]
        if err2 < err:
            for i, v in enumerate(moved):
                q[i] = v
        return err2

    return (lambda q: residual(q)[0]), refit


def test_a_pair_is_one_solution_where_its_midpoint_fits_the_pose_and_two_where_the_fold_curves(py, lib):
    """wk_pair_indistinct / pair_indistinct: two sets on one fold's double root split 1e-7 (both on the pose, their
    midpoint 2.5e-12 off it in the other joints, which a step of an eighth of the span removes) are one solution, and
    the refitted midpoint's residual comes back; two roots of a curved fold 2e-5 apart (the midpoint off by curvature x
    1e-10) are two; a pair beyond MERGE_SPAN (1e-3) is never compared; C and Python return the same residual and
    midpoint to the bit."""
    _set_lib(lib)
    floor = py.runtime.fk_rounding(1.0)
    cases = []
    for split, curvature, bend, one in ((1e-7, 1.0, 1e3, True),  # a double root split 1e-7: midpoint 2.5e-12 off
                                        (2e-5, 1.0, 0.0, False),  # two roots: the midpoint off by 1e-10
                                        (2e-5, 1e-9, 0.0, True),  # a flat fold: the pose cannot tell them apart
                                        (2e-3, 0.0, 0.0, False)):  # beyond MERGE_SPAN: distinct by rule
        root = 0.3
        residual, refit = _fold_refit([(root - split / 2, root + split / 2)], curvature, bend)
        on = 0.5 + bend * (split / 2) ** 2
        x = [root - split / 2, on, on]
        y = [root + split / 2, on, on]
        rx, ry = residual(x), residual(y)
        got = py.runtime.pair_indistinct(x, rx, y, ry, [True, True, False], refit, floor)
        mid = np.zeros(3)
        c_refit = _c_refit(refit, 3)
        rm = lib.wk_pair_indistinct(3, _ints([1, 1, 0]), _p(x), rx, _p(y), ry, c_refit, None, floor, _p(mid))
        assert (got is not None) == one == (rm >= 0.0), (split, curvature)
        if one:
            assert got[0] == rm and list(mid) == got[1] and rm <= max(rx, ry) + floor
        cases.append(rm)
    assert cases[0] <= 2.5e-15 * (1 + 1e-9)  # the step took the midpoint's 2.5e-12 off: the fold's own 2.5e-15 left


def test_the_merge_keeps_one_set_per_solution_in_both_languages(py, lib):
    """wk_merge_indistinct / merge_indistinct on random tables of sets (8 sets of 3 joints, masks of one bit and of
    two bits): every pair inside a mask on one double root merges into the better fit (flagged double root and
    singular), pairs of distinct roots stay, candidates_only compares flagged pairs only; C and Python leave the same
    values, validity, flags and residuals (to the bit) and count the same removals."""
    _set_lib(lib)
    rng = case_rng(2232)
    merges = 0
    for trial in range(60):
        roots, values = [], np.zeros((8, 3))
        for k in range(8):
            base = rng.uniform(-2.0, 2.0)
            values[k] = [base, 0.5, 0.5 + rng.choice([0.0, 1e-12])]
        for _ in range(int(rng.integers(1, 4))):  # pairs placed within a mask: one solution or two
            k = int(rng.integers(0, 8))
            k2 = k ^ int(rng.choice([1, 2, 3, 4]))
            split = float(rng.choice([1e-8, 1e-6, 2e-5]))
            values[k2] = values[k]
            values[k2][0] = values[k][0] + split
            roots.append((values[k][0], values[k2][0]) if split < 1e-6 else (values[k][0], values[k][0]))
            if split >= 1e-6:
                roots.append((values[k2][0], values[k2][0]))
        roots += [(v, v) for v in values[:, 0]]
        residual, refit = _fold_refit(roots, float(rng.choice([1.0, 1e3])))
        valid = [int(rng.uniform() < 0.9) for _ in range(8)]
        flags = [int(rng.choice([0, py.runtime.FLAG_MERGE_CANDIDATE])) | int(rng.choice([0, 0, 2])) for _ in range(8)]
        aux = np.array([[residual(v), 0.0] for v in values])
        masks, rev = [1, 6], [1, 1, 0]
        only = bool(trial % 2)
        pv, pvalid, pflags, paux = values.copy(), list(valid), list(flags), aux.copy()
        removed = py.runtime.merge_indistinct(pv, pvalid, pflags, paux, masks, [bool(r) for r in rev],
                                              refit, 1.0, candidates_only=only)
        cv, cvalid, cflags, caux = values.copy(), _ints(valid), _ints(flags, ctypes.c_uint), aux.copy()
        c_refit = _c_refit(refit, 3)
        c_removed = lib.wk_merge_indistinct(8, 3, _ints(rev), _ints(masks, ctypes.c_uint), 2, _p(cv), cvalid, cflags,
                                            _p(caux), 2, c_refit, None, 1.0, int(only))
        assert removed == c_removed and list(cvalid) == pvalid and list(cflags) == pflags
        assert np.array_equal(cv, pv, equal_nan=True) and np.array_equal(caux, paux, equal_nan=True)
        merges += removed
        floor = py.runtime.fk_rounding(1.0)
        for k in range(8):  # no two kept sets are one solution the merge could see, read on the toy pose itself:
            for k2 in range(k + 1, 8):  # within 1e-3, their plain midpoint as close to it as they are (no step helps:
                # the other joints sit at their targets, the fold is joint 0's)
                if pvalid[k] and pvalid[k2] and any((k ^ k2) & ~m == 0 for m in masks):
                    near = np.max(np.abs(pv[k] - pv[k2])) <= 1e-3
                    one = near and residual(0.5 * (pv[k] + pv[k2])) <= max(paux[k][0], paux[k2][0]) + floor
                    assert not one or (only and not (flags[k] & flags[k2] & py.runtime.FLAG_MERGE_CANDIDATE))
    assert merges > 0


# ------------------------------------------------------------------------------------------------ dense steps
def test_the_square_step_solves_to_its_conditioning_and_refuses_a_near_singular_matrix(lib):
    """wk_square_solve (the polish's square step): lstsq's answer to rounding times the conditioning (1e-13 * cond
    relative: elimination with partial pivoting is backward stable, its forward error eps * cond * growth); a (near)
    rank-deficient J is refused (pivot at or below 1e-8 of the largest entry), for the SVD to decide."""
    rng = case_rng(2206)
    x = np.zeros(6)
    for _ in range(40):
        a, b = rng.normal(size=(6, 6)), rng.normal(size=6)
        assert lib.wkt_solve_square(_p(a), 6, _p(b), _p(x)) == 1
        ref = np.linalg.lstsq(a, b, rcond=None)[0]
        assert np.max(np.abs(x - ref)) <= 1e-13 * np.linalg.cond(a) * max(1.0, np.max(np.abs(ref)))
    a[:, 5] = a[:, 4] * (1.0 + 1e-12)
    assert lib.wkt_solve_square(_p(a), 6, _p(b), _p(x)) == 0


def test_the_python_square_step_is_the_c_one_to_the_bit(py, lib):
    """_runtime.solve_square is the shared C runtime's wk_square_solve step for step (the polish's square step in
    both languages): equal bits on random 6 x 6 systems, and both refuse a pivot at or below the relative threshold
    (here 1e-8 of the largest entry)."""
    rng = case_rng(2215)
    x = np.zeros(6)
    solve = py.runtime.solve_square
    for _ in range(100):
        a, b = rng.normal(size=(6, 6)) * rng.uniform(1e-3, 1e3), rng.normal(size=6)
        assert lib.wkt_solve_square(_p(a), 6, _p(b), _p(x)) == 1
        assert solve(a, b, 1e-8) == list(x)
    a[:, 5] = a[:, 4] * (1.0 + 1e-12)
    assert lib.wkt_solve_square(_p(a), 6, _p(b), _p(x)) == 0 and solve(a, b, 1e-8) is None
    a[:, 5] = 0.0  # a held joint's zeroed column
    assert solve(a, b, 1e-6) is None



def test_the_damped_normal_step_solves_its_system_and_leaves_a_zeroed_column_still(lib):
    """wk_normal_solve (the Gauss-Newton step where J is not square or regular, and every held fit's: a calibrated
    arm's scans take ~1,500 of them a call): x = (J^T J + d I)^-1 J^T e, numpy's solve of that system to rounding
    times its conditioning (1e-13 * cond relative), for 6 x n J, n = 5..7 (7 with a held joint, as a 7-joint arm
    calls it: with 7 columns J^T J is singular and d, 1e-12, below its rounding); a zeroed column (a held joint's)
    gets a step of exactly 0 and the others solve J without it (the same system's other unknowns: its row and column
    hold only d); without damping a zeroed column is singular (0) and x is left as it was."""
    lib.wk_normal_solve.argtypes = [D, ctypes.c_int, D, ctypes.c_double, D]
    lib.wk_normal_solve.restype = ctypes.c_int
    rng = case_rng(2218)
    for n in (5, 6, 7):
        x = np.zeros(n)
        for trial in range(30):
            j, e = rng.normal(size=(6, n)) * rng.uniform(1e-2, 1e2), rng.normal(size=6)
            zeroed = [int(rng.integers(n))] if trial % 2 or n == 7 else []  # 7: a 7-joint arm's held joint
            j[:, zeroed] = 0.0
            assert lib.wk_normal_solve(_p(j), n, _p(e), 1e-12, _p(x)) == 1
            g = j.T @ j + 1e-12 * np.eye(n)
            ref = np.linalg.solve(g, j.T @ e)
            kept = [c for c in range(n) if c not in zeroed]  # a zeroed column's row holds only d: not the conditioning
            cond = np.linalg.cond(g[np.ix_(kept, kept)])
            assert np.max(np.abs(x - ref)) <= 1e-13 * cond * max(1.0, np.max(np.abs(ref))), (n, trial)
            assert all(x[z] == 0.0 for z in zeroed)
        j[:, 0] = 0.0
        x[:] = 7.25
        assert lib.wk_normal_solve(_p(j), n, _p(e), 0.0, _p(x)) == 0 and np.all(x == 7.25)

def test_one_lu_solves_each_right_hand_side_as_the_square_step_does(lib):
    """wk_lu_factor once, then wk_lu_solve per right-hand side (a calibrated arm's chord steps, and its wrist mirror's
    step on the same LU): each solution the bits of wk_square_solve's on that side (the same operations in the same
    order), and a solution of the system (numpy's, to the conditioning: 1e-13 * cond relative); both refuse the same
    near-singular matrix."""
    rng = case_rng(2216)
    x1, xs = np.zeros(6), np.zeros((4, 6))
    for _ in range(50):
        a, b = rng.normal(size=(6, 6)) * rng.uniform(1e-3, 1e3), rng.normal(size=(4, 6))
        assert lib.wkt_lu_solve_many(_p(a), 6, _p(b), 4, _p(xs)) == 1
        for i in range(4):
            assert lib.wkt_solve_square(_p(a), 6, _p(b[i]), _p(x1)) == 1 and list(xs[i]) == list(x1)
            ref = np.linalg.solve(a, b[i])
            assert np.max(np.abs(xs[i] - ref)) <= 1e-13 * np.linalg.cond(a) * np.max(np.abs(ref))
    a[:, 5] = a[:, 4] * (1.0 + 1e-12)
    assert lib.wkt_lu_solve_many(_p(a), 6, _p(b), 4, _p(xs)) == 0 and lib.wkt_solve_square(_p(a), 6, _p(b[0]),
                                                                                          _p(x1)) == 0


def test_the_conditioning_bound_decides_all_but_a_narrow_band_around_eps():
    """wk_conditioning_bound (the shared runtime) proves sigma_min / sigma_max above or below eps, or leaves it to the
    caller's SVD. Its verdicts are the SVD's wherever it gives one; it leaves undecided only ratios within ~3-30 % of
    eps = 1e-6 (the bracket on lambda_max: power steps, then U I - G positive definite), whatever the spread of the
    other singular values."""
    so = compile_shared([RUNTIME_C], [ROOT / "runtime" / "c"], "wk_runtime_bound")
    lib = load(so)
    lib.wk_conditioning_bound.argtypes = [D, ctypes.c_int, ctypes.c_double, D]
    lib.wk_conditioning_bound.restype = ctypes.c_int
    rng = case_rng(2216)
    man = np.zeros(1)
    undecided = 0
    # the geometric sweep, then ratios within 10 % of eps, where a proven verdict must still be the SVD's (the margins
    # against the rounding of G's Cholesky factor)
    for ratio in np.concatenate([np.geomspace(1e-8, 1e-4, 161), [1e-6 * 0.87, 1e-6 * 1.13],
                                 np.linspace(0.9e-6, 1.1e-6, 81)]):
        for spread in (1.0, 0.3, 1e-2):
            u, _ = np.linalg.qr(rng.normal(size=(6, 6)))
            v, _ = np.linalg.qr(rng.normal(size=(6, 6)))
            s = np.sort(np.concatenate([[1.0, ratio], rng.uniform(max(ratio, spread), 1.0, 4)]))[::-1]
            j = u @ np.diag(s * rng.uniform(0.1, 3.0)) @ v.T
            got = lib.wk_conditioning_bound(_p(j), 6, 1e-6, _p(man))
            sv = np.linalg.svd(j, compute_uv=False)
            true = sv[-1] / sv[0]
            if got:
                assert (got < 0) == (true <= 1e-6), (ratio, spread, got)
            elif not 0.9e-6 <= ratio <= 1.1e-6:
                undecided += 1
                assert 0.97e-6 <= true <= 1.28e-6, (ratio, spread)
    assert undecided <= 16


def test_the_jacobi_smallest_eigenpair_is_lapack_s(lib):
    """wk_jacobi_smallest (a calibrated arm's near-null direction: sr_along_null) against LAPACK's eigh on Gram
    matrices J^T J of 6 x n Jacobians, n = 1 .. 6, with sigma_min / sigma_max from 1 down to 1e-10 (J^T J's smallest
    eigenvalue then below its rounding): the eigenvalue to eps |G| n, the eigenvector to eps |G| n / gap (the gap to
    the next eigenvalue; its sign free), unit length; a bad n gives -1 and leaves v alone."""
    rng = case_rng(2341)
    eps = np.finfo(float).eps
    for n in range(1, 7):
        for ratio in (1.0, 1e-3, 1e-6, 1e-10):
            u, _ = np.linalg.qr(rng.normal(size=(6, 6)))
            w, _ = np.linalg.qr(rng.normal(size=(n, n)))
            sigma = np.sort(rng.uniform(0.2, 2.0, n))[::-1]
            sigma[-1] = sigma[0] * ratio if n > 1 else sigma[-1]
            jac = u[:, :n] @ np.diag(sigma) @ w.T
            g = jac.T @ jac
            vals, vecs = np.linalg.eigh(g)
            v = np.zeros(n)
            low = lib.wk_jacobi_smallest(_p(g.copy()), n, _p(v))
            scale = np.linalg.norm(g, 2) * n
            assert abs(low - vals[0]) <= 8 * eps * scale, (n, ratio)
            assert abs(np.linalg.norm(v) - 1.0) <= 8 * eps * n
            if n > 1 and vals[1] - vals[0] > 8 * eps * scale:  # a tie within rounding leaves the vector free
                assert 1.0 - abs(float(v @ vecs[:, 0])) <= 8 * eps * scale / (vals[1] - vals[0]), (n, ratio)
    v = np.full(2, 7.0)
    assert lib.wk_jacobi_smallest(_p(np.eye(9)), 9, _p(v)) == -1.0 and lib.wk_jacobi_smallest(_p(np.eye(2)), 0,
                                                                                                _p(v)) == -1.0
    assert list(v) == [7.0, 7.0]


# ------------------------------------------------------------------------------------------------ subproblem 6
def _sp6_instance(rng):
    """A random subproblem 6 built from known (q0, q4) = (a, b): n . (rot(h0, -a) p0 - rot(h4, b) p4) = d0 and
    n . rot(h0, -a) g = n . rot(h4, b) h5 (e0 = 0)."""
    n_, h0, h4, h5 = _unit(rng), _unit(rng), _unit(rng), _unit(rng)
    p0, p4 = rng.normal(size=3), rng.normal(size=3)
    a, b = rng.uniform(-math.pi, math.pi, 2)
    d0 = float(n_ @ _rot(h0, -a) @ p0 - n_ @ _rot(h4, b) @ p4)
    g = _rot(h0, a) @ _rot(h4, b) @ h5
    return (n_, h0, p0, h4, p4, d0, g, h5), (a, b)


def _c_sp6(lib, args):
    n_, h0, p0, h4, p4, d0, g, h5 = args
    q0s, q4s, f, o = np.zeros(SP6_MAX), np.zeros(SP6_MAX), (ctypes.c_uint * SP6_MAX)(), (ctypes.c_int * SP6_MAX)()
    nr = lib.wkt_sp6(_p(n_), _p(h0), _p(p0), _p(h4), _p(p4), d0, _p(g), _p(h5), _p(q0s), _p(q4s), f, o)
    return [(q0s[i], q4s[i], f[i], o[i]) for i in range(nr)]


def _sp6_root_allowance(args, a, b):
    """How far a root returned at the true (a, b) may be off, from the conditioning there: the two equations'
    residuals, each read to 64 eps of its terms' size (metres for the first, 1 for the second), through the inverse
    of their 2 x 2 Jacobian in (q0, q4) (its smallest singular value; near a merged pair, small)."""
    n_, h0, p0, h4, p4, _d0, g, h5 = args
    w, z4 = _rot(h0, -a) @ p0, _rot(h4, b) @ p4
    w0, z5 = _rot(h0, -a) @ g, _rot(h4, b) @ h5
    jac = np.array([[-n_ @ np.cross(h0, w), -n_ @ np.cross(h4, z4)], [-n_ @ np.cross(h0, w0), -n_ @ np.cross(h4, z5)]])
    scale = max(1.0, np.linalg.norm(p0), np.linalg.norm(p4))
    return 64.0 * np.finfo(float).eps * scale / max(np.linalg.svd(jac, compute_uv=False)[-1], 1e-300)


def test_sp6_returns_the_generating_pair(lib):
    """wk_sp6 on random instances built from known (q0, q4): the generating pair among its candidates, within the
    conditioning's allowance there (_sp6_root_allowance: Newton on the equations brings a simple root to their
    rounding over the smallest singular value of their Jacobian; seen: 0.14 of it over 300 seeds)."""
    rng = case_rng(2205)
    for _ in range(60):
        args, (a, b) = _sp6_instance(rng)
        out = _c_sp6(lib, args)
        assert 0 <= len(out) <= 9
        allowance = _sp6_root_allowance(args, a, b)
        assert min(_angle_gap(x, a) + _angle_gap(y, b) for x, y, _, _ in out) <= allowance, (allowance, out)


def test_python_sp6_returns_c_s_candidates(py, lib):
    """sp6._sp6_core on the instances of the C test: the same candidates as wk_sp6 in the same order, their flags
    and order equal, the angles to 1e-12 (one algorithm, operation for operation; libm's last bit may differ)."""
    rng = case_rng(2211)
    for _ in range(40):
        args, (a, b) = _sp6_instance(rng)
        n_, h0, p0, h4, p4, d0, g, h5 = args
        out = py.sp6._sp6_core(*(tuple(v) for v in (n_, h0, p0, h4, p4)), d0, 0.0, tuple(g), tuple(h5), SP6_TOLS)
        c = _c_sp6(lib, args)
        assert len(out) == len(c)
        assert all(_angle_gap(x, c0) < 1e-12 and _angle_gap(y, c4) < 1e-12 and f == cf and o == co
                   for (x, y, f, o), (c0, c4, cf, co) in zip(out, c, strict=True))
        assert min(_angle_gap(x, a) + _angle_gap(y, b) for x, y, _, _ in out) <= _sp6_root_allowance(args, a, b)


def _sp6_split_allowance(n_, h0, p0, h4, p4, d0, g, h5, a, b):
    """What the split's root at the true (a, b) may be off, from the conditioning there: the first equation (metres)
    and the second read on its parts normal to n, |n x w0|^2 - |n x z5|^2 (~delta, each read to eps), each scaled
    to a distance by its gradient, then through the inverse of the two unit gradients (kappa: large where the two
    curves cross at a small angle; where they touch the pair merges, a double root, read to sqrt(eps))."""
    eps = np.finfo(float).eps
    w, z4 = _rot(h0, -a) @ p0, _rot(h4, b) @ p4
    w0, z5 = _rot(h0, -a) @ g, _rot(h4, b) @ h5
    u, r = np.cross(n_, w0), np.cross(n_, z5)
    g1 = np.array([-n_ @ np.cross(h0, w), -n_ @ np.cross(h4, z4)])
    g2 = 2.0 * np.array([-u @ np.cross(n_, np.cross(h0, w0)), -r @ np.cross(n_, np.cross(h4, z5))])
    scale = max(np.linalg.norm(p0), np.linalg.norm(p4), abs(d0))
    kappa = 1.0 / np.linalg.svd(np.array([g1 / np.linalg.norm(g1), g2 / np.linalg.norm(g2)]), compute_uv=False)[-1]
    reach = max(scale / np.linalg.norm(g1), np.linalg.norm(u) / np.linalg.norm(g2))
    return eps * kappa * reach, math.sqrt(eps) * reach  # a simple root, a merged (double) one


def test_the_sp6_split_resolves_a_near_wrist_pair_to_eps(lib, py):
    """Subproblem 6 with joint 5 delta = 1e-5 .. 1e-12 off the wrist singularity (h5 and n normal to h4, so
    rot(h4, q4*) h5 = n at one q4*; the split is called up to ~1e-6, where the quartic merges the pair or the
    singular candidate's |n x w| is below sqrt(DOUBLE_ROOT_TOL)): from the singular point (a, q4*) the split
    returns the generating (a, q4* + delta) among its two roots within 16 x the conditioning's allowance (seen:
    4.9 x over 250 seeds; the quartic alone: sqrt(eps)); where the two curves touch it returns the merged pair,
    one root, within 16 sqrt(eps) x the same scale (a double root's accuracy). C returns Python's roots."""
    rng = case_rng(2217)
    s0, s4 = np.zeros(2), np.zeros(2)
    for i in range(40):
        h4 = _unit(rng)
        n_ = np.cross(h4, _unit(rng))
        n_ /= np.linalg.norm(n_)
        h5 = _rot(h4, rng.uniform(-math.pi, math.pi)) @ n_  # normal to h4: some q4* turns it onto n
        q4s = math.atan2(float(h4 @ np.cross(h5, n_)), float(h5 @ n_))
        h0, p0, p4 = _unit(rng), rng.normal(size=3), rng.normal(size=3)
        a, delta = rng.uniform(-math.pi, math.pi), (1.0 if i % 2 else -1.0) * 10.0 ** -(5 + i % 8)
        b = q4s + delta
        d0 = float(n_ @ _rot(h0, -a) @ p0 - n_ @ _rot(h4, b) @ p4)
        g = _rot(h0, a) @ _rot(h4, b) @ h5
        args = [tuple(v) for v in (n_, h0, p0, h4, p4)] + [d0, tuple(g), tuple(h5)]
        out = py.sp6._sp6_split(*args, a, q4s, SP6_TOLS)
        nc = lib.wkt_sp6_split(_p(n_), _p(h0), _p(p0), _p(h4), _p(p4), d0, _p(g), _p(h5), a, q4s, _p(s0), _p(s4))
        assert nc == len(out) and len(out) in (1, 2), (i, delta)
        allowance = 16.0 * _sp6_split_allowance(n_, h0, p0, h4, p4, d0, g, h5, a, b)[len(out) == 1]
        assert min(_angle_gap(x, a) + _angle_gap(y, b) for x, y in out) <= allowance, (i, delta, out, allowance)
        assert all(_angle_gap(x, c0) <= 1e-13 and _angle_gap(y, c4) <= 1e-13
                   for (x, y), c0, c4 in zip(out, s0[:nc], s4[:nc], strict=True))


# ------------------------------------------------------------------------------------------------ spatial 3R
def _place(axes, points, q, x):
    """rot_a rot_b rot_c x as a product of 4 x 4 exponentials of the three lines (axis, point)."""
    t = np.eye(4)
    for h, p, v in zip(axes, points, q, strict=True):
        e = np.eye(4)
        e[:3, :3] = _rot(h, v)
        e[:3, 3] = p - e[:3, :3] @ p
        t = t @ e
    return t[:3] @ np.append(x, 1.0)


def _point_smin(axes, points, q, x):
    """sigma_min of the placed point's Jacobian in (q_a, q_b, q_c): columns h_i x (y - r_i) of the lines as the joints
    before each moved them."""
    cols, t = [], np.eye(4)
    y = _place(axes, points, q, x)
    for h, p, v in zip(axes, points, q, strict=True):
        hi, pi = t[:3, :3] @ h, t[:3, :3] @ p + t[:3, 3]
        cols.append(np.cross(hi, y - pi))
        e = np.eye(4)
        e[:3, :3] = _rot(h, v)
        e[:3, 3] = p - e[:3, :3] @ p
        t = t @ e
    return np.linalg.svd(np.array(cols).T, compute_uv=False)[-1]


def test_spatial3_returns_the_generating_joints_among_its_roots(lib):
    """wk_spatial3 as the serial spatial3 stage calls it (scale 1, DEGENERATE_EPS) on random lines whose x is placed
    on y by known joints (numpy's product of exponentials): every candidate places x on y to 1e-9 m (Newton ends at
    the point's rounding), and the generating joints are among them within 1e-9 + 1e-13 / sigma_min of the point's
    Jacobian (a simple root at the point's rounding over sigma_min)."""
    rng = case_rng(2209)
    qa, qb, qc, f = np.zeros(S3_MAX), np.zeros(S3_MAX), np.zeros(S3_MAX), (ctypes.c_uint * S3_MAX)()
    for _ in range(40):
        axes, points = np.array([_unit(rng) for _ in range(3)]), rng.normal(size=(3, 3))
        q = rng.uniform(-math.pi, math.pi, 3)
        x = rng.normal(size=3)
        y = _place(axes, points, q, x)
        nr = lib.wkt_spatial3(_p(axes), _p(points), _p(x), _p(y), _p(qa), _p(qb), _p(qc), f)
        assert 1 <= nr <= S3_MAX
        for i in range(nr):
            assert np.max(np.abs(_place(axes, points, [qa[i], qb[i], qc[i]], x) - y)) <= 1e-9
        gap = min(max(_angle_gap(u, v) for u, v in zip((qa[i], qb[i], qc[i]), q, strict=True)) for i in range(nr))
        assert gap <= 1e-9 + 1e-13 / _point_smin(axes, points, q, x)


# ------------------------------------------------------------------------------------------------ own sources
def test_the_own_sources_import_as_they_are_and_chain_poe_is_the_product_of_exponentials():
    """own_api.py, serial_own.py, chain_poe.py and chain_rigid.py imported as they are (their imports above the
    inlining marker: the stand-ins own_stand_in.py and serial_stand_in.py, the latter reading the generated
    PUMA-560). On the stand-in's ideal chain, chain_poe's end frame (_product of _full_chain, then its home) and the
    chain with a joint held (_held) equal a numpy product of 4 x 4 matrix exponentials of the joints' twists
    (scipy's expm, built here) for random q: to 1e-12 x the chain's size (its largest point or home coordinate, at
    least 1 m). Both are products of seven rigid transforms, each rounded to a few eps of the lengths accumulated so
    far (at most ~7 x the size), and expm is accurate to a few eps of |twist q|: ~1e-14 x the size (seen: 47 eps
    over 3,000 draws), so 1e-12 leaves two orders of margin, and a wrong factor (an axis, a point, their order)
    shows at O(1)."""
    from scipy.linalg import expm

    paths = [str(RUNTIME_PY), str(ROOT / "generated" / "python")]
    sys.path[:0] = paths
    try:
        import chain_poe
        import chain_rigid
        import own_api
        import own_stand_in
        import serial_own
    finally:
        for p in paths:
            sys.path.remove(p)
    axes, points = np.array(own_stand_in._IDEAL_AXES), np.array(own_stand_in._IDEAL_POINTS)
    home = np.array(own_stand_in._IDEAL_HOME)
    chain = chain_poe._full_chain(own_stand_in._IDEAL_AXES, own_stand_in._IDEAL_POINTS, own_stand_in._IDEAL_HOME)
    assert serial_own._branch_chain(None) is serial_own._IDEAL  # no held joint: the branches' chain is the ideal one
    assert own_api._product is chain_poe._product and own_api.N_JOINTS == len(chain.kinds) == len(axes)
    size = max(1.0, float(np.max(np.abs(points))), float(np.max(np.abs(home[:3, 3]))))

    def twist(h, p, v):
        xi = np.zeros((4, 4))
        xi[:3, :3] = [[0.0, -h[2], h[1]], [h[2], 0.0, -h[0]], [-h[1], h[0], 0.0]]
        xi[:3, 3] = -np.cross(h, p)  # v = -h x p: the line's velocity at the origin
        return expm(xi * v)

    def numpy_fk(q):
        t = np.eye(4)
        for h, p, v in zip(axes, points, q, strict=True):
            t = t @ twist(h, p, v)
        return t @ home

    def end_frame(ch, q):  # the sources' product of exponentials, then the home frame, as own_api reads a chain
        r, t = chain_rigid._compose(chain_poe._product(ch, tuple(q), range(len(ch.kinds))), ch.home)
        return np.array([[*r[0], t[0]], [*r[1], t[1]], [*r[2], t[2]], [0.0, 0.0, 0.0, 1.0]])

    rng = case_rng(2218)
    for _ in range(50):
        q = rng.uniform(-math.pi, math.pi, len(axes))
        want = numpy_fk(q)
        got = end_frame(chain, q)
        assert np.max(np.abs(got - want)) <= 1e-12 * size
        f = int(rng.integers(len(axes)))
        held = chain_poe._held(chain, f, float(q[f]))
        got = end_frame(held, np.delete(q, f))
        assert held.index == tuple(i for i in range(len(axes)) if i != f)
        assert np.max(np.abs(got - want)) <= 1e-12 * size
