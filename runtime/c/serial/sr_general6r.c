/* A general 6R's stage: every solved joint by elimination (runtime/c/wk_general6r.c, written beside the robot's C),
 * on the axes, points and product of exponentials its derived kernel gives. The candidates are computed once per
 * prefix of the set index above the stage's bits and kept in the call's scratch (sr_ws); set k takes candidate
 * (k >> shift) & mask. Each candidate is checked on the chain's FK, polished to rounding where the elimination left
 * it off (a near-double root: its two eigenvalues resolved to sqrt(eps)), kept when it verifies, and dropped as a
 * duplicate of a kept one (within WK_SAME_SET, or their midpoint on the pose as well: a double root's two eigenvalues
 * polish onto one solution; sr_g6_same).
 * (a wristkin runtime source, inlined whole into a serial arm's generated C that has a general6r stage, after
 * sr_verify.c; Python's serial_general6r.py; derive/families/serial/views.py, tests/test_derived_robot.py) */
#if SR_HAS_GENERAL6R
/* the sets are ordered by their first joint that differs by more than this (Python's G6_ORDER_TOL: the C and numpy
 * eigensolvers find the roots in different orders; a set's joints agree across them to far less) */
#define SR_G6_ORDER_TOL 1e-6

/* -1, 0 or 1 as set a comes before, with or after set b (Python's _g6_order) */
static int sr_g6_order(const double *a, const double *b)
{
    int j;
    for (j = 0; j < 6; ++j)
        if (fabs(a[j] - b[j]) > SR_G6_ORDER_TOL) return a[j] < b[j] ? -1 : 1;
    return 0;
}

/* the n sets in ws in sr_g6_order (insertion sort, stable as Python's sorted) */
static void sr_g6_sort(sr_ws *ws, int n)
{
    int i, j, m;
    for (i = 1; i < n; ++i) {
        double v[6];
        const unsigned fl = ws->f[i];
        for (m = 0; m < 6; ++m) v[m] = ws->q[i][m];
        for (j = i; j > 0 && sr_g6_order(ws->q[j - 1], v) > 0; --j) {
            for (m = 0; m < 6; ++m) ws->q[j][m] = ws->q[j - 1][m];
            ws->f[j] = ws->f[j - 1];
        }
        for (m = 0; m < 6; ++m) ws->q[j][m] = v[m];
        ws->f[j] = fl;
    }
}

/* sigma_min / sigma_max of a kept set's Jacobian up to this: the pose is near a singularity, where a reading can miss
 * a pair of solutions; every reading is then solved and their sets joined (Python's G6_NEAR_SINGULAR) */
#define SR_G6_NEAR_SINGULAR 1e-3

/* why a reading asks for more (sr_g6_reading's *near, Python's G6_NEAR_*): a kept set within SR_G6_NEAR_SINGULAR of
 * singular; an eigenvalue pair near the real axis; a candidate that is no solution, or two on one solution */
#define SR_G6_NEAR_SET 1
#define SR_G6_NEAR_PAIR 2
#define SR_G6_NEAR_ROOTS 4

/* sigma_min / sigma_max of the solved joints' Jacobian (a held joint's column left out; a Cholesky bound proves most
 * sets above SR_G6_NEAR_SINGULAR, sr_gram_spectrum decides the rest: Python's eigvalsh through serial_fk's _spectrum),
 * 1 where proven above (Python's _g6_conditioning) */
static double sr_g6_conditioning(const double *q, const double *dp, const int *joints)
{
    double full[6 * SR_N], jac[36], man, ratio;
    int i, j;
    sr_k_jacobian(q, dp, full);
    for (i = 0; i < 6; ++i)
        for (j = 0; j < 6; ++j) jac[6 * i + j] = full[SR_N * i + joints[j]];
    if (wk_conditioning_bound(jac, 6, SR_G6_NEAR_SINGULAR, &man) == 1) return 1.0;
    (void)sr_gram_spectrum(jac, 6, &ratio);
    return ratio;
}

/* whether candidate x (every joint, residual err) and kept set `kept` (the solved joints' values, residual
 * kept_err; the others q's) are one solution: within WK_SAME_SET, or the pose cannot tell them apart (sr_indistinct,
 * the merge's midpoint test; Python's _g6_same says why not a conditioning bound) */
static int sr_g6_same(const double *x, double err, const double *kept, double kept_err, const int *joints,
                      const double *q, const sr_fit *fit, double floor_)
{
    double y[SR_N];
    int j;
    for (j = 0; j < SR_N; ++j) y[j] = q[j];
    for (j = 0; j < 6; ++j) y[joints[j]] = kept[j];
    return wk_same_set(SR_N, sr_revolute, x, y) || sr_indistinct(x, err, y, kept_err, fit, floor_);
}

/* The verified candidates of one reading of the loop (`clusters`: reading its clusters' subspaces,
 * wk_g6_solve_clusters) appended to ws's first n (at most SR_MAX_IK; their residuals to errs), each unless it is one
 * solution with a kept one (sr_g6_same; then the better fit stands for it); returns the new count, in *merged how many
 * of its candidates met one of its own and in *near the SR_G6_NEAR_* bits of why the reading asks for more (Python's
 * _g6_reading): out = the stage kernel's axes (18), points (18) and target [R | p] (12); q carries the joints solved
 * before the stage (a held joint's value) */
static int sr_g6_reading(const double *out, int shift, int reverse, int hidden, int clusters, const int *joints,
                         const double *q, const double *pose, const double *dp, sr_ws *ws, double *errs, int n,
                         int *merged, int *near)
{
    static const double id4[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    double frames[96], g4[16], cand[WK_G6_MAX_CANDIDATES * 6];
    const double size = fmax(fabs(pose[3]), fmax(fabs(pose[7]), fabs(pose[11])));
    const double target = SR_DOUBLE_ROOT_POLISH_TOL * fmax(1.0, size), floor_ = wk_fk_rounding(size);
    const int first = n;
    int i, j, m, nr, near_pair = 0;
    sr_fit fit;
    fit.pose = pose;
    fit.dp = dp;
    *merged = 0;
    wk_g6_z_frames(out, out + 18, frames);
    for (i = 0; i < 12; ++i) g4[i] = out[36 + i];
    g4[12] = g4[13] = g4[14] = 0.0;
    g4[15] = 1.0;
    nr = wk_g6_solve_clusters(frames, id4, g4, shift, reverse, hidden, clusters, &near_pair, cand,
                              WK_G6_MAX_CANDIDATES);
    if (near_pair) *near |= SR_G6_NEAR_PAIR;
    for (i = 0; i < nr; ++i) {
        double x[SR_N], t[12], vals[6], err, ratio;
        int dup = -1;
        for (j = 0; j < SR_N; ++j) x[j] = q[j];
        for (j = 0; j < 6; ++j) x[joints[j]] = cand[6 * i + j];
        sr_k_fk(x, dp, t);
        err = 0.0;
        for (j = 0; j < 12; ++j) {
            const double d = fabs(t[j] - pose[j]);
            if (!(d <= err)) err = d; /* a NaN fails the check */
        }
        if (!(err <= target)) err = sr_polish(x, pose, dp, target);
        if (!(err <= SR_IK_VERIFY_TOL)) { /* a root that is no solution: a cluster's far member, or a degeneracy */
            *near |= SR_G6_NEAR_ROOTS;
            continue;
        }
        for (j = 0; j < 6; ++j) {
            x[joints[j]] = wk_wrap(x[joints[j]]);
            vals[j] = x[joints[j]];
        }
        ratio = sr_g6_conditioning(x, dp, joints);
        for (m = 0; m < n && dup < 0; ++m)
            if (sr_g6_same(x, err, ws->q[m], errs[m], joints, q, &fit, floor_)) dup = m;
        if (dup >= 0) { /* one solution found twice: the better fit stands for it */
            if (dup >= first) { /* two of its roots on one solution: a double root, or a cluster's */
                ++*merged;
                *near |= SR_G6_NEAR_ROOTS;
            }
            if (err < errs[dup]) {
                for (j = 0; j < 6; ++j) ws->q[dup][j] = x[joints[j]];
                errs[dup] = err;
            }
            continue;
        }
        if (n == SR_MAX_IK) continue; /* more than 16: a degenerate pose's family, the first 16 kept */
        for (j = 0; j < 6; ++j) ws->q[n][j] = vals[j];
        errs[n] = err;
        ws->f[n] = ratio <= SR_SINGULAR_EPS ? WK_FLAG_SINGULAR_INVERSE : 0u;
        if (ratio <= SR_G6_NEAR_SINGULAR) *near |= SR_G6_NEAR_SET;
        ++n;
    }
    return n;
}

/* The verified, distinct candidates of the n readings (shift, reverse, hidden) in turn, sorted: the next is tried
 * where none of one's verifies (its equations degenerate at this pose), and once more where their count is odd.
 * Real solutions come in pairs (the determinant's real roots, counted with multiplicity, are even in number), so an
 * odd count is a double root the pose cannot split or a solution this reading missed (a near-special arm near its
 * singularities), which another reading finds; not where two of the reading's candidates met in one set (a double
 * root), and once at most. That first pass reads no cluster subspaces (an SVD each). A reading whose only trouble is
 * an eigenvalue pair near the real axis is read once more with them (the pair read as a root); near a singularity (a
 * kept set within SR_G6_NEAR_SINGULAR, then or in that second read) or where candidates are no solution or meet,
 * every reading is solved again with them (Python's _g6_candidates says why) */
static int sr_g6_candidates(const double *out, const int (*readings)[3], int n, const int *joints, const double *q,
                            const double *pose, const double *dp, sr_ws *ws)
{
    double errs[SR_MAX_IK];
    int i, found = 0, tried_odd = 0, merged = 0, near = 0, clustered = -1;
    for (i = 0; i < n; ++i) {
        found = sr_g6_reading(out, readings[i][0], readings[i][1], readings[i][2], 0, joints, q, pose, dp, ws, errs,
                              found, &merged, &near);
        if (near == SR_G6_NEAR_PAIR) { /* this reading with its clusters; their copies and far members expected */
            int again = 0, copies = 0;
            found = sr_g6_reading(out, readings[i][0], readings[i][1], readings[i][2], 1, joints, q, pose, dp, ws,
                                  errs, found, &copies, &again);
            near = again & SR_G6_NEAR_SET;
            clustered = i;
        }
        if (near || (found > 0 && (found % 2 == 0 || tried_odd || merged))) break;
        tried_odd = found > 0;
    }
    if (near) /* every reading, with its clusters' subspaces (a set kept already is kept once; the one read so already
               gives its candidates again: skipped) */
        for (i = 0; i < n; ++i)
            if (i != clustered)
                found = sr_g6_reading(out, readings[i][0], readings[i][1], readings[i][2], 1, joints, q, pose, dp,
                                      ws, errs, found, &merged, &near);
    sr_g6_sort(ws, found);
    return found;
}

/* Set k's candidate: `kernel` the stage's (axes, points, target), `parent` the set index's prefix above the stage's
 * bits (the candidates are recomputed when it changes), `idx` the candidate, `readings` the loop's readings in the
 * order they are tried; 0 when there is no such candidate */
static int sr_general6r(sr_stage_kernel kernel, long parent, int idx, const int (*readings)[3], int n_readings,
                        const int *joints, double *q, double *c, double *s, const double *pose, const double *dp,
                        sr_ws *ws, unsigned *f)
{
    if (ws->key != parent) {
        double out[48];
        kernel(pose, q, c, s, dp, out);
        ws->key = parent;
        ws->n = sr_g6_candidates(out, readings, n_readings, joints, q, pose, dp, ws);
        sr_ws_mark_near(ws);
    }
    return sr_ws_take(ws, idx, joints, q, c, s, f);
}
#endif
