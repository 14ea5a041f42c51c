/* wristkin runtime: what every generated mechanism shares (generated, do not edit). C99, libm only.
 * @generated-by@
 *
 * A mechanism is usable by copying its M.h / M.c plus wristkin_common.h and this file. */
#include "wristkin_common.h"

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>

/* 2 pi = WK_TWO_PI_HI + WK_TWO_PI_LO + O(6e-33), from pi at high precision: derive/angle_reduction.py computes
 * these constants and tests/test_runtime_sources.py holds them equal */
#define WK_PI_BELOW 3.141592653589793 /* fl(pi) < pi: |a| up to it is reduced already */
#define WK_TWO_PI_HI 0x1.921fb54442d18p+2
#define WK_TWO_PI_LO 0x1.1a62633145c07p-52
#define WK_ONE_TURN_MAX 9.4 /* < 3 pi: one turn from the reduced angle */
#define WK_WINDOW_WORDS 8

/* The bits of 1 / (2 pi) after the binary point, 32 per word, most significant first: the words up to the largest
 * double's exponent plus a window of WK_WINDOW_WORDS. */
static const uint32_t wk_inv_two_pi[38] = {
    0x28be60dbu, 0x9391054au, 0x7f09d5f4u, 0x7d4d3770u, 0x36d8a566u, 0x4f10e410u,
    0x7f9458eau, 0xf7aef158u, 0x6dc91b8eu, 0x909374b8u, 0x01924bbau, 0x82746487u,
    0x3f877ac7u, 0x2c4a69cfu, 0xba208d7du, 0x4baed121u, 0x3a671c09u, 0xad17df90u,
    0x4e64758eu, 0x60d4ce7du, 0x272117e2u, 0xef7e4a0eu, 0xc7fe25ffu, 0xf7816603u,
    0xfbcbc462u, 0xd6829b47u, 0xdb4d9fb3u, 0xc9f2c26du, 0xd3d18fd9u, 0xa797fa8bu,
    0x5d49eeb1u, 0xfaf97c5eu, 0xcf41ce7du, 0xe294a4bau, 0x9afed7ecu, 0x47e35742u,
    0x1580cc11u, 0xbf1edaeau
};

/* limb[pos..] += t (32-bit limbs, least significant first; the caller's sum fits) */
static void wk_limb_add(uint32_t *limb, int pos, uint64_t t)
{
    uint64_t carry = t;
    while (carry) {
        const uint64_t sum = (uint64_t)limb[pos] + (carry & 0xffffffffu);
        limb[pos] = (uint32_t)sum;
        carry = (carry >> 32) + (sum >> 32);
        ++pos;
    }
}

/* bits [p, p + 64) of the limbs */
static uint64_t wk_limb_bits(const uint32_t *limb, int p)
{
    const int i = p / 32, sh = p % 32;
    const uint64_t low = (uint64_t)limb[i] | (uint64_t)limb[i + 1] << 32;
    return sh ? low >> sh | (uint64_t)limb[i + 2] << (64 - sh) : low;
}

/* x > WK_ONE_TURN_MAX, finite: x = mant 2^e; the fraction of x / (2 pi) is that of mant times the window of
 * 1 / (2 pi) starting at the first word whose bits are not all multiplied into integers (a 53 x 256-bit product:
 * the words beyond add under 2^-172 turn). Its 128 bits below the binary point, as the signed fraction nearest
 * 0, times 2 pi in double-double. A double's reduced angle is at least 4.7e-19 rad (the closest multiple of
 * pi / 2 is 6381956970095103 x 2^797), so the 128 bits hold 66 significant ones and the result is correctly
 * rounded up to 2^-100 of itself. */
static double wk_reduce_far(double x)
{
    uint32_t limb[WK_WINDOW_WORDS + 2] = {0};
    int ex, e, i0, j, b;
    uint64_t mant, hi, lo, back;
    double sign = 1.0, fh, fl, dh, p;
    mant = (uint64_t)ldexp(frexp(x, &ex), 53);
    e = ex - 53; /* >= -49 as x > 9.4 */
    i0 = e > 0 ? e / 32 : 0;
    for (j = 0; j < WK_WINDOW_WORDS; ++j) {
        const uint64_t w = wk_inv_two_pi[i0 + j];
        wk_limb_add(limb, WK_WINDOW_WORDS - 1 - j, w * (mant & 0xffffffffu));
        wk_limb_add(limb, WK_WINDOW_WORDS - j, w * (mant >> 32));
    }
    b = 32 * WK_WINDOW_WORDS - (e - 32 * i0); /* the binary point, in bits from the least significant */
    hi = wk_limb_bits(limb, b - 64);
    lo = wk_limb_bits(limb, b - 128);
    if (hi >> 63) { /* fraction >= 1/2: the nearest turn is above, negate the 128-bit fraction */
        lo = ~lo + 1u;
        hi = ~hi + (lo == 0u);
        sign = -1.0;
    }
    fh = (double)hi;
    back = (uint64_t)fh;
    dh = back >= hi ? -(double)(back - hi) : (double)(hi - back);
    fl = (dh + (double)lo * 0x1p-64) * 0x1p-64;
    fh *= 0x1p-64;
    p = fh * WK_TWO_PI_HI;
    return sign * (p + (fma(fh, WK_TWO_PI_HI, -p) + (fh * WK_TWO_PI_LO + fl * WK_TWO_PI_HI)));
}

double wk_wrap(double a)
{
    const double x = fabs(a);
    double r;
    if (!(x > WK_PI_BELOW)) return a;
    if (x <= WK_ONE_TURN_MAX)
        r = (x - WK_TWO_PI_HI) - WK_TWO_PI_LO; /* x - fl(2 pi) is exact (Sterbenz) */
    else if (x <= DBL_MAX)
        r = wk_reduce_far(x);
    else
        return a - a; /* inf: NaN */
    return a < 0.0 ? -r : r;
}

const char *wk_strerror(int code)
{
    switch (code) {
    case WK_OK: return "ok";
    case WK_ERR_NULL: return "a required pointer is NULL";
    case WK_ERR_NONFINITE: return "input is not finite (NaN or inf)";
    case WK_ERR_DESIGN: return "design parameters out of range or not assemblable";
    case WK_ERR_RANGE: return "argument out of range";
    default: return "unknown error";
    }
}

int wk_all_finite(const double *v, int n)
{
    int i;
    for (i = 0; i < n; ++i)
        if (!isfinite(v[i])) return 0;
    return 1;
}

static double wk_dot3(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void wk_cross3(const double *a, const double *b, double *c)
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

/* With P = g1 g2 g3, c_i = x_j x x_k ((i, j, k) cyclic) and D = det X:
 * 1/kappa_F = 3 |D P| / (sqrt(sum_i |x_i|^2 (g_j g_k)^2) sqrt(sum_i |c_i|^2 g_i^2)): J^-1 = X^-1 diag(g) has
 * columns c_i g_i / D, J has rows x_i / g_i; both norms multiplied out so no g_i or D divides. 0 when the
 * denominator vanishes; rounding can put an isotropic J a few ulps above 1, clamped. */
double wk_inverse_kappa_f(const double x[9], const double g[3])
{
    const double g12 = g[0] * g[1], g23 = g[1] * g[2], g31 = g[2] * g[0];
    double c[9], det, n_j, n_adj, den, num, out;
    wk_cross3(x + 3, x + 6, c);
    wk_cross3(x + 6, x, c + 3);
    wk_cross3(x, x + 3, c + 6);
    det = wk_dot3(x, c);
    n_j = wk_dot3(x, x) * (g23 * g23) + wk_dot3(x + 3, x + 3) * (g31 * g31) + wk_dot3(x + 6, x + 6) * (g12 * g12);
    n_adj = wk_dot3(c, c) * g[0] * g[0] + wk_dot3(c + 3, c + 3) * g[1] * g[1] + wk_dot3(c + 6, c + 6) * g[2] * g[2];
    den = sqrt(n_j) * sqrt(n_adj);
    num = 3.0 * fabs(det * g[0] * g[1] * g[2]);
    if (!(den > 0.0)) return 0.0;
    out = num / den;
    return out < 1.0 ? out : 1.0;
}

/* Newton's polar iteration X <- (X + X^-T) / 2 converges quadratically from a deviation of 1e-6: two steps reach
 * rounding level; four are run. */
int wk_input_rotation(const double *p, double r[9], double *deviation)
{
    int i, j, k, it;
    double dev = 0.0, det;
    for (i = 0; i < 3; ++i)
        for (j = 0; j < 3; ++j) {
            double dot = 0.0;
            for (k = 0; k < 3; ++k) dot += p[4 * k + i] * p[4 * k + j];
            dot = fabs(dot - (i == j ? 1.0 : 0.0));
            if (!(dot <= dev)) dev = dot; /* NaN-propagating max */
        }
    for (i = 0; i < 3; ++i)
        for (j = 0; j < 3; ++j) r[3 * i + j] = p[4 * i + j];
    det = r[0] * (r[4] * r[8] - r[5] * r[7]) - r[1] * (r[3] * r[8] - r[5] * r[6]) + r[2] * (r[3] * r[7] - r[4] * r[6]);
    if (!(dev <= WK_ROTATION_PROJECT_TOL) || !(det > 0.0)) return 0;
    *deviation = 0.0;
    if (dev <= WK_ROTATION_EXACT_TOL) return 1;
    for (it = 0; it < 4; ++it) {
        /* X^-T = cofactor(X) / det(X) */
        double cof[9];
        cof[0] = r[4] * r[8] - r[5] * r[7];
        cof[1] = r[5] * r[6] - r[3] * r[8];
        cof[2] = r[3] * r[7] - r[4] * r[6];
        cof[3] = r[2] * r[7] - r[1] * r[8];
        cof[4] = r[0] * r[8] - r[2] * r[6];
        cof[5] = r[1] * r[6] - r[0] * r[7];
        cof[6] = r[1] * r[5] - r[2] * r[4];
        cof[7] = r[2] * r[3] - r[0] * r[5];
        cof[8] = r[0] * r[4] - r[1] * r[3];
        det = r[0] * cof[0] + r[1] * cof[1] + r[2] * cof[2];
        for (k = 0; k < 9; ++k) r[k] = 0.5 * (r[k] + cof[k] / det);
    }
    *deviation = dev;
    return 1;
}

int wk_input_frame(const double *in, double out[12])
{
    double r[9], dev = 0.0;
    int i;
    if (!wk_all_finite(in, 12)) return WK_ERR_NONFINITE;
    if (!wk_input_rotation(in, r, &dev)) return WK_ERR_DESIGN;
    for (i = 0; i < 3; ++i) {
        out[4 * i] = r[3 * i];
        out[4 * i + 1] = r[3 * i + 1];
        out[4 * i + 2] = r[3 * i + 2];
        out[4 * i + 3] = in[4 * i + 3];
    }
    return WK_OK;
}

/* Cyclic Jacobi on the symmetric n x n g (row-major, overwritten: its eigenvalues on the diagonal); v (n x n,
 * row-major, or NULL) receives the eigenvectors as columns. */
static void wk_jacobi_sweeps(double *g, int n, double *v)
{
    double scale = 0.0;
    int i, j, k, sweep;
    if (v)
        for (i = 0; i < n * n; ++i) v[i] = i % (n + 1) == 0 ? 1.0 : 0.0;
    for (i = 0; i < n; ++i) scale += g[i * n + i];
    for (sweep = 0; sweep < 50; ++sweep) {
        double off = 0.0;
        for (i = 0; i < n; ++i)
            for (j = i + 1; j < n; ++j) off += g[i * n + j] * g[i * n + j];
        if (!(off > 1e-34 * scale * scale)) break;
        for (i = 0; i < n; ++i)
            for (j = i + 1; j < n; ++j) {
                double theta, t, c, s, tau, gij = g[i * n + j];
                if (gij == 0.0) continue;
                theta = (g[j * n + j] - g[i * n + i]) / (2.0 * gij);
                t = (theta >= 0.0 ? 1.0 : -1.0) / (fabs(theta) + sqrt(theta * theta + 1.0));
                c = 1.0 / sqrt(t * t + 1.0);
                s = t * c;
                tau = s / (1.0 + c);
                g[i * n + i] -= t * gij;
                g[j * n + j] += t * gij;
                g[i * n + j] = g[j * n + i] = 0.0;
                for (k = 0; k < n; ++k) {
                    if (k == i || k == j) continue;
                    {
                        const double gki = g[k * n + i], gkj = g[k * n + j];
                        g[k * n + i] = g[i * n + k] = gki - s * (gkj + tau * gki);
                        g[k * n + j] = g[j * n + k] = gkj + s * (gki - tau * gkj);
                    }
                }
                if (v)
                    for (k = 0; k < n; ++k) {
                        const double vki = v[k * n + i], vkj = v[k * n + j];
                        v[k * n + i] = vki - s * (vkj + tau * vki);
                        v[k * n + j] = vkj + s * (vki - tau * vkj);
                    }
            }
    }
}

double wk_jacobi_spectrum(double *g, int n, double *ratio)
{
    double prod = 1.0, lo = HUGE_VAL, hi = 0.0;
    int i;
    if (n < 1 || n > WK_MAX_DIM) {
        *ratio = 0.0;
        return 0.0;
    }
    wk_jacobi_sweeps(g, n, NULL);
    for (i = 0; i < n; ++i) {
        const double l = g[i * n + i] > 0.0 ? g[i * n + i] : 0.0;
        prod *= l;
        if (l < lo) lo = l;
        if (l > hi) hi = l;
    }
    *ratio = hi > 0.0 ? sqrt(lo / hi) : 0.0;
    return sqrt(prod);
}

double wk_jacobi_smallest(double *g, int n, double *v)
{
    double vecs[WK_MAX_DIM * WK_MAX_DIM];
    int i, lo = 0;
    if (n < 1 || n > WK_MAX_DIM) return -1.0;
    wk_jacobi_sweeps(g, n, vecs);
    for (i = 1; i < n; ++i)
        if (g[i * n + i] < g[lo * n + lo]) lo = i;
    for (i = 0; i < n; ++i) v[i] = vecs[i * n + lo];
    return g[lo * n + lo];
}

/* 1 when g - shift I (m x m, row-major, symmetric) is positive definite: its Cholesky factorisation has positive
 * pivots; *prod = the product of the pivots' square roots, sqrt(det(g - shift I)). */
static int wk_cholesky(const double *g, int m, double shift, double *prod)
{
    double l[WK_MAX_DIM][WK_MAX_DIM], p = 1.0;
    int i, j, k;
    for (j = 0; j < m; ++j) {
        double d = g[j * m + j] - shift;
        for (k = 0; k < j; ++k) d -= l[j][k] * l[j][k];
        if (!(d > 0.0)) return 0;
        l[j][j] = sqrt(d);
        p *= l[j][j];
        for (i = j + 1; i < m; ++i) {
            double acc = g[i * m + j];
            for (k = 0; k < j; ++k) acc -= l[i][k] * l[j][k];
            l[i][j] = acc / l[j][j];
        }
    }
    *prod = p;
    return 1;
}

/* 1 when |det J| / ||J||_F^6 of a 6 x 6 J proves sigma_min / sigma_max above eps: sigma_max <= ||J||_F and
 * sigma_min >= |det J| / sigma_max^5, so the ratio is at least |det J| / ||J||_F^6. The factor-4 margin dwarfs
 * the rounding of the determinant by elimination with partial pivoting (relative ~1e-15 / ratio <= 1e-10 where
 * the bound can prove anything). ~70 flops: most configurations are proven here, before the Gram matrix. *man:
 * |det J|, the product of the singular values (the manipulability). */
static int wk_det_proves_regular(const double *jac, double eps, double *man)
{
    double a[36], det = 1.0, f2 = 0.0;
    int i, j, k;
    for (i = 0; i < 36; ++i) {
        a[i] = jac[i];
        f2 += jac[i] * jac[i];
    }
    if (!(f2 > 0.0)) return 0;
    for (k = 0; k < 6; ++k) {
        int p = k;
        for (i = k + 1; i < 6; ++i)
            if (fabs(a[i * 6 + k]) > fabs(a[p * 6 + k])) p = i;
        if (!(a[p * 6 + k] != 0.0)) return 0;
        if (p != k) {
            for (j = k; j < 6; ++j) {
                const double t = a[k * 6 + j];
                a[k * 6 + j] = a[p * 6 + j];
                a[p * 6 + j] = t;
            }
        }
        det *= a[k * 6 + k];
        for (i = k + 1; i < 6; ++i) {
            const double m = a[i * 6 + k] / a[k * 6 + k];
            for (j = k + 1; j < 6; ++j) a[i * 6 + j] -= m * a[k * 6 + j];
        }
    }
    *man = fabs(det);
    return fabs(det) > 4.0 * eps * f2 * f2 * f2;
}

/* The ratio within a factor ~7 of eps (near a singularity, sigma_min ~ eps sigma_max: the sets of a sweep 1e-5 rad
 * from an elbow singularity) leaves [max G_ii, trace G] too loose a bracket on lambda_max. Power steps from G's
 * largest column give L <= lambda_max (a Rayleigh quotient), and U I - G positive definite proves lambda_max < U
 * (U = 1.01 L after up to 24 steps, 6 at a time; else 1.0625 L, 1.59 L: two close largest singular values slow the
 * steps down). Then G - 1.05 eps^2 U I positive definite proves the ratio above eps, G - 0.95 eps^2 L I not
 * positive definite proves it below: margins of 0.05 eps^2 lambda_max, ~12x the backward error of G's Cholesky
 * factor (~4e-15 lambda_max; so only for eps >= 1e-6). 1 / -1 / 0 as wk_conditioning_bound; 0 leaves the ratio
 * within ~3 % of eps (~30 % when U is 1.59 L) to the caller's SVD, which took 2/3 of such calls' time before (a
 * tx2_60's sets 3.4 % from eps still went there with 5 % margins). */
static double wk_power_steps(const double *g, int m, double *v, int steps)
{
    double w[WK_MAX_DIM], vv = 0.0, vgv = 0.0;
    int i, j, it;
    for (it = 0; it < steps; ++it) {
        double norm = 0.0;
        for (i = 0; i < m; ++i) {
            w[i] = 0.0;
            for (j = 0; j < m; ++j) w[i] += g[i * m + j] * v[j];
            norm += w[i] * w[i];
        }
        if (!(norm > 0.0)) return 0.0;
        norm = 1.0 / sqrt(norm);
        for (i = 0; i < m; ++i) v[i] = w[i] * norm;
    }
    for (i = 0; i < m; ++i) {
        double gv = 0.0;
        for (j = 0; j < m; ++j) gv += g[i * m + j] * v[j];
        vv += v[i] * v[i];
        vgv += v[i] * gv;
    }
    return vgv / vv; /* the Rayleigh quotient: at most lambda_max */
}

static int wk_bracket_bound(const double *g, int m, double e2, double dmax)
{
    double v[WK_MAX_DIM], h[WK_MAX_DIM * WK_MAX_DIM], lo = dmax, hi = 0.0, unused;
    int i, chunk, top = 0;
    for (i = 1; i < m; ++i)
        if (g[i * m + i] > g[top * m + top]) top = i;
    for (i = 0; i < m; ++i) v[i] = g[i * m + top];
    for (i = 0; i < m * m; ++i) h[i] = -g[i];
    for (chunk = 0; chunk < 4 && hi == 0.0; ++chunk) {
        const double rq = wk_power_steps(g, m, v, 6);
        if (!(rq > 0.0)) return 0;
        if (rq > lo) lo = rq;
        if (!wk_cholesky(g, m, 0.95 * e2 * lo, &unused)) return -1; /* below: L alone suffices */
        if (wk_cholesky(h, m, -1.01 * lo, &unused)) hi = 1.01 * lo;
    }
    if (hi == 0.0 && wk_cholesky(h, m, -1.0625 * lo, &unused)) hi = 1.0625 * lo;
    if (hi == 0.0) {
        if (!wk_cholesky(h, m, -1.59 * lo, &unused)) return 0;
        hi = 1.59 * lo;
    }
    return wk_cholesky(g, m, 1.05 * e2 * hi, &unused) ? 1 : 0;
}

int wk_conditioning_bound(const double *jac, int n, double eps, double *man)
{
    double g[WK_MAX_DIM * WK_MAX_DIM], tr = 0.0, dmax = 0.0, unused;
    const double e2 = eps * eps;
    const int m = n <= 6 ? n : 6;
    int i, j, k;
    if (n < 1 || n > WK_MAX_DIM) return 0;
    if (n == 6) {
        double det;
        if (wk_det_proves_regular(jac, eps, &det)) {
            if (man) *man = det;
            return 1;
        }
    }
    for (i = 0; i < m; ++i)
        for (j = 0; j <= i; ++j) {
            double acc = 0.0;
            if (n <= 6)
                for (k = 0; k < 6; ++k) acc += jac[k * n + i] * jac[k * n + j];
            else
                for (k = 0; k < n; ++k) acc += jac[i * n + k] * jac[j * n + k];
            g[i * m + j] = g[j * m + i] = acc;
        }
    for (i = 0; i < m; ++i) {
        tr += g[i * m + i];
        if (g[i * m + i] > dmax) dmax = g[i * m + i];
    }
    if (!(tr > 0.0)) return 0; /* J = 0 (or not finite): the caller's spectrum says so */
    /* lambda_max of G lies in [max G_ii, trace G], and sigma_min^2 / sigma_max^2 = lambda_min / lambda_max: G -
     * 2 eps^2 trace I positive definite proves the ratio above eps, G - eps^2 max G_ii / 2 not positive definite
     * proves it below. The factor-2 margins dwarf the rounding of G and of its Cholesky factor (~1e-14 lambda_max
     * against eps^2). */
    if (wk_cholesky(g, m, 2.0 * e2 * tr, &unused)) return !man || wk_cholesky(g, m, 0.0, man) ? 1 : 0;
    if (!wk_cholesky(g, m, 0.5 * e2 * dmax, &unused)) return -1;
    if (!(e2 >= 0.99e-12)) return 0; /* the bracket's margins need eps >= 1e-6 (1e-6 squared rounds below 1e-12) */
    k = wk_bracket_bound(g, m, e2, dmax);
    return k == 1 ? (!man || wk_cholesky(g, m, 0.0, man) ? 1 : 0) : k;
}

int wk_lu_factor(const double *a, int n, double rel_pivot, double *lu, int *perm)
{
    double big = 0.0;
    int i, j, k;
    if (n < 1 || n > WK_MAX_DIM) return 0;
    for (i = 0; i < n * n; ++i) {
        lu[i] = a[i];
        if (fabs(a[i]) > big) big = fabs(a[i]);
    }
    for (i = 0; i < n; ++i) perm[i] = i;
    for (k = 0; k < n; ++k) {
        double *pk;
        int p = k;
        for (i = k + 1; i < n; ++i)
            if (fabs(lu[i * n + k]) > fabs(lu[p * n + k])) p = i;
        if (!(fabs(lu[p * n + k]) > rel_pivot * big)) return 0; /* a NaN fails too */
        if (p != k) {
            const int t = perm[p];
            perm[p] = perm[k];
            perm[k] = t;
            for (j = 0; j < n; ++j) {
                const double v = lu[p * n + j];
                lu[p * n + j] = lu[k * n + j];
                lu[k * n + j] = v;
            }
        }
        pk = lu + k * n;
        for (i = k + 1; i < n; ++i) {
            double *r = lu + i * n;
            const double m = r[k] / pk[k];
            r[k] = m;
            for (j = k + 1; j < n; ++j) r[j] -= m * pk[j];
        }
    }
    return 1;
}

void wk_lu_solve(const double *lu, const int *perm, int n, const double *b, double *x)
{
    double y[WK_MAX_DIM];
    int i, j;
    for (i = 0; i < n; ++i) y[i] = b[perm[i]];
    for (j = 0; j < n; ++j)
        for (i = j + 1; i < n; ++i) y[i] -= lu[i * n + j] * y[j];
    for (i = n - 1; i >= 0; --i) {
        double acc = y[i];
        for (j = i + 1; j < n; ++j) acc -= lu[i * n + j] * x[j];
        x[i] = acc / lu[i * n + i];
    }
}

int wk_square_solve(const double *a, int n, const double *b, double rel_pivot, double *x)
{
    double lu[WK_MAX_DIM * WK_MAX_DIM];
    int perm[WK_MAX_DIM];
    if (!wk_lu_factor(a, n, rel_pivot, lu, perm)) return 0;
    wk_lu_solve(lu, perm, n, b, x);
    return 1;
}

int wk_normal_solve(const double *jac, int n, const double *e, double damping, double *x)
{
    /* a column of J that is exactly 0 (a held joint's, zeroed by the caller) is left out: its row and column of
     * J^T J + damping I hold the damping alone, so its step is 0 and the others' elimination is the same operations
     * on the remaining m x m system (a pivot search never takes that row: its entry is 0 where another's is not).
     * G is symmetric: its upper triangle is summed and mirrored (the same products in the same order) */
    double g[WK_MAX_DIM][WK_MAX_DIM + 1], xs[WK_MAX_DIM], a[WK_MAX_DIM][6];
    int col[WK_MAX_DIM], i, j, k, m = 0;
    if (n < 1 || n > WK_MAX_DIM) return 0;
    for (j = 0; j < n; ++j) { /* the kept columns, each contiguous */
        int zero = 1;
        for (k = 0; k < 6; ++k) {
            a[m][k] = jac[k * n + j];
            zero &= a[m][k] == 0.0;
        }
        if (!zero || !(damping > 0.0)) col[m++] = j; /* undamped, a zero column makes the system singular */
        xs[j] = 0.0;
    }
    for (i = 0; i < m; ++i) {
        for (j = i; j < m; ++j) {
            double acc = i == j ? damping : 0.0;
            for (k = 0; k < 6; ++k) acc += a[i][k] * a[j][k];
            g[i][j] = g[j][i] = acc;
        }
        g[i][m] = 0.0;
        for (k = 0; k < 6; ++k) g[i][m] += a[i][k] * e[k];
    }
    for (i = 0; i < m; ++i) {
        int piv = i;
        for (k = i + 1; k < m; ++k)
            if (fabs(g[k][i]) > fabs(g[piv][i])) piv = k;
        if (g[piv][i] == 0.0) return 0;
        for (j = 0; j <= m; ++j) {
            const double t = g[i][j];
            g[i][j] = g[piv][j];
            g[piv][j] = t;
        }
        for (k = i + 1; k < m; ++k) {
            const double f = g[k][i] / g[i][i];
            for (j = i; j <= m; ++j) g[k][j] -= f * g[i][j];
        }
    }
    for (i = m - 1; i >= 0; --i) {
        double acc = g[i][m];
        for (j = i + 1; j < m; ++j) acc -= g[i][j] * xs[col[j]];
        xs[col[i]] = acc / g[i][i];
    }
    for (j = 0; j < n; ++j) x[j] = xs[j];
    return 1;
}

int wk_select(int max_sets, int n, const int *valid, const unsigned *flags, const double *values, const int *revolute,
              const double *previous, const double *lower, const double *upper, const double *weights)
{
    int k, j, best = -1, best_regular = 0;
    double best_w = 0.0, best_plain = 0.0;
    if (!valid || !flags || !values || !revolute) return -1;
    for (k = 0; k < max_sets; ++k) {
        const int regular = !(flags[k] & (WK_FLAG_SINGULAR_INVERSE | WK_FLAG_SINGULAR_DIRECT));
        double dw = 0.0, dp = 0.0;
        int ok = valid[k];
        for (j = 0; ok && j < n; ++j) {
            const double v = values[k * n + j];
            if ((lower && v < lower[j]) || (upper && v > upper[j])) ok = 0;
        }
        if (!ok) continue;
        if (previous) {
            for (j = 0; j < n; ++j) {
                double d = values[k * n + j] - previous[j];
                if (revolute[j]) d = wk_wrap(wk_wrap(values[k * n + j]) - wk_wrap(previous[j]));
                d = fabs(d);
                dw += (weights ? weights[j] : 1.0) * d;
                dp += d;
            }
            if (best < 0 || dw < best_w || (dw == best_w && dp < best_plain)) {
                best = k;
                best_w = dw;
                best_plain = dp;
            }
        } else if (best < 0 || (regular && !best_regular)) {
            best = k;
            best_regular = regular;
        }
    }
    return best;
}

/* Two valid sets that differ only in the branch of one two-root stage (sets k and k | 1 << bit) are one solution,
   a double root, when the pose cannot tell them apart: a point between them fits the pose as well as they do.
   At a fold of the chain the residual grows with the square of the distance along the fold, so the joints solved
   before the stage, off by rounding (1e-13 where the pose's 12 entries over-determine a 5-joint chain), push the
   two computed roots ~1e-6 apart, and both fit the pose to rounding; their midpoint then misses it only by that
   upstream error, at first order, which one Gauss-Newton step removes with a step far shorter than the pair's
   span. Two distinct roots leave the midpoint off the pose by curvature x (span / 2)^2 along the fold, which a
   short step cannot remove (reaching either root takes span / 2). So: refit(midpoint, span / 8) within
   WK_MERGE_ULPS eps max(1, scale) (the FK's own rounding of a pose of that size) of the pair's residuals. The pair
   becomes whichever of the two and the refitted midpoint fits best, flagged a double root. Pairs farther apart than
   WK_MERGE_SPAN in a joint are not compared: at a curvature above 1e-7 their midpoint misses by more than the
   floor, and it bounds the extra work to near-coincident pairs (wristkin_common.h's WK_MERGE_SPAN). Returns the
   number of sets removed. */
double wk_fk_rounding(double scale)
{
    return WK_MERGE_ULPS * DBL_EPSILON * (scale > 1.0 ? scale : 1.0);
}

int wk_drop_carried(int max_sets, int n, const int *revolute, double *values, int *valid, unsigned *flags,
                    double *aux, int aux_stride, const unsigned char *carried)
{
    int k, j, i, dropped = 0;
    for (k = 0; k < max_sets; ++k) {
        if (!valid[k] || !carried[k]) continue;
        for (j = 0; j < max_sets; ++j) {
            if (j == k || !valid[j] || (carried[j] && j > k)) continue;
            if (wk_same_set(n, revolute, values + (size_t)k * (size_t)n, values + (size_t)j * (size_t)n)) {
                valid[k] = 0;
                flags[k] = 0u;
                for (i = 0; i < n; ++i) values[k * n + i] = NAN;
                for (i = 0; i < aux_stride; ++i) aux[k * aux_stride + i] = NAN;
                ++dropped;
                break;
            }
        }
    }
    return dropped;
}

double wk_set_gap(int n, const int *revolute, const double *x, const double *y, double stop)
{
    double gap = 0.0;
    int j;
    for (j = 0; j < n; ++j) {
        const double d = fabs((!revolute || revolute[j]) ? wk_wrap(y[j] - x[j]) : y[j] - x[j]);
        if (!(d <= gap)) {
            gap = d;
            if (!(gap <= stop)) break; /* most pairs compared are apart: stop at the first joint beyond */
        }
    }
    return gap;
}

int wk_same_set(int n, const int *revolute, const double *x, const double *y)
{
    return wk_set_gap(n, revolute, x, y, WK_SAME_SET) <= WK_SAME_SET;
}

double wk_pair_indistinct(int n, const int *revolute, const double *x, double rx, const double *y, double ry,
                          wk_refit_fn refit, const void *ctx, double floor_, double *mid)
{
    const double span = wk_set_gap(n, revolute, x, y, WK_MERGE_SPAN);
    double accept, rm;
    int j;
    if (!(span <= WK_MERGE_SPAN)) return -1.0;
    for (j = 0; j < n; ++j) {
        const int rev = !revolute || revolute[j];
        mid[j] = x[j] + 0.5 * (rev ? wk_wrap(y[j] - x[j]) : y[j] - x[j]);
        if (rev) mid[j] = wk_wrap(mid[j]);
    }
    accept = (rx > ry ? rx : ry) + floor_;
    rm = refit(mid, 0.125 * span, accept, ctx); /* a midpoint on the pose takes no step */
    return rm <= accept ? rm : -1.0;
}

int wk_merge_indistinct(int max_sets, int n, const int *revolute, const unsigned *masks, int n_masks,
                        double *values, int *valid, unsigned *flags, double *aux, int aux_stride, wk_refit_fn refit,
                        const void *ctx, double scale, int candidates_only)
{
    const double floor_ = wk_fk_rounding(scale);
    int b, k, k2, j, removed = 0;
    double mid[WK_MERGE_MAX_JOINTS];
    unsigned candidate[WK_MERGE_MAX_SETS];
    if (!flags) return 0;
    for (k = 0; k < max_sets; ++k) {
        if (k < WK_MERGE_MAX_SETS) candidate[k] = flags[k] & WK_FLAG_MERGE_CANDIDATE;
        flags[k] &= ~WK_FLAG_MERGE_CANDIDATE; /* internal: never returned */
    }
    if (n > WK_MERGE_MAX_JOINTS || max_sets > WK_MERGE_MAX_SETS || !revolute || !masks || !values || !valid || !aux ||
        !refit)
        return 0;
    for (b = 0; b < n_masks; ++b) {
        const unsigned m = masks[b];
        for (k = 0; k < max_sets; ++k) {
            unsigned sub = 0u;
            if (((unsigned)k & m) == m || !valid[k]) continue; /* every mask bit set: no k2 above k */
            /* k2 = k's bits outside the mask with each nonzero submask of it, ascending (one bit: k2 = k | m) */
            while ((sub = (sub - m) & m) != 0u) {
                double *x, *y, rx, ry, rm;
                k2 = (int)(((unsigned)k & ~m) | sub);
                if (k2 <= k || k2 >= max_sets || !valid[k] || !valid[k2]) continue;
                if (candidates_only && !(candidate[k] && candidate[k2])) continue; /* beyond their stage's noise */
                /* two members of a one-parameter family: the refit's step moves along it, so the midpoint's fit
                   proves nothing, and each is a solution (merge_indistinct says more) */
                if ((flags[k] & WK_FLAG_INDETERMINATE) && (flags[k2] & WK_FLAG_INDETERMINATE)) continue;
                x = values + (size_t)k * (size_t)n;
                y = values + (size_t)k2 * (size_t)n;
                rx = aux[(size_t)k * (size_t)aux_stride];
                ry = aux[(size_t)k2 * (size_t)aux_stride];
                rm = wk_pair_indistinct(n, revolute, x, rx, y, ry, refit, ctx, floor_, mid);
                if (rm < 0.0) continue;
                if (rm < rx && rm < ry) {
                    for (j = 0; j < n; ++j) x[j] = mid[j];
                    aux[(size_t)k * (size_t)aux_stride] = rm;
                } else if (ry < rx) {
                    for (j = 0; j < n; ++j) x[j] = y[j];
                    aux[(size_t)k * (size_t)aux_stride] = ry;
                }
                flags[k] |= flags[k2] | WK_FLAG_DOUBLE_ROOT | WK_FLAG_SINGULAR_INVERSE;
                valid[k2] = 0;
                flags[k2] = 0u;
                aux[(size_t)k2 * (size_t)aux_stride] = NAN;
                for (j = 0; j < n; ++j) y[j] = NAN;
                ++removed;
            }
        }
    }
    return removed;
}
