/* Per-call time of a generated serial chain in a C loop: IK (all branches), FK, FK + Jacobian.
 * Compile with -DMECH=name -DMECH_H='"name.h"' -DN=joints. Inputs: seeded random joints (revolute in
 * (-pi, pi), prismatic in (-0.5, 0.5)); IK poses are their FK, so every pose is reachable.
 * FK is the bare pose (wk_*_fk_matrix); wk_*_fk adds the manipulability aux (a second Jacobian).
 * Prints one JSON object: ns per call and a checksum (so no call is optimised away). */
#define _POSIX_C_SOURCE 199309L
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include MECH_H

#define CAT3(a, b, c) a##b##c
#define FN(mech, verb) CAT3(wk_, mech, verb)
#define TYPE(mech, suffix) CAT3(wk_, mech, suffix)
#define STR2(x) #x
#define STR(x) STR2(x)

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

int main(int argc, char **argv)
{
    const int n = argc > 1 ? atoi(argv[1]) : 100000, repeats = 5;
    unsigned long long s = 0x9E3779B97F4A7C15ULL;
    double *q = malloc(sizeof(double) * (size_t)n * N), *poses = malloc(sizeof(double) * (size_t)n * 12);
    double best_ik = 1e9, best_fk = 1e9, best_jac = 1e9, jac[6 * N], pose[12];
    long checksum = 0, ik_total = 0;
    int i, j, r;
    TYPE(MECH, _ik_solutions) ik;
    TYPE(MECH, _fk_solutions) fk;
    if (!q || !poses) return 1;
    for (i = 0; i < n * N; ++i) {
        s ^= s << 13; s ^= s >> 7; s ^= s << 17;
        q[i] = ((double)(s >> 11) / 9007199254740992.0 - 0.5) * 6.283185307179586;
    }
    for (i = 0; i < n; ++i) {
        FN(MECH, _fk)(q + (size_t)i * N, NULL, &fk);
        for (j = 0; j < 12; ++j) poses[(size_t)i * 12 + j] = fk.values[0][j];
    }
    for (r = 0; r < repeats; ++r) {
        double t0 = now(), t1, t2, t3;
        for (i = 0; i < n; ++i) {
            FN(MECH, _ik)(poses + (size_t)i * 12, NULL, &ik);
            ik_total += ik.count;
        }
        t1 = now();
        for (i = 0; i < n; ++i) {
            FN(MECH, _fk_matrix)(q + (size_t)i * N, NULL, pose);
            checksum += pose[3] > 0.0;
        }
        t2 = now();
        for (i = 0; i < n; ++i) {
            FN(MECH, _fk_matrix)(q + (size_t)i * N, NULL, pose);
            FN(MECH, _jacobian)(q + (size_t)i * N, NULL, jac);
            checksum += jac[0] > 0.0;
        }
        t3 = now();
        if ((t1 - t0) / n < best_ik) best_ik = (t1 - t0) / n;
        if ((t2 - t1) / n < best_fk) best_fk = (t2 - t1) / n;
        if ((t3 - t2) / n < best_jac) best_jac = (t3 - t2) / n;
    }
    printf("{\"mechanism\": \"%s\", \"n\": %d, \"ik_ns\": %.2f, \"fk_ns\": %.2f, \"fk_jac_ns\": %.2f, "
           "\"ik_mean_count\": %.4f, \"checksum\": %ld}\n", STR(MECH), n, best_ik * 1e9, best_fk * 1e9,
           best_jac * 1e9, (double)ik_total / ((double)n * repeats), checksum);
    free(q);
    free(poses);
    return 0;
}
