/* Section profile of runtime/c/wk_general6r.c (issue 23; perf is not available on the bench machine): the solver's
 * steps timed one by one with clock_gettime over many random general 6R arms and poses. It includes the source, so
 * the static steps are called directly, in wk_g6_solve's order, on the same data. Build and run:
 *   cc -O2 -std=c99 -Iruntime/c bench/profile_general6r.c runtime/c/wk_eigen.c -lm -o /tmp/g6prof && /tmp/g6prof
 * Prints microseconds per call of each section and of the whole wk_g6_solve.
 *
 * Before issue 23's speed work (idle 2-core Xeon, gcc -O2; 20 random arms x 25 poses, labelling 0/0/0):
 *   wk_g6_solve 87.7 us: quadratic eigenproblem 43.2 (53%: the 24 x 24 companion's Hessenberg + Francis QR and
 *   the leading coefficient's LU), Newton refine 11.7 (14%: 4.5 candidates x ~3 chain FKs of 18 4x4 products),
 *   the 14 equations 10.4 (13%: 27 loop products and the 27 x 27 interpolation per equation), null vectors 6.0
 *   (7%: complete-pivoting LU per real root), complete 3.8, A/B/C 3.4, QR and N P 2.3, links 0.3.
 * After it (same machine, load ~4 from other jobs on its 2 cores; the sections now as wk_g6_solve runs hidden t3):
 *   wk_g6_solve 38 us: the deflated 16 x 16 roots 23 (wk_eig_real on 16 x 16 alone ~16: Hessenberg ~5, Francis QR
 *   ~11 with ~26 double-shift sweeps; the rest the structure's QRs, the rows per phi and K's LU), null vectors 5.5,
 *   refine 2.8, complete 2.6, QR and N P 2.1, the 14 equations 1.1, A/B/C 0.8.
 * Then (2026-11-27, AMD EPYC 2 cores; wall times on it vary by +-10 % run to run, so counted with cachegrind, the
 * emitted ur5e_tilted module's IK over 1,000 poses): 690k -> 664k instructions per IK from N as six columns of H
 * (not H^T in full), one running maximum per four columns in the complete pivoting's search (its compare-and-move
 * chain was the null vectors' bottleneck), the eigen scalings as one multiplication, one division per bulge step.
 * What is left is spread thin: wk_eig_real 30 %, the per-root work (null vector, complete, refine) 23 %, the
 * structure's QRs 7 %; the eigenproblem alone (Hessenberg + ~26 Francis sweeps, latency-bound) is ~16 us. */
#define _POSIX_C_SOURCE 199309L
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "wk_general6r.c"

static unsigned long long state = 88172645463325252ULL;
static double uniform(double lo, double hi)
{
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    return lo + (hi - lo) * (double)(state >> 11) / 9007199254740992.0;
}

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

#define ARMS 20
#define POSES 25
enum { S_LINKS, S_EQ, S_QR, S_ABC, S_QEP, S_NULL, S_COMPLETE, S_REFINE, S_N };
static const char *names[S_N] = {"loop links", "14 equations (P, Q, r)", "QR + null space + N P",
                                 "A, B, C (12 x 12) at phi", "deflated 16 x 16 roots", "null vectors (per root)",
                                 "complete t1, t2, t6", "Newton refine (3 steps)"};

int main(void)
{
    static double frames[ARMS][96], poses[ARMS][POSES][16];
    double home[16] = {1, 0, 0, 0.1, 0, 1, 0, 0.2, 0, 0, 1, 0.3, 0, 0, 0, 1}, tsec[S_N] = {0}, total = 0.0;
    double cand[WK_G6_MAX_CANDIDATES * 6];
    long roots = 0, calls = 0, real_roots = 0;
    int arm, p, i, j, rep, reps = 20;
    for (arm = 0; arm < ARMS; ++arm) {
        double axes[18], points[18], jac[36], q[6];
        for (i = 0; i < 6; ++i) {
            double nrm = 0.0;
            for (j = 0; j < 3; ++j) {
                axes[3 * i + j] = uniform(-1.0, 1.0);
                nrm += axes[3 * i + j] * axes[3 * i + j];
                points[3 * i + j] = uniform(-0.4, 0.4);
            }
            for (j = 0; j < 3; ++j) axes[3 * i + j] /= sqrt(nrm);
        }
        wk_g6_z_frames(axes, points, frames[arm]);
        for (p = 0; p < POSES; ++p) {
            for (i = 0; i < 6; ++i) q[i] = uniform(-3.0, 3.0);
            g6_fk(frames[arm], home, q, poses[arm][p], jac);
        }
    }
    /* whole solve */
    for (rep = 0; rep < reps; ++rep)
        for (arm = 0; arm < ARMS; ++arm)
            for (p = 0; p < POSES; ++p) {
                double t0 = now();
                int n = wk_g6_solve(frames[arm], home, poses[arm][p], 0, 0, 0, cand, WK_G6_MAX_CANDIDATES);
                total += now() - t0;
                calls++;
                if (rep == 0 && n > 0) roots += n;
            }
    /* sections, wk_g6_solve's body step by step */
    for (rep = 0; rep < reps; ++rep)
        for (arm = 0; arm < ARMS; ++arm)
            for (p = 0; p < POSES; ++p) {
                double loop[6][16], links[6][16], P[G6_NEQ][27], Q[G6_NEQ][G6_NY], r[G6_NEQ], t6[6][27];
                double N[6][G6_NEQ], A[144], B[144], C[144], zinv[16], pinv[16], t0, t1;
                const double *fr = frames[arm], *pose = poses[arm][p];
                int e, k, root, c;
                g6_qr f;
                t0 = now();
                for (i = 0; i < 5; ++i) {
                    g6_inverse(fr + 16 * i, zinv);
                    g6_mul(zinv, fr + 16 * (i + 1), loop[i]);
                }
                g6_inverse(fr + 80, zinv);
                g6_inverse(pose, pinv);
                g6_mul(zinv, home, loop[5]);
                g6_mul(loop[5], pinv, loop[5]);
                g6_mul(loop[5], fr, loop[5]);
                memcpy(links, loop, sizeof links);
                t1 = now(); tsec[S_LINKS] += t1 - t0; t0 = t1;
                g6_equations(links, P, Q, r);
                t1 = now(); tsec[S_EQ] += t1 - t0; t0 = t1;
                if (!g6_qr_factor(Q, &f)) continue;
                g6_left_null(&f, N);
                for (e = 0; e < 6; ++e)
                    for (k = 0; k < 27; ++k) {
                        double s = 0.0;
                        for (i = 0; i < G6_NEQ; ++i) s += N[e][i] * P[i][k];
                        t6[e][k] = s;
                    }
                t1 = now(); tsec[S_QR] += t1 - t0; t0 = t1;
                {
                    double t6r[6][27], xr[16], phi = 0.0, M[144], m[G6_MAXV][12], angles[3], tq[6];
                    int near_pair = 0;
                    int nr = g6_deflated_roots(t6, N, &phi, xr, 0, &near_pair), count;
                    g6_clusters clusters;
                    clusters.n = 0;
                    t1 = now(); tsec[S_QEP] += t1 - t0; t0 = t1;
                    if (nr < 0) continue;
                    if (rep == 0) real_roots += nr;
                    g6_rotate_hidden(t6, phi, t6r);
                    g6_quadratic(t6r, 0, A, B, C);
                    t1 = now(); tsec[S_ABC] += t1 - t0; t0 = t1;
                    for (root = 0; root < nr; ++root) {
                        const double x = xr[root];
                        for (i = 0; i < 144; ++i) M[i] = (A[i] * x + B[i]) * x + C[i];
                        count = g6_monomial_vectors(M, m, &clusters);
                        t1 = now(); tsec[S_NULL] += t1 - t0; t0 = t1;
                        for (c = 0; c < count; ++c) {
                            angles[0] = phi + 2.0 * atan(x);
                            angles[1] = g6_half_angle(m[c], 0);
                            angles[2] = g6_half_angle(m[c], 1);
                            g6_complete(angles, links, P, &f, tq);
                            t1 = now(); tsec[S_COMPLETE] += t1 - t0; t0 = t1;
                            g6_refine(fr, home, pose, tq);
                            t1 = now(); tsec[S_REFINE] += t1 - t0; t0 = t1;
                        }
                    }
                }
            }
    printf("wk_g6_solve: %.1f us per call (%d arms x %d poses, %.1f candidates, %.1f real/infinite roots per pose)\n",
           1e6 * total / (double)calls, ARMS, POSES, (double)roots / (ARMS * POSES),
           (double)real_roots / (ARMS * POSES));
    {
        double sum = 0.0;
        for (i = 0; i < S_N; ++i) sum += tsec[i];
        for (i = 0; i < S_N; ++i)
            printf("  %-28s %6.2f us  %4.1f%%\n", names[i], 1e6 * tsec[i] / (double)calls, 100.0 * tsec[i] / sum);
        printf("  %-28s %6.2f us (timer overhead included)\n", "sum of sections", 1e6 * sum / (double)calls);
    }
    return 0;
}
