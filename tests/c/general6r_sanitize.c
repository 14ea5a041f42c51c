/* Sanitizer driver for runtime/c/wk_general6r.c (ASan/UBSan, built by tests/test_general6r.py): random arms
   (axes and points from the xorshift stream) at random joints through every labelling, then hostile poses (NaN,
   inf, zero, huge translations, a non-rigid matrix) and out-of-range arguments; the output rows are followed by
   canaries that must survive. argv[1]: a seed mixed into the stream (WRISTKIN_TEST_SEED). Prints "ok <cases>"
   or the first violated check and exits 1 then. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sanitize.h"
#include "wk_general6r.h"

#define CANARY 7.25
#define ROWS 8 /* a small max_out: the solver must stop at it */
#define FAIL(...) do { printf(__VA_ARGS__); printf("\n"); return 1; } while (0)

static double out[ROWS + 1][6];

static void rot(const double *k, double t, double *r) /* Rodrigues, 3x3 */
{
    const double c = cos(t), s = sin(t), v = 1.0 - c;
    r[0] = c + k[0] * k[0] * v; r[1] = k[0] * k[1] * v - k[2] * s; r[2] = k[0] * k[2] * v + k[1] * s;
    r[3] = k[1] * k[0] * v + k[2] * s; r[4] = c + k[1] * k[1] * v; r[5] = k[1] * k[2] * v - k[0] * s;
    r[6] = k[2] * k[0] * v - k[1] * s; r[7] = k[2] * k[1] * v + k[0] * s; r[8] = c + k[2] * k[2] * v;
}

static void mul4(const double *a, const double *b, double *o)
{
    double t[16];
    int i, j, k;
    for (i = 0; i < 4; ++i)
        for (j = 0; j < 4; ++j) {
            t[4 * i + j] = 0.0;
            for (k = 0; k < 4; ++k) t[4 * i + j] += a[4 * i + k] * b[4 * k + j];
        }
    memcpy(o, t, sizeof t);
}

/* the pose of the POE chain at q: prod exp(S_i q_i) home */
static void fk(const double *axes, const double *points, const double *home, const double *q, double *pose)
{
    double t[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}, e[16];
    int i, r, c;
    for (i = 0; i < 6; ++i) {
        double m[9];
        rot(axes + 3 * i, q[i], m);
        memset(e, 0, sizeof e);
        for (r = 0; r < 3; ++r) {
            for (c = 0; c < 3; ++c) e[4 * r + c] = m[3 * r + c];
            e[4 * r + 3] = points[3 * i + r] - (m[3 * r] * points[3 * i] + m[3 * r + 1] * points[3 * i + 1] +
                                                m[3 * r + 2] * points[3 * i + 2]);
        }
        e[15] = 1.0;
        mul4(t, e, t);
    }
    mul4(t, home, pose);
}

static int canaries_ok(void)
{
    int j;
    for (j = 0; j < 6; ++j)
        if (out[ROWS][j] != CANARY) return 0;
    return 1;
}

int main(int argc, char **argv)
{
    double axes[18], points[18], home[16] = {1, 0, 0, 0.1, 0, 1, 0, 0.2, 0, 0, 1, 0.3, 0, 0, 0, 1}, pose[16], q[6];
    double frames[96];
    int arm, i, j, n, shift, rev, hidden, cases = 0;
    state ^= (unsigned long long)(argc > 1 ? strtoul(argv[1], NULL, 10) : 0) * 0x9E3779B97F4A7C15ULL;
    for (j = 0; j < 6; ++j) out[ROWS][j] = CANARY;
    for (arm = 0; arm < 12; ++arm) {
        for (i = 0; i < 6; ++i) {
            double nrm = 0.0;
            for (j = 0; j < 3; ++j) {
                axes[3 * i + j] = uniform(-1.0, 1.0);
                nrm += axes[3 * i + j] * axes[3 * i + j];
                points[3 * i + j] = uniform(-0.5, 0.5);
            }
            for (j = 0; j < 3; ++j) axes[3 * i + j] /= sqrt(nrm);
        }
        if (arm % 3 == 0) /* parallel neighbours: a degenerate labelling among the others */
            for (j = 0; j < 3; ++j) axes[3 + j] = axes[j];
        wk_g6_z_frames(axes, points, frames);
        for (i = 0; i < 6; ++i) q[i] = uniform(-3.0, 3.0);
        fk(axes, points, home, q, pose);
        for (shift = 0; shift < 6; ++shift)
            for (rev = 0; rev < 2; ++rev)
                for (hidden = 0; hidden < 3; ++hidden) {
                    n = wk_g6_solve(frames, home, pose, shift, rev, hidden, &out[0][0], ROWS);
                    if (n < -1 || n > ROWS) FAIL("arm %d labelling %d %d %d: count %d", arm, shift, rev, hidden, n);
                    for (i = 0; i < n; ++i)
                        for (j = 0; j < 6; ++j)
                            if (!isfinite(out[i][j])) FAIL("arm %d: a non-finite candidate", arm);
                    if (!canaries_ok()) FAIL("arm %d: wrote past max_out", arm);
                    ++cases;
                }
    }
    {
        const double bad[5] = {NAN, INFINITY, 0.0, 1e300, -1e-310};
        for (i = 0; i < 5; ++i) {
            double p[16];
            memcpy(p, pose, sizeof p);
            p[3] = bad[i];
            if (i == 2) memset(p, 0, sizeof p);
            n = wk_g6_solve(frames, home, p, 0, 0, 0, &out[0][0], ROWS);
            if (n < -1 || n > ROWS || !canaries_ok()) FAIL("hostile pose %d: count %d", i, n);
            ++cases;
        }
        if (wk_g6_solve(frames, home, pose, 6, 0, 0, &out[0][0], ROWS) != -1) FAIL("shift 6 accepted");
        if (wk_g6_solve(frames, home, pose, 0, 0, 3, &out[0][0], ROWS) != -1) FAIL("hidden 3 accepted");
        if (wk_g6_solve(NULL, home, pose, 0, 0, 0, &out[0][0], ROWS) != -1) FAIL("NULL frames accepted");
        if (wk_g6_solve(frames, home, pose, 0, 0, 0, &out[0][0], 0) != 0) FAIL("max_out 0 wrote candidates");
        cases += 4;
    }
    printf("ok %d\n", cases);
    return 0;
}
