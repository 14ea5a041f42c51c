/* wristkin: the general 6R arm's inverse kinematics by elimination (C99, libm only; do not edit).
 * @generated-by@
 *
 * See wk_general6r.h; the method is runtime/python/general6r.py's, step for step (the hidden angle t3 deflated to a
 * 16 x 16 eigenproblem, its origin phi chosen alike), except that the 24 x 24 fallback (hidden t4 or t5, or the
 * structure not met) chooses its own leading coefficient (wk_generalized_quadratic_eig: the problem, its reversal
 * or a Moebius rotation), where the Python picks phi. Where the time goes: bench/profile_general6r.c. */
#include "wk_general6r.h"

#include "wk_eigen.h"

#include <math.h>
#include <string.h>

#define G6_NEQ 14
#define G6_NY 8
#define G6_PI 3.14159265358979323846
#define G6_SQRT3 1.73205080756887729353

/* interpolation: the (1, c, s) coefficients of f(t) = c0 + c1 cos t + c2 sin t from f at the grid */
static const double g6_binv[3][3] = { {1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0},
                                     {2.0 / 3.0, -1.0 / 3.0, -1.0 / 3.0},
                                     {0.0, 1.0 / G6_SQRT3, -1.0 / G6_SQRT3} };

static void g6_mul(const double *a, const double *b, double *o)
{
    double t[16];
    int i, j, k;
    for (i = 0; i < 4; ++i)
        for (j = 0; j < 4; ++j) {
            double s = 0.0;
            for (k = 0; k < 4; ++k) s += a[4 * i + k] * b[4 * k + j];
            t[4 * i + j] = s;
        }
    memcpy(o, t, sizeof t);
}

static void g6_inverse(const double *t, double *o)
{
    double r[16];
    int i, j;
    for (i = 0; i < 3; ++i) {
        for (j = 0; j < 3; ++j) r[4 * i + j] = t[4 * j + i];
        r[4 * i + 3] = -(t[i] * t[3] + t[4 + i] * t[7] + t[8 + i] * t[11]);
    }
    r[12] = r[13] = r[14] = 0.0;
    r[15] = 1.0;
    memcpy(o, r, sizeof r);
}

/* cos and sin of the interpolation grid 0, 2 pi / 3, 4 pi / 3 */
static const double g6_grid_cs[3][2] = { {1.0, 0.0}, {-0.5, 0.5 * G6_SQRT3}, {-0.5, -0.5 * G6_SQRT3} };

/* the 14 functions of a line (direction d, point p): d, p, p.p, p.d, p x d, (p.p) d - 2 (p.d) p */
static void g6_fourteen(const double *d, const double *p, double *e)
{
    const double pp = p[0] * p[0] + p[1] * p[1] + p[2] * p[2], pd = p[0] * d[0] + p[1] * d[1] + p[2] * d[2];
    int i;
    for (i = 0; i < 3; ++i) {
        e[i] = d[i];
        e[3 + i] = p[i];
        e[11 + i] = pp * d[i] - 2.0 * pd * p[i];
    }
    e[6] = pp;
    e[7] = pd;
    e[8] = p[1] * d[2] - p[2] * d[1];
    e[9] = p[2] * d[0] - p[0] * d[2];
    e[10] = p[0] * d[1] - p[1] * d[0];
}

/* a line (d, p: 6 doubles) moved by the rigid 4 x 4 t, or turned by Rz of (c, s) (sign -1: Rz(-angle)) */
static void g6_line_move(const double *t, const double *l, double *o)
{
    int i;
    for (i = 0; i < 3; ++i) {
        o[i] = t[4 * i] * l[0] + t[4 * i + 1] * l[1] + t[4 * i + 2] * l[2];
        o[3 + i] = t[4 * i] * l[3] + t[4 * i + 1] * l[4] + t[4 * i + 2] * l[5] + t[4 * i + 3];
    }
}

static void g6_line_turn(const double *cs, double sign, const double *l, double *o)
{
    const double c = cs[0], s = sign * cs[1];
    int k;
    for (k = 0; k < 6; k += 3) {
        const double x = l[k], y = l[k + 1];
        o[k] = c * x - s * y;
        o[k + 1] = s * x + c * y;
        o[k + 2] = l[k + 2];
    }
}

/* P[e][9 m3 + 3 m4 + m5] (the constant term already minus r), Q[e][k], r[e] of the labelled loop: the line of
 * joint 6 from both sides at the grid (a tree of line moves: 3 + 9 + 27 on the left, 3 + 9 on the right), then
 * the interpolation one axis at a time (separable: 3 x 14 x 27 x 3 products instead of 14 x 27 x 27) */
static void g6_equations(double links[6][16], double P[G6_NEQ][27], double Q[G6_NEQ][G6_NY], double *r)
{
    static const int y_index[G6_NY][2] = { {2, 2}, {2, 1}, {1, 2}, {1, 1}, {2, 0}, {1, 0}, {0, 2}, {0, 1} };
    double vals[27][G6_NEQ], tmp[27][G6_NEQ], rvals[9][G6_NEQ], rtmp[9][G6_NEQ], R[G6_NEQ][9];
    double l0[6], lc[3][6], lb[9][6], la[6], t[6], k1i[16], k2i[16], k6i[16], zline[6] = {0, 0, 1, 0, 0, 0};
    int a, b, c, e, m, i;
    g6_line_move(links[4], zline, l0);
    for (c = 0; c < 3; ++c) {
        g6_line_turn(g6_grid_cs[c], 1.0, l0, t);
        g6_line_move(links[3], t, lc[c]);
    }
    for (b = 0; b < 3; ++b)
        for (c = 0; c < 3; ++c) {
            g6_line_turn(g6_grid_cs[b], 1.0, lc[c], t);
            g6_line_move(links[2], t, lb[3 * b + c]);
        }
    for (a = 0; a < 3; ++a)
        for (i = 0; i < 9; ++i) {
            g6_line_turn(g6_grid_cs[a], 1.0, lb[i], la);
            g6_fourteen(la, la + 3, vals[9 * a + i]);
        }
    /* interpolation along c, then b, then a: vals[9 a + 3 b + c] -> P[e][9 m3 + 3 m4 + m5] */
    for (a = 0; a < 9; ++a)
        for (m = 0; m < 3; ++m)
            for (e = 0; e < G6_NEQ; ++e)
                tmp[3 * a + m][e] = g6_binv[m][0] * vals[3 * a][e] + g6_binv[m][1] * vals[3 * a + 1][e] +
                                    g6_binv[m][2] * vals[3 * a + 2][e];
    for (a = 0; a < 3; ++a)
        for (m = 0; m < 3; ++m)
            for (c = 0; c < 3; ++c)
                for (e = 0; e < G6_NEQ; ++e)
                    vals[9 * a + 3 * m + c][e] = g6_binv[m][0] * tmp[9 * a + c][e] +
                                                 g6_binv[m][1] * tmp[9 * a + 3 + c][e] +
                                                 g6_binv[m][2] * tmp[9 * a + 6 + c][e];
    for (m = 0; m < 3; ++m)
        for (i = 0; i < 9; ++i)
            for (e = 0; e < G6_NEQ; ++e)
                P[e][9 * m + i] = g6_binv[m][0] * vals[i][e] + g6_binv[m][1] * vals[9 + i][e] +
                                  g6_binv[m][2] * vals[18 + i][e];
    /* the right side K2^-1 Rz(-t2) K1^-1 Rz(-t1) K6^-1 (e_z, o) at t1 = grid a, t2 = grid b */
    g6_inverse(links[0], k1i);
    g6_inverse(links[1], k2i);
    g6_inverse(links[5], k6i);
    g6_line_move(k6i, zline, l0);
    for (a = 0; a < 3; ++a) {
        g6_line_turn(g6_grid_cs[a], -1.0, l0, t);
        g6_line_move(k1i, t, lc[a]);
        for (b = 0; b < 3; ++b) {
            g6_line_turn(g6_grid_cs[b], -1.0, lc[a], t);
            g6_line_move(k2i, t, la);
            g6_fourteen(la, la + 3, rvals[3 * a + b]);
        }
    }
    for (a = 0; a < 3; ++a)
        for (m = 0; m < 3; ++m)
            for (e = 0; e < G6_NEQ; ++e)
                rtmp[3 * a + m][e] = g6_binv[m][0] * rvals[3 * a][e] + g6_binv[m][1] * rvals[3 * a + 1][e] +
                                     g6_binv[m][2] * rvals[3 * a + 2][e];
    for (m = 0; m < 3; ++m)
        for (i = 0; i < 3; ++i)
            for (e = 0; e < G6_NEQ; ++e)
                R[e][3 * m + i] = g6_binv[m][0] * rtmp[i][e] + g6_binv[m][1] * rtmp[3 + i][e] +
                                  g6_binv[m][2] * rtmp[6 + i][e];
    for (e = 0; e < G6_NEQ; ++e) {
        for (a = 0; a < G6_NY; ++a) Q[e][a] = R[e][3 * y_index[a][0] + y_index[a][1]];
        r[e] = R[e][0];
        P[e][0] -= r[e];
    }
}

/* Householder QR of Q (14 x 8): the reflections in v (column k below the diagonal, v[k][k] their head), the
 * diagonal of R in diag; 0 when a column is (numerically) dependent. */
typedef struct {
    double a[G6_NEQ][G6_NY]; /* R above the diagonal, the reflections' tails below */
    double head[G6_NY];      /* each reflection's first entry */
    double beta[G6_NY];      /* I - beta v v^T */
    double diag[G6_NY];
} g6_qr;

static int g6_qr_factor(double Q[G6_NEQ][G6_NY], g6_qr *f)
{
    int i, j, k;
    double scale = 0.0;
    memcpy(f->a, Q, sizeof f->a);
    for (i = 0; i < G6_NEQ; ++i)
        for (j = 0; j < G6_NY; ++j)
            if (fabs(Q[i][j]) > scale) scale = fabs(Q[i][j]);
    for (k = 0; k < G6_NY; ++k) {
        double norm = 0.0, alpha, vtv;
        for (i = k; i < G6_NEQ; ++i) norm += f->a[i][k] * f->a[i][k];
        norm = sqrt(norm);
        if (!(norm > 1e-13 * scale)) return 0;
        alpha = f->a[k][k] > 0.0 ? -norm : norm;
        f->head[k] = f->a[k][k] - alpha;
        vtv = f->head[k] * f->head[k];
        for (i = k + 1; i < G6_NEQ; ++i) vtv += f->a[i][k] * f->a[i][k];
        f->beta[k] = vtv > 0.0 ? 2.0 / vtv : 0.0;
        for (j = k + 1; j < G6_NY; ++j) {
            double s = f->head[k] * f->a[k][j];
            for (i = k + 1; i < G6_NEQ; ++i) s += f->a[i][k] * f->a[i][j];
            s *= f->beta[k];
            f->a[k][j] -= s * f->head[k];
            for (i = k + 1; i < G6_NEQ; ++i) f->a[i][j] -= s * f->a[i][k];
        }
        f->diag[k] = alpha;
    }
    return 1;
}

/* x := H_k x, the k-th reflection (symmetric: its own inverse) */
static void g6_qr_reflect(const g6_qr *f, int k, double *x)
{
    double s = f->head[k] * x[k];
    int i;
    for (i = k + 1; i < G6_NEQ; ++i) s += f->a[i][k] * x[i];
    s *= f->beta[k];
    x[k] -= s * f->head[k];
    for (i = k + 1; i < G6_NEQ; ++i) x[i] -= s * f->a[i][k];
}

/* x := H^T x (the reflections applied in order) */
static void g6_qr_apply(const g6_qr *f, double *x)
{
    int k;
    for (k = 0; k < G6_NY; ++k) g6_qr_reflect(f, k, x);
}

/* x := H x = H_1 ... H_8 x (the reflections applied in reverse order): H e_j is column j of the orthogonal factor */
static void g6_qr_apply_back(const g6_qr *f, double *x)
{
    int k;
    for (k = G6_NY - 1; k >= 0; --k) g6_qr_reflect(f, k, x);
}

/* N (6 x 14): the left null space of Q, the last six columns of its orthogonal factor H (six applications, not
 * the fourteen of H^T in full) */
static void g6_left_null(const g6_qr *f, double N[6][G6_NEQ])
{
    int e, i;
    for (e = 0; e < 6; ++e) {
        for (i = 0; i < G6_NEQ; ++i) N[e][i] = i == G6_NY + e ? 1.0 : 0.0;
        g6_qr_apply_back(f, N[e]);
    }
}

/* the least-squares y of Q y = b */
static void g6_qr_solve(const g6_qr *f, const double *b, double *y)
{
    double x[G6_NEQ];
    int i, j;
    memcpy(x, b, sizeof x);
    g6_qr_apply(f, x);
    for (i = G6_NY - 1; i >= 0; --i) {
        double s = x[i];
        for (j = i + 1; j < G6_NY; ++j) s -= f->a[i][j] * y[j];
        y[i] = s / f->diag[i];
    }
}

/* the (u, v) half angles from a monomial vector m[4][3] of u^i v^j: 2 atan2(num, den) of the neighbours along the
 * axis where (den, num) is largest */
static double g6_half_angle(const double *m, int axis)
{
    double best = -1.0, den = 1.0, num = 0.0;
    int i, j;
    for (i = 0; i < (axis == 0 ? 3 : 4); ++i)
        for (j = 0; j < (axis == 0 ? 3 : 2); ++j) {
            const double d = m[3 * i + j], n = axis == 0 ? m[3 * (i + 1) + j] : m[3 * i + j + 1];
            const double h = hypot(d, n);
            if (h > best) {
                best = h;
                den = d;
                num = n;
            }
        }
    return 2.0 * atan2(num, den);
}

/* Gaussian elimination with partial pivoting, k <= 4: a x = b in place (b: k x k right-hand sides); 0 if singular */
static int g6_small_solve(int k, double *a, double *b)
{
    int i, j, c, p;
    for (c = 0; c < k; ++c) {
        p = c;
        for (i = c + 1; i < k; ++i)
            if (fabs(a[i * k + c]) > fabs(a[p * k + c])) p = i;
        if (!(fabs(a[p * k + c]) > 0.0)) return 0;
        for (j = 0; j < k; ++j) {
            double t = a[c * k + j];
            a[c * k + j] = a[p * k + j];
            a[p * k + j] = t;
            t = b[c * k + j];
            b[c * k + j] = b[p * k + j];
            b[p * k + j] = t;
        }
        for (i = c + 1; i < k; ++i) {
            const double f = a[i * k + c] / a[c * k + c];
            for (j = 0; j < k; ++j) {
                a[i * k + j] -= f * a[c * k + j];
                b[i * k + j] -= f * b[c * k + j];
            }
        }
    }
    for (c = k - 1; c >= 0; --c)
        for (j = 0; j < k; ++j) {
            double s = b[c * k + j];
            for (i = c + 1; i < k; ++i) s -= a[c * k + i] * b[i * k + j];
            b[c * k + j] = s / a[c * k + c];
        }
    return 1;
}

#define G6_MAXK 4 /* the most solutions one root's (nearly) shared null space gives */
#define G6_MAXV (1 + G6_MAXK) /* a root's vectors: its null vector and a cluster's G6_MAXK */

/* max |a[i][j]| over i, j >= k of the 12 x 12 a (-1 when every entry there is NaN): four running maxima, not one
 * chain of compare-and-move through (12 - k)^2 entries, which bounded the complete pivoting's time */
static double g6_abs_max(const double *a, int k)
{
    double m[4] = {-1.0, -1.0, -1.0, -1.0};
    int i, j;
    for (i = k; i < 12; ++i) {
        const double *row = a + 12 * i;
        for (j = k; j + 3 < 12; j += 4) {
            const double x0 = fabs(row[j]), x1 = fabs(row[j + 1]), x2 = fabs(row[j + 2]), x3 = fabs(row[j + 3]);
            m[0] = x0 > m[0] ? x0 : m[0];
            m[1] = x1 > m[1] ? x1 : m[1];
            m[2] = x2 > m[2] ? x2 : m[2];
            m[3] = x3 > m[3] ? x3 : m[3];
        }
        for (; j < 12; ++j) {
            const double x = fabs(row[j]);
            m[0] = x > m[0] ? x : m[0];
        }
    }
    if (m[1] > m[0]) m[0] = m[1];
    if (m[3] > m[2]) m[2] = m[3];
    return m[2] > m[0] ? m[2] : m[0];
}

/* The null vector of M (12 x 12) by LU with complete pivoting (rank-revealing in practice: the pivots decrease):
 * U's last pivot ~ 0, the rest solved by back substitution with z_last = 1. Returns 0 (the caller takes the SVD
 * path) when the second-smallest pivot is within WK_G6_NULL_TOL of the largest: a null space of dimension > 1;
 * second receives that ratio. */
static int g6_lu_null(const double *M, double *v, double *second)
{
    double a[144], z[12], big, norm = 0.0;
    int rp[12], cp[12], i, j, k;
    memcpy(a, M, sizeof a);
    for (i = 0; i < 12; ++i) rp[i] = cp[i] = i;
    for (k = 0; k < 12; ++k) {
        int pi = k, pj = k, found = 0;
        big = g6_abs_max(a, k);
        for (i = k; i < 12 && !found; ++i) /* the first entry (row by row) that large */
            for (j = k; j < 12; ++j)
                if (fabs(a[12 * i + j]) == big) {
                    pi = i;
                    pj = j;
                    found = 1;
                    break;
                }
        if (pi != k) {
            for (j = 0; j < 12; ++j) {
                const double t = a[12 * k + j];
                a[12 * k + j] = a[12 * pi + j];
                a[12 * pi + j] = t;
            }
            i = rp[k]; rp[k] = rp[pi]; rp[pi] = i;
        }
        if (pj != k) {
            for (i = 0; i < 12; ++i) {
                const double t = a[12 * i + k];
                a[12 * i + k] = a[12 * i + pj];
                a[12 * i + pj] = t;
            }
            j = cp[k]; cp[k] = cp[pj]; cp[pj] = j;
        }
        if (!(big > 0.0)) break;
        for (i = k + 1; i < 12; ++i) {
            const double f = a[12 * i + k] / a[12 * k + k];
            for (j = k + 1; j < 12; ++j) a[12 * i + j] -= f * a[12 * k + j];
            a[12 * i + k] = 0.0;
        }
    }
    *second = fabs(a[0]) > 0.0 ? fabs(a[12 * 10 + 10]) / fabs(a[0]) : 0.0;
    if (!(*second > WK_G6_NULL_TOL)) return 0;
    z[11] = 1.0;
    for (i = 10; i >= 0; --i) {
        double s = 0.0;
        for (j = i + 1; j < 12; ++j) s -= a[12 * i + j] * z[j];
        z[i] = s / a[12 * i + i];
    }
    for (i = 0; i < 12; ++i) norm += z[i] * z[i];
    norm = sqrt(norm);
    for (i = 0; i < 12; ++i) v[cp[i]] = z[i] / norm;
    return 1;
}

/* The vectors of the span of basis (k rows of 12) with the shift structure u^(i+1) v^j = u u^i v^j: eigenvectors of
 * the k x k pencil it gives, those with a real u (|Im u| <= real_tol (1 + |u|)), written to m. Returns how many. */
static int g6_shift_vectors(double basis[G6_MAXK][12], int k, double real_tol, double m[][12])
{
    double down[9][G6_MAXK], up[9][G6_MAXK], nd = 0.0, nu = 0.0, lhs[G6_MAXK * G6_MAXK], rhs[G6_MAXK * G6_MAXK];
    double e[G6_MAXK * G6_MAXK], wr[G6_MAXK], wi[G6_MAXK], wk[WK_EIG_WORK(G6_MAXK)];
    int n = 0, swap, i, j, c;
    for (i = 0; i < 9; ++i)
        for (c = 0; c < k; ++c) {
            down[i][c] = basis[c][i];
            up[i][c] = basis[c][i + 3];
            nd += down[i][c] * down[i][c];
            nu += up[i][c] * up[i][c];
        }
    swap = nd < nu; /* u large: read the shift the other way (1 / u), better scaled */
    /* normal equations of the least-squares E with lhs E = rhs (9 x k each) */
    for (i = 0; i < k; ++i)
        for (j = 0; j < k; ++j) {
            double s = 0.0, t = 0.0;
            for (c = 0; c < 9; ++c) {
                const double li = swap ? up[c][i] : down[c][i];
                s += li * (swap ? up[c][j] : down[c][j]);
                t += li * (swap ? down[c][j] : up[c][j]);
            }
            lhs[i * k + j] = s;
            rhs[i * k + j] = t;
        }
    if (!g6_small_solve(k, lhs, rhs)) return 0;
    memcpy(e, rhs, sizeof(double) * (size_t)(k * k));
    if (wk_eig_real(k, e, wr, wi, wk) != WK_EIG_OK) return 0;
    for (c = 0; c < k; ++c) {
        double shifted[G6_MAXK * G6_MAXK], vec[G6_MAXK], r2[2];
        if (!(fabs(wi[c]) <= real_tol * (1.0 + hypot(wr[c], wi[c])))) continue;
        memcpy(shifted, rhs, sizeof(double) * (size_t)(k * k));
        for (i = 0; i < k; ++i) shifted[i * k + i] -= wr[c];
        if (wk_null_vector(k, shifted, vec, r2) != WK_EIG_OK) continue;
        for (i = 0; i < 12; ++i) {
            double s = 0.0;
            for (j = 0; j < k; ++j) s += basis[j][i] * vec[j];
            m[n][i] = s;
        }
        ++n;
    }
    return n;
}

/* sigma_2 / sigma_max of M(x) up to this (above WK_G6_NULL_TOL): x is one of a cluster of nearly equal roots, whose
 * k <= G6_MAXK smallest singular vectors give the cluster's solutions (general6r.py's G6_CLUSTER_TOL says why) */
#define G6_CLUSTER_TOL 1e-4
#define G6_CLUSTER_REAL_TOL 1e-3 /* the shift pencil's |Im u| / (1 + |u|) up to this on a cluster's subspace */
#define G6_SHIFT_REAL_TOL 1e-6   /* the same on an exact null space */
/* the LU's second-smallest pivot over its first above this: no cluster (the SVD, ~30 us, is not run). Complete
 * pivoting's pivots track the singular values: that ratio over sigma_2 / sigma_max was 1.25 to 11.6 at the real
 * roots of the near-special KR 6 and the tilted UR5e (852 roots), at most 6.2 where sigma_2 <= G6_CLUSTER_TOL */
#define G6_CLUSTER_SCREEN 2e-3

/* a root whose null vector lies within this of a cluster subspace already read (|v - B B^T v|, v a unit vector) is
 * that cluster's member: its solutions were offered with the subspace, the SVD is not run again */
#define G6_CLUSTER_COVER 1e-2
#define G6_MAXCL 12 /* cluster subspaces remembered per solve (24 roots, two each at least) */

/* the cluster subspaces read so far in one solve (orthonormal rows) */
typedef struct {
    int off; /* clusters not read at all (the caller's cheap first pass) */
    int n, k[G6_MAXCL];
    double basis[G6_MAXCL][G6_MAXK][12];
} g6_clusters;

/* whether the unit vector v lies within G6_CLUSTER_COVER of one of the subspaces in cl */
static int g6_covered(const g6_clusters *cl, const double *v)
{
    int c, j, i;
    for (c = 0; c < cl->n; ++c) {
        double r[12], rr = 0.0;
        memcpy(r, v, sizeof r);
        for (j = 0; j < cl->k[c]; ++j) {
            double d = 0.0;
            for (i = 0; i < 12; ++i) d += cl->basis[c][j][i] * v[i];
            for (i = 0; i < 12; ++i) r[i] -= d * cl->basis[c][j][i];
        }
        for (i = 0; i < 12; ++i) rr += r[i] * r[i];
        if (rr <= G6_CLUSTER_COVER * G6_CLUSTER_COVER) return 1;
    }
    return 0;
}

/* The monomial vectors of the root x with M = M(x) (12 x 12), as general6r.py's _g6_monomial_vectors: its null
 * vector; where k > 1 solutions share the hidden angle (a null space of dimension k) the k vectors of that space
 * with the shift structure instead; and where they share it only nearly (a cluster), the null vector and, unless
 * an earlier member of the cluster gave them (cl), the cluster subspace's vectors. Returns how many were written to
 * m (rows of 12). */
static int g6_monomial_vectors(const double *M, double m[G6_MAXV][12], g6_clusters *cl)
{
    double basis[G6_MAXK][12], rel[12], second = 0.0;
    int n = 0, k = 0;
    if (g6_lu_null(M, m[0], &second)) {
        n = 1; /* a simple root: the LU's null vector (the SVD below is 20x slower) */
        if (cl->off || second > G6_CLUSTER_SCREEN || g6_covered(cl, m[0])) return 1;
    }
    if (wk_small_singular_vectors(12, M, G6_MAXK, basis[0], rel) != WK_EIG_OK) return n;
    while (k < 12 && rel[k] <= WK_G6_NULL_TOL) ++k;
    if (k > 1) /* an exact multiple root: its null space's vectors only */
        return g6_shift_vectors(basis, k < G6_MAXK ? k : G6_MAXK, G6_SHIFT_REAL_TOL, m);
    if (n == 0) { /* the LU's pivots said a null space of dimension > 1, the singular values one */
        memcpy(m[0], basis[0], sizeof m[0]);
        n = 1;
        if (cl->off || g6_covered(cl, m[0])) return n; /* the LU's vector passed these above */
    }
    k = 0;
    while (k < G6_MAXK && rel[k] <= G6_CLUSTER_TOL) ++k;
    if (k < 2) return n;
    if (cl->n < G6_MAXCL) {
        cl->k[cl->n] = k;
        memcpy(cl->basis[cl->n++], basis, sizeof basis);
    }
    return n + g6_shift_vectors(basis, k, G6_CLUSTER_REAL_TOL, m + n);
}

/* ------------------------------------------------------------------ hidden t3: the (1 + x^2)^4 deflated
 * (runtime/python/general6r.py's docstring has the derivation): two complex combinations mu = a + i b of the six
 * equations have no 1/z part (z = e^(i t3)); each turns a pair of quadratic rows into a pair of linear ones, so
 * the 12 x 12 polynomial's determinant drops to degree 16 and the eigenproblem to 16 x 16 (~3x cheaper than the
 * 24 x 24 companion). Where d0 real combinations are free of t3 altogether (parallel axes elsewhere: the tilted
 * UR5e, the xArm6), their rows r g0 = 0 restrict the monomial vector to 12 - 2 d0 dimensions instead. */

#define G6_DEFLATE_TOL 1e-8 /* structure not met to this (relative): the 24 x 24 path */
/* |Im x| / (1 + |x|) up to this: a real root moved off the axis by rounding (Python's G6_REAL_TOL: a double root
 * splits by ~sqrt(c n eps / rcond(K)) into a complex pair, 6.6e-6 seen at rcond ~1e-4; verification decides) */
#define G6_REAL_TOL 1e-4
/* |Im x| / (1 + |x|) of a pair up to this (beyond G6_REAL_TOL): a nearly defective cluster's members can come out
 * this far off the axis (general6r.py's G6_CLUSTER_IM_TOL); reported, and read as a root when clusters are read */
#define G6_CLUSTER_IM_TOL 1e-2
#define G6_RCOND_GOOD 1e-4 /* the leading coefficient this well conditioned: no further origin phi tried */
#define G6_NPHI 4
static const double g6_phis[G6_NPHI] = {0.0, 2.0 * G6_PI / 3.0, -2.0 * G6_PI / 3.0, G6_PI / 2.0};

/* Householder QR with column pivoting of a (rows x cols, row-major, rows <= 12, cols <= 8): q (rows x rows,
 * row-major) receives Q, whose first `rank` columns span the columns of a and the others their orthogonal
 * complement. rank >= 0 is what the caller expects; -1 lets the pivots decide (a pivot below G6_DEFLATE_TOL of the
 * first ends it). Only Q's columns from the rank on (the complement) are written unless all_columns. Returns the
 * rank, or -1 when a expected rank is not met (a pivot too small, or what is left of the other columns above that
 * tolerance). */
static int g6_span_qr(int rows, int cols, const double *a, int rank, int all_columns, double *q)
{
    double w[12][8], v[8][12], beta[8], first = 0.0;
    int i, j, k, steps = rank >= 0 ? rank : (rows < cols ? rows : cols);
    for (i = 0; i < rows; ++i)
        for (j = 0; j < cols; ++j) w[i][j] = a[cols * i + j];
    for (k = 0; k < steps; ++k) {
        double best = -1.0, norm, alpha, vtv = 0.0;
        int p = k;
        for (j = k; j < cols; ++j) {
            double s = 0.0;
            for (i = k; i < rows; ++i) s += w[i][j] * w[i][j];
            if (s > best) {
                best = s;
                p = j;
            }
        }
        if (p != k)
            for (i = 0; i < rows; ++i) {
                const double t = w[i][k];
                w[i][k] = w[i][p];
                w[i][p] = t;
            }
        norm = sqrt(best);
        if (k == 0) first = norm;
        if (!(first > 0.0)) return -1;
        if (!(norm > G6_DEFLATE_TOL * first)) {
            if (rank >= 0) return -1;
            steps = k; /* the numerical rank */
            break;
        }
        alpha = w[k][k] > 0.0 ? -norm : norm;
        for (i = 0; i < rows; ++i) v[k][i] = i < k ? 0.0 : w[i][k];
        v[k][k] -= alpha;
        for (i = k; i < rows; ++i) vtv += v[k][i] * v[k][i];
        beta[k] = 2.0 / vtv;
        for (j = k; j < cols; ++j) {
            double s = 0.0;
            for (i = k; i < rows; ++i) s += v[k][i] * w[i][j];
            s *= beta[k];
            for (i = k; i < rows; ++i) w[i][j] -= s * v[k][i];
        }
    }
    for (j = steps; j < cols; ++j) { /* the rest of the columns must lie in the span */
        double s = 0.0;
        for (i = steps; i < rows; ++i) s += w[i][j] * w[i][j];
        if (!(sqrt(s) <= G6_DEFLATE_TOL * first)) return -1;
    }
    for (j = all_columns ? 0 : steps; j < rows; ++j) { /* Q e_j = H_0 ... H_(steps-1) e_j */
        double e[12];
        for (i = 0; i < rows; ++i) e[i] = i == j ? 1.0 : 0.0;
        for (k = steps - 1; k >= 0; --k) {
            double s = 0.0;
            for (i = k; i < rows; ++i) s += v[k][i] * e[i];
            s *= beta[k];
            for (i = k; i < rows; ++i) e[i] -= s * v[k][i];
        }
        for (i = 0; i < rows; ++i) q[rows * i + j] = e[i];
    }
    return steps;
}

/* (1 + u^2) (f0 + f1 c + f2 s) as coefficients of u^0, u^1, u^2 (c = (1 - u^2) / (1 + u^2), s = 2u / (1 + u^2)):
 * for f = 1, c, s: (1, 0, 1), (1, 0, -1), (0, 2, 0) */
#define G6_HALF(f, g, k, stride)                      \
    do {                                              \
        (g)[0] = (f)[0] + (f)[(stride)];              \
        (g)[(k)] = 2.0 * (f)[2 * (stride)];           \
        (g)[2 * (k)] = (f)[0] - (f)[(stride)];        \
    } while (0)

/* f (3 x 3 over (1, c, s) of the two non-hidden angles) times (1 + u^2)(1 + v^2) as a row over the 12 monomials
 * u^i v^j (index 3 i + j), and its u multiple */
static void g6_trig_rows(const double *f, double *row, double *shifted)
{
    double h[9];
    int i;
    for (i = 0; i < 3; ++i) G6_HALF(f + i, h + i, 3, 3); /* along u: h[3 i + b] over u^i, (1, c, s)_v b */
    for (i = 0; i < 12; ++i) row[i] = shifted[i] = 0.0;
    for (i = 0; i < 3; ++i) G6_HALF(h + 3 * i, row + 3 * i, 1, 1);
    for (i = 0; i < 9; ++i) shifted[3 + i] = row[i];
}

/* The six equations' coefficients with the hidden angle's origin at phi: t3 = phi + t', (c3, s3) rotated into
 * (c', s'); hidden is t3 here (index 0 of the 27) */
static void g6_rotate_hidden(double t6[6][27], double phi, double out[6][27])
{
    const double c = cos(phi), s = sin(phi);
    int e, k;
    for (e = 0; e < 6; ++e)
        for (k = 0; k < 9; ++k) {
            out[e][k] = t6[e][k];
            out[e][9 + k] = c * t6[e][9 + k] + s * t6[e][18 + k];
            out[e][18 + k] = c * t6[e][18 + k] - s * t6[e][9 + k];
        }
}

/* The 12 x 12 A, B, C of (1 + x^2) times the six equations (hidden = phi + 2 atan x, rotated already in t6) over
 * the monomials u^i v^j of the other two, the equations in rows 0..5 and their u multiples in 6..11 */
static void g6_quadratic(double t6[6][27], int hidden, double *A, double *B, double *C)
{
    static const int stride[3][3] = { {9, 3, 1}, {3, 9, 1}, {1, 9, 3} }; /* of hidden, u, v in the 27 */
    const int sh = stride[hidden][0], su = stride[hidden][1], sv = stride[hidden][2];
    int e, h, i, j;
    for (i = 0; i < 144; ++i) A[i] = B[i] = C[i] = 0.0;
    for (e = 0; e < 6; ++e)
        for (h = 0; h < 3; ++h) {
            double f[9], row[12], shifted[12];
            for (i = 0; i < 3; ++i)
                for (j = 0; j < 3; ++j) f[3 * i + j] = t6[e][sh * h + su * i + sv * j];
            g6_trig_rows(f, row, shifted);
            /* over x: (1 + x^2), (1 - x^2), 2 x for h = 1, c, s */
            for (i = 0; i < 12; ++i) {
                const double w = row[i], ws = shifted[i];
                if (h == 0) {
                    C[12 * e + i] += w;
                    A[12 * e + i] += w;
                    C[12 * (6 + e) + i] += ws;
                    A[12 * (6 + e) + i] += ws;
                } else if (h == 1) {
                    C[12 * e + i] += w;
                    A[12 * e + i] -= w;
                    C[12 * (6 + e) + i] += ws;
                    A[12 * (6 + e) + i] -= ws;
                } else {
                    B[12 * e + i] += 2.0 * w;
                    B[12 * (6 + e) + i] += 2.0 * ws;
                }
            }
        }
}

/* LU with partial pivoting of the n x n a in place; 0 if a pivot is exactly zero */
static int g6_lu(int n, double *a, int *piv)
{
    int i, j, k;
    for (k = 0; k < n; ++k) {
        int p = k;
        for (i = k + 1; i < n; ++i)
            if (fabs(a[n * i + k]) > fabs(a[n * p + k])) p = i;
        piv[k] = p;
        if (!(a[n * p + k] != 0.0)) return 0;
        if (p != k)
            for (j = 0; j < n; ++j) {
                const double t = a[n * k + j];
                a[n * k + j] = a[n * p + j];
                a[n * p + j] = t;
            }
        for (i = k + 1; i < n; ++i) {
            const double f = a[n * i + k] /= a[n * k + k];
            for (j = k + 1; j < n; ++j) a[n * i + j] -= f * a[n * k + j];
        }
    }
    return 1;
}

/* b (n x cols, row-major) := (LU)^-1 b */
static void g6_lu_solve(int n, const double *lu, const int *piv, double *b, int cols)
{
    int i, j, k;
    for (k = 0; k < n; ++k)
        if (piv[k] != k)
            for (j = 0; j < cols; ++j) {
                const double t = b[cols * k + j];
                b[cols * k + j] = b[cols * piv[k] + j];
                b[cols * piv[k] + j] = t;
            }
    for (i = 1; i < n; ++i)
        for (k = 0; k < i; ++k) {
            const double f = lu[n * i + k];
            for (j = 0; j < cols; ++j) b[cols * i + j] -= f * b[cols * k + j];
        }
    for (i = n - 1; i >= 0; --i) {
        for (k = i + 1; k < n; ++k) {
            const double f = lu[n * i + k];
            for (j = 0; j < cols; ++j) b[cols * i + j] -= f * b[cols * k + j];
        }
        for (j = 0; j < cols; ++j) b[cols * i + j] /= lu[n * i + i];
    }
}

/* The deflated pencil's rows, split by the hidden angle's origin phi (each is linear in cos phi, sin phi): the
 * linear rows L0 + x K (Re L of the (a; b), then their u multiples) are a0 + c pr + s qr and b0 + c qr - s pr
 * (2 pr = a gc + b gs, 2 qr = a gs - b gc: Re L = (a g0 + kr) + x (b g0 - ki) with 2 kappa = mu (gc - i gs) at phi);
 * the quadratic rows (the complementary equations and their u multiples) are, with k1, kc, ks their (1, c, s) parts
 * in the hidden angle, A = k1 - kc, B = 2 ks, C = k1 + kc, kc = c gc + s gs, ks = c gs - s gc. Every row is
 * already times m0, the basis of the monomial vectors the d0 rows free of t3 leave (nm = 12 - 2 d0 columns). */
typedef struct {
    int nm, nl, nq;                                     /* columns, linear rows (8 - 4 d0), quadratic (4 + 2 d0) */
    double a0[8][12], b0[8][12], pr[8][12], qr[8][12]; /* linear rows */
    double k1[8][12], kc[8][12], ks[8][12];            /* quadratic rows */
} g6_deflated;

/* rows (n x 12) := rows m0 (12 x nm, row-major) */
static void g6_times_m0(double rows[8][12], int n, const double *m0, int nm)
{
    int r, i, k;
    for (r = 0; r < n; ++r) {
        double t[12];
        for (k = 0; k < nm; ++k) {
            double s = 0.0;
            for (i = 0; i < 12; ++i) s += rows[r][i] * m0[nm * i + k];
            t[k] = s;
        }
        for (k = 0; k < 12; ++k) rows[r][k] = k < nm ? t[k] : 0.0;
    }
}

/* r0 (6 x d0), ab (12 x nab = 4 - 2 d0: a over b), comp (6 x nc = 2 + d0), all row-major */
static int g6_deflated_parts(double t6[6][27], const double *r0, int d0, const double *ab, int nab,
                             const double *comp, int nc, g6_deflated *d)
{
    double m0[144];
    int j, e, k, nm = 12;
    for (j = 0; j < nab; ++j) {
        double f[4][9];
        for (k = 0; k < 9; ++k) {
            double ag0 = 0.0, bg0 = 0.0, agc = 0.0, ags = 0.0, bgc = 0.0, bgs = 0.0;
            for (e = 0; e < 6; ++e) {
                const double a = ab[nab * e + j], b = ab[nab * (6 + e) + j];
                ag0 += a * t6[e][k];
                bg0 += b * t6[e][k];
                agc += a * t6[e][9 + k];
                ags += a * t6[e][18 + k];
                bgc += b * t6[e][9 + k];
                bgs += b * t6[e][18 + k];
            }
            f[0][k] = ag0;
            f[1][k] = bg0;
            f[2][k] = 0.5 * (agc + bgs);
            f[3][k] = 0.5 * (ags - bgc);
        }
        g6_trig_rows(f[0], d->a0[j], d->a0[nab + j]);
        g6_trig_rows(f[1], d->b0[j], d->b0[nab + j]);
        g6_trig_rows(f[2], d->pr[j], d->pr[nab + j]);
        g6_trig_rows(f[3], d->qr[j], d->qr[nab + j]);
    }
    for (j = 0; j < nc; ++j) {
        double f[3][9];
        for (k = 0; k < 27; ++k) {
            double s = 0.0;
            for (e = 0; e < 6; ++e) s += comp[nc * e + j] * t6[e][k];
            f[k / 9][k % 9] = s;
        }
        g6_trig_rows(f[0], d->k1[j], d->k1[nc + j]);
        g6_trig_rows(f[1], d->kc[j], d->kc[nc + j]);
        g6_trig_rows(f[2], d->ks[j], d->ks[nc + j]);
    }
    if (d0 > 0) { /* m0: the complement of the rows r0 g0 (and their u multiples) in the 12 monomials */
        double rows[4][12], rt[12 * 4], q[144];
        for (j = 0; j < d0; ++j) {
            double f[9];
            for (k = 0; k < 9; ++k) {
                double s = 0.0;
                for (e = 0; e < 6; ++e) s += r0[d0 * e + j] * t6[e][k];
                f[k] = s;
            }
            g6_trig_rows(f, rows[j], rows[d0 + j]);
        }
        for (j = 0; j < 2 * d0; ++j)
            for (k = 0; k < 12; ++k) rt[2 * d0 * k + j] = rows[j][k];
        if (g6_span_qr(12, 2 * d0, rt, 2 * d0, 0, q) != 2 * d0) return 0;
        nm = 12 - 2 * d0;
        for (k = 0; k < 12; ++k)
            for (j = 0; j < nm; ++j) m0[nm * k + j] = q[12 * k + 2 * d0 + j];
        g6_times_m0(d->a0, 2 * nab, m0, nm);
        g6_times_m0(d->b0, 2 * nab, m0, nm);
        g6_times_m0(d->pr, 2 * nab, m0, nm);
        g6_times_m0(d->qr, 2 * nab, m0, nm);
        g6_times_m0(d->k1, 2 * nc, m0, nm);
        g6_times_m0(d->kc, 2 * nc, m0, nm);
        g6_times_m0(d->ks, 2 * nc, m0, nm);
    }
    d->nm = nm;
    d->nl = 2 * nab;
    d->nq = 2 * nc;
    return 1;
}

/* 2^-e with 2^e the largest |entry| of the n values (a row's exact power-of-two equilibration), 1 for zeros */
static double g6_row_scale(const double *x, int n)
{
    double big = 0.0;
    int i, e = 0;
    for (i = 0; i < n; ++i)
        if (fabs(x[i]) > big) big = fabs(x[i]);
    if (!(big > 0.0) || !isfinite(big)) return 1.0;
    (void)frexp(big, &e);
    return ldexp(1.0, -e);
}

/* K (nm x nm: the linear rows' x coefficient, then the quadratic rows' x^2 coefficient), L0 (nl x nm), Bq and Cq
 * (nq x nm) at phi, row-major with stride nm, each row (with its partners) equilibrated by a power of two */
static void g6_deflated_at(const g6_deflated *d, double phi, double *K, double *L0, double *Bq, double *Cq)
{
    const double c = cos(phi), s = sin(phi);
    const int nm = d->nm;
    double sc;
    int r, k;
    for (r = 0; r < d->nl; ++r) {
        double *l0 = L0 + nm * r, *l1 = K + nm * r;
        for (k = 0; k < nm; ++k) {
            l0[k] = d->a0[r][k] + c * d->pr[r][k] + s * d->qr[r][k];
            l1[k] = d->b0[r][k] + c * d->qr[r][k] - s * d->pr[r][k];
        }
        sc = g6_row_scale(l0, nm);
        if (g6_row_scale(l1, nm) < sc) sc = g6_row_scale(l1, nm);
        for (k = 0; k < nm; ++k) {
            l0[k] *= sc;
            l1[k] *= sc;
        }
    }
    for (r = 0; r < d->nq; ++r) {
        double *a = K + nm * (d->nl + r), *b = Bq + nm * r, *cc = Cq + nm * r;
        for (k = 0; k < nm; ++k) {
            const double kc = c * d->kc[r][k] + s * d->ks[r][k], ks = c * d->ks[r][k] - s * d->kc[r][k];
            a[k] = d->k1[r][k] - kc;
            b[k] = 2.0 * ks;
            cc[k] = d->k1[r][k] + kc;
        }
        sc = g6_row_scale(a, nm);
        if (g6_row_scale(b, nm) < sc) sc = g6_row_scale(b, nm);
        if (g6_row_scale(cc, nm) < sc) sc = g6_row_scale(cc, nm);
        for (k = 0; k < nm; ++k) {
            a[k] *= sc;
            b[k] *= sc;
            cc[k] *= sc;
        }
    }
}

/* 1-norm reciprocal condition of the n x n k from its LU (explicit inverse: at 12 it costs about an LU) */
static double g6_rcond(int n, const double *k, const double *lu, const int *piv)
{
    double inv[144], nk = 0.0, ni = 0.0;
    int i, j;
    for (i = 0; i < n * n; ++i) inv[i] = (i % (n + 1) == 0) ? 1.0 : 0.0;
    g6_lu_solve(n, lu, piv, inv, n);
    for (j = 0; j < n; ++j) {
        double sk = 0.0, si = 0.0;
        for (i = 0; i < n; ++i) {
            sk += fabs(k[n * i + j]);
            si += fabs(inv[n * i + j]);
        }
        if (sk > nk) nk = sk;
        if (!(si <= ni)) ni = si;
    }
    return (nk > 0.0 && isfinite(ni) && ni > 0.0) ? 1.0 / (nk * ni) : 0.0;
}

/* The roots x (real ones in xr, at most 16) of the hidden t3 = phi + 2 atan x by the deflated 16 x 16
 * eigenproblem, phi chosen as the Python does (the first of g6_phis whose K has rcond > G6_RCOND_GOOD, else the
 * best). Returns the number of real roots, or -1 when the structure is not met (the caller takes the 24 x 24 path)
 * or the eigenvalues fail. */
static int g6_deflated_roots(double t6[6][27], double N[6][G6_NEQ], double *phi_out, double *xr, int wide,
                             int *near_pair)
{
    static const int blocks[4] = {0, 3, 8, 11};
    double z[12 * 8], xy[6 * 8], qz[144], qr0[36], ab[12 * 4], r0[6 * 2], span[6 * 8], qs[36], comp[6 * 4];
    double K[144], L0[96], Bq[96], Cq[96], lu[144], best_lu[144], bL0[96], bBq[96], bCq[96], rhs[12 * 16];
    double S[256], wr[16], wi[16], work[WK_EIG_WORK(16)], best = -1.0;
    g6_deflated d;
    int piv[12], best_piv[12], e, j, k, i, n = 0, rank, d0, nab, nc, nm, nl, nq;
    for (e = 0; e < 6; ++e) /* [[X, Y], [-Y, X]], X + i Y = N W4 */
        for (j = 0; j < 4; ++j) {
            const double x = N[e][blocks[j]], y = N[e][blocks[j] + 1];
            z[8 * e + j] = x;
            z[8 * e + 4 + j] = y;
            z[8 * (6 + e) + j] = -y;
            z[8 * (6 + e) + 4 + j] = x;
            xy[8 * e + j] = x;
            xy[8 * e + 4 + j] = y;
        }
    if (g6_span_qr(12, 8, z, 8, 0, qz) != 8) return -1;
    rank = g6_span_qr(6, 8, xy, -1, 0, qr0); /* [X Y]'s left null space: real combinations free of t3 */
    d0 = 6 - rank;
    if (rank < 0 || d0 > 2) return -1;
    for (i = 0; i < 6; ++i)
        for (j = 0; j < d0; ++j) r0[d0 * i + j] = qr0[6 * i + rank + j];
    nab = 4 - 2 * d0;
    {
        double proj[12 * 4], qp[144];
        for (i = 0; i < 12; ++i)
            for (j = 0; j < 4; ++j) proj[4 * i + j] = qz[12 * i + 8 + j];
        for (j = 0; j < 4 && d0 > 0; ++j) /* the (r; 0), (0; r) directions out */
            for (k = 0; k < d0; ++k) {
                double sa = 0.0, sb = 0.0;
                for (i = 0; i < 6; ++i) {
                    sa += r0[d0 * i + k] * proj[4 * i + j];
                    sb += r0[d0 * i + k] * proj[4 * (6 + i) + j];
                }
                for (i = 0; i < 6; ++i) {
                    proj[4 * i + j] -= sa * r0[d0 * i + k];
                    proj[4 * (6 + i) + j] -= sb * r0[d0 * i + k];
                }
            }
        if (d0 == 0) {
            memcpy(ab, proj, sizeof proj);
        } else if (d0 == 1) {
            if (g6_span_qr(12, 4, proj, 2, 1, qp) != 2) return -1;
            for (i = 0; i < 12; ++i)
                for (j = 0; j < 2; ++j) ab[2 * i + j] = qp[12 * i + j];
        }
    }
    nc = 2 + d0;
    {
        const int cols = d0 + 2 * nab;
        for (i = 0; i < 6; ++i) {
            for (j = 0; j < d0; ++j) span[cols * i + j] = r0[d0 * i + j];
            for (j = 0; j < nab; ++j) {
                span[cols * i + d0 + j] = ab[nab * i + j];
                span[cols * i + d0 + nab + j] = ab[nab * (6 + i) + j];
            }
        }
        if (g6_span_qr(6, cols, span, 4 - d0, 0, qs) != 4 - d0) return -1;
        for (i = 0; i < 6; ++i)
            for (j = 0; j < nc; ++j) comp[nc * i + j] = qs[6 * i + 4 - d0 + j];
    }
    if (!g6_deflated_parts(t6, r0, d0, ab, nab, comp, nc, &d)) return -1;
    nm = d.nm;
    nl = d.nl;
    nq = d.nq;
    for (k = 0; k < G6_NPHI; ++k) {
        double rc;
        g6_deflated_at(&d, g6_phis[k], K, L0, Bq, Cq);
        memcpy(lu, K, sizeof(double) * (size_t)(nm * nm));
        rc = g6_lu(nm, lu, piv) ? g6_rcond(nm, K, lu, piv) : 0.0;
        if (rc > best) {
            best = rc;
            *phi_out = g6_phis[k];
            memcpy(best_lu, lu, sizeof lu);
            memcpy(best_piv, piv, sizeof piv);
            memcpy(bL0, L0, sizeof L0);
            memcpy(bBq, Bq, sizeof Bq);
            memcpy(bCq, Cq, sizeof Cq);
        }
        if (rc > G6_RCOND_GOOD) break;
    }
    if (!(best > 64.0 * 12.0 * 2.220446049250313e-16)) return -1;
    /* x m = K^-1 [-L0 m; s] (the top nm rows of S), x s = -Cq m - Bq x m (the last nq); nm + nq = 16 */
    memset(rhs, 0, sizeof rhs);
    for (i = 0; i < nl; ++i)
        for (j = 0; j < nm; ++j) rhs[16 * i + j] = -bL0[nm * i + j];
    for (i = 0; i < nq; ++i) rhs[16 * (nl + i) + nm + i] = 1.0;
    g6_lu_solve(nm, best_lu, best_piv, rhs, 16);
    memcpy(S, rhs, sizeof(double) * (size_t)(16 * nm));
    for (i = 0; i < nq; ++i)
        for (j = 0; j < 16; ++j) {
            double s = j < nm ? -bCq[nm * i + j] : 0.0;
            for (k = 0; k < nm; ++k) s -= bBq[nm * i + k] * rhs[16 * k + j];
            S[16 * (nm + i) + j] = s;
        }
    if (wk_eig_real(16, S, wr, wi, work) != WK_EIG_OK) return -1;
    for (k = 0; k < 16; ++k) { /* a near-real pair once, at its real part */
        const double off = fabs(wi[k]) / (1.0 + hypot(wr[k], wi[k]));
        if (off > G6_REAL_TOL && off <= G6_CLUSTER_IM_TOL) *near_pair = 1;
        if (wi[k] >= 0.0 && off <= (wide ? G6_CLUSTER_IM_TOL : G6_REAL_TOL)) xr[n++] = wr[k];
    }
    return n;
}

void wk_g6_z_frames(const double *axes, const double *points, double *frames)
{
    int i, k;
    for (i = 0; i < 6; ++i) {
        const double *a = axes + 3 * i;
        const double na = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
        double z[3], e[3] = {0.0, 0.0, 0.0}, x[3], y[3], nx;
        int small = 0;
        for (k = 0; k < 3; ++k) z[k] = a[k] / na;
        for (k = 1; k < 3; ++k)
            if (fabs(z[k]) < fabs(z[small])) small = k;
        e[small] = 1.0;
        x[0] = z[1] * e[2] - z[2] * e[1];
        x[1] = z[2] * e[0] - z[0] * e[2];
        x[2] = z[0] * e[1] - z[1] * e[0];
        nx = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
        for (k = 0; k < 3; ++k) x[k] /= nx;
        y[0] = z[1] * x[2] - z[2] * x[1];
        y[1] = z[2] * x[0] - z[0] * x[2];
        y[2] = z[0] * x[1] - z[1] * x[0];
        for (k = 0; k < 3; ++k) {
            frames[16 * i + 4 * k] = x[k];
            frames[16 * i + 4 * k + 1] = y[k];
            frames[16 * i + 4 * k + 2] = z[k];
            frames[16 * i + 4 * k + 3] = points[3 * i + k];
        }
        frames[16 * i + 12] = frames[16 * i + 13] = frames[16 * i + 14] = 0.0;
        frames[16 * i + 15] = 1.0;
    }
}

/* theta1, theta2 and theta6 for theta3..5 (angles), from the least-squares Y and the loop */
static void g6_complete(const double *angles, double links[6][16], double P[G6_NEQ][27], const g6_qr *f,
                        double *t)
{
    double fb[3][3], lhs[G6_NEQ], y[G6_NY], cs[5][2], col[2][3], h;
    int i, e, a, k;
    for (i = 0; i < 3; ++i) {
        fb[i][0] = 1.0;
        fb[i][1] = cos(angles[i]);
        fb[i][2] = sin(angles[i]);
    }
    for (e = 0; e < G6_NEQ; ++e) { /* P contracted with (1, c, s) of t5, then t4, then t3 */
        double s = 0.0;
        for (a = 0; a < 3; ++a) {
            double sb = 0.0;
            for (k = 0; k < 3; ++k)
                sb += fb[1][k] * (P[e][9 * a + 3 * k] + fb[2][1] * P[e][9 * a + 3 * k + 1] +
                                  fb[2][2] * P[e][9 * a + 3 * k + 2]);
            s += fb[0][a] * sb;
        }
        lhs[e] = s;
    }
    g6_qr_solve(f, lhs, y);
    t[0] = atan2(y[4], y[5]);
    t[1] = atan2(y[6], y[7]);
    t[2] = angles[0];
    t[3] = angles[1];
    t[4] = angles[2];
    /* Rz(t6) = (Rz(t1) K1 ... Rz(t5) K5)^-1 K6^-1: its first column from the rotations alone, (R e_x, R e_y) . (the
     * first row of K6's rotation), R the product's rotation (its first two columns, from the right) */
    h = hypot(y[4], y[5]);
    cs[0][0] = h > 0.0 ? y[5] / h : 1.0;
    cs[0][1] = h > 0.0 ? y[4] / h : 0.0;
    h = hypot(y[6], y[7]);
    cs[1][0] = h > 0.0 ? y[7] / h : 1.0;
    cs[1][1] = h > 0.0 ? y[6] / h : 0.0;
    for (i = 0; i < 3; ++i) {
        cs[2 + i][0] = fb[i][1];
        cs[2 + i][1] = fb[i][2];
    }
    for (k = 0; k < 2; ++k) {
        double v[3] = {k == 0 ? 1.0 : 0.0, k == 1 ? 1.0 : 0.0, 0.0}, w[3];
        for (i = 4; i >= 0; --i) {
            const double *m = links[i];
            for (a = 0; a < 3; ++a) w[a] = m[4 * a] * v[0] + m[4 * a + 1] * v[1] + m[4 * a + 2] * v[2];
            v[0] = cs[i][0] * w[0] - cs[i][1] * w[1];
            v[1] = cs[i][1] * w[0] + cs[i][0] * w[1];
            v[2] = w[2];
        }
        for (a = 0; a < 3; ++a) col[k][a] = v[a];
    }
    t[5] = atan2(col[1][0] * links[5][0] + col[1][1] * links[5][1] + col[1][2] * links[5][2],
                 col[0][0] * links[5][0] + col[0][1] * links[5][1] + col[0][2] * links[5][2]);
}

/* prod Z_i Rz(q_i) Z_i^-1 . home (t) and the geometric Jacobian (6 x 6 row-major, linear velocity first). Each
 * Z Rz(q) Z^-1 is the turn about the line (axis a, point p) = (z column, origin) of Z: R = c I + s [a]x +
 * (1 - c) a a^T, translation p - R p (Rodrigues; a third of the 4 x 4 products' cost) */
static void g6_fk(const double *frames, const double *home, const double *q, double *t, double *jac)
{
    double R[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, tr[3] = {0, 0, 0}, ax[6][3], pt[6][3], acc[16];
    int i, r, k;
    for (i = 0; i < 6; ++i) {
        const double *z = frames + 16 * i;
        const double a[3] = {z[2], z[6], z[10]}, p[3] = {z[3], z[7], z[11]};
        const double c = cos(q[i]), s = sin(q[i]), v = 1.0 - c;
        double E[9], et[3], R2[9];
        for (r = 0; r < 3; ++r) {
            ax[i][r] = R[3 * r] * a[0] + R[3 * r + 1] * a[1] + R[3 * r + 2] * a[2];
            pt[i][r] = R[3 * r] * p[0] + R[3 * r + 1] * p[1] + R[3 * r + 2] * p[2] + tr[r];
        }
        E[0] = c + v * a[0] * a[0];
        E[1] = v * a[0] * a[1] - s * a[2];
        E[2] = v * a[0] * a[2] + s * a[1];
        E[3] = v * a[1] * a[0] + s * a[2];
        E[4] = c + v * a[1] * a[1];
        E[5] = v * a[1] * a[2] - s * a[0];
        E[6] = v * a[2] * a[0] - s * a[1];
        E[7] = v * a[2] * a[1] + s * a[0];
        E[8] = c + v * a[2] * a[2];
        for (r = 0; r < 3; ++r) et[r] = p[r] - (E[3 * r] * p[0] + E[3 * r + 1] * p[1] + E[3 * r + 2] * p[2]);
        for (r = 0; r < 3; ++r) {
            tr[r] += R[3 * r] * et[0] + R[3 * r + 1] * et[1] + R[3 * r + 2] * et[2];
            for (k = 0; k < 3; ++k)
                R2[3 * r + k] = R[3 * r] * E[k] + R[3 * r + 1] * E[3 + k] + R[3 * r + 2] * E[6 + k];
        }
        memcpy(R, R2, sizeof R);
    }
    for (r = 0; r < 3; ++r) {
        for (k = 0; k < 3; ++k) acc[4 * r + k] = R[3 * r + k];
        acc[4 * r + 3] = tr[r];
    }
    acc[12] = acc[13] = acc[14] = 0.0;
    acc[15] = 1.0;
    g6_mul(acc, home, t);
    for (i = 0; i < 6; ++i) {
        const double d[3] = {t[3] - pt[i][0], t[7] - pt[i][1], t[11] - pt[i][2]};
        jac[0 * 6 + i] = ax[i][1] * d[2] - ax[i][2] * d[1];
        jac[1 * 6 + i] = ax[i][2] * d[0] - ax[i][0] * d[2];
        jac[2 * 6 + i] = ax[i][0] * d[1] - ax[i][1] * d[0];
        for (r = 0; r < 3; ++r) jac[(3 + r) * 6 + i] = ax[i][r];
    }
}

static double g6_pose_error(const double *t, const double *pose)
{
    double err = 0.0;
    int i;
    for (i = 0; i < 12; ++i) {
        const double e = fabs(t[i] - pose[i]);
        if (!(e <= err)) err = e;
    }
    return err;
}

/* Newton steps on the chain's pose error (Python's g6_refine): the eigenproblem leaves a root ~1e-9 off where
 * roots are close; a few steps bring it to rounding, so every caller verifies the same set */
#define G6_REFINE_DONE 0x1p-50 /* ~4 eps: the pose error at rounding (relative to 1 + |p|_1) */
#define G6_REFINE_NEAR 1e-10   /* below this pose error (relative), a step may raise it while the steps contract */

/* Newton steps on the chain's pose error (Python's g6_refine_many): the eigenproblem leaves a root ~1e-9 off where
 * roots are close; a few steps bring it to rounding, so every caller verifies the same set. At a double root (two
 * solutions meeting: J singular there) Newton converges only linearly, halving the distance per step while the
 * pose error, already near rounding, goes up and down: there a step is taken while the steps contract, and the
 * iterate with the smallest error is kept. */
static void g6_refine(const double *frames, const double *home, const double *pose, double *q)
{
    double t[16], jac[36], err, best[6], best_err, last = HUGE_VAL;
    int it, i, c;
    /* rounding of the pose error: a few units of eps times the pose's size */
    const double scale = 1.0 + fabs(pose[3]) + fabs(pose[7]) + fabs(pose[11]);
    const double done = G6_REFINE_DONE * scale, near = G6_REFINE_NEAR * scale;
    g6_fk(frames, home, q, t, jac);
    err = g6_pose_error(t, pose);
    if (err <= done) return;
    memcpy(best, q, sizeof best);
    best_err = err;
    for (it = 0; it < WK_G6_REFINE_STEPS; ++it) {
        double e[6], a[36], trial[6], t2[16], jac2[36], err2, size = 0.0;
        int ok = 1;
        e[0] = pose[3] - t[3];
        e[1] = pose[7] - t[7];
        e[2] = pose[11] - t[11];
        e[3] = e[4] = e[5] = 0.0;
        for (c = 0; c < 3; ++c) { /* 1/2 sum over columns of t_c x pose_c */
            const double u[3] = {t[c], t[4 + c], t[8 + c]}, v[3] = {pose[c], pose[4 + c], pose[8 + c]};
            e[3] += 0.5 * (u[1] * v[2] - u[2] * v[1]);
            e[4] += 0.5 * (u[2] * v[0] - u[0] * v[2]);
            e[5] += 0.5 * (u[0] * v[1] - u[1] * v[0]);
        }
        memcpy(a, jac, sizeof a);
        for (c = 0; c < 6 && ok; ++c) { /* Gaussian elimination with partial pivoting on J step = e */
            int p = c, r;
            for (r = c + 1; r < 6; ++r)
                if (fabs(a[6 * r + c]) > fabs(a[6 * p + c])) p = r;
            if (!(fabs(a[6 * p + c]) > 0.0)) {
                ok = 0;
                break;
            }
            for (i = 0; i < 6; ++i) {
                const double tmp = a[6 * c + i];
                a[6 * c + i] = a[6 * p + i];
                a[6 * p + i] = tmp;
            }
            {
                const double tmp = e[c];
                e[c] = e[p];
                e[p] = tmp;
            }
            for (r = c + 1; r < 6; ++r) {
                const double f = a[6 * r + c] / a[6 * c + c];
                for (i = c; i < 6; ++i) a[6 * r + i] -= f * a[6 * c + i];
                e[r] -= f * e[c];
            }
        }
        if (!ok) break;
        for (c = 5; c >= 0; --c) {
            double s = e[c];
            for (i = c + 1; i < 6; ++i) s -= a[6 * c + i] * e[i];
            e[c] = s / a[6 * c + c];
        }
        for (i = 0; i < 6; ++i) {
            trial[i] = q[i] + e[i];
            if (!(fabs(e[i]) <= size)) size = fabs(e[i]);
        }
        g6_fk(frames, home, trial, t2, jac2);
        err2 = g6_pose_error(t2, pose);
        if (!(err2 < err) && !(err2 <= near && size <= 0.75 * last)) break;
        memcpy(q, trial, sizeof trial);
        memcpy(t, t2, sizeof t2);
        memcpy(jac, jac2, sizeof jac2);
        err = err2;
        last = size;
        if (err < best_err) {
            best_err = err;
            memcpy(best, q, sizeof best);
        }
        if (err <= done) break; /* at rounding: a further step cannot improve (saves its FK) */
    }
    memcpy(q, best, sizeof best);
}


/* The candidates of one root x (hidden = phi + 2 atan x, or phi + pi when infinite): the monomial vectors in M(x)'s
 * null space, the other two angles from them, t1, t2, t6 from the loop, refined on the chain; appended at row n of
 * q (up to max_out). Returns the new count. */
static int g6_emit(const double *A, const double *B, const double *C, double x, int infinite, double phi, int hidden,
                   double links[6][16], double P[G6_NEQ][27], const g6_qr *f, const int *joints, double sign,
                   const double *frames, const double *home, const double *pose, double *q, int n, int max_out,
                   g6_clusters *cl)
{
    double M[144], m[G6_MAXV][12], angles[3];
    const int a = hidden == 0 ? 1 : 0, b = hidden == 2 ? 1 : 2;
    int i, c, count;
    for (i = 0; i < 144; ++i) M[i] = infinite ? A[i] : (A[i] * x + B[i]) * x + C[i];
    count = g6_monomial_vectors(M, m, cl);
    for (c = 0; c < count && n < max_out; ++c) {
        double t[6];
        angles[hidden] = phi + (infinite ? G6_PI : 2.0 * atan(x));
        angles[a] = g6_half_angle(m[c], 0);
        angles[b] = g6_half_angle(m[c], 1);
        g6_complete(angles, links, P, f, t);
        for (i = 0; i < 6; ++i) q[6 * n + joints[i]] = sign * t[i];
        g6_refine(frames, home, pose, q + 6 * n);
        ++n;
    }
    return n;
}

int wk_g6_solve(const double *frames, const double *home, const double *pose, int shift, int reverse, int hidden,
                double *q, int max_out)
{
    return wk_g6_solve_clusters(frames, home, pose, shift, reverse, hidden, 0, NULL, q, max_out);
}

int wk_g6_solve_clusters(const double *frames, const double *home, const double *pose, int shift, int reverse,
                         int hidden, int clusters, int *near_pair, double *q, int max_out)
{
    int unused = 0;
    double loop[6][16], links[6][16], P[G6_NEQ][27], Q[G6_NEQ][G6_NY], r[G6_NEQ], t6[6][27], N[6][G6_NEQ];
    double A[144], B[144], C[144], zinv[16], pinv[16];
    int joints[6], i, e, n = 0, k, root;
    double sign;
    g6_qr f;
    g6_clusters cl;
    wk_qep_result qep;
    cl.n = 0;
    cl.off = !clusters;
    if (!near_pair) near_pair = &unused;
    *near_pair = 0;
    if (!frames || !home || !pose || !q || shift < 0 || shift > 5 || hidden < 0 || hidden > 2 || max_out < 0) return -1;
    for (i = 0; i < 5; ++i) {
        g6_inverse(frames + 16 * i, zinv);
        g6_mul(zinv, frames + 16 * (i + 1), loop[i]);
    }
    g6_inverse(frames + 80, zinv);
    g6_inverse(pose, pinv);
    g6_mul(zinv, home, loop[5]);
    g6_mul(loop[5], pinv, loop[5]);
    g6_mul(loop[5], frames, loop[5]);
    for (i = 0; i < 6; ++i) {
        /* reversed: K6^-1 Rz(-q6) K5^-1 ... K1^-1 Rz(-q1) = I read from Rz(-q6): links K5^-1 .. K1^-1, K6^-1 */
        static const int rev_link[6] = {4, 3, 2, 1, 0, 5};
        const int src = (i + shift) % 6;
        if (reverse) {
            g6_inverse(loop[rev_link[src]], links[i]);
            joints[i] = 5 - src;
        } else {
            memcpy(links[i], loop[src], sizeof links[i]);
            joints[i] = src;
        }
    }
    sign = reverse ? -1.0 : 1.0;
    g6_equations(links, P, Q, r);
    if (!g6_qr_factor(Q, &f)) return -1;
    g6_left_null(&f, N);
    for (e = 0; e < 6; ++e)
        for (k = 0; k < 27; ++k) {
            double s = 0.0;
            for (i = 0; i < G6_NEQ; ++i) s += N[e][i] * P[i][k];
            t6[e][k] = s;
        }
    if (hidden == 0) { /* the (1 + x^2)^4 deflated: a 16 x 16 eigenproblem */
        double t6r[6][27], xr[16], phi = 0.0;
        const int nr = g6_deflated_roots(t6, N, &phi, xr, clusters, near_pair);
        if (nr >= 0) {
            g6_rotate_hidden(t6, phi, t6r);
            g6_quadratic(t6r, 0, A, B, C);
            for (root = 0; root < nr; ++root)
                n = g6_emit(A, B, C, xr[root], 0, phi, hidden, links, P, &f, joints, sign, frames, home, pose, q,
                            n, max_out, &cl);
            return n;
        }
    }
    g6_quadratic(t6, hidden, A, B, C);
    if (wk_generalized_quadratic_eig(12, A, B, C, 0.0, &qep) != WK_EIG_OK) return -1;
    for (root = 0; root < qep.n_complex; ++root) { /* a pair near the real axis, read as Python reads it */
        const double off = qep.complex_im[root] / (1.0 + hypot(qep.complex_re[root], qep.complex_im[root]));
        if (off > G6_REAL_TOL && off <= G6_CLUSTER_IM_TOL) *near_pair = 1;
        if (off <= (clusters ? G6_CLUSTER_IM_TOL : G6_REAL_TOL))
            n = g6_emit(A, B, C, qep.complex_re[root], 0, 0.0, hidden, links, P, &f, joints, sign, frames, home, pose,
                        q, n, max_out, &cl);
    }
    for (root = 0; root < qep.n_real + qep.n_infinite; ++root) {
        const int infinite = root >= qep.n_real;
        n = g6_emit(A, B, C, infinite ? 0.0 : qep.real[root], infinite, 0.0, hidden, links, P, &f, joints, sign,
                    frames, home, pose, q, n, max_out, &cl);
    }
    return n;
}
