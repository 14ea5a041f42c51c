/* A serial arm's checks of an IK set on its FK: the pose error, the damped Gauss-Newton polish and refit, and the
 * member of the wrist's singular family nearest a previous set.
 * (a wristkin runtime source, inlined whole into every serial arm's generated C after its SR_* constants and
 * switches, the sr_design / sr_ik_solutions / sr_fk_solutions types, its derived kernels sr_k_* and stage
 * functions; derive/runtime_files.py, derive/families/serial/views.py, tests/test_serial_runtime.py) */
/* max |t - pose| and the twist error of the pose t (position, then 1/2 sum of column cross products) */
static double sr_twist_error(const double *t, const double *pose, double *e)
{
    double err = 0.0;
    int i;
    for (i = 0; i < 12; ++i) {
        const double e = fabs(t[i] - pose[i]);
        if (!(e <= err)) err = e;
    }
    e[0] = pose[3] - t[3];
    e[1] = pose[7] - t[7];
    e[2] = pose[11] - t[11];
    e[3] = e[4] = e[5] = 0.0;
    for (i = 0; i < 3; ++i) {
        const double a0 = t[i], a1 = t[4 + i], a2 = t[8 + i], b0 = pose[i], b1 = pose[4 + i], b2 = pose[8 + i];
        e[3] += 0.5 * (a1 * b2 - a2 * b1);
        e[4] += 0.5 * (a2 * b0 - a0 * b2);
        e[5] += 0.5 * (a0 * b1 - a1 * b0);
    }
    return err;
}

/* max |FK(q) - pose| and the twist error */
static double sr_pose_error(const double *q, const double *pose, const double *dp, double *e)
{
    double t[12];
    sr_k_fk(q, dp, t);
    return sr_twist_error(t, pose, e);
}

/* The Gauss-Newton step dq from J and the twist error e: J's LU where it is square and regular (the normal
 * equations square its conditioning and cost several times as much); near singular (a pivot at or below 1e-6 of J's
 * largest entry, where the damping 1e-12 on J^T J starts to matter) or a zeroed column (the held joint's, and `hold`
 * unless -1: those joints keep their values, their steps 0): the damped normal equations. 0 when both refuse. */
static int sr_gn_solve(double *jac, const double *e, double *dq, int hold)
{
    int j;
    for (j = 0; j < 6; ++j) {
#if SR_HELD >= 0
        jac[j * SR_N + SR_HELD] = 0.0;
#endif
        if (hold >= 0) jac[j * SR_N + hold] = 0.0;
    }
#if SR_N == 6
    if (hold < 0 && wk_square_solve(jac, 6, e, 1e-6, dq)) return 1; /* a zeroed column: no regular square J */
#endif
    return wk_normal_solve(jac, SR_N, e, 1e-12, dq);
}

/* One damped Gauss-Newton step from q (pose error e, residual err), no longer than max_step in any joint, joint
 * `hold` fixed unless -1: the new residual with q and e moved, or err with both unchanged when the step is refused
 * (singular, too long) or does not help */
static double sr_gn_step(double *q, const double *pose, const double *dp, double *e, double err, double max_step,
                         int hold)
{
    double jac[6 * SR_N], dq[SR_N], trial[SR_N], e2[6], err2;
    int j;
    sr_k_jacobian(q, dp, jac);
    if (!sr_gn_solve(jac, e, dq, hold)) return err;
    for (j = 0; j < SR_N; ++j) {
        if (!(fabs(dq[j]) <= max_step)) return err;
        trial[j] = q[j] + dq[j];
    }
    err2 = sr_pose_error(trial, pose, dp, e2);
    if (!(err2 < err)) return err;
    for (j = 0; j < SR_N; ++j) q[j] = trial[j];
    for (j = 0; j < 6; ++j) e[j] = e2[j];
    return err2;
}

/* Damped Gauss-Newton on the pose error (removes the sqrt(eps) error a tangent root passes downstream): at most
 * SR_POLISH_STEPS steps, until the residual is at most `target` or a step no longer helps */
static double sr_polish(double *q, const double *pose, const double *dp, double target)
{
    double e[6], err = sr_pose_error(q, pose, dp, e);
    int it;
    for (it = 0; it < SR_POLISH_STEPS && err > target; ++it) {
        const double err2 = sr_gn_step(q, pose, dp, e, err, HUGE_VAL, -1);
        if (!(err2 < err)) break;
        err = err2;
    }
    return err;
}

#if SR_CALIBRATED
/* a calibrated arm's search along its near-null direction: the held fit's steps, the held joint's Newton steps and
 * their longest (Python's HELD_FIT_STEPS, NULL_SEARCH_STEPS, NULL_SEARCH_MAX_STEP) */
#define SR_HELD_FIT_STEPS 8
#define SR_NULL_SEARCH_STEPS 20
#define SR_NULL_SEARCH_MAX_STEP 0.5
#define SR_NULL_SEARCH_HALVINGS 6

/* Damped Gauss-Newton on the other joints with joint `hold` fixed, until a step no longer helps: the residual, q
 * and e moved (Python's _held_fit) */
static double sr_held_fit(double *q, const double *pose, const double *dp, int hold, double *e)
{
    double err = sr_pose_error(q, pose, dp, e);
    int it;
    for (it = 0; it < SR_HELD_FIT_STEPS; ++it) {
        const double err2 = sr_gn_step(q, pose, dp, e, err, HUGE_VAL, hold);
        if (!(err2 < err)) break;
        err = err2;
    }
    return err;
}

/* The near-null direction n of J at q (a held joint's column left out; the eigenvector of J^T J's smallest
 * eigenvalue) and jn = J n */
static void sr_null_direction(const double *q, const double *dp, double *n, double *jn)
{
    double jac[6 * SR_N], g[SR_N * SR_N];
    int i, j;
    sr_k_jacobian(q, dp, jac);
#if SR_HELD >= 0
    for (j = 0; j < 6; ++j) jac[j * SR_N + SR_HELD] = 0.0;
#endif
    sr_gram(jac, SR_N, g);
    (void)wk_jacobi_smallest(g, SR_N, n);
    for (i = 0; i < 6; ++i) {
        jn[i] = 0.0;
        for (j = 0; j < SR_N; ++j) jn[i] += jac[i * SR_N + j] * n[j];
    }
}

/* A calibrated arm's set that Gauss-Newton could not bring onto the pose (residual err): the joint carrying most of
 * the near-null direction n held and the others fitted, then Newton steps (J n) . e n_j / |J n|^2 on the held joint
 * taken along n (n read again at each point, a step that does not help halved SR_NULL_SEARCH_HALVINGS times at most)
 * while they help and the residual is above `target`; then polished (Python's _along_null says why): the residual,
 * qk replaced when it improves on err. */
static double sr_along_null(double *qk, const double *pose, const double *dp, double target, double err)
{
    double q[SR_N], trial[SR_N], n[SR_N], jn[6], e[6], e2[6], err1, err2;
    int it, j, hold = 0;
    for (j = 0; j < SR_N; ++j) q[j] = qk[j];
    sr_null_direction(q, dp, n, jn);
#if SR_HELD >= 0
    n[SR_HELD] = 0.0;
#endif
    for (j = 1; j < SR_N; ++j)
        if (fabs(n[j]) > fabs(n[hold])) hold = j;
    err1 = sr_held_fit(q, pose, dp, hold, e);
    for (it = 0; it < SR_NULL_SEARCH_STEPS && !(err1 <= target); ++it) {
        double s2 = 0.0, g = 0.0, step;
        int half;
        sr_null_direction(q, dp, n, jn);
        for (j = 0; j < 6; ++j) {
            s2 += jn[j] * jn[j];
            g += jn[j] * e[j];
        }
        step = s2 > 0.0 ? g * n[hold] / s2 : 0.0;
        step = step < -SR_NULL_SEARCH_MAX_STEP ? -SR_NULL_SEARCH_MAX_STEP :
               (step > SR_NULL_SEARCH_MAX_STEP ? SR_NULL_SEARCH_MAX_STEP : step);
        if (!(step != 0.0)) break;
        for (half = 0; half <= SR_NULL_SEARCH_HALVINGS; ++half) {
            for (j = 0; j < SR_N; ++j) trial[j] = q[j] + step * n[j] / n[hold]; /* along n: the fit corrects less */
            err2 = sr_held_fit(trial, pose, dp, hold, e2);
            if (err2 < err1) break;
            step *= 0.5;
        }
        if (!(err2 < err1)) break;
        for (j = 0; j < SR_N; ++j) q[j] = trial[j];
        for (j = 0; j < 6; ++j) e[j] = e2[j];
        err1 = err2;
    }
    err2 = sr_polish(q, pose, dp, target);
    if (!(err2 < err)) return err;
    for (j = 0; j < SR_N; ++j) qk[j] = sr_revolute[j] ? wk_wrap(q[j]) : q[j];
    return err2;
}
#endif

/* (cos, sin) of a Gauss-Newton step's angle: their series where it is small (the polish's steps: 1e-7 on a
 * calibrated arm; the terms left are below 1e-22 at 1e-2), else libm's */
static void sr_step_cs(double x, double *cx, double *sx)
{
    if (fabs(x) <= 1e-2) {
        const double x2 = x * x;
        *cx = 1.0 - x2 * (0.5 - x2 * (1.0 / 24.0 - x2 * (1.0 / 720.0)));
        *sx = x * (1.0 - x2 * (1.0 / 6.0 - x2 * (1.0 / 120.0 - x2 * (1.0 / 5040.0))));
    } else {
        *cx = cos(x);
        *sx = sin(x);
    }
}

#define SR_CHORD_STEPS 4 /* chord steps on one LU at most before the full polish decides */

/* The LU of the Jacobian a set's polish factored (sr_polish_cs), kept for its wrist mirror: at the mirrored set (q4 + pi,
 * -q5, q6 + pi) every column of J is the base set's but q5's, negated (the wrist centre and the axes of q4 and q6 stay;
 * q5's turns over), exactly on the ideal geometry and to the calibration's size on the true chain */
typedef struct {
    double lu[36];
    int perm[6];
    int ok;
} sr_chord;

/* sr_polish from a set the stages solved, whose (cos, sin) c, s and check t = fk_cs(q, c, s) with residual err the
 * caller has. Chord steps: J (from c, s: no trigonometry) factored once, or the base set's LU reused with q5's step
 * negated where `mirror` says this set is its wrist mirror; each step's trial has its (cos, sin) from the angle-sum
 * rule, checked by fk_cs. A calibrated arm polishes every set, its stages' error the calibration's (~1e-7), so the
 * chord contracts it by ~1e-7 a step: one or two steps, one LU per mirror pair. A step that does not lower the
 * residual, a singular J (a pivot at or below 1e-6 of its largest entry) or steps left above `target`: sr_polish's
 * full Gauss-Newton decides from there. c and s are the caller's copies, moved with q. Without a square J (a held
 * joint, not six joints): one step by sr_gn_solve. */
static double sr_polish_cs(double *q, double *c, double *s, const double *t, double err, const double *pose,
                           const double *dp, double target, sr_chord *chord, int mirror)
{
    double e[6], jac[6 * SR_N], dq[SR_N], trial[SR_N], tc[SR_N], ts[SR_N], t2[12], e2[6], err2;
    int j, it, steps = 1, have_lu = 0;
    if (err <= target) return err;
    (void)sr_twist_error(t, pose, e);
    if (!(SR_CALIBRATED && mirror && chord->ok)) {
#if SR_CALIBRATED
        sr_k_jacobian_cs(q, c, s, dp, jac); /* every set of a calibrated arm comes here: no trigonometry */
#else
        sr_k_jacobian(q, dp, jac);
#endif
#if SR_N == 6 && SR_HELD < 0
        chord->ok = wk_lu_factor(jac, 6, 1e-6, chord->lu, chord->perm);
#endif
        mirror = 0;
    }
#if SR_N == 6 && SR_HELD < 0
    have_lu = chord->ok;
#endif
    if (have_lu && SR_CALIBRATED) steps = SR_CHORD_STEPS;
    for (it = 0; it < steps; ++it) {
#if SR_N == 6 && SR_HELD < 0
        if (have_lu) {
            wk_lu_solve(chord->lu, chord->perm, 6, e, dq);
#if SR_WRIST_J5 >= 0
            if (mirror) dq[SR_WRIST_J5] = -dq[SR_WRIST_J5];
#endif
        } else
#endif
        if (!sr_gn_solve(jac, e, dq, -1)) break;
        for (j = 0; j < SR_N; ++j) {
            if (dq[j] != dq[j]) break; /* a NaN step: the plain polish decides */
            trial[j] = q[j] + dq[j];
            tc[j] = c[j];
            ts[j] = s[j];
            if (sr_revolute[j]) {
                double cd, sd;
                sr_step_cs(dq[j], &cd, &sd);
                tc[j] = c[j] * cd - s[j] * sd;
                ts[j] = s[j] * cd + c[j] * sd;
            }
        }
        if (j < SR_N) break;
        sr_k_fk_cs(trial, tc, ts, dp, t2);
        err2 = sr_twist_error(t2, pose, e2);
        if (!(err2 < err)) break;
        for (j = 0; j < SR_N; ++j) {
            q[j] = trial[j];
            c[j] = tc[j];
            s[j] = ts[j];
        }
        for (j = 0; j < 6; ++j) e[j] = e2[j];
        err = err2;
        if (err <= target) return err;
    }
    return sr_polish(q, pose, dp, target);
}

#if SR_N_FOLD_MASKS > 0 || SR_HAS_GENERAL6R
/* the pose and design a set is fitted to (wk_merge_indistinct's refit) */
typedef struct {
    const double *pose;
    const double *dp;
} sr_fit;

/* the residual after at most one damped Gauss-Newton step no longer than max_step in any joint; none when the
 * residual is at most `accept` already (a midpoint the pose cannot tell from the pair: one FK, no Jacobian) */
static double sr_refit(double *q, double max_step, double accept, const void *ctx)
{
    const sr_fit *fit = (const sr_fit *)ctx;
    double e[6], err2;
    const double err = sr_pose_error(q, fit->pose, fit->dp, e);
    int j;
    if (err <= accept) return err;
    err2 = sr_gn_step(q, fit->pose, fit->dp, e, err, max_step, -1);
    if (err2 < err)
        for (j = 0; j < SR_N; ++j)
            if (sr_revolute[j]) q[j] = wk_wrap(q[j]);
    return err2;
}
#endif

#if SR_FAMILY_SCAN || SR_HAS_GENERAL6R
/* Whether two verified sets (residuals ex, ey) are one solution as wk_merge_indistinct decides (wk_pair_indistinct,
 * refitted on the pose; Python's _indistinct) */
static int sr_indistinct(const double *x, double ex, const double *y, double ey, const sr_fit *fit, double floor_)
{
    double mid[SR_N];
    return wk_pair_indistinct(SR_N, sr_revolute, x, ex, y, ey, sr_refit, fit, floor_, mid) >= 0.0;
}
#endif

#if SR_FAMILY_SCAN
/* a calibrated arm's family scan (Python's FAMILY_SCAN_POINTS) */
#define SR_FAMILY_SCAN_POINTS 36
#define SR_FAMILY_PARTNER_PROBE 1e-3

/* set x (residual err) into out unless it fails the check or is one of the n there already (wk_same_set): the new
 * count */
static int sr_scan_keep(const double *x, double err, double (*out)[SR_N], double *res, int n)
{
    int m, j;
    if (!(err <= SR_IK_VERIFY_TOL)) return n;
    for (m = 0; m < n; ++m)
        if (wk_same_set(SR_N, sr_revolute, x, out[m])) return n;
    for (j = 0; j < SR_N; ++j) out[n][j] = x[j];
    res[n] = err;
    return n + 1;
}

/* The true chain's solutions along a calibrated arm's family through set q, parametrised by joint `hold` (q4: the
 * wrist's; q1: the shoulder's; Python's _family_scan says why): `hold` at SR_FAMILY_SCAN_POINTS points round the
 * circle, the others fitted with it held; each local minimum of the fit's residual searched along the near-null
 * direction to `target`, and from a fold's other root estimated about the solution found (its residual a probe
 * either side: Python's reasons). Up to `max_out` verified, distinct sets into out (their residuals into res);
 * returns their count. */
static int sr_family_scan(const double *q, int hold, const double *pose, const double *dp, double target, int max_out,
                          double (*out)[SR_N], double *res)
{
    double pts[SR_FAMILY_SCAN_POINTS][SR_N], errs[SR_FAMILY_SCAN_POINTS], x[SR_N], root[SR_N], e[6];
    const double spacing = 2.0 * SR_PI / SR_FAMILY_SCAN_POINTS;
    int i, j, n = 0;
    for (j = 0; j < SR_N; ++j) x[j] = q[j];
    for (i = 0; i < SR_FAMILY_SCAN_POINTS; ++i) {
        x[hold] = wk_wrap(q[hold] + 2.0 * SR_PI * i / SR_FAMILY_SCAN_POINTS);
        errs[i] = sr_held_fit(x, pose, dp, hold, e);
        for (j = 0; j < SR_N; ++j) pts[i][j] = x[j];
    }
    for (i = 0; i < SR_FAMILY_SCAN_POINTS && n < max_out; ++i) {
        const int before = i == 0 ? SR_FAMILY_SCAN_POINTS - 1 : i - 1, after = (i + 1) % SR_FAMILY_SCAN_POINTS;
        double err, a, b;
        int n0;
        if (!(errs[i] <= errs[before] && errs[i] <= errs[after])) continue;
        for (j = 0; j < SR_N; ++j) x[j] = pts[i][j];
        err = sr_along_null(x, pose, dp, target, HUGE_VAL);
        n0 = n;
        n = sr_scan_keep(x, err, out, res, n);
        if (n == n0 || n >= max_out) continue;
        for (j = 0; j < SR_N; ++j) root[j] = x[j];
        x[hold] = root[hold] + SR_FAMILY_PARTNER_PROBE; /* the fold's other root (Python's reasons) */
        a = sr_held_fit(x, pose, dp, hold, e);
        for (j = 0; j < SR_N; ++j) x[j] = root[j];
        x[hold] = root[hold] - SR_FAMILY_PARTNER_PROBE;
        b = sr_held_fit(x, pose, dp, hold, e);
        if (a != b) {
            const double step = -SR_FAMILY_PARTNER_PROBE * (a + b) / (a - b);
            if (fabs(step) <= spacing) {
                for (j = 0; j < SR_N; ++j) x[j] = root[j];
                x[hold] = wk_wrap(root[hold] + step);
                (void)sr_held_fit(x, pose, dp, hold, e);
                err = sr_along_null(x, pose, dp, target, HUGE_VAL);
                n = sr_scan_keep(x, err, out, res, n);
            }
        }
    }
    return n;
}
#endif

#if SR_WRIST_STAGE >= 0
/* The member of the wrist family (q4 + t, q6 - sigma t) whose q4 is previous's q4; sigma from the Jacobian's
 * wrist columns (their axes coincide at the singularity). */
static void sr_nearest_member(double *q, const double *previous, const double *dp)
{
    double jac[6 * SR_N], dot = 0.0, t;
    int i;
    sr_k_jacobian(q, dp, jac);
    for (i = 3; i < 6; ++i) dot += jac[i * SR_N + SR_WRIST_J4] * jac[i * SR_N + SR_WRIST_J6];
    t = wk_wrap(wk_wrap(previous[SR_WRIST_J4]) - q[SR_WRIST_J4]);
    q[SR_WRIST_J4] = wk_wrap(q[SR_WRIST_J4] + t);
    q[SR_WRIST_J6] = wk_wrap(q[SR_WRIST_J6] - (dot >= 0.0 ? 1.0 : -1.0) * t);
}
#endif
