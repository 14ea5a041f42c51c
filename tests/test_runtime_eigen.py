"""runtime/c/wk_eigen.c (issue 23 groundwork): real eigenvalues, the quadratic eigenproblem, null vectors.

The source is compiled as it is with the strict flags (cbuild) and called through ctypes; the references are
numpy / scipy (LAPACK) and, for polynomials, mpmath at 50 digits on the very double coefficients. Every check
is conditioning-aware: a simple eigenvalue may be off by c n eps ||A|| / s (s = |y^H x| for unit left/right
eigenvectors), a multiple or clustered one by the k-th root of that, a quadratic eigenvalue by the backward
error over |y^H M'(x) x|; nothing is compared to a fixed number of digits. The sanitizer driver
(tests/c/eigen_sanitize.c) runs the hostile and special inputs under ASan/UBSan with canaries after every
output. Random cases follow WRISTKIN_TEST_SEED (tests/seeding.py).
"""

from __future__ import annotations

import ctypes
import math
import subprocess
from fractions import Fraction
from pathlib import Path

import cbuild  # tests/ is on sys.path under pytest
import mpmath
import numpy as np
import pytest
import scipy.linalg
from scipy.optimize import linear_sum_assignment
from seeding import TEST_SEED, case_rng

ROOT = Path(__file__).resolve().parent.parent
RUNTIME_C = ROOT / "runtime" / "c"
SOURCE = RUNTIME_C / "wk_eigen.c"
EPS = 2.0**-52
OK, ERR_NOCONV, ERR_INPUT, ERR_SINGULAR = 0, -1, -2, -3
FLAG_DOUBLE = 1
TOL_DEFAULT = 2.0**-20  # WK_QEP_TOL_DEFAULT
# the backward-error constant c in c n eps ||A||: LAPACK-style analyses give small multiples of n; 16 leaves room
# for the reference's own error (it is compared against ours) without hiding a wrong algorithm (errors of a
# wrong eigenvalue are O(||A||), 10^12 times larger)
C_BACK = 16.0

_DP = np.ctypeslib.ndpointer(dtype=np.float64, flags="C_CONTIGUOUS")


class QepResult(ctypes.Structure):
    _fields_ = [("n_real", ctypes.c_int), ("real", ctypes.c_double * 24), ("real_flags", ctypes.c_uint * 24),
                ("n_complex", ctypes.c_int), ("complex_re", ctypes.c_double * 12),
                ("complex_im", ctypes.c_double * 12), ("n_infinite", ctypes.c_int), ("rcond", ctypes.c_double),
                ("growth", ctypes.c_double), ("angle", ctypes.c_double)]


@pytest.fixture(scope="module")
def lib():
    so = cbuild.load(cbuild.compile_shared([SOURCE], [RUNTIME_C], name="wk_eigen"))
    so.wk_eig_real.argtypes = [ctypes.c_int, _DP, _DP, _DP, _DP]
    so.wk_eig_real.restype = ctypes.c_int
    so.wk_generalized_quadratic_eig.argtypes = [ctypes.c_int, _DP, _DP, _DP, ctypes.c_double,
                                                ctypes.POINTER(QepResult)]
    so.wk_generalized_quadratic_eig.restype = ctypes.c_int
    so.wk_null_vector.argtypes = [ctypes.c_int, _DP, _DP, _DP]
    so.wk_null_vector.restype = ctypes.c_int
    so.wk_null_vector_lu.argtypes = [ctypes.c_int, _DP, _DP, ctypes.POINTER(ctypes.c_double)]
    so.wk_null_vector_lu.restype = ctypes.c_int
    so.wk_small_singular_vectors.argtypes = [ctypes.c_int, _DP, ctypes.c_int, _DP, _DP]
    so.wk_small_singular_vectors.restype = ctypes.c_int
    return so


def eig(lib, a):
    a = np.array(a, dtype=float, order="C")
    n = a.shape[0]
    wr, wi, work = np.full(n + 2, 7.25), np.full(n + 2, 7.25), np.full(2 * n + 2, 7.25)
    rc = lib.wk_eig_real(n, a, wr, wi, work)
    assert list(wr[n:]) == [7.25, 7.25] and list(wi[n:]) == [7.25, 7.25] and list(work[2 * n:]) == [7.25, 7.25]
    return rc, wr[:n] + 1j * wi[:n], wr[:n], wi[:n]


def qep(lib, A, B, C, tol=0.0):
    res = QepResult()
    arr = [np.ascontiguousarray(X, dtype=float) for X in (A, B, C)]
    rc = lib.wk_generalized_quadratic_eig(arr[0].shape[0], *arr, tol, ctypes.byref(res))
    return rc, res


def null_vector(lib, M):
    M = np.ascontiguousarray(M, dtype=float)
    m = M.shape[0]
    v, rel = np.full(m + 2, 7.25), np.full(4, 7.25)
    rc = lib.wk_null_vector(m, M, v, rel)
    assert list(v[m:]) == [7.25, 7.25] and list(rel[2:]) == [7.25, 7.25]
    return rc, v[:m], rel[:2]


# ------------------------------------------------------------------------------ wk_eig_real
def _eigen_tolerances(a):
    """Per reference eigenvalue, how far a backward-stable solver may put it: C_BACK n eps ||A||_F / s_i to first
    order; where that exceeds sqrt(eps) ||A|| the first-order theory no longer holds (a near-multiple
    eigenvalue), and a cluster of k is spread by up to (C_BACK n eps)^(1/k) ||A||: the k = 2 bound is used."""
    n = a.shape[0]
    w, vl, vr = scipy.linalg.eig(a, left=True, right=True)
    s = np.abs(np.sum(vl.conj() * vr, axis=0)) / (np.linalg.norm(vl, axis=0) * np.linalg.norm(vr, axis=0))
    na = np.linalg.norm(a)
    first = C_BACK * n * EPS * na / np.maximum(s, 1e-300)
    return w, np.where(first < math.sqrt(EPS) * na, first, 4 * math.sqrt(C_BACK * n * EPS) * na)


def assert_same_spectrum(ours, ref, tol, what=""):
    """A one-to-one matching of the two multisets in which every pair is within the reference's tolerance."""
    cost = np.abs(ours[:, None] - ref[None, :])
    rows, cols = linear_sum_assignment(cost)
    bad = [(ours[r], ref[c], tol[c]) for r, c in zip(rows, cols, strict=True) if cost[r, c] > tol[c]]
    assert not bad, f"{what}: {bad[:3]}"


def assert_pairs_well_formed(wr, wi):
    k = 0
    while k < len(wr):
        if wi[k] == 0.0:
            k += 1
            continue
        assert wi[k] > 0 and k + 1 < len(wr) and wi[k + 1] == -wi[k] and wr[k + 1] == wr[k]
        k += 2


@pytest.mark.parametrize("n", range(1, 33))
def test_eig_random_matches_lapack_within_conditioning(lib, n):
    rng = case_rng(9100 + n)
    for trial in range(8):
        a = rng.standard_normal((n, n)) * (10.0 ** rng.uniform(-3, 3) if trial % 2 else 1.0)
        rc, ours, wr, wi = eig(lib, a)
        assert rc == OK
        assert_pairs_well_formed(wr, wi)
        ref, tol = _eigen_tolerances(a)
        assert_same_spectrum(ours, ref, tol, f"n={n} trial={trial}")


def test_eig_is_backward_stable_on_the_trace_and_determinant_scale(lib):
    """Non-normal (upper-triangular-dominated) matrices: the eigenvalues are ill-conditioned, but sum and
    product are not; the sum of the computed ones must equal the trace to c n eps ||A||."""
    rng = case_rng(9140)
    for n in (5, 12, 24, 32):
        a = np.triu(rng.standard_normal((n, n)) * 100) + rng.standard_normal((n, n)) * 1e-3
        rc, ours, _, _ = eig(lib, a)
        assert rc == OK
        assert abs(ours.sum() - np.trace(a)) <= C_BACK * n * EPS * np.linalg.norm(a) * n


def test_eig_triangular_and_diagonal_are_exact(lib):
    """Nothing below the diagonal: Hessenberg reduction and QR leave the (power-of-two scaled, balanced)
    diagonal untouched, so the eigenvalues are the diagonal entries bit for bit."""
    rng = case_rng(9141)
    for n in (1, 2, 3, 7, 16, 32):
        a = np.triu(rng.standard_normal((n, n)))
        rc, ours, _, wi = eig(lib, a)
        assert rc == OK and not wi.any()
        assert sorted(ours.real) == sorted(np.diag(a))


def test_eig_zero_subnormal_huge_and_graded(lib):
    rng = case_rng(9142)
    for n in (1, 2, 5, 17, 32):
        rc, ours, _, _ = eig(lib, np.zeros((n, n)))
        assert rc == OK and not ours.any()
        base = rng.uniform(-1, 1, (n, n))
        for scale in (-1060, -1040, 1000, 1010):  # subnormal entries (14, 34 bits); entries ~ 1e301 .. 1e304
            a = np.ldexp(base, scale)
            rc, ours, _, _ = eig(lib, a)
            assert rc == OK and np.all(np.isfinite(ours))
            # the reference on the same matrix, scaled exactly by a power of two where LAPACK is comfortable
            ref, tol = _eigen_tolerances(np.ldexp(a, -scale))
            tol = tol + np.ldexp(1.0, -1074 - scale)  # a subnormal eigenvalue is itself rounded to 2^-1074
            assert_same_spectrum(np.ldexp(ours.real, -scale) + 1j * np.ldexp(ours.imag, -scale), ref, tol,
                                 f"n={n} scale=2^{scale}")
        idx = np.arange(n)
        for step in (10, 20, 30):  # graded: a_ij ~ 2^(step (i - j)), up to 2^+-930
            a = base * np.ldexp(1.0, step * (idx[:, None] - idx[None, :]))
            rc, ours, _, _ = eig(lib, a)
            assert rc == OK
            d = np.ldexp(1.0, step * idx)  # D^-1 a D is O(1): the same eigenvalues, well scaled for LAPACK
            ref, tol = _eigen_tolerances((a * d[None, :]) / d[:, None])
            # our contract is normwise in a (2^930 here: vacuous); balancing is an exact diagonal similarity, so
            # the eigenvalues must in fact be as good as those of the balanced matrix
            assert_same_spectrum(ours, ref, tol, f"graded n={n} step={step}")


def test_eig_complex_pairs_from_2x2_blocks(lib):
    rng = case_rng(9143)
    for n in (2, 4, 10, 24, 32):
        blocks = []
        for _ in range(n // 2):
            re, b, c = rng.uniform(-2, 2), rng.uniform(0.1, 2), rng.uniform(0.1, 2)
            blocks.append(np.array([[re, b], [-c, re]]))
        q, _ = np.linalg.qr(rng.standard_normal((n, n)))
        a = q @ scipy.linalg.block_diag(*blocks) @ q.T
        rc, ours, wr, wi = eig(lib, a)
        assert rc == OK
        assert_pairs_well_formed(wr, wi)
        assert np.count_nonzero(wi) == n  # every one complex: b c > 0 in each block
        truth = np.concatenate([[bl[0, 0] + 1j * math.sqrt(bl[0, 1] * -bl[1, 0]),
                                 bl[0, 0] - 1j * math.sqrt(bl[0, 1] * -bl[1, 0])] for bl in blocks])
        _, tol = _eigen_tolerances(a)
        ref = scipy.linalg.eigvals(a)
        order = linear_sum_assignment(np.abs(truth[:, None] - ref[None, :]))[1]
        assert_same_spectrum(ours, truth, 2 * tol[order], f"n={n}")


def test_eig_cyclic_permutation_needs_the_exceptional_shift(lib):
    """The cyclic shift has all eigenvalues on the unit circle and the standard shift stalls on it."""
    for n in range(2, 33):
        a = np.roll(np.eye(n), 1, axis=0)
        rc, ours, _, _ = eig(lib, a)
        assert rc == OK
        truth = np.exp(2j * np.pi * np.arange(n) / n)
        assert_same_spectrum(ours, truth, np.full(n, C_BACK * n * EPS * math.sqrt(n)), f"n={n}")


def test_eig_defective_and_derogatory_eigenvalues_converge(lib):
    """Jordan blocks (QR converges only linearly) and many equal 2x2 Jordan blocks. The first version computed
    the bulge's first column as h00^2 - (s1 + s2) h00 + s1 s2, which cancels to pure rounding when the shifts
    sit within sqrt(eps) of the cluster, and gave up (30 iterations) on 78 of these; a Jordan block of k is
    determined to (c n eps)^(1/k) ||A||."""
    rng = case_rng(9144)
    for n in (2, 3, 6, 9, 13, 20, 24):
        for k in sorted({2, n // 2, n}):
            for lam in (0.0, 0.7):
                j = lam * np.eye(n) + np.diag(np.ones(n - 1), 1)
                if k < n:
                    j[k - 1:, k - 1:] = np.diag(rng.uniform(-2, 2, n - k + 1))
                    j[k - 1, k - 1] = lam  # the block's last entry stays lam
                q, _ = np.linalg.qr(rng.standard_normal((n, n)))
                a = q @ j @ q.T
                rc, ours, _, _ = eig(lib, a)
                assert rc == OK, (n, k, lam)
                na = np.linalg.norm(a)
                spread = 4 * (C_BACK * n * EPS * na) ** (1.0 / k) * na ** (1 - 1.0 / k)
                near = np.abs(ours - lam) <= spread
                assert near.sum() >= k, (n, k, lam, np.sort_complex(ours))
    for n2 in (10, 16, 24, 32):
        a0 = np.kron(np.eye(n2 // 2), np.array([[0.5, 1.0], [0.0, 0.5]]))
        q, _ = np.linalg.qr(rng.standard_normal((n2, n2)))
        rc, ours, _, _ = eig(lib, q @ a0 @ q.T)
        assert rc == OK
        assert np.abs(ours - 0.5).max() <= 4 * math.sqrt(C_BACK * n2 * EPS) * np.linalg.norm(a0)


@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf])
def test_eig_refuses_nonfinite_input(lib, bad):
    for n in (1, 4, 32):
        a = np.ones((n, n))
        a[n // 2, n // 3] = bad
        rc, ours, _, _ = eig(lib, a)
        assert rc == ERR_INPUT and not ours.any()


def test_eig_refuses_sizes_out_of_range(lib):
    a = np.ones(34 * 34)
    w = np.zeros(80)
    assert lib.wk_eig_real(0, a, w, w, w) == ERR_INPUT
    assert lib.wk_eig_real(33, a, w, w, w) == ERR_INPUT
    assert lib.wk_eig_real(-1, a, w, w, w) == ERR_INPUT


# ------------------------------------------------------------------------------ companion matrices
def _poly_exact(roots):
    """Exact coefficients (highest first) of prod (x - r)."""
    c = [Fraction(1)]
    for r in roots:
        c = [a - Fraction(r) * b for a, b in zip([*c, Fraction(0)], [Fraction(0), *c], strict=True)]
    return c


def _poly_from_roots(roots):
    return [float(x) for x in _poly_exact(roots)]


def _true_roots(coef, roots):
    """The roots of the double coefficients as they are: the dyadic roots themselves when the coefficients
    came out exact, else mpmath at 50 digits (the rounding is then part of the problem)."""
    if [Fraction(c) for c in coef] == _poly_exact(roots):
        return [mpmath.mpf(r) for r in roots]
    with mpmath.workdps(50):
        return mpmath.polyroots([mpmath.mpf(x) for x in coef], maxsteps=800, extraprec=800)


def _root_radius(coef, r, delta):
    """How far a normwise coefficient perturbation of relative size delta (|da_i| <= delta max|a|) can move the
    root r: min over k of (k! delta S / |p^(k)(r)|)^(1/k), S = max|a| sum |r|^i (Taylor: the first derivative
    that does not vanish decides; k = 1 for a simple root, k = 2 for a double one or a tight cluster)."""
    with mpmath.workdps(50):
        n = len(coef) - 1
        big = max(abs(x) for x in coef)
        s = big * sum(abs(r) ** i for i in range(n + 1))
        best = mpmath.inf
        d = [mpmath.mpf(x) for x in coef]
        for k in range(1, n + 1):
            d = [c * (len(d) - 1 - i) for i, c in enumerate(d[:-1])]  # the next derivative, highest first
            dk = abs(mpmath.polyval(d, r))
            if dk > 0:
                best = min(best, (math.factorial(k) * delta * s / dk) ** (mpmath.mpf(1) / k))
        return float(best)


def _companion(coef):
    n = len(coef) - 1
    a = np.zeros((n, n))
    a[0, :] = -np.array(coef[1:]) / coef[0]
    a[1:, :-1] += np.eye(n - 1)
    return a


def _root_sets(rng):
    def dy(bits=4, lo=-3, hi=2):
        return float(Fraction(int(rng.integers(1, 1 << bits)) * (1 if rng.random() < 0.5 else -1), 1 << bits)
                     * Fraction(2) ** int(rng.integers(lo, hi + 1)))
    for _ in range(6):
        yield [dy() for _ in range(int(rng.integers(1, 13)))]                  # random simple (maybe repeated)
    for gap in (2.0**-10, 2.0**-17, 2.0**-23):                                   # clusters ~1e-3, 1e-5, 1e-7 apart
        r = dy()
        yield [r, r + gap, *[dy() for _ in range(int(rng.integers(0, 8)))]]
        yield [r, r + gap, r + 2 * gap, *[dy() for _ in range(int(rng.integers(0, 6)))]]
    r = dy()
    yield [r, r, *[dy() for _ in range(5)]]                                      # double
    yield [r, r, r, *[dy() for _ in range(4)]]                                   # triple
    yield [r, r, dy(), dy(), dy(), dy()] * 2                                      # two doubles, up to quadruple


def test_companion_roots_within_their_conditioning(lib):
    rng = case_rng(9150)
    for roots in _root_sets(rng):
        coef = _poly_from_roots(roots)
        n = len(coef) - 1
        rc, ours, _, _ = eig(lib, _companion(coef))
        assert rc == OK
        truth = _true_roots(coef, roots)
        delta = C_BACK * (n + 1) * EPS
        tol = np.array([4 * _root_radius(coef, t, delta) for t in truth])
        assert_same_spectrum(ours, np.array([complex(t) for t in truth]), tol, f"roots {roots}")


# ------------------------------------------------------------------------------ quadratic eigenproblem
def _reals(res):
    return list(zip(res.real[:res.n_real], res.real_flags[:res.n_real], strict=True))


def _pairs(res):
    return list(zip(res.complex_re[:res.n_complex], res.complex_im[:res.n_complex], strict=True))


def _expand(res):
    """Our result as the 2m eigenvalues (doubles twice, pairs both ways, infinities as inf)."""
    out = []
    for x, f in _reals(res):
        out += [x, x] if f & FLAG_DOUBLE else [x]
    for re, im in _pairs(res):
        out += [complex(re, im), complex(re, -im)]
    return np.array(out, dtype=complex), res.n_infinite


def _param_scale(A, B, C):
    """g with x = g mu balancing ||A|| g^2 against ||C|| (the parameter scaling wk_eigen.c applies, up to
    its rounding to a power of two), and the largest scaled coefficient norm."""
    na, nb, nc = (np.linalg.norm(X, 2) for X in (A, B, C))
    g = math.sqrt(nc / na) if na > 0 and nc > 0 else 1.0
    return g, max(na * g * g, nb * g, nc)


def _backward_error(A, B, C, x):
    """The normwise backward error the contract bounds (wk_eigen.h): the smallest delta such that x is exact
    for coefficients perturbed by delta times the largest scaled one, A g^2, B g, C in mu = x / g:
    sigma_min(M(x)) / (n_max (|mu|^2 + |mu| + 1)). (Weights per coefficient, ||C|| for C, would call a root
    at 1e-16 of a problem with C = 0 wrong though its error is 1e-16 absolute.)"""
    s = np.linalg.svd(A * x * x + B * x + C, compute_uv=False)[-1]
    g, nmax = _param_scale(A, B, C)
    mu = abs(x) / g
    return s / (nmax * (mu * mu + mu + 1))


def _qep_reference(A, B, C, tol):
    """scipy's QZ on the first companion pencil: the finite eigenvalues, how many are infinite (beyond 2 / tol
    as ours are), and each finite one's first-order error per unit backward error (as _backward_error weighs
    it) n_max (|mu|^2 + |mu| + 1) / |y^H M'(x) z| with y, z the unit left/right null vectors of M(x)."""
    m = A.shape[0]
    eye, zero = np.eye(m), np.zeros((m, m))
    g, nmax = _param_scale(A, B, C)  # in mu = x / g with coefficients A g^2, B g, C over n_max: well scaled
    lhs = np.block([[zero, eye], [-C / nmax, -B * g / nmax]])
    rhs = np.block([[eye, zero], [zero, A * g * g / nmax]])
    ab = scipy.linalg.eig(lhs, rhs, right=False, homogeneous_eigvals=True)
    alpha, beta = ab[0] * g, ab[1]
    finite = np.abs(beta) * 2.0 > tol * np.abs(alpha)
    lam = alpha[finite] / beta[finite]
    sens = []
    for x in lam:
        u, _, vh = np.linalg.svd(A * x * x + B * x + C)
        y, z = u[:, -1], vh[-1].conj()
        d = abs(y.conj() @ ((2 * x * A + B) @ z))
        g, nmax = _param_scale(A, B, C)
        mu = abs(x) / g
        sens.append(nmax * (mu * mu + mu + 1) / max(d, 1e-300))
    return lam, int((~finite).sum()), np.array(sens)


def assert_qep_ok(A, B, C, rc, res, tol=TOL_DEFAULT, what=""):
    m = A.shape[0]
    assert rc == OK, what
    ours, n_inf = _expand(res)
    assert len(ours) + n_inf == 2 * m, what
    assert list(res.real[:res.n_real]) == sorted(res.real[:res.n_real]) and np.all(np.isfinite(ours))
    # our backward error is c m eps growth (wk_eigen.h); the reference's, QZ on the companion pencil of the
    # scaled coefficients, c m eps (1 + tau) with tau = ||B|| g / sqrt(||A|| g^2 ||C||) (Higham, Li & Tisseur)
    g, nmax = _param_scale(A, B, C)
    assert res.growth >= 1.0
    eta = C_BACK * 2 * m * EPS * res.growth
    na, nb, nc = (np.linalg.norm(X, 2) for X in (A, B, C))
    eta_ref = C_BACK * 2 * m * EPS * (1 + (nb / math.sqrt(na * nc) if na > 0 and nc > 0 else 1.0))
    for x, f in _reals(res):
        allowed = eta
        if f & FLAG_DOUBLE:  # the real part of a pair within tol of the axis: |Im x| <= tol (1 + x^2) / 2 more
            mu = abs(x) / g
            allowed += tol * (1 + x * x) / 2 * np.linalg.norm(2 * x * A + B, 2) / (nmax * (mu * mu + mu + 1))
        assert _backward_error(A, B, C, x) <= allowed, (what, x, f)
    for re, im in _pairs(res):
        assert _backward_error(A, B, C, complex(re, im)) <= eta, (what, re, im)
    lam, ref_inf, sens = _qep_reference(A, B, C, tol)
    assert n_inf == ref_inf, (what, n_inf, ref_inf)
    # none missed, none spurious: one-to-one within first-order error (sqrt of it at a near-double root)
    first = (eta + eta_ref) * sens
    lim = np.where(first < 1e-6 * (1 + np.abs(lam)), first, 4 * np.sqrt(first * (1 + np.abs(lam))))
    lim = lim + np.where(np.abs(lam.imag) * 2 <= tol * (1 + np.abs(lam) ** 2), tol * (1 + np.abs(lam) ** 2), 0)
    assert_same_spectrum(ours, lam, lim, what)


@pytest.mark.parametrize("m", range(1, 13))
def test_qep_random_against_qz_on_the_linearisation(lib, m):
    rng = case_rng(9200 + m)
    for trial in range(6):
        A, B, C = (rng.standard_normal((m, m)) * 10.0 ** rng.uniform(-2, 2) for _ in range(3))
        rc, res = qep(lib, A, B, C)
        assert_qep_ok(A, B, C, rc, res, what=f"m={m} trial={trial}")


@pytest.mark.parametrize("m", [1, 2, 5, 12])
def test_qep_singular_leading_coefficient_gives_infinite_not_huge_roots(lib, m):
    """A singular: det M has degree < 2m, the missing roots are at x = inf (theta = pi) and must be reported
    as such, never as a huge finite real root."""
    rng = case_rng(9220 + m)
    for rank_drop in range(1, m + 1):
        A, B, C = (rng.standard_normal((m, m)) for _ in range(3))
        A = A @ np.diag([0.0] * rank_drop + [1.0] * (m - rank_drop)) @ np.linalg.qr(rng.standard_normal((m, m)))[0]
        rc, res = qep(lib, A, B, C)
        assert res.n_infinite == rank_drop
        assert all(abs(x) < 1e6 for x in res.real[:res.n_real])
        assert_qep_ok(A, B, C, rc, res, what=f"m={m} drop={rank_drop}")


@pytest.mark.parametrize("m", [1, 3, 12])
def test_qep_singular_constant_coefficient_gives_zero_root(lib, m):
    rng = case_rng(9240 + m)
    for rank_drop in range(1, min(m, 3) + 1):
        A, B, C = (rng.standard_normal((m, m)) for _ in range(3))
        C[:rank_drop, :] = 0.0  # rank_drop roots at exactly x = 0
        rc, res = qep(lib, A, B, C)
        assert_qep_ok(A, B, C, rc, res, what=f"m={m} drop={rank_drop}")
        # a semisimple root at 0 of multiplicity k = rank_drop: each copy within the backward error times its
        # sensitivity n_max / sigma_min(Y^H B Z), Y, Z the left/right null spaces of C = M(0) (Tisseur 2000)
        u, _, vh = np.linalg.svd(C)
        d = np.linalg.svd(u[:, -rank_drop:].T @ B @ vh[-rank_drop:].T, compute_uv=False)[-1]
        limit = 4 * C_BACK * 2 * m * EPS * res.growth * _param_scale(A, B, C)[1] / d
        zeros = [2 if f else 1 for x, f in _reals(res) if abs(x) <= limit]
        assert sum(zeros) == rank_drop, (list(res.real[:res.n_real]), limit)


def test_qep_both_singular_uses_a_rotation(lib):
    """A and C singular (x = 0 and x = inf both roots): neither the problem nor its reversal can be inverted,
    a Moebius rotation of the projective line is used."""
    rng = case_rng(9250)
    for m in (2, 6, 12):
        A, B, C = (rng.standard_normal((m, m)) for _ in range(3))
        A[:, 0] = 0.0
        C[-1, :] = 0.0
        rc, res = qep(lib, A, B, C)
        assert res.angle not in (0.0, math.pi / 2) and res.n_infinite == 1
        assert_qep_ok(A, B, C, rc, res, what=f"m={m}")


def test_qep_zero_leading_coefficient(lib):
    rng = case_rng(9251)
    for m in (1, 4, 12):
        B, C = rng.standard_normal((m, m)), rng.standard_normal((m, m))
        rc, res = qep(lib, np.zeros((m, m)), B, C)
        assert res.n_infinite == m
        assert_qep_ok(np.zeros((m, m)), B, C, rc, res, what=f"m={m}")
        lin = np.linalg.eigvals(-np.linalg.solve(B, C))
        ours, _ = _expand(res)
        assert_same_spectrum(ours, lin, np.full(m, 1e-8 * (1 + np.abs(lin).max())), f"linear m={m}")


def test_qep_double_root_comes_back_real_and_a_clear_complex_pair_does_not(lib):
    """(x - 3/4)^2 I mixed by random orthogonal factors: the double root may split by ~sqrt(backward error) into
    a pair either side of the axis; within tol it is one real root flagged double. (x - 1/2)^2 + 1e-10 (Im x =
    1e-5, theta's imaginary part 1.6e-5 >> tol) stays complex; + 1e-14 (1.6e-7 < tol) is reported real."""
    rng = case_rng(9252)
    for m in (1, 3, 12):
        for c0, expect_real in ((0.5625, True), (0.25 + 1e-10, False), (0.25 + 1e-14, True)):
            b0 = -1.5 if c0 == 0.5625 else -1.0
            u, _ = np.linalg.qr(rng.standard_normal((m, m)))
            v, _ = np.linalg.qr(rng.standard_normal((m, m)))
            d = rng.uniform(0.5, 2.0, m)
            A, B, C = (u * d) @ v, (u * (b0 * d)) @ v, (u * (c0 * d)) @ v
            rc, res = qep(lib, A, B, C)
            assert rc == OK
            ours, n_inf = _expand(res)
            assert n_inf == 0 and len(ours) == 2 * m
            root = 0.75 if c0 == 0.5625 else 0.5
            near_real = [x for x in res.real[:res.n_real] if abs(x - root) <= 1e-6]
            if expect_real:
                assert sum(2 if f else 1 for x, f in _reals(res)
                           if abs(x - root) <= 1e-6) == 2 * m, (m, c0, list(res.real[:res.n_real]))
            else:
                assert not near_real and res.n_complex == m
            assert_qep_ok(A, B, C, rc, res, what=f"m={m} c0={c0}")


def test_qep_is_invariant_under_exact_power_of_two_scalings(lib):
    """x = 2^-k x' (A 2^2k, B 2^k, C) and an overall 2^j on all three are absorbed by the exact parameter and
    coefficient scalings: the same internal problem, so the roots come back scaled bit for bit. Only the
    classification is absolute in x (tol is an angle of theta = 2 atan x): at k = 600 every root is within
    2^-600 of 0, so the complex pairs come back as flagged real doubles at their real parts. Before the
    scalings were applied in one step, A 2^1200 flushed C to zero first and every root came back 0."""
    rng = case_rng(9254)
    for m in (1, 5, 12):
        A, B, C = (rng.standard_normal((m, m)) for _ in range(3))
        rc, base = qep(lib, A, B, C)
        assert rc == OK
        for k, j in ((3, 0), (11, 0), (-3, 0), (-9, 0), (0, 900), (0, -1000), (5, -400), (600, -600), (700, -900)):
            rc, res = qep(lib, np.ldexp(A, 2 * k + j), np.ldexp(B, k + j), np.ldexp(C, j))
            assert rc == OK and res.n_infinite == base.n_infinite, (m, k, j)
            plain = [np.ldexp(x, k) for x, f in _reals(res) if not f]
            flagged = [np.ldexp(x, k) for x, f in _reals(res) if f]
            assert plain == list(base.real[:base.n_real]), (m, k, j)
            if k < 100:
                assert not flagged and [np.ldexp(y, k) for y in res.complex_im[:res.n_complex]] == \
                    list(base.complex_im[:base.n_complex]), (m, k, j)
            else:
                assert sorted(flagged) == sorted(base.complex_re[:base.n_complex]) and res.n_complex == 0


def test_qep_refuses_bad_input_and_singular_pencils(lib):
    rng = case_rng(9253)
    A, B, C = (rng.standard_normal((4, 4)) for _ in range(3))
    for bad in (math.nan, math.inf):
        for X in (A, B, C):
            keep = X[1, 2]
            X[1, 2] = bad
            assert qep(lib, A, B, C)[0] == ERR_INPUT
            X[1, 2] = keep
    assert qep(lib, A, B, C, tol=math.nan)[0] == ERR_INPUT
    assert qep(lib, A, B, C, tol=0.75)[0] == ERR_INPUT
    z = np.zeros((13, 13))
    assert qep(lib, z, z, z)[0] == ERR_INPUT
    # a common null vector of A, B and C: det M(x) = 0 for every x
    for X in (A, B, C):
        X[:, 0] = 0.0
    rc, res = qep(lib, A, B, C)
    assert rc == ERR_SINGULAR and res.n_real == res.n_complex == res.n_infinite == 0
    assert qep(lib, np.zeros((3, 3)), np.zeros((3, 3)), np.zeros((3, 3)))[0] == ERR_SINGULAR


# ------------------------------------------------------------------------------ null vectors
def null_vector_lu(lib, M):
    M = np.ascontiguousarray(M, dtype=float)
    m = M.shape[0]
    v, resid = np.full(m + 2, 7.25), ctypes.c_double(-1.0)
    rc = lib.wk_null_vector_lu(m, M, v, ctypes.byref(resid))
    assert list(v[m:]) == [7.25, 7.25]
    return rc, v[:m], resid.value


@pytest.mark.parametrize("m", range(1, 25))
def test_null_vector_against_svd(lib, m):
    rng = case_rng(9300 + m)
    for trial in range(6):
        M = rng.standard_normal((m, m))
        if trial % 3 == 1 and m > 1:  # exactly-ish rank deficient
            u, s, vh = np.linalg.svd(M)
            s[-1] = 0.0
            M = (u * s) @ vh
        if trial % 3 == 2 and m > 1:  # a tiny but resolvable smallest singular value
            u, s, vh = np.linalg.svd(M)
            s[-1] = s[0] * 1e-9
            M = (u * s) @ vh
        rc, v, rel = null_vector(lib, M)
        assert rc == OK
        s = np.linalg.svd(M, compute_uv=False)
        slack = C_BACK * m * EPS
        assert abs(np.linalg.norm(v) - 1) <= slack
        assert np.linalg.norm(M @ v) <= s[-1] + slack * s[0]
        assert abs(rel[0] - s[-1] / s[0]) <= slack
        if m > 1:
            assert abs(rel[1] - s[-2] / s[0]) <= slack
            gap = s[-2] / s[0] - s[-1] / s[0]
            if gap > 1e-6:  # v is determined: its angle to the true singular vector <= c m eps / gap
                vt = np.linalg.svd(M)[2][-1]
                assert min(np.linalg.norm(v - vt), np.linalg.norm(v + vt)) <= slack / gap * 4
        else:
            assert rel[1] == 1.0


@pytest.mark.parametrize("m", [1, 2, 5, 12])
def test_small_singular_vectors_against_svd(lib, m):
    """The k smallest right singular vectors (a general 6R cluster's subspace): the singular values ascending and
    within backward error of LAPACK's, each vector a unit one with |M v_j| = sigma_j to that error, the k of them
    orthonormal, and their span the reference's where the gap after sigma_k determines it (angle <= c m eps /
    gap). A cluster of three singular values 1e-9 .. 1e-6 with a gap of 1e-3 after it is the 6R's case."""
    rng = case_rng(9340 + m)
    for trial in range(6):
        M = rng.standard_normal((m, m))
        if trial % 2 == 1 and m > 3:
            u, s, vh = np.linalg.svd(M)
            s[-3:] = s[0] * np.array([1e-6, 1e-7, 1e-9])
            s[:-3] = np.maximum(s[:-3], 1e-3 * s[0])
            M = (u * s) @ vh
        k = min(m, 3)
        v, rel = np.full(k * m + 2, 7.25), np.full(m + 2, 7.25)
        assert lib.wk_small_singular_vectors(m, np.ascontiguousarray(M), k, v, rel) == OK
        assert list(v[k * m:]) == [7.25, 7.25] and list(rel[m:]) == [7.25, 7.25]
        v, rel = v[: k * m].reshape(k, m), rel[:m]
        u, s, vh = np.linalg.svd(M)
        slack = C_BACK * m * EPS
        assert np.all(np.diff(rel) >= 0.0)
        assert np.max(np.abs(rel - s[::-1] / s[0])) <= slack
        assert np.max(np.abs(v @ v.T - np.eye(k))) <= slack
        for j in range(k):
            assert abs(np.linalg.norm(M @ v[j]) - s[m - 1 - j]) <= slack * s[0]
        if k < m and s[m - k - 1] - s[m - k] > 1e-6 * s[0]:
            ref = vh[m - k:]  # the reference span's basis
            sines = np.linalg.svd(v @ ref.T, compute_uv=False)
            assert np.min(sines) >= 1.0 - slack * s[0] / (s[m - k - 1] - s[m - k])


def test_small_singular_vectors_refuses_bad_input(lib):
    M = np.eye(4)
    v, rel = np.zeros(16), np.zeros(4)
    assert lib.wk_small_singular_vectors(4, M, 0, v, rel) != OK
    assert lib.wk_small_singular_vectors(4, M, 5, v, rel) != OK
    bad = M.copy()
    bad[1, 2] = np.nan
    assert lib.wk_small_singular_vectors(4, bad, 2, v, rel) != OK


def test_null_vector_of_the_quadratic_at_its_eigenvalues(lib):
    """The 6R back-substitution step: at each real eigenvalue x, v spans the null space of M(x)."""
    rng = case_rng(9330)
    for _ in range(5):
        A, B, C = (rng.standard_normal((12, 12)) for _ in range(3))
        rc, res = qep(lib, A, B, C)
        assert rc == OK
        for x in res.real[:res.n_real]:
            M = A * x * x + B * x + C
            rc, v, rel = null_vector(lib, M)
            assert rc == OK
            assert np.linalg.norm(M @ v) <= C_BACK * 24 * EPS / res.rcond * np.linalg.norm(M, 2) * 10
            assert rel[1] > 1e3 * rel[0]  # a simple eigenvalue: a one-dimensional null space


def test_null_vector_lu_at_the_quadratic_eigenvalues_equals_the_svd_one(lib):
    """The cheap route (complete-pivoting LU + inverse iteration) where the 6R back-substitution needs it: at
    every real root the same vector as the Jacobi SVD's, to its determination c m eps / gap, and a residual
    no worse than the SVD's plus rounding."""
    rng = case_rng(9331)
    for m in (3, 6, 12):
        for _ in range(4):
            A, B, C = (rng.standard_normal((m, m)) for _ in range(3))
            rc, res = qep(lib, A, B, C)
            assert rc == OK
            for x, f in _reals(res):
                if f:
                    continue  # a double root: a two-dimensional null space is wk_null_vector's case
                M = A * x * x + B * x + C
                rc, v, resid = null_vector_lu(lib, M)
                rcj, vj, rel = null_vector(lib, M)
                assert rc == OK and rcj == OK
                fro = np.linalg.norm(M)
                assert abs(np.linalg.norm(v) - 1) <= C_BACK * m * EPS
                assert abs(resid - np.linalg.norm(M @ v) / fro) <= C_BACK * m * EPS
                assert np.linalg.norm(M @ v) <= 4 * np.linalg.norm(M @ vj) + C_BACK * m * EPS * fro
                gap = rel[1] - rel[0]
                assert min(np.linalg.norm(v - vj), np.linalg.norm(v + vj)) <= 4 * C_BACK * m * EPS / gap


@pytest.mark.parametrize("m", range(1, 25))
def test_null_vector_lu_on_rank_deficient_matrices(lib, m):
    rng = case_rng(9332 + m)
    for _ in range(4):
        u, s, vh = np.linalg.svd(rng.standard_normal((m, m)))
        s[-1] = 0.0
        M = (u * s) @ vh
        rc, v, resid = null_vector_lu(lib, M)
        assert rc == OK and abs(np.linalg.norm(v) - 1) <= C_BACK * m * EPS
        assert np.linalg.norm(M @ v) <= C_BACK * m * EPS * np.linalg.norm(M) + 1e-300
        if m > 1:  # the null vector is determined: gap = s[-2] / s[0]
            gap = s[-2] / s[0]
            assert min(np.linalg.norm(v - vh[-1]), np.linalg.norm(v + vh[-1])) <= 4 * C_BACK * m * EPS / gap


def test_null_vector_zero_nonfinite_and_sizes(lib):
    rc, v, resid = null_vector_lu(lib, np.zeros((4, 4)))
    assert rc == OK and list(v) == [1, 0, 0, 0] and resid == 0.0
    bad = np.eye(3)
    bad[1, 1] = math.inf
    assert null_vector_lu(lib, bad)[0] == ERR_INPUT
    assert lib.wk_null_vector_lu(25, np.zeros(625), np.zeros(30), None) == ERR_INPUT
    rc, v, rel = null_vector(lib, np.zeros((5, 5)))
    assert rc == OK and list(v) == [1, 0, 0, 0, 0] and list(rel) == [0, 0]
    M = np.ones((3, 3))
    M[2, 2] = math.nan
    assert null_vector(lib, M)[0] == ERR_INPUT
    big = np.zeros(25 * 25)
    out = np.zeros(30)
    assert lib.wk_null_vector(25, big, out, out) == ERR_INPUT
    assert lib.wk_null_vector(0, big, out, out) == ERR_INPUT


def test_iteration_caps_return_no_convergence_not_a_loop():
    """The caps, made tiny at compile time (the only reason they are overridable): QR with a budget of 0
    iterations and Jacobi with 1 sweep must give up with WK_EIG_ERR_NOCONV, outputs zeroed, and the quadratic
    must pass the QR's code on."""
    so = cbuild.load(cbuild.compile_shared([SOURCE], [RUNTIME_C], name="wk_eigen_caps",
                                           extra_flags=["-DWK_EIG_ITMAX=0", "-DWK_NULL_SWEEPS=1"]))
    so.wk_eig_real.argtypes = [ctypes.c_int, _DP, _DP, _DP, _DP]
    so.wk_generalized_quadratic_eig.argtypes = [ctypes.c_int, _DP, _DP, _DP, ctypes.c_double,
                                                ctypes.POINTER(QepResult)]
    so.wk_null_vector.argtypes = [ctypes.c_int, _DP, _DP, _DP]
    rng = case_rng(9400)
    rc, ours, _, _ = eig(so, rng.standard_normal((8, 8)))
    assert rc == ERR_NOCONV and not ours.any()
    rc, res = qep(so, *(rng.standard_normal((4, 4)) for _ in range(3)))
    assert rc == ERR_NOCONV and res.n_real == res.n_complex == res.n_infinite == 0
    assert null_vector(so, rng.standard_normal((6, 6)))[0] == ERR_NOCONV
    # already triangular: nothing to iterate, so even a zero budget succeeds
    assert eig(so, np.triu(rng.standard_normal((8, 8))))[0] == OK


# ------------------------------------------------------------------------------ under the sanitizers
def _sanitizer_available() -> bool:
    probe = subprocess.run([cbuild.compiler(), "-fsanitize=address,undefined", "-x", "c", "-", "-o", "/dev/null"],
                           input="int main(void){return 0;}", capture_output=True, text=True)
    return probe.returncode == 0


@pytest.mark.c_only  # no numpy result enters: the repeated passes on other kernels skip it
@pytest.mark.skipif(not _sanitizer_available(), reason="compiler has no ASan/UBSan runtime")
def test_eigen_under_asan_ubsan():
    exe = cbuild.compile_executable([ROOT / "tests" / "c" / "eigen_sanitize.c", SOURCE], [RUNTIME_C,
                                    ROOT / "tests" / "c"], "eigen_sanitize", extra_flags=cbuild.SANITIZE_FLAGS)
    run = subprocess.run([str(exe), str(TEST_SEED)], capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stdout + run.stderr
    assert run.stdout.startswith("ok ")
    assert "runtime error" not in run.stderr and "AddressSanitizer" not in run.stderr
