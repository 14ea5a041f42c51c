/* wristkin: dense real eigenvalues, the quadratic eigenproblem and null vectors (C99, libm only; do not edit).
 * @generated-by@
 *
 * Algorithms from the literature (written for this file): Parlett & Reinsch, "Balancing a matrix for
 * calculation of eigenvalues and eigenvectors" (1969); Householder reduction to Hessenberg form and the Francis
 * implicit double-shift QR step (Golub & Van Loan, Matrix Computations, 4th ed., 7.4-7.5); the companion
 * linearisation of a quadratic matrix polynomial (Tisseur & Meerbergen, SIAM Review 43, 2001) with the
 * Fan-Lin-Van Dooren parameter scaling; Hestenes' one-sided Jacobi SVD (Demmel & Veselic 1992) with
 * Drmac and Veselic's QR preconditioner (2008).
 * Contracts in wk_eigen.h.
 */
#include "wk_eigen.h"

#include <float.h>
#include <math.h>

#define WK_EIG_EPS DBL_EPSILON
#ifndef WK_NULL_SWEEPS /* Jacobi sweeps allowed; overridable only for the test of the no-convergence path */
#define WK_NULL_SWEEPS 60
#endif
/* QR iterations allowed: 30 per eigenvalue, as one budget of 30 n for the whole matrix (EISPACK's hqr): a
 * defective eigenvalue converges only linearly (a Jordan block of 6: ~40 iterations for the first deflation,
 * then the rest of the block follows quickly), so a per-window cap of 30 would give up on matrices LAPACK solves */
#ifndef WK_EIG_ITMAX /* overridable only so that a test can reach the no-convergence path */
#define WK_EIG_ITMAX 30
#endif

static int wk_eig_finite(int count, const double *x)
{
    int i;
    for (i = 0; i < count; ++i)
        if (!isfinite(x[i]))
            return 0;
    return 1;
}

static int wk_eig_all_zero(int count, const double *x)
{
    int i;
    for (i = 0; i < count; ++i)
        if (x[i] != 0.0)
            return 0;
    return 1;
}

/* The exponent e with max|x| in [2^(e-1), 2^e) (0 when all are zero): scaling by 2^-e is exact and brings the
 * largest entry near 1, so nothing below overflows or loses precision in the subnormal range. */
static int wk_eig_exponent(int count, const double *x)
{
    double amax = 0.0;
    int i, e = 0;
    for (i = 0; i < count; ++i)
        if (fabs(x[i]) > amax)
            amax = fabs(x[i]);
    if (amax == 0.0)
        return 0;
    (void)frexp(amax, &e);
    return e;
}

/* Parlett-Reinsch: scale row i by 1/f and column i by f (f a power of 2, so exact and a similarity) until
 * no row/column pair's off-diagonal 1-norms improve their sum by 5%. The total scale of an index is kept
 * within 2^+-900, so that no scale itself overflows and a row is not pushed wholesale into underflow. */
static void wk_eig_balance(int n, double *a, double *scale)
{
    const double big = 0x1p+900, small = 0x1p-900;
    int i, j, sweep, done = 0;
    for (i = 0; i < n; ++i)
        scale[i] = 1.0;
    for (sweep = 0; sweep < 64 && !done; ++sweep) {
        done = 1;
        for (i = 0; i < n; ++i) {
            double c = 0.0, r = 0.0, g, f = 1.0, s;
            for (j = 0; j < n; ++j) {
                if (j == i)
                    continue;
                c += fabs(a[j * n + i]);
                r += fabs(a[i * n + j]);
            }
            if (c == 0.0 || r == 0.0)
                continue;
            s = c + r;
            /* c and f move together: the column sum after scaling by f is c f, the row sum r / f; c here
             * tracks c0 f^2 so that c0 f^2 ~ r is the balance point. */
            g = r / 2.0;
            while (c < g && scale[i] * f < big) {
                f *= 2.0;
                c *= 4.0;
            }
            g = r * 2.0;
            while (c >= g && scale[i] * f > small) {
                f /= 2.0;
                c /= 4.0;
            }
            if ((c + r) / f < 0.95 * s) {
                double fi = 1.0 / f;
                done = 0;
                scale[i] *= f;
                for (j = 0; j < n; ++j)
                    a[i * n + j] *= fi;
                for (j = 0; j < n; ++j)
                    a[j * n + i] *= f;
            }
        }
    }
}

/* Householder reduction to upper Hessenberg form, H = Q^T a Q (Q not kept: only eigenvalues are wanted).
 * v, w: n doubles of workspace each. */
static void wk_eig_hessenberg(int n, double *a, double *v, double *w)
{
    int i, j, k;
    for (k = 0; k + 2 < n; ++k) {
        double amax = 0.0, sigma = 0.0, tail = 0.0, alpha, beta;
        for (i = k + 1; i < n; ++i)
            if (fabs(a[i * n + k]) > amax)
                amax = fabs(a[i * n + k]);
        if (amax == 0.0)
            continue;
        for (i = k + 1; i < n; ++i) {
            v[i] = a[i * n + k] / amax; /* scaled: the reflector is the same, the squares cannot overflow */
            sigma += v[i] * v[i];
            if (i > k + 1)
                tail += v[i] * v[i];
        }
        if (tail == 0.0)
            continue; /* already Hessenberg in this column */
        alpha = -copysign(sqrt(sigma), v[k + 1]);
        v[k + 1] -= alpha;
        /* v^T v = 2 (sigma - alpha v1_old) = -2 alpha v[k+1] > 0, so 2 / v^T v = 1 / (-alpha v[k+1]) */
        beta = 1.0 / (-alpha * v[k + 1]);
        /* from the left: w = beta v^T a (columns k+1..), then a -= v w, both row by row (contiguous) */
        for (j = k + 1; j < n; ++j)
            w[j] = 0.0;
        for (i = k + 1; i < n; ++i)
            for (j = k + 1; j < n; ++j)
                w[j] += v[i] * a[i * n + j];
        for (j = k + 1; j < n; ++j)
            w[j] *= beta;
        for (i = k + 1; i < n; ++i)
            for (j = k + 1; j < n; ++j)
                a[i * n + j] -= v[i] * w[j];
        a[(k + 1) * n + k] = alpha * amax;
        for (i = k + 2; i < n; ++i)
            a[i * n + k] = 0.0;
        for (i = 0; i < n; ++i) {
            double s = 0.0;
            for (j = k + 1; j < n; ++j)
                s += a[i * n + j] * v[j];
            s *= beta;
            for (j = k + 1; j < n; ++j)
                a[i * n + j] -= s * v[j];
        }
    }
}

/* Eigenvalues of [[p, q], [r, s]]: (e1, e2) real (im = 0) or re +- i im. */
static void wk_eig_2x2(double p, double q, double r, double s, double *e1, double *e2, double *im)
{
    double h = 0.5 * (p - s), bc = q * r, disc = h * h + bc;
    *im = 0.0;
    if (disc >= 0.0) {
        /* z = h + sign(h) sqrt(disc) has no cancellation, the second root comes from the product e1 e2 = ps - qr;
         * s + z itself may cancel (a root small next to |p| + |s|): normwise accurate, as LAPACK's dlanv2 */
        double z = h + copysign(sqrt(disc), h);
        *e1 = s + z;
        *e2 = (z != 0.0) ? s - bc / z : s;
    } else {
        *e1 = *e2 = s + h;
        *im = sqrt(-disc);
    }
}

/* Francis double-shift QR on the Hessenberg matrix h (n x n), eigenvalues only: each step works on the active
 * unreduced window [l, hi]. Returns WK_EIG_OK or WK_EIG_ERR_NOCONV. */
static int wk_eig_hqr(int n, double *h, double *wr, double *wi)
{
    const double eps = WK_EIG_EPS;
    /* below this a subdiagonal entry is negligible whatever its neighbours (the smallest normal number scaled
     * by n / eps, as LAPACK's dlahqr does): keeps an underflowing subdiagonal from stalling the iteration */
    const double smlnum = DBL_MIN * ((double)n / eps);
    double norm = 0.0;
    int i, j, hi = n - 1, its = 0, budget = WK_EIG_ITMAX * n;
    for (i = 0; i < n; ++i)
        for (j = (i > 0 ? i - 1 : 0); j < n; ++j)
            norm += h[i * n + j] * h[i * n + j]; /* entries <= ~1 (scaled): no overflow */
    norm = sqrt(norm); /* ||H||_F, invariant under the orthogonal QR steps */
    while (hi >= 0) {
        int l, k;
        double sr, si, p, q, r;
        for (l = hi; l > 0; --l) {
            double sub = fabs(h[l * n + l - 1]);
            double tst = fabs(h[(l - 1) * n + l - 1]) + fabs(h[l * n + l]);
            if (tst == 0.0)
                tst = norm;
            /* Wilkinson's local test: small next to its diagonal neighbours (keeps the small eigenvalues of
             * a graded matrix accurate); a zero diagonal pair falls back to ||H||_F */
            if (sub <= eps * tst || sub <= smlnum) {
                h[l * n + l - 1] = 0.0;
                break;
            }
        }
        if (l == hi) { /* a 1x1 block deflated */
            wr[hi] = h[hi * n + hi];
            wi[hi] = 0.0;
            --hi;
            its = 0;
            continue;
        }
        if (l == hi - 1) { /* a 2x2 block deflated */
            double e1, e2, im;
            wk_eig_2x2(h[l * n + l], h[l * n + hi], h[hi * n + l], h[hi * n + hi], &e1, &e2, &im);
            if (im == 0.0) {
                wr[l] = e1;
                wr[hi] = e2;
                wi[l] = wi[hi] = 0.0;
            } else {
                wr[l] = wr[hi] = e1;
                wi[l] = im;
                wi[hi] = -im;
            }
            hi -= 2;
            its = 0;
            continue;
        }
        if (budget-- == 0)
            return WK_EIG_ERR_NOCONV;
        /* shifts: the eigenvalues of the trailing 2x2 (Wilkinson's double shift); when both are real, the
         * one nearer h[hi][hi] twice. Every 10th iteration on one window an exceptional pair built from the last
         * subdiagonals, 0.75 e + h[hi][hi] +- i sqrt(0.4375) e, breaks the cycles the standard shift can fall
         * into (e.g. a cyclic permutation matrix). */
        if (its > 0 && its % 10 == 0) {
            double e = fabs(h[hi * n + hi - 1]) + fabs(h[(hi - 1) * n + hi - 2]);
            sr = 0.75 * e + h[hi * n + hi];
            si = sqrt(0.4375) * e;
        } else {
            double e1, e2;
            wk_eig_2x2(h[(hi - 1) * n + hi - 1], h[(hi - 1) * n + hi], h[hi * n + hi - 1], h[hi * n + hi], &e1, &e2,
                       &si);
            sr = (fabs(e1 - h[hi * n + hi]) <= fabs(e2 - h[hi * n + hi])) ? e1 : e2;
            if (si != 0.0)
                sr = e1;
        }
        ++its;
        /* first column of (H - s1 I)(H - s2 I) at the window's top, s1,2 = sr +- i si, in factored form:
         * (h00 - sr)^2 + si^2 + h01 h10, not h00^2 - (s1 + s2) h00 + s1 s2, whose cancellation leaves nothing
         * but rounding when the shifts are within sqrt(eps) of h00 (a cluster, a defective eigenvalue) and
         * turns the step into a random rotation */
        {
            double h00 = h[l * n + l], h01 = h[l * n + l + 1], h10 = h[(l + 1) * n + l];
            double h11 = h[(l + 1) * n + l + 1], h21 = h[(l + 2) * n + l + 1];
            double d0 = h00 - sr, d1 = h11 - sr;
            p = d0 * d0 + si * si + h01 * h10;
            q = h10 * (d0 + d1);
            r = h21 * h10;
        }
        /* chase the bulge down with 3x3 (last: 2x2) reflectors */
        for (k = l; k < hi; ++k) {
            int nr = (k < hi - 1) ? 3 : 2, last;
            double scal, nrm, v1, v2, tau;
            if (k > l) {
                p = h[k * n + k - 1];
                q = h[(k + 1) * n + k - 1];
                r = (nr == 3) ? h[(k + 2) * n + k - 1] : 0.0;
            }
            scal = fabs(p) + fabs(q) + fabs(r);
            if (scal == 0.0)
                continue;
            { /* one division on the bulge's critical path, not three (as LAPACK's dlarfg scales by a reciprocal) */
                const double inv = 1.0 / scal;
                p *= inv;
                q *= inv;
                r *= inv;
            }
            nrm = copysign(sqrt(p * p + q * q + r * r), p);
            if (k > l) {
                h[k * n + k - 1] = -nrm * scal;
                h[(k + 1) * n + k - 1] = 0.0;
                if (nr == 3)
                    h[(k + 2) * n + k - 1] = 0.0;
            }
            /* reflector I - tau u u^T with u = (1, v1, v2) maps (p, q, r) to (-nrm, 0, 0) */
            tau = (p + nrm) / nrm;
            {
                const double inv = 1.0 / (p + nrm); /* |p + nrm| >= |nrm| > 0: p and nrm share their sign */
                v1 = q * inv;
                v2 = r * inv;
            }
            last = (k + 3 < hi) ? k + 3 : hi;
            /* rows k.. from the left (columns k..hi), columns k.. from the right (rows l..last); the 3- and
             * 2-row cases as separate loops without branches, which the compiler can vectorise */
            if (nr == 3) {
                double *r0 = h + k * n, *r1 = r0 + n, *r2 = r1 + n;
                for (j = k; j <= hi; ++j) {
                    double d = tau * (r0[j] + v1 * r1[j] + v2 * r2[j]);
                    r0[j] -= d;
                    r1[j] -= d * v1;
                    r2[j] -= d * v2;
                }
                for (i = l; i <= last; ++i) {
                    double *row = h + i * n + k;
                    double d = tau * (row[0] + v1 * row[1] + v2 * row[2]);
                    row[0] -= d;
                    row[1] -= d * v1;
                    row[2] -= d * v2;
                }
            } else {
                double *r0 = h + k * n, *r1 = r0 + n;
                for (j = k; j <= hi; ++j) {
                    double d = tau * (r0[j] + v1 * r1[j]);
                    r0[j] -= d;
                    r1[j] -= d * v1;
                }
                for (i = l; i <= last; ++i) {
                    double *row = h + i * n + k;
                    double d = tau * (row[0] + v1 * row[1]);
                    row[0] -= d;
                    row[1] -= d * v1;
                }
            }
        }
    }
    return WK_EIG_OK;
}

/* x[i] := x[i] 2^e for count entries: one multiplication by the power of two where it is a normal number (then
 * exactly ldexp's result, rounding included where a product falls into the subnormal range), ldexp beyond */
static void wk_eig_times_pow2(int count, double *x, int e)
{
    int i;
    if (e == 0)
        return;
    if (e > -1000 && e < 1000) {
        const double f = ldexp(1.0, e);
        for (i = 0; i < count; ++i)
            x[i] *= f;
    } else {
        for (i = 0; i < count; ++i)
            x[i] = ldexp(x[i], e);
    }
}

int wk_eig_real(int n, double *a, double *wr, double *wi, double *work)
{
    int e, e2, i, rc;
    if (!a || !wr || !wi || !work || n < 1 || n > WK_EIG_MAXN)
        return WK_EIG_ERR_INPUT;
    for (i = 0; i < n; ++i)
        wr[i] = wi[i] = 0.0;
    if (!wk_eig_finite(n * n, a))
        return WK_EIG_ERR_INPUT;
    /* balancing comes first, on the matrix as given: a scaling to max ~ 1 before it would flush the small
     * entries of a graded matrix (2^+-620 and more) to zero, and balancing is what makes them matter. Only
     * a matrix near the ends of the range is scaled first, so that the row and column sums cannot overflow
     * (32 terms below 2^1017). */
    e = wk_eig_exponent(n * n, a);
    e = (e > 960 || e < -960) ? e : 0;
    wk_eig_times_pow2(n * n, a, -e);
    wk_eig_balance(n, a, work);
    /* then to max ~ 1 (balancing can also shrink a graded matrix as a whole by 2^-500 and more): else the
     * shifts' products in the QR step fall into the subnormal range and lose their bits */
    e2 = wk_eig_exponent(n * n, a);
    wk_eig_times_pow2(n * n, a, -e2);
    e += e2;
    wk_eig_hessenberg(n, a, work + n, work); /* the balancing scales are not needed any more */
    rc = wk_eig_hqr(n, a, wr, wi);
    if (rc != WK_EIG_OK) {
        for (i = 0; i < n; ++i)
            wr[i] = wi[i] = 0.0;
        return rc;
    }
    wk_eig_times_pow2(n, wr, e);
    wk_eig_times_pow2(n, wi, e);
    for (i = 0; i < n; ++i) {
        if (!isfinite(wr[i]) || !isfinite(wi[i]))
            rc = WK_EIG_ERR_INPUT; /* |lambda| <= n max|a| can exceed DBL_MAX: refused, not returned as inf */
    }
    if (rc != WK_EIG_OK)
        for (i = 0; i < n; ++i)
            wr[i] = wi[i] = 0.0;
    return rc;
}

/* ------------------------------------------------------------------ quadratic eigenproblem */

/* LU with partial pivoting of the m x m row-major a in place (piv: row swaps). 0 when a pivot is exactly
 * zero (singular), else 1. */
static int wk_qep_lu(int m, double *a, int *piv)
{
    int i, j, k;
    for (k = 0; k < m; ++k) {
        int p = k;
        for (i = k + 1; i < m; ++i)
            if (fabs(a[i * m + k]) > fabs(a[p * m + k]))
                p = i;
        piv[k] = p;
        if (a[p * m + k] == 0.0)
            return 0;
        if (p != k)
            for (j = 0; j < m; ++j) {
                double t = a[k * m + j];
                a[k * m + j] = a[p * m + j];
                a[p * m + j] = t;
            }
        for (i = k + 1; i < m; ++i) {
            double f = a[i * m + k] /= a[k * m + k];
            for (j = k + 1; j < m; ++j)
                a[i * m + j] -= f * a[k * m + j];
        }
    }
    return 1;
}

/* Solve (LU) x = b in place for `cols` right-hand sides stored as the columns of the m x cols row-major b. */
static void wk_qep_solve(int m, const double *lu, const int *piv, double *b, int cols)
{
    int i, j, k;
    for (k = 0; k < m; ++k)
        if (piv[k] != k)
            for (j = 0; j < cols; ++j) {
                double t = b[k * cols + j];
                b[k * cols + j] = b[piv[k] * cols + j];
                b[piv[k] * cols + j] = t;
            }
    for (j = 0; j < cols; ++j) {
        for (i = 1; i < m; ++i) {
            double s = b[i * cols + j];
            for (k = 0; k < i; ++k)
                s -= lu[i * m + k] * b[k * cols + j];
            b[i * cols + j] = s;
        }
        for (i = m - 1; i >= 0; --i) {
            double s = b[i * cols + j];
            for (k = i + 1; k < m; ++k)
                s -= lu[i * m + k] * b[k * cols + j];
            b[i * cols + j] = s / lu[i * m + i];
        }
    }
}

static double wk_qep_norm1(int m, const double *a)
{
    double best = 0.0;
    int i, j;
    for (j = 0; j < m; ++j) {
        double s = 0.0;
        for (i = 0; i < m; ++i)
            s += fabs(a[i * m + j]);
        if (s > best)
            best = s;
    }
    return best;
}

/* The coefficients after the Moebius rotation x = (c y + s) / (c - s y): multiplying M(x) by (c - s y)^2,
 *   A' = c^2 A - c s B + s^2 C = (c - s y)^2 M(x) at y = inf,  B' = 2 c s A + (c^2 - s^2) B - 2 c s C,
 *   C' = s^2 A + c s B + c^2 C.  (c, s) = (1, 0) is the problem itself, (0, 1) its reversal (y = -1/x). */
static void wk_qep_rotate(int m, const double *A, const double *B, const double *C, double c, double s,
                          double *a2, double *b2, double *c2)
{
    int i;
    for (i = 0; i < m * m; ++i) {
        a2[i] = c * c * A[i] - c * s * B[i] + s * s * C[i];
        b2[i] = 2.0 * c * s * (A[i] - C[i]) + (c * c - s * s) * B[i];
        c2[i] = s * s * A[i] + c * s * B[i] + c * c * C[i];
    }
}

/* 1-norm reciprocal condition number of L (m x m), computed from its explicit inverse (m <= 12: the exact
 * value costs little more than an estimator); lu/piv receive its factorisation. 0 when singular. */
static double wk_qep_rcond(int m, const double *L, double *lu, int *piv)
{
    double inv[WK_QEP_MAXM * WK_QEP_MAXM], nl = wk_qep_norm1(m, L), ni;
    int i;
    for (i = 0; i < m * m; ++i)
        lu[i] = L[i];
    if (nl == 0.0 || !wk_qep_lu(m, lu, piv))
        return 0.0;
    for (i = 0; i < m * m; ++i)
        inv[i] = (i % (m + 1) == 0) ? 1.0 : 0.0;
    wk_qep_solve(m, lu, piv, inv, m);
    ni = wk_qep_norm1(m, inv);
    return (isfinite(ni) && ni > 0.0) ? 1.0 / (nl * ni) : 0.0;
}

static void wk_qep_sort(int k, double *x, unsigned *f)
{
    int i, j;
    for (i = 1; i < k; ++i)
        for (j = i; j > 0 && x[j - 1] > x[j]; --j) {
            double t = x[j];
            unsigned u = f[j];
            x[j] = x[j - 1];
            f[j] = f[j - 1];
            x[j - 1] = t;
            f[j - 1] = u;
        }
}

/* Why this linearisation. The companion form [[0, I], [-L^-1 C', -L^-1 B']] needs the leading coefficient L
 * inverted, and its backward error grows with cond(L); in the 6R elimination A is singular at poses where
 * theta = pi solves (x = inf) and ill-conditioned near them, C likewise at theta = 0. So the leading
 * coefficient is chosen, not assumed: among Moebius rotations x = (c y + s) / (c - s y) of the projective line
 * (angle 0 = the problem as given, pi/2 = its reversal, and four fixed angles tried only when the better of
 * A and C has rcond < 2^-10, e.g. both singular) the one whose leading coefficient s^2 M(x = -c/s) has the
 * largest reciprocal condition (a later one only if at least twice that of the earlier ones).
 * A rotation keeps the three coefficients' norms comparable (an orthogonal change of the homogeneous
 * variables), so it costs no accuracy, unlike a general Moebius map. Before that, x = g mu with g = a power
 * of 2 near sqrt(||C|| / ||A||) (Fan, Lin & Van Dooren's scaling, rounded so that it is exact) makes
 * ||A|| ~ ||C||, which is what makes the companion linearisation's backward error comparable to the
 * polynomial's. The pencil is reported singular when even the best rcond is below 64 m eps: then
 * det M(x) vanishes (numerically) at all six points, which a regular 12 x 12 problem with 24 eigenvalues does
 * not do unless it is within rounding of a singular one.
 *
 * Why tol is an angle. x = tan(theta/2), and d theta = 2 dx / (1 + x^2): 2 |Im x| / (1 + |x|^2) is the
 * imaginary part of theta. A real double root (a tangency: two IK branches meeting) perturbed by the backward
 * error delta ~ c m eps / rcond splits by ~ sqrt(delta) -- into two reals or into a complex pair; delta
 * ~ 1e-13 gives ~ 3e-7, so the default 2^-20 ~ 9.5e-7 keeps such pairs as one real root flagged DOUBLE (the
 * caller verifies and polishes on the true chain; poly_real_roots.c's tol_touch 1e-12, a backward error,
 * is the same split). A genuine complex pair that close to the real axis is a near-tangency the caller's
 * check rejects. Likewise |x| >= 2 / tol (theta within ~tol of pi) is reported as infinite, never as a huge
 * finite real root. */
int wk_generalized_quadratic_eig(int m, const double *A, const double *B, const double *C, double tol,
                                 wk_qep_result *out)
{
    /* cos and sin of 0, pi/2 and the fixed angles 0.4, 1.1, 2.0, 2.6 (radians; arbitrary, no two close) */
    static const double rot[6][2] = { {1.0, 0.0},
                                     {0.0, 1.0},
                                     {0.92106099400288508, 0.38941834230865049},
                                     {0.45359612142557731, 0.89120736006143534},
                                     {-0.41614683654714241, 0.90929742682568170},
                                     {-0.85688875336894723, 0.51550137182146428} };
    double As[WK_QEP_MAXM * WK_QEP_MAXM], Bs[WK_QEP_MAXM * WK_QEP_MAXM], Cs[WK_QEP_MAXM * WK_QEP_MAXM];
    double a2[WK_QEP_MAXM * WK_QEP_MAXM], b2[WK_QEP_MAXM * WK_QEP_MAXM], c2[WK_QEP_MAXM * WK_QEP_MAXM];
    double lu[WK_QEP_MAXM * WK_QEP_MAXM], best_lu[WK_QEP_MAXM * WK_QEP_MAXM];
    double comp[4 * WK_QEP_MAXM * WK_QEP_MAXM], rhs[WK_QEP_MAXM * 2 * WK_QEP_MAXM];
    double wr[2 * WK_QEP_MAXM], wi[2 * WK_QEP_MAXM], work[WK_EIG_WORK(2 * WK_QEP_MAXM)];
    int piv[WK_QEP_MAXM], best_piv[WK_QEP_MAXM];
    double na, nb, nc, g = 1.0, best = -1.0, c, s;
    int i, j, k, n2 = 2 * m, mm = m * m, eg = 0, best_k = 0, rc;
    if (!out)
        return WK_EIG_ERR_INPUT;
    out->n_real = out->n_complex = out->n_infinite = 0;
    out->rcond = 0.0;
    out->growth = 0.0;
    out->angle = 0.0;
    if (!A || !B || !C || m < 1 || m > WK_QEP_MAXM || !(tol < 0.5) || isnan(tol))
        return WK_EIG_ERR_INPUT;
    if (!wk_eig_finite(mm, A) || !wk_eig_finite(mm, B) || !wk_eig_finite(mm, C))
        return WK_EIG_ERR_INPUT;
    if (tol <= 0.0)
        tol = WK_QEP_TOL_DEFAULT;
    /* exact power-of-two scalings, applied in one step so that nothing underflows on the way: x = g mu with
     * g^2 ~ max|C| / max|A| (the exponents of the largest entries, within a factor m of the norms' ratio),
     * then all three coefficients by the one power of two that brings the largest entry near 1 */
    {
        int ea = wk_eig_exponent(mm, A), eb = wk_eig_exponent(mm, B), ec = wk_eig_exponent(mm, C), e3;
        int za = wk_eig_all_zero(mm, A), zc = wk_eig_all_zero(mm, C);
        eg = (za || zc) ? 0 : ec - ea;
        eg = eg >= 0 ? eg / 2 : -((1 - eg) / 2); /* floor(eg / 2): the same rounding at every scale */
        if (eg > 1000) /* g itself representable; products with it are formed only below 2 / tol */
            eg = 1000;
        if (eg < -1000)
            eg = -1000;
        g = ldexp(1.0, eg);
        e3 = za ? -2000 : ea + 2 * eg;
        if (!wk_eig_all_zero(mm, B) && eb + eg > e3)
            e3 = eb + eg;
        if (!zc && ec > e3)
            e3 = ec;
        if (e3 == -2000)
            e3 = 0;
        for (i = 0; i < mm; ++i) {
            As[i] = ldexp(A[i], 2 * eg - e3);
            Bs[i] = ldexp(B[i], eg - e3);
            Cs[i] = ldexp(C[i], -e3);
        }
    }
    na = wk_qep_norm1(m, As);
    nb = wk_qep_norm1(m, Bs);
    nc = wk_qep_norm1(m, Cs);
    if (na == 0.0 && nb == 0.0 && nc == 0.0)
        return WK_EIG_ERR_SINGULAR; /* all three zero */
    for (k = 0; k < 6; ++k) {
        double rcond;
        wk_qep_rotate(m, As, Bs, Cs, rot[k][0], rot[k][1], a2, b2, c2);
        rcond = wk_qep_rcond(m, a2, lu, piv);
        /* a later candidate must be twice as well conditioned to win: ties (A = 0 makes every rotation's
         * leading coefficient s^2 C) keep the problem as given or its reversal, where the infinite
         * eigenvalues land exactly on y = 0 */
        if (rcond > 2.0 * best || (k == 0 && rcond > best)) {
            best = rcond;
            best_k = k;
            for (i = 0; i < mm; ++i)
                best_lu[i] = lu[i];
            for (i = 0; i < m; ++i)
                best_piv[i] = piv[i];
        }
        /* the rotations only when neither A nor C will do: each candidate costs an LU and an inverse (~4 us
         * at m = 12, a fifth of the whole solve for all four); rcond >= 2^-10 costs at most 10 bits over a
         * perfectly conditioned leading coefficient, and a rotation rarely beats the better of A and C by more */
        if (k == 1 && best >= 0x1p-10)
            break;
    }
    out->rcond = best;
    if (!(best >= 64.0 * m * WK_EIG_EPS))
        return WK_EIG_ERR_SINGULAR;
    c = rot[best_k][0];
    s = rot[best_k][1];
    out->angle = atan2(s, c);
    wk_qep_rotate(m, As, Bs, Cs, c, s, a2, b2, c2);
    /* rhs = [C' B'] (m x 2m), solved in place to [L^-1 C', L^-1 B'] */
    for (i = 0; i < m; ++i)
        for (j = 0; j < m; ++j) {
            rhs[i * n2 + j] = c2[i * m + j];
            rhs[i * n2 + m + j] = b2[i * m + j];
        }
    wk_qep_solve(m, best_lu, best_piv, rhs, n2);
    out->growth = 1.0;
    for (j = 0; j < n2; ++j) {
        double col = 0.0;
        for (i = 0; i < m; ++i)
            col += fabs(rhs[i * n2 + j]);
        if (col > out->growth)
            out->growth = col;
    }
    for (i = 0; i < n2 * n2; ++i)
        comp[i] = 0.0;
    for (i = 0; i < m; ++i) {
        comp[i * n2 + m + i] = 1.0;
        for (j = 0; j < n2; ++j)
            comp[(m + i) * n2 + j] = -rhs[i * n2 + j];
    }
    if (!wk_eig_finite(n2 * n2, comp))
        return WK_EIG_ERR_SINGULAR;
    rc = wk_eig_real(n2, comp, wr, wi, work);
    if (rc != WK_EIG_OK)
        return rc;
    for (k = 0; k < n2; ++k) {
        if (wi[k] == 0.0) {
            /* x = g (c y + s) / (c - s y), real */
            double num = c * wr[k] + s, den = c - s * wr[k];
            if (fabs(den) * 2.0 <= tol * g * fabs(num)) {
                ++out->n_infinite; /* |x| >= 2 / tol (den = 0 included) */
            } else {
                out->real[out->n_real] = g * num / den;
                out->real_flags[out->n_real++] = 0u;
            }
        } else if (wi[k] > 0.0) {
            /* x = g (c y + s) / (c - s y) with y = yr + i yi: numerator (c yr + s) + i c yi, denominator
             * (c - s yr) - i s yi; the division as (num * conj(den)) / |den|^2, entries ~ 1 so no overflow */
            double nr = c * wr[k] + s, ni = c * wi[k], dr = c - s * wr[k], di = -s * wi[k];
            double d2 = dr * dr + di * di;
            if (2.0 * sqrt(d2) <= tol * g * sqrt(nr * nr + ni * ni)) { /* g, not g^2: that may overflow */
                out->n_infinite += 2;
            } else {
                double xr = g * (nr * dr + ni * di) / d2, xi = g * (ni * dr - nr * di) / d2;
                if (2.0 * fabs(xi) <= tol * (1.0 + xr * xr + xi * xi)) {
                    out->real[out->n_real] = xr;
                    out->real_flags[out->n_real++] = WK_QEP_FLAG_DOUBLE;
                } else {
                    out->complex_re[out->n_complex] = xr;
                    out->complex_im[out->n_complex++] = fabs(xi);
                }
            }
        }
    }
    wk_qep_sort(out->n_real, out->real, out->real_flags);
    return WK_EIG_OK;
}

/* ------------------------------------------------------------------ null vector */

/* Hestenes' one-sided Jacobi with Drmac and Veselic's QR preconditioner (SIAM J. Matrix Anal. Appl. 29, 2008):
 * M^T Pi = Q R by Householder QR with column pivoting (Pi picks M's rows by decreasing remaining norm), so that
 * M = Pi R^T Q^T; then pairs of columns of X = R^T are rotated until all are mutually orthogonal to working
 * precision (|x_p . x_q| <= m eps |x_p| |x_q|), the rotations accumulated in W. Then X W = U Sigma, the column norms
 * are the singular values (M's: only orthogonal factors moved), and M's right singular vectors are Q W's columns.
 * Why the detour: X^T X = R R^T is nearly diagonal for a pivoted R (its rows decay), so fewer sweeps converge: on
 * the xArm6's general 6R cluster reads (12 x 12 M(x), 354 of them) 7-11 sweeps on M itself (9 mostly), 5-6 on X,
 * the last of them only checking; with the column norms carried through the rotations, 265k -> 169k instructions
 * a call there, 27.7 -> 23.7 us on random 12 x 12 (bench/eigen.py, side by side). The vectors are taken from Q W
 * (orthogonal factors, accumulated), not from a normalised column of X, which for sigma ~ 0 would be rounding
 * noise. Each sigma is within ~ c m eps sigma_max. At most WK_NULL_SWEEPS sweeps. */
/* x . y over m entries */
static double wk_jacobi_dot(int m, const double *x, const double *y)
{
    double s = 0.0;
    int i;
    for (i = 0; i < m; ++i)
        s += x[i] * y[i];
    return s;
}

/* x := H x for the Householder reflector H = I - tau (1, v)(1, v)^T acting on entries k..m-1 (v[k+1..m-1] holds the
 * vector's tail, its head is 1) */
static void wk_reflect(int m, int k, const double *v, double tau, double *x)
{
    double d = x[k];
    int i;
    for (i = k + 1; i < m; ++i)
        d += v[i] * x[i];
    d *= tau;
    x[k] -= d;
    for (i = k + 1; i < m; ++i)
        x[i] -= d * v[i];
}

/* The preconditioned one-sided Jacobi of wk_null_vector: V (m x m, row-major) receives the right singular vectors
 * as its columns and sig the singular values of M / 2^e (unordered; e an exact power-of-two scaling, the same for
 * all). */
static int wk_jacobi_right(int m, const double *M, double *V, double *sig)
{
    /* a: M^T / 2^e column-major (column c of a is row c of M), then R in its upper triangle and the reflectors'
     * vectors below it; wt, vt: X's and W's columns stored contiguously (the pair loops run down two contiguous
     * arrays, which the compiler can vectorise) */
    double a[WK_NULL_MAXM * WK_NULL_MAXM], wt[WK_NULL_MAXM * WK_NULL_MAXM], vt[WK_NULL_MAXM * WK_NULL_MAXM];
    double tau[WK_NULL_MAXM], nrm2[WK_NULL_MAXM];
    int i, j, k, p, q, sweep, rotated = 1, e;
    e = wk_eig_exponent(m * m, M);
    for (i = 0; i < m * m; ++i)
        a[i] = ldexp(M[i], -e);
    for (k = 0; k < m; ++k) { /* Householder QR of M^T with column pivoting */
        double *ak, best = -1.0, alpha, xnorm = 0.0, beta;
        int piv = k;
        for (j = k; j < m; ++j) { /* remaining column norms, recomputed (m <= 24: cheaper than downdating) */
            double s2 = 0.0;
            for (i = k; i < m; ++i)
                s2 += a[j * m + i] * a[j * m + i];
            if (s2 > best) {
                best = s2;
                piv = j;
            }
        }
        if (piv != k)
            for (i = 0; i < m; ++i) {
                const double t = a[k * m + i];
                a[k * m + i] = a[piv * m + i];
                a[piv * m + i] = t;
            }
        ak = a + k * m;
        alpha = ak[k];
        for (i = k + 1; i < m; ++i)
            xnorm += ak[i] * ak[i];
        tau[k] = 0.0;
        if (xnorm == 0.0)
            continue; /* already triangular in this column: H = I */
        beta = -copysign(sqrt(alpha * alpha + xnorm), alpha);
        tau[k] = (beta - alpha) / beta;
        {
            const double inv = 1.0 / (alpha - beta); /* |alpha - beta| >= |beta| > 0 */
            for (i = k + 1; i < m; ++i)
                ak[i] *= inv;
        }
        ak[k] = beta;
        for (j = k + 1; j < m; ++j) /* H on the later columns */
            wk_reflect(m, k, ak, tau[k], a + j * m);
    }
    for (j = 0; j < m; ++j) /* column j of X = R^T is row j of R */
        for (i = 0; i < m; ++i) {
            wt[j * m + i] = i >= j ? a[i * m + j] : 0.0;
            vt[j * m + i] = (i == j) ? 1.0 : 0.0;
        }
    for (sweep = 0; sweep < WK_NULL_SWEEPS && rotated; ++sweep) {
        rotated = 0;
        for (j = 0; j < m; ++j) /* the squared column norms, exact at each sweep's start, updated by the rotations */
            nrm2[j] = wk_jacobi_dot(m, wt + j * m, wt + j * m);
        for (p = 0; p < m - 1; ++p)
            for (q = p + 1; q < m; ++q) {
                double *wp = wt + p * m, *wq = wt + q * m, *vp = vt + p * m, *vq = vt + q * m;
                const double al = nrm2[p], be = nrm2[q], ga = wk_jacobi_dot(m, wp, wq);
                double zeta, t, cs, sn;
                /* orthogonal to m eps, not eps: at eps a pair whose rotation angle is below one ulp of 1
                 * (cos rounds to 1, sin ~ eps) changes nothing and is "rotated" again every sweep until the cap
                 * (WRISTKIN_TEST_SEED=526, m = 11; 524, m = 17): the sigmas are unaffected at that level */
                if (ga == 0.0 || fabs(ga) <= m * WK_EIG_EPS * sqrt(al) * sqrt(be))
                    continue;
                rotated = 1;
                /* the rotation that zeroes the (p, q) entry of X^T X: t = tan of its angle, the smaller root
                 * of t^2 + 2 zeta t - 1 = 0 (for huge zeta, t ~ 1 / (2 zeta) avoids squaring it) */
                zeta = (be - al) / (2.0 * ga);
                if (fabs(zeta) > 1e150)
                    t = 0.5 / zeta;
                else
                    t = copysign(1.0, zeta) / (fabs(zeta) + sqrt(1.0 + zeta * zeta));
                cs = 1.0 / sqrt(1.0 + t * t);
                sn = cs * t;
                for (i = 0; i < m; ++i) {
                    const double x = wp[i], y = wq[i], c = vp[i], d = vq[i];
                    wp[i] = cs * x - sn * y;
                    wq[i] = sn * x + cs * y;
                    vp[i] = cs * c - sn * d;
                    vq[i] = sn * c + cs * d;
                }
                /* the new norms are al - t ga and be + t ga (the rotation moves t ga from the smaller column to
                 * the larger); the one that shrinks below half of what it was has cancelled bits, so it is summed
                 * again (a column converging onto the null space shrinks by orders of magnitude per rotation) */
                nrm2[p] = al - t * ga;
                nrm2[q] = be + t * ga;
                if (!(nrm2[p] >= 0.5 * al))
                    nrm2[p] = wk_jacobi_dot(m, wp, wp);
                if (!(nrm2[q] >= 0.5 * be))
                    nrm2[q] = wk_jacobi_dot(m, wq, wq);
            }
    }
    if (rotated)
        return WK_EIG_ERR_NOCONV;
    for (k = m - 1; k >= 0; --k) { /* W := Q W = H_0 H_1 ... H_{m-1} W, the last reflector first */
        const double *ak = a + k * m;
        if (tau[k] == 0.0)
            continue;
        for (j = 0; j < m; ++j)
            wk_reflect(m, k, ak, tau[k], vt + j * m);
    }
    for (j = 0; j < m; ++j) {
        const double *w = wt + j * m;
        double amax = 0.0, ss = 0.0;
        for (i = 0; i < m; ++i)
            if (fabs(w[i]) > amax)
                amax = fabs(w[i]);
        if (amax > 0.0)
            for (i = 0; i < m; ++i)
                ss += (w[i] / amax) * (w[i] / amax);
        sig[j] = amax * sqrt(ss); /* scaled sum: a tiny column's norm does not underflow */
        for (i = 0; i < m; ++i)
            V[i * m + j] = vt[j * m + i];
    }
    return WK_EIG_OK;
}

int wk_null_vector(int m, const double *M, double *v, double *rel)
{
    double all[WK_NULL_MAXM];
    int rc;
    if (!M || !v || m < 1 || m > WK_NULL_MAXM)
        return WK_EIG_ERR_INPUT;
    rc = wk_small_singular_vectors(m, M, 1, v, all);
    if (rc == WK_EIG_OK && rel) {
        rel[0] = all[0];
        rel[1] = m > 1 ? all[1] : 1.0;
    }
    return rc;
}

int wk_small_singular_vectors(int m, const double *M, int k, double *v, double *rel)
{
    double V[WK_NULL_MAXM * WK_NULL_MAXM], sig[WK_NULL_MAXM];
    int order[WK_NULL_MAXM], i, j, rc;
    double smax = 0.0;
    if (!M || !v || !rel || m < 1 || m > WK_NULL_MAXM || k < 1 || k > m)
        return WK_EIG_ERR_INPUT;
    if (!wk_eig_finite(m * m, M))
        return WK_EIG_ERR_INPUT;
    rc = wk_jacobi_right(m, M, V, sig);
    if (rc != WK_EIG_OK)
        return rc;
    for (j = 0; j < m; ++j) { /* ascending by insertion, ties in column order (stable) */
        int at = j;
        while (at > 0 && sig[order[at - 1]] > sig[j]) {
            order[at] = order[at - 1];
            --at;
        }
        order[at] = j;
        if (sig[j] > smax)
            smax = sig[j];
    }
    for (j = 0; j < m; ++j)
        rel[j] = smax > 0.0 ? sig[order[j]] / smax : 0.0;
    for (j = 0; j < k; ++j)
        for (i = 0; i < m; ++i)
            v[j * m + i] = V[i * m + order[j]];
    return WK_EIG_OK;
}

/* LU with complete pivoting (P M Q = L U) and inverse iteration: the cheap route to a null vector when M is
 * known to be (nearly) singular with a one-dimensional null space, as M(x) at a simple eigenvalue x is. The
 * start vector is the exact null vector of U with its last pivot set to zero (complete pivoting puts the
 * smallest pivot last), then two steps w = (M^T M)^-1 v, v = w / |w| through the same factors; a pivot below
 * eps |u_11| is replaced by that (the usual perturbation of inverse iteration: it changes M by at most
 * eps ||M|| and keeps the solves finite). M^T M, not M: inverse iteration with M alone converges to the
 * eigenvector of M's smallest eigenvalue, whose residual is sigma_min / |cos(left, right null vectors)| --
 * 80 times sigma_min in a 3 x 3 test case. Each step shrinks the component outside the right singular
 * vector by (sigma_min / sigma_2)^2, so at an eigenvalue one step already reaches rounding level. */
int wk_null_vector_lu(int m, const double *M, double *v, double *resid)
{
    double U[WK_NULL_MAXM * WK_NULL_MAXM], S[WK_NULL_MAXM * WK_NULL_MAXM], z[WK_NULL_MAXM];
    double floor_piv, nrm, fro = 0.0, res = 0.0;
    int pcol[WK_NULL_MAXM]; /* P is not needed: it only ever appears as P P^T */
    int i, j, k, it, e;
    if (!M || !v || m < 1 || m > WK_NULL_MAXM)
        return WK_EIG_ERR_INPUT;
    if (resid)
        *resid = 0.0;
    if (!wk_eig_finite(m * m, M))
        return WK_EIG_ERR_INPUT;
    e = wk_eig_exponent(m * m, M);
    for (i = 0; i < m * m; ++i) {
        S[i] = U[i] = ldexp(M[i], -e); /* S: the scaled M, kept for the residual */
        fro += S[i] * S[i];
    }
    fro = sqrt(fro);
    if (fro == 0.0) {
        for (i = 0; i < m; ++i)
            v[i] = (i == 0) ? 1.0 : 0.0;
        return WK_EIG_OK;
    }
    for (k = 0; k < m; ++k) {
        int pi = k, pj = k;
        for (i = k; i < m; ++i)
            for (j = k; j < m; ++j)
                if (fabs(U[i * m + j]) > fabs(U[pi * m + pj])) {
                    pi = i;
                    pj = j;
                }
        pcol[k] = pj;
        for (j = 0; j < m; ++j) { /* rows k <-> pi (whole rows: L's multipliers move with them) */
            double t = U[k * m + j];
            U[k * m + j] = U[pi * m + j];
            U[pi * m + j] = t;
        }
        for (i = 0; i < m; ++i) { /* columns k <-> pj */
            double t = U[i * m + k];
            U[i * m + k] = U[i * m + pj];
            U[i * m + pj] = t;
        }
        if (U[k * m + k] == 0.0)
            continue; /* the rest is zero: nothing to eliminate */
        for (i = k + 1; i < m; ++i) {
            double f = U[i * m + k] /= U[k * m + k];
            for (j = k + 1; j < m; ++j)
                U[i * m + j] -= f * U[k * m + j];
        }
    }
    floor_piv = WK_EIG_EPS * fabs(U[0]);
    for (k = 0; k < m; ++k)
        if (fabs(U[k * m + k]) < floor_piv)
            U[k * m + k] = copysign(floor_piv, U[k * m + k]);
    /* start: U z = 0 with z_last = 1 and the last pivot taken as zero */
    z[m - 1] = 1.0;
    for (i = m - 2; i >= 0; --i) {
        double s = 0.0;
        for (j = i + 1; j < m; ++j)
            s -= U[i * m + j] * z[j];
        z[i] = s / U[i * m + i];
    }
    for (it = 0; it < 3; ++it) {
        double amax = 0.0;
        if (it > 0) { /* z = M^-1 M^-T v = (Q U^-1 L^-1 P)(P^T L^-T U^-T Q^T) v, the Q of the end applied below */
            for (i = 0; i < m; ++i)
                z[i] = v[i];
            for (k = 0; k < m; ++k) { /* Q^T */
                double t = z[k];
                z[k] = z[pcol[k]];
                z[pcol[k]] = t;
            }
            for (i = 0; i < m; ++i) { /* U^-T */
                for (j = 0; j < i; ++j)
                    z[i] -= U[j * m + i] * z[j];
                z[i] /= U[i * m + i];
            }
            for (i = m - 2; i >= 0; --i) /* L^-T */
                for (j = i + 1; j < m; ++j)
                    z[i] -= U[j * m + i] * z[j];
            for (j = 0; j < m; ++j) /* rescaled between the solves: together they reach 1 / sigma_min^2 */
                if (fabs(z[j]) > amax)
                    amax = fabs(z[j]);
            if (!(amax > 0.0) || !isfinite(amax))
                return WK_EIG_ERR_NOCONV;
            for (j = 0; j < m; ++j)
                z[j] /= amax;
            amax = 0.0;
            /* P^T and then P cancel (P P^T = I): z goes straight into the L solve */
            for (i = 1; i < m; ++i)
                for (j = 0; j < i; ++j)
                    z[i] -= U[i * m + j] * z[j];
            for (i = m - 1; i >= 0; --i) {
                for (j = i + 1; j < m; ++j)
                    z[i] -= U[i * m + j] * z[j];
                z[i] /= U[i * m + i];
            }
        }
        for (k = m - 1; k >= 0; --k) { /* v = Q z */
            double t = z[k];
            z[k] = z[pcol[k]];
            z[pcol[k]] = t;
        }
        for (i = 0; i < m; ++i) /* normalised in two steps: the solve can be huge (1 / sigma_min) */
            if (fabs(z[i]) > amax)
                amax = fabs(z[i]);
        if (!(amax > 0.0) || !isfinite(amax))
            return WK_EIG_ERR_NOCONV;
        nrm = 0.0;
        for (i = 0; i < m; ++i) {
            v[i] = z[i] / amax;
            nrm += v[i] * v[i];
        }
        nrm = sqrt(nrm);
        for (i = 0; i < m; ++i)
            v[i] /= nrm;
    }
    for (i = 0; i < m; ++i) {
        double s = 0.0;
        for (j = 0; j < m; ++j)
            s += S[i * m + j] * v[j];
        res += s * s;
    }
    if (resid)
        *resid = sqrt(res) / fro;
    return WK_EIG_OK;
}
