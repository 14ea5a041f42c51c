"""Every real root of a real polynomial of degree <= 8: the source that generated Python modules inline (from the
marker line on; derive/runtime_files.py), linted and tested here as it is (tests/test_poly_real_roots.py)."""

# wristkin: inlined from here
# ---------------------------------------------------------------------------
# Every real root of a real polynomial of degree <= 8 (pure Python, math only).
#
# Same algorithm, constants and operation order as wk_poly_real_roots in
# runtime/c/poly_real_roots.c (see the comment there):
# normalise by max|k|, drop leading |k_i| <= 1e-14 max|k| (status DEGREE_DROP),
# deflate exact x^m factors, Fujiwara bound rounded up to a power of two,
# then derivative recursion: the roots of p^(k+1) split [-B, B] into monotone
# pieces of p^(k); critical points whose value is below the evaluation error
# bound are roots (DOUBLE when the sign does not change), near-zero extrema
# within tol_touch (normwise: |p| <= tol max|a_i| sum |x|^i) are touching roots
# (DOUBLE), and each sign-changing piece is solved by safeguarded
# Halley/Newton/bisection.
# The imports are local so that this partial can be included anywhere in a module.
# ---------------------------------------------------------------------------

_POLY_MAXDEG = 8
_POLY_FLAG_DOUBLE = 1
_POLY_STATUS_OK = 0
_POLY_STATUS_DEGREE_DROP = 1  # leading coefficient(s) treated as zero
_POLY_STATUS_ZERO = 2  # identically zero polynomial: no roots reported
_POLY_STATUS_BAD_INPUT = 4  # degree outside 0..8 or a non-finite coefficient
_POLY_STATUS_MAXITER = 8  # a root search hit the iteration cap (root still bracketed)
_POLY_TOL_TOUCH = 1e-12
_POLY_TOL_INNER = 1e-9  # touch tolerance on inner levels: only adds harmless splits
_POLY_TOL_LEAD = 1e-14
_POLY_EPS = 2.220446049250313e-16
_POLY_DMAX = 1.7976931348623157e308
_POLY_TINY = 1e-300
_POLY_MAXIT = 100


def _poly_eval(a, m, x):
    v = a[m]
    for i in range(m - 1, -1, -1):
        v = v * x + a[i]
    return v


def _poly_eval_scale(a, m, x):
    """p(x), the error scale S(x) = sum |a_i| |x|^i and W(x) = sum |x|^i."""
    v = a[m]
    s = abs(a[m])
    w = 1.0
    ax = abs(x)
    for i in range(m - 1, -1, -1):
        v = v * x + a[i]
        s = s * ax + abs(a[i])
        w = w * ax + 1.0
    return v, s, w


def _poly_eval3(a, da, dda, m, x):
    """p, p', p'' and the error scale S at x (m >= 2)."""
    v = a[m]
    d = da[m - 1]
    dd = dda[m - 2]
    s = abs(a[m])
    ax = abs(x)
    for i in range(m - 1, 1, -1):
        v = v * x + a[i]
        s = s * ax + abs(a[i])
        d = d * x + da[i - 1]
        dd = dd * x + dda[i - 2]
    v = v * x + a[1]
    s = s * ax + abs(a[1])
    d = d * x + da[0]
    return v * x + a[0], d, dd, s * ax + abs(a[0])


def _poly_split(lo, hi):
    """Bisection point: the midpoint, unless the ends differ in magnitude by more than 2^8; then the power
    of two halfway in exponent on the side of the larger end (a root near 0 takes ~log2(1100) steps)."""
    import math

    amin, amax, big = abs(lo), abs(hi), hi
    if amin > amax:
        amin, amax, big = amax, amin, lo
    emax = math.frexp(amax)[1]
    emin = math.frexp(amin)[1] if amin > 0.0 else -1074
    if emax - emin <= 8:
        return lo + 0.5 * (hi - lo)
    e = emax + emin
    e = e // 2 if e >= 0 else -((-e) // 2)
    t = math.ldexp(1.0, e)
    return -t if big < 0.0 else t


def _poly_search(a, da, dda, m, lo, hi, x, dx, tol_z):
    """Bracketed root search, p(lo) < 0 < p(hi) (lo may exceed hi), from x. -> (root, p'(root), hit_cap).

    Each iteration: the Halley step 2 f f' / (2 f'^2 - f f'') (Newton when that denominator is not
    positive) is kept when strictly inside the bracket and, if the previous step was one too, at least
    halving it (quartering after 12 steps); else bisection (so at least every other step halves the
    bracket).  Done when |p(x)| <= tol_z*S(x) (rounding noise), when the step is at the ulp level, when
    two successive steps dxp, dxn predict an error below one ulp ((dxn/dxp)^3 |dxn| after two Halley
    steps, else (dxn/dxp)^2 |dxn|) and the step did not cancel most of x, or after _POLY_MAXIT steps;
    the prediction only after a Newton-like step (Halley's denominator at most 4 p'^2).
    (The C version runs the searches of a level in lockstep; each search does exactly the same
    arithmetic.)
    """
    dxp = 0.0
    hal_prev = 0
    df = 0.0
    it = 0
    while True:
        f, df, ddf, sc = _poly_eval3(a, da, dda, m, x)
        it += 1
        if f == 0.0:
            return x, df, False
        if f < 0.0:
            lo = x
        else:
            hi = x
        xn = lo
        dxn = 0.0
        hal = 0
        newton = True
        if df != 0.0:
            den = 2.0 * df * df - f * ddf
            if den > 0.0:
                dxn = 2.0 * f * df / den
                hal = 1
                newton = den <= 4.0 * df * df
            else:
                dxn = f / df  # may be +-inf (float division overflows to inf): then not inside
            xn = x - dxn
        inside = lo < xn < hi or hi < xn < lo
        if abs(f) <= tol_z * sc or (df != 0.0 and abs(dxn) <= 2.0 * _POLY_EPS * abs(x) + _POLY_TINY):
            return (xn if inside else x), df, False
        if inside and (dxp == 0.0 or abs((4.0 if it > 12 else 2.0) * dxn) <= abs(dx)):
            r = dxn / dxp if dxp != 0.0 else 1.0  # may be inf: then no stop
            pred = r * r * abs(r) * abs(dxn) if (hal and hal_prev) else r * r * abs(dxn)
            dx = dxn
            dxp = dxn
            hal_prev = hal
            x_old = x
            x = xn
            # (not after a step that cancelled most of x: xn then carries the rounding error of x)
            # only after a step Newton's to within a factor 2 (Halley's 2 f'^2 / den >= 1/2): landed next to a
            # critical point of p (f' ~ 0, f not small), Halley's step is tiny for its curvature term, not for
            # convergence, and the ratio of steps predicts nothing (a degree-5 level stopped at p = -46 next to p's
            # extremum, 0.66 from its root, and the uw FK lost two assembly modes: fuzz seeds 20 and 917)
            if pred <= _POLY_EPS * abs(xn) + _POLY_TINY and abs(xn) >= 0.5 * abs(x_old) and newton:
                return x, df, False
        else:
            dxp = 0.0
            hal_prev = 0
            dx = 0.5 * (hi - lo)
            xn = _poly_split(lo, hi)
            x = xn
            if xn == lo or xn == hi or abs(dx) <= 2.0 * _POLY_EPS * abs(xn) + _POLY_TINY:
                return x, df, False
        if it >= _POLY_MAXIT:
            return x, df, True


def _poly_sign(v):
    return (v > 0.0) - (v < 0.0)


def _poly_level(a, da, dda, m, part, curv, bound, nrm, tol_t, tol_z):
    """Roots of a (degree m >= 2; da, dda: p', p'') given the sorted roots `part` of da and p'' there.

    -> (list of (root, p'(root), flag), hit_cap)
    """
    import math

    np_ = len(part)
    last = np_ + 1
    lead = _poly_sign(a[m])
    s0 = -lead if m % 2 else lead  # exact: no root outside (-bound, bound)
    x = [-bound] + list(part) + [bound]
    v = [0.0] * (np_ + 2)
    sc = [0.0] * (np_ + 2)
    ws = [0.0] * (np_ + 2)
    s = [0] * (np_ + 2)
    s[0] = s0
    s[last] = lead
    # |p| grows monotonically outwards from the outermost critical points: only the signs matter
    v[0] = s0 * _POLY_DMAX
    v[last] = lead * _POLY_DMAX
    for j in range(1, np_ + 1):
        v[j], sc[j], ws[j] = _poly_eval_scale(a, m, x[j])
        s[j] = 0 if abs(v[j]) <= tol_z * sc[j] else _poly_sign(v[j])
    items = []  # ascending: (x, p'(x), flag), each fixed root or search result
    hit = False
    j = 0
    while j <= np_:
        if s[j] == 0:
            # run of unresolved critical points: one root at the most zero-like
            j2 = j
            best = j
            while s[j2 + 1] == 0:
                j2 += 1
                if abs(v[j2]) * sc[best] < abs(v[best]) * sc[j2]:
                    best = j2
            flag = _POLY_FLAG_DOUBLE if s[j - 1] == s[j2 + 1] else 0
            items.append((x[best], _poly_eval(da, m - 1, x[best]), flag))
            j = j2 + 1
            continue
        if (
            j >= 1
            and s[j - 1] == s[j]
            and s[j + 1] == s[j]
            and abs(v[j]) <= tol_t * nrm * ws[j]
            and abs(v[j]) <= abs(v[j - 1])
            and abs(v[j]) <= abs(v[j + 1])
        ):
            items.append((x[j], _poly_eval(da, m - 1, x[j]), _POLY_FLAG_DOUBLE))
        if s[j] * s[j + 1] < 0:
            # start from the quadratic model p(c) + p''(c)/2 t^2 at the nearer critical end
            tb = _POLY_DMAX
            x0 = 0.5 * (x[j] + x[j + 1])
            if j >= 1 and curv[j - 1] != 0.0:
                tb = math.sqrt(2.0 * abs(v[j]) / abs(curv[j - 1]))
                x0 = x[j] + tb
            if j + 1 <= np_ and curv[j] != 0.0:
                t = math.sqrt(2.0 * abs(v[j + 1]) / abs(curv[j]))
                if t < tb:
                    x0 = x[j + 1] - t
            if not x[j] < x0 < x[j + 1]:
                x0 = 0.5 * (x[j] + x[j + 1])
            lo, hi = (x[j], x[j + 1]) if s[j] < 0 else (x[j + 1], x[j])
            r, d, h = _poly_search(a, da, dda, m, lo, hi, x0, x[j + 1] - x[j], tol_z)
            hit = hit or h
            items.append((r, d, 0))
        j += 1
    out = []
    for it in items:
        if len(out) >= _POLY_MAXDEG:
            break
        if out and not it[0] > out[-1][0]:
            continue  # keep strictly increasing
        out.append(it)
    return out, hit


def _poly_real_roots(coef, tol_touch=_POLY_TOL_TOUCH):
    """Real roots of sum coef[i] x^i (degree len(coef)-1 <= 8). -> (roots ascending, flags, status).

    flags[i] & _POLY_FLAG_DOUBLE: touching / unresolved double root.  status: bit set of _POLY_STATUS_*.
    """
    import math

    n = len(coef) - 1
    if n < 0 or n > _POLY_MAXDEG:
        return [], [], _POLY_STATUS_BAD_INPUT
    c = [float(k) for k in coef]
    mx = 0.0
    for k in c:
        if not abs(k) <= _POLY_DMAX:
            return [], [], _POLY_STATUS_BAD_INPUT
        if abs(k) > mx:
            mx = abs(k)
    if mx == 0.0:
        return [], [], _POLY_STATUS_ZERO
    st = _POLY_STATUS_OK
    ne = n
    while ne > 0 and abs(c[ne]) <= _POLY_TOL_LEAD * mx:
        ne -= 1
    if ne < n:
        st |= _POLY_STATUS_DEGREE_DROP
    m0 = 0
    while c[m0] == 0.0:
        m0 += 1
    deg = ne - m0
    a = [c[i + m0] / mx for i in range(deg + 1)]
    out = []
    if deg == 1:
        out = [(-a[0] / a[1], 0.0, 0)]
    elif deg >= 2:
        emax = -1100
        for k in range(1, deg + 1):
            r = abs(a[deg - k] / a[deg])
            if k == deg:
                r *= 0.5
            if r == 0.0:
                continue
            e = math.frexp(r)[1]
            q = (e + k - 1) // k if e >= 0 else -((-e) // k)
            emax = max(emax, q)
        bound = math.ldexp(1.0, emax + 1)
        d = [a]
        for k in range(1, deg + 1):
            prev = d[k - 1]
            d.append([prev[i + 1] * float(i + 1) for i in range(deg - k + 1)])
        tol_z = 2.0 * float(deg + 1) * _POLY_EPS
        lin = d[deg - 1]
        p0 = min(max(-lin[0] / lin[1], -bound), bound)
        part = [p0]
        curv = [lin[1]]
        for k in range(deg - 2, -1, -1):
            nrm = 0.0
            for c_ in d[k]:
                if abs(c_) > nrm:
                    nrm = abs(c_)
            out, hit = _poly_level(
                d[k],
                d[k + 1],
                d[k + 2],
                deg - k,
                part,
                curv,
                bound,
                nrm,
                tol_touch if k == 0 else _POLY_TOL_INNER,
                tol_z,
            )
            if hit:
                st |= _POLY_STATUS_MAXITER
            part = [o[0] for o in out]
            curv = [o[1] for o in out]
    roots = [o[0] for o in out]
    flags = [o[2] for o in out]
    if m0 > 0 and 0.0 not in roots:
        i = 0
        while i < len(roots) and roots[i] < 0.0:
            i += 1
        roots.insert(i, 0.0)
        flags.insert(i, _POLY_FLAG_DOUBLE if m0 % 2 == 0 else 0)
    return roots, flags, st
