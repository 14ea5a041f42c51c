/* Per-call timing of the generated underactuated-wrist IK and FK in a plain C loop.
 *
 * Inputs are pre-generated from fixed seeds (xorshift64*, one stream each for IK and FK), so every run times the same calls:
 *   IK poses: first FK mode of joint triples uniform in [0, 2pi)^3 (all reachable)
 *   FK joints: uniform in [0, 2pi)
 * A checksum over the outputs keeps the calls from being optimised away.
 * Prints one JSON object on stdout: ns per call for IK and FK, the call counts and the checksum.
 *
 * Usage: bench_underactuated_wrist [n_ik [n_fk [repeats]]]   (defaults 200000 50000 3; best of repeats)
 */
#define _POSIX_C_SOURCE 199309L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "underactuated_wrist.h"

static const double PI = 3.14159265358979323846;

/* Separate streams for IK and FK inputs, so bench/run.py can reproduce the first rows of each. */
#define IK_SEED 0x9E3779B97F4A7C15ULL
#define FK_SEED 0xD1B54A32D192ED03ULL

static double uniform01(unsigned long long *state)
{
    unsigned long long x = *state;
    x ^= x >> 12;
    x ^= x << 25;
    x ^= x >> 27;
    *state = x;
    return (double)((x * 0x2545F4914F6CDD1DULL) >> 11) * (1.0 / 9007199254740992.0); /* [0, 1) */
}

static double now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}

static double ik_checksum(const wk_underactuated_wrist_ik_solutions *s)
{
    double acc = (double)s->count + (double)s->status;
    int k;
    for (k = 0; k < WK_UNDERACTUATED_WRIST_MAX_IK; ++k) {
        if (s->valid[k]) {
            acc += s->values[k][0] + s->values[k][1] + s->values[k][2];
        }
    }
    return acc;
}

static double fk_checksum(const wk_underactuated_wrist_fk_solutions *s)
{
    double acc = (double)s->count + (double)s->status;
    int k;
    for (k = 0; k < s->count && k < WK_UNDERACTUATED_WRIST_MAX_FK; ++k) {
        acc += s->values[k][0] + s->values[k][1] + s->values[k][2];
    }
    return acc;
}

static long arg_or(int argc, char **argv, int i, long fallback)
{
    if (argc > i) {
        long v = strtol(argv[i], NULL, 10);
        if (v > 0) {
            return v;
        }
    }
    return fallback;
}

int main(int argc, char **argv)
{
    const long n_ik = arg_or(argc, argv, 1, 200000L);
    const long n_fk = arg_or(argc, argv, 2, 50000L);
    const long repeats = arg_or(argc, argv, 3, 3L);
    double *poses = malloc((size_t)n_ik * 3 * sizeof *poses);
    double *joints = malloc((size_t)n_fk * 3 * sizeof *joints);
    wk_underactuated_wrist_ik_solutions ik_out;
    wk_underactuated_wrist_fk_solutions fk_out;
    double checksum = 0.0, best_ik = HUGE_VAL, best_fk = HUGE_VAL;
    long i, r, ik_errors = 0, fk_errors = 0, fk_modes = 0;
    unsigned long long ik_state = IK_SEED, fk_state = FK_SEED;

    if (poses == NULL || joints == NULL) {
        fprintf(stderr, "out of memory\n");
        free(poses);
        free(joints);
        return 1;
    }
    /* IK poses: the first FK assembly mode of random joint triples, so every pose is reachable and the
       whole workspace is covered (triples with no assembly mode are skipped) */
    for (i = 0; i < n_ik;) {
        double q[3];
        wk_underactuated_wrist_fk_solutions fk;
        q[0] = 2.0 * PI * uniform01(&ik_state);
        q[1] = 2.0 * PI * uniform01(&ik_state);
        q[2] = 2.0 * PI * uniform01(&ik_state);
        if (wk_underactuated_wrist_fk(q, NULL, &fk) != WK_OK || fk.count == 0) continue;
        poses[3 * i + 0] = fk.values[0][0];
        poses[3 * i + 1] = fk.values[0][1];
        poses[3 * i + 2] = fk.values[0][2];
        ++i;
    }
    for (i = 0; i < 3 * n_fk; ++i) {
        joints[i] = 2.0 * PI * uniform01(&fk_state);
    }

    /* Warm-up (caches, branch predictors, CPU frequency). */
    for (i = 0; i < n_ik / 10 + 1; ++i) {
        wk_underactuated_wrist_ik(&poses[3 * (i % n_ik)], NULL, &ik_out);
        checksum += ik_checksum(&ik_out);
    }
    for (i = 0; i < n_fk / 10 + 1; ++i) {
        wk_underactuated_wrist_fk(&joints[3 * (i % n_fk)], NULL, &fk_out);
        checksum += fk_checksum(&fk_out);
    }

    for (r = 0; r < repeats; ++r) {
        double t0, t1, ns;
        t0 = now_ns();
        for (i = 0; i < n_ik; ++i) {
            if (wk_underactuated_wrist_ik(&poses[3 * i], NULL, &ik_out) < 0) {
                ++ik_errors;
            }
            checksum += ik_checksum(&ik_out);
        }
        t1 = now_ns();
        ns = (t1 - t0) / (double)n_ik;
        if (ns < best_ik) {
            best_ik = ns;
        }

        t0 = now_ns();
        for (i = 0; i < n_fk; ++i) {
            if (wk_underactuated_wrist_fk(&joints[3 * i], NULL, &fk_out) < 0) {
                ++fk_errors;
            }
            fk_modes += fk_out.count;
            checksum += fk_checksum(&fk_out);
        }
        t1 = now_ns();
        ns = (t1 - t0) / (double)n_fk;
        if (ns < best_fk) {
            best_fk = ns;
        }
    }

    printf("{\"ik_ns\": %.3f, \"fk_ns\": %.3f, \"n_ik\": %ld, \"n_fk\": %ld, \"repeats\": %ld, "
           "\"ik_errors\": %ld, \"fk_errors\": %ld, \"fk_mean_modes\": %.4f, \"checksum\": %.17g, "
           "\"first_pose\": [%.17g, %.17g, %.17g], \"first_joints\": [%.17g, %.17g, %.17g]}\n",
           best_ik, best_fk, n_ik, n_fk, repeats, ik_errors, fk_errors,
           (double)fk_modes / (double)(n_fk * repeats), checksum, poses[0], poses[1], poses[2], joints[0],
           joints[1], joints[2]);
    free(poses);
    free(joints);
    return 0;
}
