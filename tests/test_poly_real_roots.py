"""Real-root finder partials (C: wk_poly_real_roots, Python: _poly_real_roots) against exact truth.

Most polynomials are built so that their double coefficients are *exact*: every root is a dyadic
rational with few significant bits, every complex pair is x^2 + b x + c with dyadic b, c, and the
product is checked with Fractions to be representable. Their real roots are then known exactly:
random (thousands, degrees 1..8), clustered (2^-10, 2^-17, 2^-23 ~ 1e-3, 1e-5, 1e-7 apart), double,
triple, touching or not, magnitudes 2^-10..2^10, no real root. A smaller set with arbitrary float
roots (and the degree-drop cases) uses mpmath.polyroots at 50 digits as the reference.

The checks are conditioning-aware. Every true real root r must have a returned root within
rad(r, L) = 4 min_k (L S(r) k! / |p^(k)(r)|)^(1/k), the distance by which a relative perturbation L
of the coefficients can move it, with S(r) = sum |a_i||r|^i and L = 32 (n+1) eps for plain roots;
for roots flagged touching/double also within the normwise radius (S -> max|a_i| sum |r|^i) at
L = 4 tol_touch. Returned roots map one-to-one onto distinct true roots (nothing doubled), except
touching roots standing for a complex pair, whose normwise backward error |p(x)|/(max|a_i| sum |x|^i)
must be within tol_touch; a clearly near-zero extremum must come back flagged. No NaN, count <=
degree, strictly ascending, and the status bits as expected.
"""
from __future__ import annotations

import ctypes
import functools
import math
import os
import platform
import random
import subprocess
import tempfile
from fractions import Fraction
from pathlib import Path

import cbuild  # tests/ is on sys.path under pytest (as for tests/c_solvers.py)
import mpmath
import numpy as np
import pytest

ROOT = Path(__file__).resolve().parent.parent
C_PARTIAL = ROOT / "runtime" / "c" / "poly_real_roots.c"  # real sources, inlined into the generated files
PY_PARTIAL = ROOT / "runtime" / "python" / "poly_real_roots.py"
HARNESS = ROOT / "tests" / "c" / "poly_roots_harness.c"

EPS = 2.0**-52
TOL_TOUCH = 1e-12
FLAG_DOUBLE = 1
ST_DROP, ST_ZERO, ST_BAD, ST_MAXIT = 1, 2, 4, 8
MP_DPS = 30


# ------------------------------------------------------------------------------ the two implementations
def _load_python():
    ns: dict = {}
    exec(compile(PY_PARTIAL.read_text(), str(PY_PARTIAL), "exec"), ns)
    return ns


PY = _load_python()


def _build_c_library() -> Path:
    """The partial and the harness in one translation unit, so the build cache sees the partial's bytes."""
    src_dir = cbuild.BUILD_DIR / "poly_roots_src"
    src_dir.mkdir(parents=True, exist_ok=True)
    combined = src_dir / "poly_roots_combined.c"
    text = ("#define WK_POLY_PARTIAL_INLINED 1\n" + f'#line 1 "{C_PARTIAL.name}"\n' + C_PARTIAL.read_text()
            + f'\n#line 1 "{HARNESS.name}"\n' + HARNESS.read_text())
    if not combined.exists() or combined.read_text() != text:
        combined.write_text(text)
    return cbuild.compile_shared([combined], [], name="poly_roots")


@pytest.fixture(scope="module")
def clib():
    lib = cbuild.load(_build_c_library())
    dp, up = ctypes.POINTER(ctypes.c_double), ctypes.POINTER(ctypes.c_uint)
    lib.wk_test_poly_real_roots.restype = ctypes.c_int
    lib.wk_test_poly_real_roots.argtypes = [dp, ctypes.c_int, dp, up, ctypes.POINTER(ctypes.c_int)]
    lib.wk_test_poly_real_roots_tol.restype = ctypes.c_int
    lib.wk_test_poly_real_roots_tol.argtypes = [dp, ctypes.c_int, dp, up, ctypes.POINTER(ctypes.c_int),
                                                ctypes.c_double]
    return lib


def c_roots(lib, coef, n=None, tol_touch=None):
    n = len(coef) - 1 if n is None else n
    cbuf = (ctypes.c_double * max(len(coef), 1))(*coef)
    # sentinels past the result must survive (no out-of-bounds writes)
    roots = (ctypes.c_double * 10)(*([7.25] * 10))
    flags = (ctypes.c_uint * 10)(*([99] * 10))
    st = ctypes.c_int(-1)
    if tol_touch is None:
        k = lib.wk_test_poly_real_roots(cbuf, n, roots, flags, ctypes.byref(st))
    else:
        k = lib.wk_test_poly_real_roots_tol(cbuf, n, roots, flags, ctypes.byref(st), tol_touch)
    assert 0 <= k <= 8
    assert list(roots[8:]) == [7.25, 7.25] and list(flags[8:]) == [99, 99]
    return list(roots[:k]), list(flags[:k]), st.value


def py_roots(coef, tol_touch=None):
    if tol_touch is None:
        return PY["_poly_real_roots"](coef)
    return PY["_poly_real_roots"](coef, tol_touch=tol_touch)


# ------------------------------------------------------------------------------ exact construction
def _poly_mul(c, f):
    out = [Fraction(0)] * (len(c) + len(f) - 1)
    for i, ci in enumerate(c):
        for j, fj in enumerate(f):
            out[i + j] += ci * fj
    return out


def _dyadic(rng, bits, emin, emax, signed=True):
    """A random m * 2^e with an odd m of `bits` bits (few significant bits keep products exact)."""
    m = rng.randrange(1 << (bits - 1), 1 << bits) | 1
    val = Fraction(m, 1 << bits) * Fraction(2) ** rng.randint(emin, emax)
    return -val if signed and rng.random() < 0.5 else val


class Case:
    """A polynomial with exactly known real roots (distinct values, Fractions) or mpmath truth."""

    def __init__(self, coef, truth, label, *, exact=True, expect_status=0):
        self.coef = [float(c) for c in coef]
        self.truth = sorted(truth)
        self.label = label
        self.exact = exact
        self.expect_status = expect_status
        self.touch_points = []  # near-zero extrema that must come back as flagged roots
        self.ref = None


def exact_case(label, real_roots, quads=(), scale_exp=0, sign=1, extra_lead=None):
    """Product of (x - r) and (x^2 + b x + c); None if a coefficient is not exactly a double."""
    c = [Fraction(sign) * Fraction(2) ** scale_exp]
    for r in real_roots:
        c = _poly_mul(c, [-Fraction(r), Fraction(1)])
    for b, cc in quads:
        c = _poly_mul(c, [Fraction(cc), Fraction(b), Fraction(1)])
    for v in c:
        if Fraction(float(v)) != v or (v != 0 and abs(float(v)) < 1e-290):
            return None
    case = Case(c, set(Fraction(r) for r in real_roots), label)
    case.quads = [(Fraction(b), Fraction(cc)) for b, cc in quads]
    return case


def _random_quad(rng, bits=5, emin=-3, emax=2, imag_min_exp=None):
    re = _dyadic(rng, bits, emin, emax)
    lo = emin - 2 if imag_min_exp is None else imag_min_exp
    im = _dyadic(rng, bits, lo, emax, signed=False)
    return -2 * re, re * re + im * im


def gen_random(rng, count):
    """Degrees 1..8, random dyadic real roots and complex pairs at mixed scales."""
    cases = []
    while len(cases) < count:
        deg = rng.randint(1, 8)
        npairs = rng.randint(0, deg // 2)
        nreal = deg - 2 * npairs
        bits = rng.randint(3, 7)
        reals = [_dyadic(rng, bits, -4, 3) for _ in range(nreal)]
        quads = [_random_quad(rng, bits) for _ in range(npairs)]
        case = exact_case(f"random#{len(cases)} deg={deg}", reals, quads, scale_exp=rng.randint(-20, 20),
                          sign=rng.choice((-1, 1)))
        if case is not None:
            cases.append(case)
    return cases


def _fill(rng, deg, case_roots, case_quads, bits=4):
    """Pad with random real roots / complex pairs up to degree `deg`."""
    reals, quads = list(case_roots), list(case_quads)
    while len(reals) + 2 * len(quads) < deg:
        if deg - len(reals) - 2 * len(quads) >= 2 and rng.random() < 0.5:
            quads.append(_random_quad(rng, bits, -2, 1))
        else:
            reals.append(_dyadic(rng, bits, -3, 2))
    return reals, quads


def _gen(rng, count, label, make):
    cases, tries = [], 0
    while len(cases) < count:
        tries += 1
        assert tries < 200 * count, f"cannot build exact {label} cases"
        reals, quads = make(rng)
        case = exact_case(f"{label}#{len(cases)}", reals, quads, sign=rng.choice((-1, 1)))
        # keep |k_n| well above the 1e-14 max|k| degree-drop threshold (tested on its own)
        if case is not None and max(map(abs, case.coef)) <= 1e12 * abs(case.coef[-1]):
            cases.append(case)
    return cases


def gen_cluster(rng, count, gap_exp, size):
    """`size` distinct real roots 2^gap_exp apart (gap 2^-10, 2^-17, 2^-23 ~ 1e-3, 7.6e-6, 1.2e-7)."""
    def make(rng):
        center = _dyadic(rng, 4, -2, 1)
        gap = Fraction(2) ** gap_exp * rng.choice((1, 3))
        roots = [center + k * gap for k in range(size)]
        return _fill(rng, rng.randint(size, 8), roots, [])
    return _gen(rng, count, f"cluster(size={size}, gap=2^{gap_exp})", make)


def gen_multiple(rng, count, mult):
    """An exact double or triple root (plus random other factors)."""
    def make(rng):
        a = _dyadic(rng, 4, -2, 1)
        return _fill(rng, rng.randint(mult, 8), [a] * mult, [])
    return _gen(rng, count, f"multiplicity {mult}", make)


def gen_touching(rng, count, im_exp):
    """(x - a)^2 + 2^(2 im_exp): an extremum at a with value ~ 2^(2 im_exp) (no real root there).

    Where its normwise backward error is below tol_touch/100, `a` must come back as a flagged root.
    """
    def make(rng):
        a = rng.choice((0, 1, 3)) * Fraction(rng.choice((-1, 1)), rng.choice((1, 2, 4, 8)))
        return _fill(rng, rng.randint(2, 8), [], [(-2 * a, a * a + Fraction(2) ** (2 * im_exp))], bits=2)
    cases = _gen(rng, count, f"touching(imag=2^{im_exp})", make)
    for case in cases:
        c = [Fraction(v) for v in case.coef]
        a = -case.quads[0][0] / 2  # the centre of the touching factor
        value = abs(sum(ci * a**i for i, ci in enumerate(c)))
        wscale = max(map(abs, c)) * sum(abs(a) ** i for i in range(len(c)))
        isolated = all(abs(r - a) > Fraction(1, 1024) for r in case.truth)  # else no extremum at a
        if isolated and value <= Fraction(TOL_TOUCH) / 100 * wscale:
            case.touch_points.append(a)
    return cases


def gen_magnitudes(rng, count):
    """Real roots spread over 2^-10 .. 2^10 (~1e-3 .. 1e3)."""
    def make(rng):
        deg = rng.randint(2, 8)
        exps = [rng.randint(-10, 10) for _ in range(deg)]
        return [Fraction(rng.choice((-1, 1)) * rng.choice((1, 3, 5, 7))) * Fraction(2) ** e for e in exps], []
    return _gen(rng, count, "magnitudes", make)


def gen_no_real(rng, count):
    def make(rng):
        return [], [_random_quad(rng, 4) for _ in range(rng.randint(1, 4))]
    return _gen(rng, count, "no real root", make)


def mp_truth_case(coef, label, expect_status=0):
    """Reference real roots by mpmath.polyroots (50 digits) for coefficients that are not exact products."""
    mpmath.mp.dps = 50
    c = [mpmath.mpf(float(v)) for v in coef]
    while c and c[-1] == 0:
        c.pop()
    if len(c) <= 1:
        return Case(coef, [], label, exact=False, expect_status=expect_status)
    zs = mpmath.polyroots(c[::-1], maxsteps=400, extraprec=150)
    reals = sorted(mpmath.re(z) for z in zs if abs(mpmath.im(z)) <= mpmath.mpf(10) ** -25 * max(1, abs(z)))
    distinct = []
    for r in reals:  # a multiple root would come out as a tight group
        if not distinct or abs(r - distinct[-1]) > mpmath.mpf(10) ** -20 * max(1, abs(r)):
            distinct.append(r)
    return Case(coef, distinct, label, exact=False, expect_status=expect_status)


# ------------------------------------------------------------------------------ checks
def _horner(a, x):
    v = mpmath.mpf(0)
    for c in reversed(a):
        v = v * x + c
    return v


def _scale(a, x):
    return sum(abs(c) * abs(x) ** i for i, c in enumerate(a))


def _wscale(a, x):
    """max_i |a_i| * sum_i |x|^i: the normwise scale of the touching test."""
    return max(abs(c) for c in a) * sum(abs(x) ** i for i in range(len(a)))


def radius(a, r, level, normwise=False):
    """4 min_k (level S(r) k!/|p^(k)(r)|)^(1/k): how far a relative coefficient error `level` moves r.

    S(r) = sum |a_i||r|^i (componentwise) or max|a_i| sum |r|^i (normwise, for touching roots).
    """
    s = _wscale(a, r) if normwise else _scale(a, r)
    best = mpmath.inf
    d = a
    for k in range(1, len(a)):
        d = [d[i] * i for i in range(1, len(d))]
        pk = abs(_horner(d, r))
        if pk != 0:
            best = min(best, (level * s * math.factorial(k) / pk) ** (mpmath.mpf(1) / k))
    return 4 * best + 4 * EPS * abs(r) + mpmath.mpf(10) ** -300


def backward_error(a, x):
    """Normwise: the smallest relative change of the coefficients (in max-norm) making x a root."""
    return abs(_horner(a, x)) / _wscale(a, x)


class Reference:
    """Normalised coefficients, truth and radii of a case, computed once (mpmath, MP_DPS digits)."""

    def __init__(self, case: Case, dropped: bool):
        mpmath.mp.dps = MP_DPS
        mx = max(abs(v) for v in case.coef)
        a = [mpmath.mpf(v) / mpmath.mpf(mx) for v in case.coef]
        if dropped:  # the truth of a dropped case is given for the truncated polynomial
            a.pop()
            while a and abs(a[-1]) <= 1e-14:
                a.pop()
        self.a = a
        self.level = 32 * len(a) * EPS  # 32 (deg + 1) eps
        self.truth = [mpmath.mpf(t.numerator) / t.denominator if isinstance(t, Fraction) else t
                      for t in case.truth]
        self.rad_plain = [radius(a, t, self.level) for t in self.truth]
        self._rad_touch = None

    @property
    def rad_touch(self):
        if self._rad_touch is None:
            self._rad_touch = [max(radius(self.a, t, 4 * TOL_TOUCH, normwise=True), rp)
                               for t, rp in zip(self.truth, self.rad_plain, strict=True)]
        return self._rad_touch


def _match(edges, n_right):
    """Maximum bipartite matching size (tiny graphs: augmenting paths)."""
    owner = [-1] * n_right

    def augment(i, seen):
        for j in edges[i]:
            if j not in seen:
                seen.add(j)
                if owner[j] < 0 or augment(owner[j], seen):
                    owner[j] = i
                    return True
        return False

    return sum(augment(i, set()) for i in range(len(edges)))


def check(case: Case, result, who):
    roots, flags, status = result
    ctx = (f"{who} {case.label}: coef={case.coef!r} truth={[float(t) for t in case.truth]} got={roots} "
           f"flags={flags} status={status}")
    n = len(case.coef) - 1
    assert status == case.expect_status, ctx
    assert len(roots) == len(flags) <= max(n, 0), ctx
    assert all(math.isfinite(x) for x in roots), ctx
    assert all(b > a for a, b in zip(roots, roots[1:], strict=False)), ctx
    assert all(f in (0, FLAG_DOUBLE) for f in flags), ctx
    if status & ST_ZERO:
        assert not roots, ctx
        return
    if case.ref is None:
        case.ref = Reference(case, bool(status & ST_DROP))
    ref = case.ref
    mpmath.mp.dps = MP_DPS
    xs = [mpmath.mpf(x) for x in roots]
    edges = []
    for x, f in zip(xs, flags, strict=True):
        rad = ref.rad_touch if f else ref.rad_plain
        edges.append([j for j, t in enumerate(ref.truth) if abs(x - t) <= rad[j]])
    # no true real root is lost: a plain root within rad_plain, or a flagged one within rad_touch
    for j, t in enumerate(ref.truth):
        if not any(j in e for e in edges):
            radii = f"{float(ref.rad_plain[j]):.3g}/{float(ref.rad_touch[j]):.3g}"
            raise AssertionError(f"missed root {float(t)!r} (radius {radii}); {ctx}")
    # no spurious root: near a true root, or a touching root with a tiny backward error (complex pair)
    for x, f, e in zip(xs, flags, edges, strict=True):
        if not e:
            be = backward_error(ref.a, x)
            assert f and be <= TOL_TOUCH * 1.01 + ref.level, \
                f"spurious root {float(x)!r} (backward error {float(be):.3g}); {ctx}"
    # a clearly near-zero extremum is reported as a touching root
    for t in map(float, case.touch_points):
        near = [x for x, f in zip(roots, flags, strict=True) if f and abs(x - t) <= 1e-6 * max(1.0, abs(t))]
        assert near, f"touching point {t!r} not reported; {ctx}"
    # nothing doubled: the roots with a true root nearby map one-to-one onto distinct true roots, apart
    # from touching roots that may stand for a complex pair
    matched = [i for i, e in enumerate(edges) if e]
    size = _match([edges[i] for i in matched], len(ref.truth))
    if size < len(matched):
        spare = [i for i in matched if flags[i] and backward_error(ref.a, xs[i]) <= TOL_TOUCH * 1.01]
        assert size + len(spare) >= len(matched), f"a true root is reported twice; {ctx}"


# ------------------------------------------------------------------------------ suites
def _suite(seed):
    rng = random.Random(seed)
    cases = []
    for gap_exp in (-10, -17, -23):
        cases += gen_cluster(rng, 40, gap_exp, 2)
    cases += gen_cluster(rng, 25, -10, 3)
    cases += gen_cluster(rng, 20, -17, 3)
    cases += gen_cluster(rng, 15, -10, 4)
    cases += gen_multiple(rng, 40, 2)
    cases += gen_multiple(rng, 25, 3)
    cases += gen_touching(rng, 25, -24)  # extremum value ~2^-48: reported as touching (flag)
    cases += gen_touching(rng, 25, -12)  # value ~2^-24 > tol_touch: no root
    cases += gen_magnitudes(rng, 60)
    cases += gen_no_real(rng, 30)
    return cases


@functools.cache
def random_cases():
    return gen_random(random.Random(20240611), 2500)


@functools.cache
def hard_cases():
    return _suite(7)


@functools.cache
def float_cases():
    """Float (non-exact) roots: mpmath reference; random, clustered 1e-7 and 1e-5, magnitudes."""
    rng = random.Random(99)
    out = []
    for i in range(24):
        deg = rng.randint(2, 8)
        roots = [rng.uniform(-2, 2) for _ in range(deg)]
        if i % 3 == 1:
            roots[1] = roots[0] + 1e-7
        elif i % 3 == 2:
            roots[1] = roots[0] + 1e-5
            roots[-1] = 10 ** rng.uniform(-3, 3)
        c = [1.0]
        for r in roots:
            c = [0.0] + c
            for k in range(len(c) - 1):
                c[k] -= r * c[k + 1]
        out.append(mp_truth_case(c, f"float#{i}"))
    return out


def test_random_exact_roots_c(clib):
    for case in random_cases():
        check(case, c_roots(clib, case.coef), "C")


def test_random_exact_roots_python():
    for case in random_cases()[:1200]:
        check(case, py_roots(case.coef), "Python")


@pytest.mark.parametrize("impl", ["C", "Python"])
def test_clustered_multiple_touching_magnitudes(clib, impl):
    for case in hard_cases():
        check(case, c_roots(clib, case.coef) if impl == "C" else py_roots(case.coef), impl)


def test_touching_extremum_is_flagged(clib):
    """A near-zero extremum (complex pair 2^-24 off the axis) is one root flagged double, at the extremum."""
    rng = random.Random(5)
    cases = gen_touching(rng, 20, -24)
    assert sum(bool(case.touch_points) for case in cases) >= 15
    assert any(case.touch_points == [0] for case in cases)  # at x = 0, where k0 is tiny too
    for case in cases:
        check(case, c_roots(clib, case.coef), "C")
        check(case, py_roots(case.coef), "Python")
    # exact double and triple root at 3/8 (times a positive quadratic): one root each, doubles flagged
    for mult, flag in ((2, FLAG_DOUBLE), (3, 0), (4, FLAG_DOUBLE)):
        case = exact_case("mult", [Fraction(3, 8)] * mult, [(Fraction(1), Fraction(5, 4))])
        for res in (c_roots(clib, case.coef), py_roots(case.coef)):
            assert len(res[0]) == 1 and res[1] == [flag], (mult, res)
            assert abs(res[0][0] - 0.375) < 1e-4, (mult, res)


def test_near_double_pair_resolved_or_flagged(clib):
    """Two real roots 2^-23 (~1.2e-7) apart: two roots, or one flagged double between them."""
    for center in (Fraction(3, 8), Fraction(-5, 4), Fraction(13, 16)):
        gap = Fraction(1, 2**23)
        case = exact_case("pair", [center, center + gap, Fraction(-2), Fraction(3, 2)], [(1, Fraction(9, 8))])
        for res in (c_roots(clib, case.coef), py_roots(case.coef)):
            near = [(x, f) for x, f in zip(res[0], res[1], strict=True) if abs(x - float(center)) < 1e-5]
            assert len(near) == 2 or (len(near) == 1 and near[0][1] == FLAG_DOUBLE), res
            assert len(res[0]) == len(near) + 2, res


def test_a_search_landing_next_to_a_critical_point_goes_on_to_the_root(clib):
    """The underactuated wrist's eliminant at fuzz seed 20: at its degree-5 level the first Halley step landed
    next to an extremum of the derivative (p' ~ -0.01, p = -46), where the next step is tiny for its curvature
    term; the ratio of the two steps predicted convergence, the search stopped 0.66 from its root and the levels
    above lost two roots of the eliminant (two assembly modes). All six real roots (numpy's companion eigenvalues,
    each a sign change of p checked here in exact arithmetic), C and Python bit for bit."""
    coef = [-0.00023888917989762755, -0.011855567557413522, 0.06829027477980376, 1.1478972256751352,
            -0.5404710226692486, -0.18555360768068818, -0.942294490649326, -0.21062696277960347, 0.3662586769457714]
    c, py = c_roots(clib, coef), py_roots(coef)
    assert c == py or not _gcc_x86_64()
    expected = sorted(r.real for r in np.roots(coef[::-1]) if abs(r.imag) < 1e-12)
    assert len(expected) == 6 and len(py[0]) == 6 and not any(py[1])
    for x, e in zip(py[0], expected, strict=True):
        assert abs(x - e) <= 1e-12
        lo, hi = Fraction(x - 1e-9), Fraction(x + 1e-9)
        value = [sum(Fraction(k) * t**i for i, k in enumerate(coef)) for t in (lo, hi)]
        assert value[0] * value[1] < 0  # a root of the polynomial as given lies within 1e-9


@pytest.mark.parametrize("impl", ["C", "Python"])
def test_float_coefficients_against_mpmath(clib, impl):
    for case in float_cases():
        check(case, c_roots(clib, case.coef) if impl == "C" else py_roots(case.coef), impl)


def test_degree_drop(clib):
    """|k8| <= 1e-14 max|k|: dropped (status DEGREE_DROP), roots of the degree-7 part; above: kept."""
    rng = random.Random(11)
    base = [c for c in gen_random(rng, 400) if len(c.coef) == 8][:20]
    assert base
    for case in base:
        mx = max(abs(v) for v in case.coef)
        dropped = Case(case.coef + [mx * 2.0**-50], [Fraction(t) for t in case.truth],
                       case.label + " +tiny k8", expect_status=ST_DROP)
        check(dropped, c_roots(clib, dropped.coef), "C")
        check(dropped, py_roots(dropped.coef), "Python")
        kept = mp_truth_case(case.coef + [mx * 2.0**-40], case.label + " +small k8")
        check(kept, c_roots(clib, kept.coef), "C")
        check(kept, py_roots(kept.coef), "Python")
        assert max(map(abs, c_roots(clib, kept.coef)[0])) > 1e6  # the far root ~ -k7/k8 is found too
    # both leading coefficients tiny: degree 8 -> 6
    case = exact_case("d6", [Fraction(1, 2), Fraction(-3, 4)], [(1, 1), (0, Fraction(1, 4))])
    coef = case.coef + [1e-16, -1e-17]
    res = c_roots(clib, coef)
    assert res[2] == ST_DROP and res[0] == pytest.approx([-0.75, 0.5], rel=1e-14), res
    pres = py_roots(coef)
    assert pres[2] == ST_DROP and pres[0] == pytest.approx([-0.75, 0.5], rel=1e-14), pres


def test_special_inputs(clib):
    for impl in ("C", "Python"):
        def run(coef, n=None, impl=impl):
            return c_roots(clib, coef, n) if impl == "C" else py_roots(coef if n is None else coef[: n + 1])

        assert run([0.0] * 9) == ([], [], ST_ZERO)
        assert run([0.0]) == ([], [], ST_ZERO)
        assert run([2.5]) == ([], [], 0)  # nonzero constant: no root
        assert run([0.0, 0.0, 3.0]) == ([0.0], [FLAG_DOUBLE], 0)  # 3 x^2
        assert run([0.0, 0.0, 0.0, -1.0]) == ([0.0], [0], 0)  # -x^3
        assert run([-6.0, 2.0]) == ([3.0], [0], 0)
        assert run([1.0, 0.0, 1.0]) == ([], [], 0)  # x^2 + 1
        assert run([1.0, 1e-15]) == ([], [], ST_DROP)  # degree 1 -> 0
        assert run([float("nan"), 1.0])[2] == ST_BAD
        assert run([1.0, float("inf")])[2] == ST_BAD
        r, f, s = run([-1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0])  # x^8 - 1
        assert s == 0 and f == [0, 0] and r == pytest.approx([-1.0, 1.0], rel=1e-15)
        r, f, s = run([2e300, -3e300, 1e300])  # huge coefficients: roots 1, 2
        assert s == 0 and r == pytest.approx([1.0, 2.0], rel=1e-15)
        r, f, s = run([2e-300, -3e-300, 1e-300])  # tiny coefficients
        assert s == 0 and r == pytest.approx([1.0, 2.0], rel=1e-15)
        r, f, s = run([1.0, -8.0, 28.0, -56.0, 70.0, -56.0, 28.0, -8.0, 1.0])  # (x - 1)^8: one double root
        assert s == 0 and f == [FLAG_DOUBLE] and abs(r[0] - 1.0) < 0.05
    for n in (-1, 9):
        assert c_roots(clib, [1.0] * 10, n)[2] == ST_BAD
    assert py_roots([1.0] * 10)[2] == ST_BAD and py_roots([])[2] == ST_BAD


def test_tol_touch_parameter(clib):
    """A larger tol_touch turns a shallow extremum (value ~2^-24) into a touching root."""
    case = exact_case("t", [], [(-Fraction(3, 4), Fraction(9, 64) + Fraction(1, 2**24)), (1, 2)])
    assert c_roots(clib, case.coef)[0] == [] and py_roots(case.coef)[0] == []
    for res in (c_roots(clib, case.coef, tol_touch=1e-6), py_roots(case.coef, tol_touch=1e-6)):
        # the extremum of the product sits ~2e-8 from 3/8
        assert res[1] == [FLAG_DOUBLE] and res[0][0] == pytest.approx(0.375, abs=1e-6), res


@functools.cache
def coefficient_vectors():
    """Arbitrary coefficient vectors (not built from roots): (mode, coefficients)."""
    rng = random.Random(3)
    out = []
    for t in range(3000):
        n = rng.randint(1, 8)
        mode = t % 4
        if mode == 0:
            coef = [rng.choice((-1, 1)) * 10 ** rng.uniform(-300, 300) for _ in range(n + 1)]
        elif mode == 1:
            coef = [rng.gauss(0, 1) * 10 ** rng.uniform(-20, 20) for _ in range(n + 1)]
        elif mode == 2:
            pool = (0.0, 1.0, -1.0, 1e-300, 1e300, 5e-324, rng.gauss(0, 1))
            coef = [rng.choice(pool) for _ in range(n + 1)]
        else:
            coef = [rng.gauss(0, 1) for _ in range(n + 1)]
        out.append((mode, coef))
    return out


def test_random_coefficients_backward_error(clib):
    """Arbitrary coefficient vectors, including 1e+-20 and 1e+-300 magnitudes, zeros and subnormals:
    every returned root has a tiny normwise backward error (componentwise too, where normalising by
    max|k| does not underflow), nothing is NaN, no search hits its cap."""
    for mode, coef in coefficient_vectors():
        n = len(coef) - 1
        res = c_roots(clib, coef)
        roots, flags, status = res
        ctx = (mode, coef, res)
        assert py_roots(coef) == res or not _gcc_x86_64(), ctx
        assert not status & (ST_MAXIT | ST_BAD) and len(roots) <= n, ctx
        assert all(math.isfinite(x) for x in roots), ctx
        assert all(b > a for a, b in zip(roots, roots[1:], strict=False)), ctx
        mx = max(map(abs, coef))
        k = len(coef)
        while k > 1 and abs(coef[k - 1]) <= 1e-14 * mx:
            k -= 1
        c = [Fraction(v) for v in coef[:k]]
        for x, f in zip(roots, flags, strict=True):
            fx = Fraction(x)
            val = abs(sum(ci * fx**i for i, ci in enumerate(c)))
            normwise = val / (max(map(abs, c)) * sum(abs(fx) ** i for i in range(len(c))))
            assert normwise <= (1.01 * TOL_TOUCH if f else 1e-14), ctx
            if mode in (1, 3) and not f:
                assert val <= 64 * k * EPS * sum(abs(ci) * abs(fx) ** i for i, ci in enumerate(c)), ctx


@functools.cache
def _gcc_x86_64() -> bool:
    try:
        out = subprocess.run([cbuild.compiler(), "--version"], capture_output=True, text=True).stdout
    except OSError:
        return False
    return platform.machine() in ("x86_64", "AMD64") and "Free Software Foundation" in out


@pytest.mark.skipif(not _gcc_x86_64(),
                    reason="bit-identical C/Python needs no FMA contraction (gcc -std=c99 on x86-64)")
def test_c_and_python_agree_bitwise(clib):
    for case in random_cases()[:1200] + hard_cases():
        assert c_roots(clib, case.coef) == tuple(py_roots(case.coef)), case.label


# ------------------------------------------------------------------------------ sanitizers
def _sanitizer_available() -> str | None:
    with tempfile.TemporaryDirectory() as tmp:
        src = Path(tmp) / "t.c"
        src.write_text("#include <stdio.h>\nint main(void){ puts(\"ok\"); return 0; }\n")
        exe = Path(tmp) / "t"
        try:
            r = subprocess.run([cbuild.compiler(), *cbuild.SANITIZE_FLAGS, "-o", str(exe), str(src)],
                               capture_output=True, text=True)
        except (OSError, RuntimeError) as exc:
            return f"no C compiler: {exc}"
        if r.returncode != 0:
            return f"the compiler cannot build with -fsanitize=address,undefined: {r.stderr.strip()[:200]}"
        r = subprocess.run([str(exe)], capture_output=True, text=True)
        if r.returncode != 0 or r.stdout.strip() != "ok":
            return f"sanitizer runtime does not run here: {r.stderr.strip()[:200]}"
    return None


def test_sanitizers_asan_ubsan(clib):
    reason = _sanitizer_available()
    if reason:
        pytest.skip(reason)
    exe = cbuild.compile_executable([HARNESS], [], name="poly_roots_sanitize",
                                    extra_flags=[*cbuild.SANITIZE_FLAGS, "-DWK_POLY_HARNESS_MAIN"])
    env = dict(os.environ, ASAN_OPTIONS="detect_leaks=0:abort_on_error=0",
               UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1")
    # built-in LCG cases (random, clustered, double roots) and special inputs
    r = subprocess.run([str(exe)], capture_output=True, text=True, env=env, timeout=300)
    assert r.returncode == 0, r.stderr[-3000:]
    # the test suites' polynomials: same results as the -O2 shared library, bit for bit
    cases = [case.coef for case in random_cases() + hard_cases() + float_cases()]
    cases += [coef for _, coef in coefficient_vectors()]
    with tempfile.NamedTemporaryFile("w", suffix=".txt", delete=False) as fh:
        for coef in cases:
            fh.write(f"{len(coef) - 1} " + " ".join(repr(v) for v in coef) + "\n")
        path = fh.name
    try:
        r = subprocess.run([str(exe), path], capture_output=True, text=True, env=env, timeout=300)
    finally:
        os.unlink(path)
    assert r.returncode == 0, r.stderr[-3000:]
    lines = r.stdout.splitlines()
    assert len(lines) == len(cases)
    for coef, line in zip(cases, lines, strict=True):
        tok = line.split()
        cnt, status = int(tok[0]), int(tok[1])
        got = ([float.fromhex(t) for t in tok[2::2]], [int(t) for t in tok[3::2]], status)
        assert cnt == len(got[0])
        assert got == c_roots(clib, coef), coef
