/* Per-call time of runtime/c/wk_eigen.c in a C loop: wk_eig_real on random 24 x 24 matrices, the quadratic
 * eigenproblem on random 12 x 12 A, B, C, and wk_null_vector / wk_null_vector_lu on random 12 x 12
 * matrices. Inputs are drawn
 * before timing (the eigensolver overwrites its matrix: each call gets a fresh copy, the copy is timed too,
 * ~0.1 us). Best of 5 repeats over `cases` inputs. Prints one JSON object: ns per call and a checksum. */
#define _POSIX_C_SOURCE 199309L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "wk_eigen.h"

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static unsigned long long s = 0x9E3779B97F4A7C15ULL;
static double urand(void)
{
    s ^= s << 13;
    s ^= s >> 7;
    s ^= s << 17;
    return 2.0 * ((double)(s >> 11) / 9007199254740992.0) - 1.0;
}

int main(int argc, char **argv)
{
    const int cases = argc > 1 ? atoi(argv[1]) : 2000, repeats = 5, n = 24, m = 12;
    double *mats = malloc(sizeof(double) * (size_t)cases * n * n);
    double *abc = malloc(sizeof(double) * (size_t)cases * 3 * m * m);
    double a[24 * 24], wr[24], wi[24], work[WK_EIG_WORK(24)], v[12], rel[2];
    double best[4] = {1e9, 1e9, 1e9, 1e9}, checksum = 0.0;
    long fails = 0, nreal = 0;
    int i, r;
    wk_qep_result res;
    if (!mats || !abc || cases < 1) return 1;
    for (i = 0; i < cases * n * n; ++i) mats[i] = urand();
    for (i = 0; i < cases * 3 * m * m; ++i) abc[i] = urand();
    for (r = 0; r < repeats; ++r) {
        double t0 = now(), t1, t2, t3, t4;
        for (i = 0; i < cases; ++i) {
            memcpy(a, mats + (size_t)i * n * n, sizeof a);
            fails += wk_eig_real(n, a, wr, wi, work) != WK_EIG_OK;
            checksum += wr[0];
        }
        t1 = now();
        for (i = 0; i < cases; ++i) {
            const double *p = abc + (size_t)i * 3 * m * m;
            fails += wk_generalized_quadratic_eig(m, p, p + m * m, p + 2 * m * m, 0.0, &res) != WK_EIG_OK;
            nreal += res.n_real;
            checksum += res.n_real ? res.real[0] : 0.0;
        }
        t2 = now();
        for (i = 0; i < cases; ++i) {
            fails += wk_null_vector(m, mats + (size_t)i * n * n, v, rel) != WK_EIG_OK;
            checksum += v[0];
        }
        t3 = now();
        for (i = 0; i < cases; ++i) {
            fails += wk_null_vector_lu(m, mats + (size_t)i * n * n, v, rel) != WK_EIG_OK;
            checksum += v[0];
        }
        t4 = now();
        if (t4 - t3 < best[3]) best[3] = t4 - t3;
        if (t1 - t0 < best[0]) best[0] = t1 - t0;
        if (t2 - t1 < best[1]) best[1] = t2 - t1;
        if (t3 - t2 < best[2]) best[2] = t3 - t2;
    }
    printf("{\"eig_real_n24_ns\": %.1f, \"qep_m12_ns\": %.1f, \"null_vector_m12_ns\": %.1f, \"null_vector_lu_m12_ns\": %.1f, \"fails\": %ld, "
           "\"mean_real_roots_m12\": %.3f, \"checksum\": %.6g}\n",
           1e9 * best[0] / cases, 1e9 * best[1] / cases, 1e9 * best[2] / cases, 1e9 * best[3] / cases, fails,
           (double)nreal / ((double)cases * repeats), checksum);
    free(mats);
    free(abc);
    return 0;
}
