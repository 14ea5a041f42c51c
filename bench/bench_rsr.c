/* Per-call time of the generated 3-RSR wrist and SCARA + 3-RSR hybrid in a C loop: IK (all branches) and FK.
 * Inputs: seeded random joints in the working range (legs in [25, 75] deg); IK poses are their FK, so every
 * pose is reachable. Prints one JSON object: ns per call, mean solution counts and a checksum. */
#define _POSIX_C_SOURCE 199309L
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "rsr_wrist.h"
#include "scara_rsr.h"

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static unsigned long long s = 0x9E3779B97F4A7C15ULL;
static double urand(double lo, double hi)
{
    s ^= s << 13;
    s ^= s >> 7;
    s ^= s << 17;
    return lo + (hi - lo) * ((double)(s >> 11) / 9007199254740992.0);
}

int main(int argc, char **argv)
{
    const int n = argc > 1 ? atoi(argv[1]) : 100000, repeats = 5;
    double *wq = malloc(sizeof(double) * (size_t)n * 3), *wp = malloc(sizeof(double) * (size_t)n * 3);
    double *hq = malloc(sizeof(double) * (size_t)n * 7), *hp = malloc(sizeof(double) * (size_t)n * 13);
    double best[4] = {1e9, 1e9, 1e9, 1e9}, checksum = 0.0;
    long counts[2] = {0, 0};
    int i, j, r;
    wk_rsr_wrist_ik_solutions wik;
    wk_rsr_wrist_fk_solutions wfk;
    wk_scara_rsr_ik_solutions hik;
    wk_scara_rsr_fk_solutions hfk;
    if (!wq || !wp || !hq || !hp) return 1;
    for (i = 0; i < n; ++i) {
        for (j = 0; j < 3; ++j) wq[3 * i + j] = urand(0.4363, 1.309);
        wk_rsr_wrist_fk(wq + 3 * i, NULL, &wfk);
        for (j = 0; j < 3; ++j) wp[3 * i + j] = wfk.values[0][j];
        for (j = 0; j < 4; ++j) hq[7 * i + j] = j == 2 ? urand(0.0, 0.3) : urand(-3.1, 3.1);
        for (j = 4; j < 7; ++j) hq[7 * i + j] = urand(0.4363, 1.309);
        wk_scara_rsr_fk(hq + 7 * i, NULL, &hfk);
        for (j = 0; j < 13; ++j) hp[13 * i + j] = hfk.values[0][j];
    }
    for (r = 0; r < repeats; ++r) {
        double t[5];
        t[0] = now();
        for (i = 0; i < n; ++i) {
            wk_rsr_wrist_ik(wp + 3 * i, NULL, &wik);
            counts[0] += wik.count;
        }
        t[1] = now();
        for (i = 0; i < n; ++i) {
            wk_rsr_wrist_fk(wq + 3 * i, NULL, &wfk);
            checksum += wfk.values[0][2];
        }
        t[2] = now();
        for (i = 0; i < n; ++i) {
            wk_scara_rsr_ik(hp + 13 * i, NULL, &hik);
            counts[1] += hik.count;
        }
        t[3] = now();
        for (i = 0; i < n; ++i) {
            wk_scara_rsr_fk(hq + 7 * i, NULL, &hfk);
            checksum += hfk.values[0][3];
        }
        t[4] = now();
        for (j = 0; j < 4; ++j)
            if ((t[j + 1] - t[j]) / n < best[j]) best[j] = (t[j + 1] - t[j]) / n;
    }
    printf("{\"wrist_ik_ns\": %.1f, \"wrist_fk_ns\": %.1f, \"hybrid_ik_ns\": %.1f, \"hybrid_fk_ns\": %.1f, "
           "\"wrist_ik_mean_count\": %.3f, \"hybrid_ik_mean_count\": %.3f, \"checksum\": %.6g}\n",
           best[0] * 1e9, best[1] * 1e9, best[2] * 1e9, best[3] * 1e9, (double)counts[0] / (repeats * (double)n),
           (double)counts[1] / (repeats * (double)n), checksum);
    free(wq);
    free(wp);
    free(hq);
    free(hp);
    return 0;
}
