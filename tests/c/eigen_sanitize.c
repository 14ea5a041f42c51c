/* Sanitizer driver for runtime/c/wk_eigen.c (ASan/UBSan, built by tests/test_runtime_eigen.py): random,
   special (zero, subnormal, huge, triangular, cyclic, rank-deficient) and hostile (NaN, inf, NULL, sizes out
   of range) inputs through all three entry points, every output array followed by canaries that must survive.
   argv[1]: a seed mixed into the xorshift stream (WRISTKIN_TEST_SEED). Prints "ok <cases>" or the first
   violated check, and exits 1 then. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sanitize.h"
#include "wk_eigen.h"

#define CANARY 7.25
#define PAD 4
#define FAIL(...) do { printf(__VA_ARGS__); printf("\n"); return 1; } while (0)

static double a[WK_EIG_MAXN * WK_EIG_MAXN + PAD], keep[WK_EIG_MAXN * WK_EIG_MAXN];
static double wr[WK_EIG_MAXN + PAD], wi[WK_EIG_MAXN + PAD], work[WK_EIG_WORK(WK_EIG_MAXN) + PAD];

static void fill_canaries(void)
{
    int i;
    for (i = 0; i < PAD; ++i)
        wr[WK_EIG_MAXN + i] = wi[WK_EIG_MAXN + i] = work[WK_EIG_WORK(WK_EIG_MAXN) + i] =
            a[WK_EIG_MAXN * WK_EIG_MAXN + i] = CANARY;
}

static int canaries_ok(void)
{
    int i;
    for (i = 0; i < PAD; ++i)
        if (wr[WK_EIG_MAXN + i] != CANARY || wi[WK_EIG_MAXN + i] != CANARY ||
            work[WK_EIG_WORK(WK_EIG_MAXN) + i] != CANARY || a[WK_EIG_MAXN * WK_EIG_MAXN + i] != CANARY)
            return 0;
    return 1;
}

/* The matrix of kind k (n x n) into a. */
static void make(int kind, int n)
{
    int i, j;
    for (i = 0; i < n * n; ++i)
        a[i] = uniform(-1.0, 1.0);
    switch (kind) {
    case 1: for (i = 0; i < n * n; ++i) a[i] = 0.0; break;
    case 2: for (i = 0; i < n * n; ++i) a[i] *= 1e-310; break;      /* subnormal */
    case 3: for (i = 0; i < n * n; ++i) a[i] *= 1e307; break;       /* huge */
    case 4: for (i = 0; i < n; ++i) for (j = 0; j < i; ++j) a[i * n + j] = 0.0; break; /* triangular */
    case 5: for (i = 0; i < n * n; ++i) a[i] = (i % n == (i / n + n - 1) % n) ? 1.0 : 0.0; break; /* cyclic */
    case 6: for (i = 0; i < n; ++i) for (j = 0; j < n; ++j) a[i * n + j] *= ldexp(1.0, 30 * (i - j)); break; /* graded */
    case 7: for (i = 0; i < n; ++i) a[i * n] = 0.0; break;          /* a zero column */
    default: break;
    }
}

int main(int argc, char **argv)
{
    static double A[WK_QEP_MAXM * WK_QEP_MAXM], B[WK_QEP_MAXM * WK_QEP_MAXM], C[WK_QEP_MAXM * WK_QEP_MAXM];
    double M[WK_NULL_MAXM * WK_NULL_MAXM], v[WK_NULL_MAXM + PAD], rel[2 + PAD];
    wk_qep_result res;
    long cases = 0;
    int n, kind, i, j, rc;
    unsigned long long seed = argc > 1 ? strtoull(argv[1], NULL, 10) : 0;
    state ^= seed * 0x9E3779B97F4A7C15ULL;
    if (state == 0) state = 88172645463325252ULL;
    for (n = 1; n <= WK_EIG_MAXN; ++n)
        for (kind = 0; kind < 8; ++kind) {
            double tr = 0.0, sum = 0.0, nrm = 0.0;
            make(kind, n);
            fill_canaries();
            for (i = 0; i < n; ++i) tr += a[i * n + i];
            for (i = 0; i < n * n; ++i) nrm += fabs(a[i]);
            rc = wk_eig_real(n, a, wr, wi, work);
            ++cases;
            if (!canaries_ok()) FAIL("eig n=%d kind=%d: canary overwritten", n, kind);
            if (rc != WK_EIG_OK) FAIL("eig n=%d kind=%d: rc %d", n, kind, rc);
            for (i = 0; i < n; ++i) {
                if (!isfinite(wr[i]) || !isfinite(wi[i])) FAIL("eig n=%d kind=%d: non-finite eigenvalue", n, kind);
                sum += wr[i];
                if (wi[i] != 0.0 && (i + 1 >= n || wi[i] <= 0.0 || wi[i + 1] != -wi[i] || wr[i + 1] != wr[i]))
                    FAIL("eig n=%d kind=%d: conjugate pair %d not as documented", n, kind, i);
                if (wi[i] != 0.0) ++i, sum += wr[i];
            }
            /* the trace is invariant: backward stability bounds |sum - trace| by ~ n eps ||A|| (1-norm of
               entries here, so a loose but scale-aware check) */
            if (fabs(sum - tr) > 64.0 * n * 2.220446049250313e-16 * nrm + 1e-300)
                FAIL("eig n=%d kind=%d: trace %g vs sum %g", n, kind, tr, sum);
            /* hostile: a NaN or inf anywhere -> input error, outputs zeroed */
            make(0, n);
            a[(n * n) / 2] = (kind % 2) ? NAN : -INFINITY;
            fill_canaries();
            rc = wk_eig_real(n, a, wr, wi, work);
            if (rc != WK_EIG_ERR_INPUT || !canaries_ok() || wr[0] != 0.0) FAIL("eig n=%d: NaN/inf not refused", n);
        }
    for (i = 0; i < WK_EIG_MAXN * WK_EIG_MAXN; ++i) keep[i] = a[i];
    if (wk_eig_real(0, a, wr, wi, work) != WK_EIG_ERR_INPUT || wk_eig_real(33, a, wr, wi, work) != WK_EIG_ERR_INPUT ||
        wk_eig_real(3, NULL, wr, wi, work) != WK_EIG_ERR_INPUT || wk_eig_real(3, a, wr, NULL, work) != WK_EIG_ERR_INPUT)
        FAIL("eig: bad sizes or NULL not refused");
    if (memcmp(keep, a, sizeof keep) != 0) FAIL("eig: a refused call wrote the matrix"); /* bits: a holds a NaN */

    for (n = 1; n <= WK_QEP_MAXM; ++n)
        for (kind = 0; kind < 6; ++kind) {
            int total;
            for (i = 0; i < n * n; ++i) {
                A[i] = uniform(-1.0, 1.0);
                B[i] = uniform(-1.0, 1.0);
                C[i] = uniform(-1.0, 1.0);
            }
            if (kind == 1) for (i = 0; i < n; ++i) A[i * n] = 0.0;           /* singular A: x = inf */
            if (kind == 2) for (j = 0; j < n; ++j) C[j] = 0.0;               /* singular C: x = 0 */
            if (kind == 3) for (i = 0; i < n; ++i) A[i * n] = C[i * n] = 0.0; /* both */
            if (kind == 4) for (i = 0; i < n * n; ++i) A[i] = 0.0;           /* all eigenvalues infinite or linear */
            if (kind == 5) for (i = 0; i < n * n; ++i) { A[i] *= 1e-200; C[i] *= 1e200; }
            rc = wk_generalized_quadratic_eig(n, A, B, C, 0.0, &res);
            ++cases;
            if (rc != WK_EIG_OK) FAIL("qep m=%d kind=%d: rc %d", n, kind, rc);
            total = 2 * res.n_complex + res.n_infinite;
            for (i = 0; i < res.n_real; ++i) {
                total += (res.real_flags[i] & WK_QEP_FLAG_DOUBLE) ? 2 : 1;
                if (!isfinite(res.real[i]) || (i > 0 && res.real[i] < res.real[i - 1]))
                    FAIL("qep m=%d kind=%d: real roots not finite ascending", n, kind);
            }
            if (total != 2 * n) FAIL("qep m=%d kind=%d: %d eigenvalues accounted for", n, kind, total);
            if ((kind == 1 || kind == 3 || kind == 4) && res.n_infinite < 1)
                FAIL("qep m=%d kind=%d: the infinite eigenvalue missing", n, kind);
            A[n * n - 1] = NAN;
            if (wk_generalized_quadratic_eig(n, A, B, C, 0.0, &res) != WK_EIG_ERR_INPUT)
                FAIL("qep m=%d: NaN not refused", n);
            for (i = 0; i < n * n; ++i) A[i] = B[i] = 0.0;
            for (i = 0; i < n; ++i) C[i * n] = 0.0; /* det(C) = 0 and A = B = 0: singular pencil */
            if (wk_generalized_quadratic_eig(n, A, B, C, 0.0, &res) != WK_EIG_ERR_SINGULAR)
                FAIL("qep m=%d: singular pencil not reported", n);
        }
    if (wk_generalized_quadratic_eig(13, A, B, C, 0.0, &res) != WK_EIG_ERR_INPUT ||
        wk_generalized_quadratic_eig(2, NULL, B, C, 0.0, &res) != WK_EIG_ERR_INPUT ||
        wk_generalized_quadratic_eig(2, A, B, C, 0.0, NULL) != WK_EIG_ERR_INPUT ||
        wk_generalized_quadratic_eig(2, A, B, C, NAN, &res) != WK_EIG_ERR_INPUT)
        FAIL("qep: bad sizes, NULL or tol not refused");

    for (n = 1; n <= WK_NULL_MAXM; ++n)
        for (kind = 0; kind < 4; ++kind) {
            double nv = 0.0;
            for (i = 0; i < n * n; ++i) M[i] = (kind == 1) ? 0.0 : uniform(-1.0, 1.0);
            if (kind == 2) for (i = 0; i < n; ++i) M[i * n + n - 1] = M[i * n];  /* two equal columns */
            if (kind == 3) for (i = 0; i < n * n; ++i) M[i] *= 1e-305;
            for (i = 0; i < PAD; ++i) v[n + i] = rel[2 + i] = CANARY;
            rc = wk_null_vector(n, M, v, rel);
            ++cases;
            if (rc != WK_EIG_OK) FAIL("null m=%d kind=%d: rc %d", n, kind, rc);
            for (i = 0; i < PAD; ++i)
                if (v[n + i] != CANARY || rel[2 + i] != CANARY) FAIL("null m=%d: canary overwritten", n);
            for (i = 0; i < n; ++i) nv += v[i] * v[i];
            if (fabs(nv - 1.0) > 64.0 * n * 2.220446049250313e-16) FAIL("null m=%d kind=%d: |v| = %g", n, kind, nv);
            if (!(rel[0] >= 0.0 && rel[0] <= rel[1] && rel[1] <= 1.0)) FAIL("null m=%d kind=%d: rel", n, kind);
            if (kind == 2 && n > 1 && rel[0] > 1e-13) FAIL("null m=%d: rank-deficient, rel %g", n, rel[0]);
            for (i = 0; i < PAD; ++i) v[n + i] = CANARY;
            rc = wk_null_vector_lu(n, M, v, rel);
            if (rc != WK_EIG_OK) FAIL("null_lu m=%d kind=%d: rc %d", n, kind, rc);
            for (i = 0; i < PAD; ++i)
                if (v[n + i] != CANARY) FAIL("null_lu m=%d: canary overwritten", n);
            for (nv = 0.0, i = 0; i < n; ++i) nv += v[i] * v[i];
            if (fabs(nv - 1.0) > 64.0 * n * 2.220446049250313e-16) FAIL("null_lu m=%d kind=%d: |v| = %g", n, kind, nv);
            if (kind == 2 && n > 1 && rel[0] > 1e-13) FAIL("null_lu m=%d: rank-deficient, resid %g", n, rel[0]);
            M[0] = INFINITY;
            if (wk_null_vector(n, M, v, NULL) != WK_EIG_ERR_INPUT) FAIL("null m=%d: inf not refused", n);
            if (wk_null_vector_lu(n, M, v, NULL) != WK_EIG_ERR_INPUT) FAIL("null_lu m=%d: inf not refused", n);
        }
    if (wk_null_vector(25, M, v, rel) != WK_EIG_ERR_INPUT || wk_null_vector(0, M, v, rel) != WK_EIG_ERR_INPUT ||
        wk_null_vector(3, M, NULL, rel) != WK_EIG_ERR_INPUT)
        FAIL("null: bad sizes or NULL not refused");
    printf("ok %ld\n", cases);
    return 0;
}
