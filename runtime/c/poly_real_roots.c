/* ------------------------------------------------------------------------
 * wk_poly: every real root of a real polynomial of degree <= 8.
 *
 * Included verbatim into generated C99 sources (no Jinja in this file).
 * Needs only <math.h>; no allocation, no VLAs, fixed-size stack arrays.
 *
 * Algorithm (mirrored exactly by _poly_real_roots in runtime/python/poly_real_roots.py):
 *   1. Reject non-finite input / n outside 0..8 (status BAD_INPUT).
 *      All-zero input -> status ZERO, no roots.
 *   2. Normalise by max|k_i|; drop leading coefficients with
 *      |k_i| <= 1e-14 max|k| (status DEGREE_DROP); deflate exact zero
 *      trailing coefficients (x^m factor -> root 0, flagged DOUBLE if m even).
 *   3. Root bound B: Fujiwara's bound rounded up to a power of two
 *      (frexp/ldexp only).  By Gauss-Lucas it bounds every derivative too.
 *   4. Derivative recursion: the roots of p^(k+1) (found first; the linear
 *      p^(deg-1) in closed form) split [-B, B] into pieces on which p^(k)
 *      is monotone.  At each such critical point c the value v = p^(k)(c)
 *      and the Horner error scale S(c) = sum |a_i| |c|^i are computed:
 *        - |v| <= tol_z*S (tol_z = 2(deg+1) eps, the rounding-error bound
 *          of the evaluation): the sign is not trustworthy, c is a root
 *          (a run of such neighbouring points is one root); flagged
 *          DOUBLE when the signs on both sides agree (even multiplicity);
 *        - extremum (same sign on both sides, |v| a local minimum of |p|)
 *          with |v| <= tol * max_i|a_i| * sum_i |c|^i (normwise backward
 *          error: a perturbation of the coefficients by tol relative to the
 *          largest one makes c a root): touching root at c, flagged DOUBLE
 *          (tol = tol_touch at level 0, 1e-9 for inner levels, where the
 *          extra point is only a harmless extra split).  Normwise, not
 *          sum |a_i||c|^i: a coefficient that is small through cancellation
 *          (say k0 for a double root near x = 0) carries an error of the
 *          size of the others, and the componentwise scale would miss it;
 *        - each piece whose end signs differ holds exactly one root:
 *          safeguarded Halley (see wk_poly_step: Halley/Newton steps kept
 *          only inside the bracket and while they shrink, else bisection,
 *          in exponent when the ends differ by > 2^8 in magnitude), started
 *          from the quadratic model p(c) + p''(c)/2 t^2 at the nearer
 *          critical end, stopped at the rounding-noise level or when the
 *          convergence rate predicts an error below one ulp.  All searches
 *          of one level run in lockstep with batched evaluations
 *          (independent Horner chains overlap in the CPU); each search does
 *          exactly the arithmetic of the Python version, which runs them
 *          one after the other.
 *   Roots are produced in ascending order and are strictly increasing.
 *
 * Result: number of roots (<= degree); roots[0..r-1] ascending; flags[i]
 * has WK_POLY_FLAG_DOUBLE when the root is a touching / unresolved double
 * root; *status is a bit set of WK_POLY_STATUS_*.
 * ------------------------------------------------------------------------ */
#ifndef WK_POLY_REAL_ROOTS_INCLUDED
#define WK_POLY_REAL_ROOTS_INCLUDED

#include <math.h>

#define WK_POLY_MAXDEG 8
#define WK_POLY_FLAG_DOUBLE 1u
#define WK_POLY_STATUS_OK 0
#define WK_POLY_STATUS_DEGREE_DROP 1 /* leading coefficient(s) treated as zero */
#define WK_POLY_STATUS_ZERO 2        /* identically zero polynomial: no roots reported */
#define WK_POLY_STATUS_BAD_INPUT 4   /* n outside 0..8 or a non-finite coefficient */
#define WK_POLY_STATUS_MAXITER 8     /* a root search hit the iteration cap (root still bracketed) */
#ifndef WK_POLY_TOL_TOUCH
#define WK_POLY_TOL_TOUCH 1e-12 /* |p(x_e)| <= tol * max|k_i| * sum |x_e|^i  => touching root */
#endif
#define WK_POLY_TOL_INNER 1e-9 /* touch tolerance on inner levels: only adds harmless splits */
#define WK_POLY_TOL_LEAD 1e-14
#define WK_POLY_EPS 2.220446049250313e-16
#define WK_POLY_DMAX 1.7976931348623157e308
#define WK_POLY_TINY 1e-300
#define WK_POLY_MAXIT 100

/* p(x) by Horner, a[0..m] ascending. */
static double wk_poly_eval(const double *a, int m, double x)
{
    double v = a[m];
    int i;
    for (i = m - 1; i >= 0; --i) v = v * x + a[i];
    return v;
}

/* p(x), the error scale S(x) = sum |a_i| |x|^i and W(x) = sum |x|^i. */
static double wk_poly_eval_scale(const double *a, int m, double x, double *scale, double *wsum)
{
    double v = a[m], s = fabs(a[m]), w = 1.0, ax = fabs(x);
    int i;
    for (i = m - 1; i >= 0; --i) {
        v = v * x + a[i];
        s = s * ax + fabs(a[i]);
        w = w * ax + 1.0;
    }
    *scale = s;
    *wsum = w;
    return v;
}

/* p, p', p'' and S = sum |a_i| |x|^i at the points x[0..nb-1] (m >= 2; da,
 * dda: coefficients of p', p'').  The loop over points is innermost, so the
 * nb independent Horner chains overlap instead of waiting on each other. */
static void wk_poly_eval3(const double *a, const double *da, const double *dda, int m, const double *x, int nb,
                          double *f, double *df, double *ddf, double *sc)
{
    int i, b;
    if (nb == 1) {
        double v = a[m], s = fabs(a[m]), d = da[m - 1], dd = dda[m - 2], x0 = x[0], ax = fabs(x0);
        for (i = m - 1; i >= 2; --i) {
            v = v * x0 + a[i];
            s = s * ax + fabs(a[i]);
            d = d * x0 + da[i - 1];
            dd = dd * x0 + dda[i - 2];
        }
        v = v * x0 + a[1];
        s = s * ax + fabs(a[1]);
        d = d * x0 + da[0];
        f[0] = v * x0 + a[0];
        sc[0] = s * ax + fabs(a[0]);
        df[0] = d;
        ddf[0] = dd;
        return;
    }
    for (b = 0; b < nb; ++b) {
        f[b] = a[m];
        sc[b] = fabs(a[m]);
        df[b] = da[m - 1];
        ddf[b] = dda[m - 2];
    }
    for (i = m - 1; i >= 2; --i) {
        for (b = 0; b < nb; ++b) {
            f[b] = f[b] * x[b] + a[i];
            sc[b] = sc[b] * fabs(x[b]) + fabs(a[i]);
            df[b] = df[b] * x[b] + da[i - 1];
            ddf[b] = ddf[b] * x[b] + dda[i - 2];
        }
    }
    for (b = 0; b < nb; ++b) {
        f[b] = f[b] * x[b] + a[1];
        sc[b] = sc[b] * fabs(x[b]) + fabs(a[1]);
        df[b] = df[b] * x[b] + da[0];
        f[b] = f[b] * x[b] + a[0];
        sc[b] = sc[b] * fabs(x[b]) + fabs(a[0]);
    }
}

/* Bisection point of the bracket (lo, hi): the midpoint, unless the ends
 * differ in magnitude by more than a factor 2^8; then the power of two halfway
 * between them in exponent, on the side of the larger end (a root near 0 is
 * then reached in ~log2(1100) steps rather than ~1100). */
static double wk_poly_split(double lo, double hi)
{
    double amin = fabs(lo), amax = fabs(hi), big = hi, t;
    int emin = -1074, emax, e;
    if (amin > amax) {
        t = amin;
        amin = amax;
        amax = t;
        big = lo;
    }
    (void)frexp(amax, &emax);
    if (amin > 0.0) (void)frexp(amin, &emin);
    if (emax - emin <= 8) return lo + 0.5 * (hi - lo);
    e = emax + emin;
    e = (e >= 0) ? e / 2 : -((-e) / 2);
    t = ldexp(1.0, e);
    return (big < 0.0) ? -t : t;
}

/* State of one bracketed root search: p(lo) < 0 < p(hi) (lo may exceed hi). */
typedef struct {
    double lo, hi, x, dx, dxp, df;
    int it, hal, done;
} wk_poly_job;

/* One iteration of the safeguarded Halley/Newton/bisection search, given
 * f, df, ddf = p, p', p'' and sc = S at J->x.
 * The Halley step 2 f f' / (2 f'^2 - f f'') (Newton when that denominator is
 * not positive) is kept when it stays strictly inside the bracket and, if the
 * previous step was one too, at least halves it (quarters it after 12 steps:
 * no endless linear convergence); otherwise bisection (so at least every
 * other step halves the bracket).  Done when |p(x)| is
 * within the rounding error bound tol_z*S(x), when the step is at the ulp
 * level (the last step is taken when inside), when two successive steps
 * dxp, dxn predict an error below one ulp after dxn ((dxn/dxp)^3 |dxn| after
 * two Halley steps, else (dxn/dxp)^2 |dxn|) and the step did not cancel most
 * of x, or after WK_POLY_MAXIT steps; the prediction only after a
 * Newton-like step (Halley's denominator at most 4 p'^2). */
static void wk_poly_step(wk_poly_job *J, double f, double df, double ddf, double sc, double tol_z, int *maxit)
{
    double den, dxn, xn, r, pred, x = J->x;
    int inside, newton = 1, hal = 0;
    J->df = df;
    J->it += 1;
    if (f == 0.0) {
        J->done = 1;
        return;
    }
    if (f < 0.0) J->lo = x; else J->hi = x;
    xn = J->lo; /* sentinel: not strictly inside */
    dxn = 0.0;
    if (df != 0.0) {
        den = 2.0 * df * df - f * ddf;
        if (den > 0.0) {
            dxn = 2.0 * f * df / den;
            hal = 1;
            newton = den <= 4.0 * df * df;
        } else {
            dxn = f / df; /* may be +-inf: then not inside */
        }
        xn = x - dxn;
    }
    inside = (xn > J->lo && xn < J->hi) || (xn > J->hi && xn < J->lo);
    if (fabs(f) <= tol_z * sc || (df != 0.0 && fabs(dxn) <= 2.0 * WK_POLY_EPS * fabs(x) + WK_POLY_TINY)) {
        if (inside) J->x = xn;
        J->done = 1;
        return;
    }
    if (inside && (J->dxp == 0.0 || fabs((J->it > 12 ? 4.0 : 2.0) * dxn) <= fabs(J->dx))) {
        r = (J->dxp != 0.0) ? dxn / J->dxp : 1.0; /* may be inf: then no stop */
        pred = (hal && J->hal) ? r * r * fabs(r) * fabs(dxn) : r * r * fabs(dxn);
        J->dx = dxn;
        J->dxp = dxn;
        J->hal = hal;
        J->x = xn;
        /* (not after a step that cancelled most of x: xn then carries the rounding error of x; and only after a step
         * Newton's to within a factor 2, Halley's 2 f'^2 / den >= 1/2: next to a critical point of p, f' ~ 0 and f
         * not small, Halley's step is tiny for its curvature term and the ratio of steps predicts nothing) */
        if (pred <= WK_POLY_EPS * fabs(xn) + WK_POLY_TINY && fabs(xn) >= 0.5 * fabs(x) && newton) J->done = 1;
    } else {
        J->dxp = 0.0; /* no step history */
        J->hal = 0;
        J->dx = 0.5 * (J->hi - J->lo);
        xn = wk_poly_split(J->lo, J->hi);
        J->x = xn;
        if (xn == J->lo || xn == J->hi || fabs(J->dx) <= 2.0 * WK_POLY_EPS * fabs(xn) + WK_POLY_TINY)
            J->done = 1;
    }
    if (!J->done && J->it >= WK_POLY_MAXIT) {
        J->done = 1;
        *maxit = 1;
    }
}

static int wk_poly_sign(double v)
{
    return (v > 0.0) - (v < 0.0);
}

/* Roots of a (degree m >= 2; da, dda: p', p'') given the sorted critical
 * points part[0..np-1] (roots of da) and p'' there (curv).  Writes roots,
 * p' at them and flags to out/outd/outf; returns the count. */
static int wk_poly_level(const double *a, const double *da, const double *dda, int m, const double *part,
                         const double *curv, int np, double bound, double nrm, double tol_t, double tol_z,
                         double *out,
                         double *outd, unsigned *outf, int *maxit)
{
    double x[WK_POLY_MAXDEG + 2], v[WK_POLY_MAXDEG + 2], sc[WK_POLY_MAXDEG + 2], ws[WK_POLY_MAXDEG + 2];
    int s[WK_POLY_MAXDEG + 2];
    /* items in ascending order: fixed roots (job < 0) or bracket searches */
    double ix[WK_POLY_MAXDEG + 2];
    unsigned iflag[WK_POLY_MAXDEG + 2];
    int ijob[WK_POLY_MAXDEG + 2];
    wk_poly_job jobs[WK_POLY_MAXDEG + 1];
    double bx[WK_POLY_MAXDEG + 1], bf[WK_POLY_MAXDEG + 1], bdf[WK_POLY_MAXDEG + 1];
    double bddf[WK_POLY_MAXDEG + 1], bsc[WK_POLY_MAXDEG + 1];
    int act[WK_POLY_MAXDEG + 1];
    int j, j2, b, best, active, nit = 0, nj = 0, cnt = 0, last = np + 1, lead = wk_poly_sign(a[m]);
    double x0, t, tb, d;
    x[0] = -bound;
    x[last] = bound;
    s[0] = (m % 2) ? -lead : lead; /* exact: no root outside (-bound, bound) */
    s[last] = lead;
    /* |p| grows monotonically outwards from the outermost critical points: only the signs matter */
    v[0] = s[0] * WK_POLY_DMAX;
    v[last] = lead * WK_POLY_DMAX;
    sc[0] = sc[last] = ws[0] = ws[last] = 0.0;
    for (j = 1; j <= np; ++j) {
        x[j] = part[j - 1];
        v[j] = wk_poly_eval_scale(a, m, x[j], &sc[j], &ws[j]);
        s[j] = (fabs(v[j]) <= tol_z * sc[j]) ? 0 : wk_poly_sign(v[j]);
    }
    for (j = 0; j <= np; ++j) {
        if (s[j] == 0) {
            /* run of unresolved critical points: one root at the most zero-like */
            j2 = j;
            best = j;
            while (s[j2 + 1] == 0) {
                ++j2;
                if (fabs(v[j2]) * sc[best] < fabs(v[best]) * sc[j2]) best = j2;
            }
            ix[nit] = x[best];
            iflag[nit] = (s[j - 1] == s[j2 + 1]) ? WK_POLY_FLAG_DOUBLE : 0u;
            ijob[nit++] = -1;
            j = j2;
            continue; /* the piece (x[j2], x[j2+1]) has no resolvable sign change */
        }
        if (j >= 1 && s[j - 1] == s[j] && s[j + 1] == s[j] && fabs(v[j]) <= tol_t * nrm * ws[j]
            && fabs(v[j]) <= fabs(v[j - 1]) && fabs(v[j]) <= fabs(v[j + 1])) {
            ix[nit] = x[j]; /* touching root at a near-zero extremum */
            iflag[nit] = WK_POLY_FLAG_DOUBLE;
            ijob[nit++] = -1;
        }
        if (s[j] * s[j + 1] < 0) {
            /* start from the quadratic model p(c) + p''(c)/2 t^2 at the nearer critical end */
            tb = WK_POLY_DMAX;
            x0 = 0.5 * (x[j] + x[j + 1]);
            if (j >= 1 && curv[j - 1] != 0.0) {
                tb = sqrt(2.0 * fabs(v[j]) / fabs(curv[j - 1]));
                x0 = x[j] + tb;
            }
            if (j + 1 <= np && curv[j] != 0.0) {
                t = sqrt(2.0 * fabs(v[j + 1]) / fabs(curv[j]));
                if (t < tb) x0 = x[j + 1] - t;
            }
            if (!(x0 > x[j] && x0 < x[j + 1])) x0 = 0.5 * (x[j] + x[j + 1]);
            jobs[nj].lo = (s[j] < 0) ? x[j] : x[j + 1];
            jobs[nj].hi = (s[j] < 0) ? x[j + 1] : x[j];
            jobs[nj].x = x0;
            jobs[nj].dx = x[j + 1] - x[j];
            jobs[nj].dxp = 0.0;
            jobs[nj].df = 0.0;
            jobs[nj].it = 0;
            jobs[nj].hal = 0;
            jobs[nj].done = 0;
            iflag[nit] = 0u;
            ijob[nit++] = nj++;
        }
    }
    /* all searches of this level advance in lockstep, their polynomial
     * evaluations batched (independent work for the CPU to overlap) */
    for (;;) {
        active = 0;
        for (b = 0; b < nj; ++b) {
            if (!jobs[b].done) {
                act[active] = b;
                bx[active++] = jobs[b].x;
            }
        }
        if (!active) break;
        wk_poly_eval3(a, da, dda, m, bx, active, bf, bdf, bddf, bsc);
        for (b = 0; b < active; ++b) wk_poly_step(&jobs[act[b]], bf[b], bdf[b], bddf[b], bsc[b], tol_z, maxit);
    }
    for (j = 0; j < nit && cnt < WK_POLY_MAXDEG; ++j) {
        if (ijob[j] >= 0) {
            t = jobs[ijob[j]].x;
            d = jobs[ijob[j]].df;
        } else {
            t = ix[j];
            d = wk_poly_eval(da, m - 1, t);
        }
        if (cnt > 0 && !(t > out[cnt - 1])) continue; /* keep strictly increasing */
        out[cnt] = t;
        outd[cnt] = d;
        outf[cnt++] = iflag[j];
    }
    return cnt;
}

/* Main entry: coef[0..n] ascending (k0..kn), n <= 8; roots/flags hold 8. tol_touch: WK_POLY_TOL_TOUCH, or the
 * caller's bound on its coefficients' rounding (relative to the largest) where it knows a larger one. One entry (no
 * default-argument wrapper): a module that includes this file uses every static function in it. */
static int wk_poly_real_roots(const double *coef, int n, double *roots, unsigned *flags, int *status,
                              double tol_touch)
{
    double d[WK_POLY_MAXDEG + 1][WK_POLY_MAXDEG + 1];
    double part[WK_POLY_MAXDEG], curv[WK_POLY_MAXDEG];
    double out[WK_POLY_MAXDEG], outd[WK_POLY_MAXDEG];
    unsigned outf[WK_POLY_MAXDEG];
    double mx = 0.0, bound, r, tol_z, nrm;
    int i, k, ne, m0, deg, np, e, q, emax, cnt = 0, maxit = 0, st = WK_POLY_STATUS_OK;

    if (n < 0 || n > WK_POLY_MAXDEG) {
        *status = WK_POLY_STATUS_BAD_INPUT;
        return 0;
    }
    for (i = 0; i <= n; ++i) {
        if (!(fabs(coef[i]) <= WK_POLY_DMAX)) { /* NaN or inf */
            *status = WK_POLY_STATUS_BAD_INPUT;
            return 0;
        }
        if (fabs(coef[i]) > mx) mx = fabs(coef[i]);
    }
    if (mx == 0.0) {
        *status = WK_POLY_STATUS_ZERO;
        return 0;
    }
    ne = n;
    while (ne > 0 && fabs(coef[ne]) <= WK_POLY_TOL_LEAD * mx) --ne;
    if (ne < n) st |= WK_POLY_STATUS_DEGREE_DROP;
    m0 = 0;
    while (coef[m0] == 0.0) ++m0; /* stops at ne: coef[ne] != 0 */
    deg = ne - m0;
    for (i = 0; i <= deg; ++i) d[0][i] = coef[i + m0] / mx;

    if (deg == 1) {
        out[0] = -d[0][0] / d[0][1];
        outf[0] = 0u;
        cnt = 1;
    } else if (deg >= 2) {
        /* Fujiwara: |z| <= 2 max_k |a_{deg-k}/a_deg|^(1/k) (last term with a_0/2); r < 2^e
         * gives r^(1/k) < 2^ceil(e/k), so bound = 2^(emax+1) > every |z|. */
        emax = -1100;
        for (k = 1; k <= deg; ++k) {
            r = fabs(d[0][deg - k] / d[0][deg]);
            if (k == deg) r *= 0.5;
            if (r == 0.0) continue;
            (void)frexp(r, &e);
            q = (e >= 0) ? (e + k - 1) / k : -((-e) / k);
            if (q > emax) emax = q;
        }
        bound = ldexp(1.0, emax + 1);
        for (k = 1; k <= deg; ++k)
            for (i = 0; i <= deg - k; ++i) d[k][i] = d[k - 1][i + 1] * (double)(i + 1);
        tol_z = 2.0 * (double)(deg + 1) * WK_POLY_EPS;
        /* linear p^(deg-1) */
        part[0] = -d[deg - 1][0] / d[deg - 1][1];
        if (part[0] < -bound) part[0] = -bound;
        if (part[0] > bound) part[0] = bound;
        curv[0] = d[deg - 1][1];
        np = 1;
        for (k = deg - 2; k >= 0; --k) {
            nrm = 0.0;
            for (i = 0; i <= deg - k; ++i)
                if (fabs(d[k][i]) > nrm) nrm = fabs(d[k][i]);
            cnt = wk_poly_level(d[k], d[k + 1], d[k + 2], deg - k, part, curv, np, bound, nrm,
                                (k == 0) ? tol_touch : WK_POLY_TOL_INNER, tol_z, out, outd, outf, &maxit);
            for (i = 0; i < cnt; ++i) {
                part[i] = out[i];
                curv[i] = outd[i];
            }
            np = cnt;
        }
    }
    if (maxit) st |= WK_POLY_STATUS_MAXITER;

    /* merge the deflated root x = 0 (multiplicity m0) */
    k = 0;
    for (i = 0; i < cnt && out[i] < 0.0; ++i) {
        roots[k] = out[i];
        flags[k++] = outf[i];
    }
    if (m0 > 0 && !(i < cnt && out[i] == 0.0)) {
        roots[k] = 0.0;
        flags[k++] = (m0 % 2 == 0) ? WK_POLY_FLAG_DOUBLE : 0u;
    }
    for (; i < cnt; ++i) {
        roots[k] = out[i];
        flags[k++] = outf[i];
    }
    *status = st;
    return k;
}

#endif /* WK_POLY_REAL_ROOTS_INCLUDED */
