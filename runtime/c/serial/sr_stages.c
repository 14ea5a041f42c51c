/* A serial arm's IK stage solvers: each solves its joints and their (cos, sin) algebraically from the stage
 * kernel's coefficients (out), so no stage after the first needs trigonometry, and the FK check (fk_cs) needs none
 * either. The generated sr_solve_stage<k> call them with the stage's joints and branch bit; each returns 1 when
 * the stage has a root on this branch (flags in *f), else 0.
 * (a wristkin runtime source, inlined whole into every serial arm's generated C after its SR_* constants and
 * switches, the sr_design / sr_ik_solutions / sr_fk_solutions types, its derived kernels sr_k_* and stage
 * functions; derive/runtime_files.py, derive/families/serial/views.py, tests/test_serial_runtime.py) */
/* a stage kernel: what a family probes its next stage with, what the general 6R's stage reads once per prefix */
typedef void (*sr_stage_kernel)(const double *pose, const double *q, const double *c, const double *s,
                                const double *dp, double *out);

/* One IK call's scratch for the stage that computes several candidates at once (the general 6R's, the spatial 3R's,
 * subproblem 6's, the arm angle's or the held elbow's: a chain has one at most, derive/serial_core/views.py), kept
 * across the set words that share the prefix above its bits; sized by that stage's candidates and joints */
#define SR_S3_KEEP 4 /* a spatial 3R's candidates kept (Pieper's bound on a 3R's positions) */
#define SR_SP6_KEEP 4 /* subproblem 6's candidates kept (its quartic's real roots) */
#if SR_HAS_GENERAL6R
#define SR_WS_SETS SR_MAX_IK
#define SR_WS_JOINTS 6
#elif SR_HAS_SPATIAL3
#define SR_WS_SETS SR_S3_KEEP
#define SR_WS_JOINTS 3
#elif SR_HAS_SP6
#define SR_WS_SETS SR_SP6_KEEP
#define SR_WS_JOINTS 2
#elif SR_HAS_ARM_ANGLE
#define SR_WS_SETS 4   /* two elbows x two shoulders */
#define SR_WS_JOINTS 4 /* the shoulder's three and the elbow */
#elif SR_HAS_HELD_ELBOW
#define SR_WS_SETS 4   /* the core's sets (two shoulders: the elbow held) */
#define SR_WS_JOINTS 3 /* the shoulder's three */
#else
#define SR_WS_SETS 0
#endif
typedef struct {
#if SR_WS_SETS > 0
    long key; /* the prefix the candidates were computed for (-1: none yet) */
    int n;
    double q[SR_WS_SETS][SR_WS_JOINTS];
    double amp[SR_WS_SETS]; /* how much a candidate's last joint amplifies the input's rounding (subproblem 6's) */
    unsigned f[SR_WS_SETS];
#else
    int unused; /* C99 has no empty structs */
#endif
} sr_ws;

/* a fresh scratch for one IK call */
static void sr_ws_init(sr_ws *ws)
{
#if SR_WS_SETS > 0
    ws->key = -1;
    ws->n = 0;
#else
    ws->unused = 0;
#endif
}

#if SR_WS_SETS > 0
/* WK_FLAG_MERGE_CANDIDATE on each of the scratch's candidates within WK_MERGE_SPAN in every joint of another (their
 * joints revolute): near a double root of the stage the two may be one solution, which wk_merge_indistinct decides
 * on the whole set (the stage's bits are one of its masks); Python's _ws_mark_near */
static void sr_ws_mark_near(sr_ws *ws)
{
    int i, j, m;
    for (i = 0; i < ws->n; ++i)
        for (j = i + 1; j < ws->n; ++j) {
            int near = 1;
            for (m = 0; m < SR_WS_JOINTS && near; ++m) near = fabs(wk_wrap(ws->q[j][m] - ws->q[i][m])) <= WK_MERGE_SPAN;
            if (near) {
                ws->f[i] |= WK_FLAG_MERGE_CANDIDATE;
                ws->f[j] |= WK_FLAG_MERGE_CANDIDATE;
            }
        }
}

/* Candidate idx of the scratch into q, c, s at the stage's joints (wrapped: Newton's steps and band splits reach past
 * pi), its flags into *f; 0 when there is no such candidate */
static int sr_ws_take(const sr_ws *ws, int idx, const int *joints, double *q, double *c, double *s, unsigned *f)
{
    int j;
    if (idx >= ws->n) return 0;
    for (j = 0; j < SR_WS_JOINTS; ++j) {
        const double v = wk_wrap(ws->q[idx][j]);
        q[joints[j]] = v;
        c[joints[j]] = cos(v);
        s[joints[j]] = sin(v);
    }
    *f = ws->f[idx];
    return 1;
}
#endif

#if SR_HAS_TRIG_LINEAR || SR_WRIST_STAGE >= 0
/* the root a two-root stage takes in set k: +1 when bit `bit` of k is 0 (the +acos root, the first wrist branch) */
static double sr_sign(int k, int bit)
{
    return ((k >> bit) & 1) == 0 ? 1.0 : -1.0;
}
#endif

#if SR_HAS_FAMILY_STAGE
/* A stage whose equation vanishes (a one-parameter family in joint j): its representative, previous's value when
 * given (the member nearest it), else 0 (Python's _family_member) */
static void sr_family_member(int j, double *q, double *c, double *s, const double *prev)
{
    const double v = prev ? prev[j] : 0.0;
    q[j] = v;
    c[j] = v == 0.0 ? 1.0 : cos(v);
    s[j] = v == 0.0 ? 0.0 : sin(v);
}
#endif

#if SR_HAS_TRIG_LINEAR
static double sr_clamp1(double x)
{
    return x > 1.0 ? 1.0 : (x < -1.0 ? -1.0 : x);
}

/* The design's size: its largest length, at least 1 (Python's _design_size) */
static inline double sr_design_size(const double *dp)
{
    double size = 1.0;
    int i;
    for (i = 0; i < SR_N_LENGTHS; ++i)
        if (fabs(dp[i]) > size) size = fabs(dp[i]);
    return size;
}

/* (sin w, scale) of the roots phi +- w: below sqrt(tol x scale) they are one double root (Python's _root_gap). From
 * u alone 1 - u^2 carries a few eps of rounding (scale 1, tol SR_ROOT_GAP_TOL); a factored stage gives the factors
 * Dm, Dp of 4 R^2 (1 - u^2), each to its own precision, and Em, the scale of Dm's rounding (its tol: a distance's
 * SR_ROOT_GAP_TOL, a wrist's half-gap SR_WRIST_FAMILY_TOL, then SR_WRIST_EXACT_TOL) */
static inline void sr_root_gap(const double *out, int factored, double r, double u, double amp_before, double *sg,
                               double *scale)
{
    if (!factored) {
        *sg = sqrt(1.0 - u * u);
        *scale = 1.0;
    } else {
        /* the product and |Dm| <= |Dp|: a length derived as positive and given negative swaps the factors and their
         * signs (Python's _root_gap) */
        const double prod = out[3] * out[4];
        /* Dm's rounding is never below eps of the stage's size r (Em = 0 exactly: a UR wrist at q5 = 0) */
        *scale = fabs(out[3]) <= fabs(out[4]) ? fmin(1.0, fmax(out[5], DBL_EPSILON * r) * amp_before / (2.0 * r)) :
                                                1.0;
        *sg = prod > 0.0 ? sqrt(prod) / (2.0 * r) : 0.0;
    }
}

/* Joint j from A cos q + B sin q + C = 0 (out = A, B, C, a factored stage's also Dm, Dp, Em): q = atan2(B, A) +
 * sgn acos(-C / sqrt(A^2 + B^2)). floor_tol > 0 (a wrist's half-gap): one double root below its band only, the two
 * roots flagged indeterminate up to gap_tol's (Python's _trig_linear). inline: each stage of this kind calls it with
 * its own constant joint, bit and form, as straight-line code would */
static inline int sr_trig_linear(const double *out, int factored, double gap_tol, double floor_tol, int j,
                                 double sgn, double *q, double *c, double *s, const double *prev, double *amp,
                                 double amp_before, double size, unsigned *f)
{
    const double r = sqrt(out[0] * out[0] + out[1] * out[1]);
    double u = 0.0, sg, scale, band, ca, sa;
    int family = r <= SR_ON_AXIS_TOL * size; /* (A, B) at the rounding of the design's lengths (Python's _trig_linear) */
    if (!family) {
        u = -out[2] / r;
        /* the band grows with the rounding the stages before amplified into u (Python's TANGENT_MAX says why it
         * may), and with a calibrated robot's geometry (Python's TANGENT_CALIBRATED) */
        if (!(fabs(u) <= 1.0 + fmax(fmax(SR_TANGENT_TOL, fmin(SR_TANGENT_MAX, SR_STAGE_NOISE * amp_before)),
                                    SR_TANGENT_CALIBRATED))) {
            if (!(r <= SR_TANGENT_CALIBRATED * size)) return 0;
            family = 1; /* a calibrated robot's (A, B) within its geometry's deviation (Python's reasons) */
        }
    }
    if (family) {
        /* |C| within sqrt(SR_DOUBLE_ROOT_TOL): an upstream double root's residue (see Python); the FK check decides */
        if (fabs(out[2]) > sqrt(SR_DOUBLE_ROOT_TOL) || sgn < 0.0) return 0;
        sr_family_member(j, q, c, s, prev); /* one-parameter family: its representative */
        *f = WK_FLAG_INDETERMINATE | WK_FLAG_SINGULAR_INVERSE;
        amp[j] = 1.0;
        return 1;
    }
    u = sr_clamp1(u);
    sr_root_gap(out, factored, r, u, amp_before, &sg, &scale);
    band = factored ? sqrt((floor_tol > 0.0 ? floor_tol : gap_tol) * scale) : sqrt(SR_ROOT_GAP_TOL);
    if (sg <= band) {
        if (sgn < 0.0) return 0; /* a double root is one solution: reported once, by the + branch */
        *f = WK_FLAG_DOUBLE_ROOT | WK_FLAG_SINGULAR_INVERSE;
        sg = 0.0; /* at its centre: within the band sin w is rounding (see Python) */
    } else if (floor_tol > 0.0 && factored && sg * sg <= gap_tol * scale) {
        *f = WK_FLAG_INDETERMINATE | WK_FLAG_SINGULAR_INVERSE; /* within rounding of the wrist's family (see Python) */
    } else if (sg * sg <= (factored ? gap_tol : SR_ROOT_GAP_TOL) * amp_before) {
        *f = WK_FLAG_MERGE_CANDIDATE; /* within the stages' noise of a double root: the merge decides (see Python) */
    }
    /* the roots phi +- w amplify the input's rounding by 1 / sin w (a double root: 1 / band) */
    amp[j] = 1.0 / ((*f & WK_FLAG_DOUBLE_ROOT) ? band : sg);
    /* q = atan2(B, A) + sgn acos(u): its cos and sin follow from (A, B, u) */
    ca = out[0] / r;
    sa = out[1] / r;
    c[j] = ca * u - sgn * sa * sg;
    s[j] = sa * u + sgn * ca * sg;
    q[j] = atan2(s[j], c[j]);
    return 1;
}
#endif

#if SR_HAS_ROTATION2D

#if SR_HAS_FAMILY_PROBE
/* The next stage's C = C0 + C1 cos t + C2 sin t over joint j's value t, from its kernel `probe` at t = 0, pi and
 * pi / 2 (q, c, s[j] left at the last; Python's _reach_terms) */
static void sr_reach_terms(int j, double *q, double *c, double *s, sr_stage_kernel probe, const double *pose,
                           const double *dp, double *c0, double *c1, double *c2)
{
    double o[6], c_zero;
    q[j] = 0.0, c[j] = 1.0, s[j] = 0.0;
    probe(pose, q, c, s, dp, o);
    c_zero = o[2];
    q[j] = SR_PI, c[j] = -1.0, s[j] = 0.0;
    probe(pose, q, c, s, dp, o);
    *c0 = 0.5 * (c_zero + o[2]);
    *c1 = 0.5 * (c_zero - o[2]);
    q[j] = 0.5 * SR_PI, c[j] = 0.0, s[j] = 1.0;
    probe(pose, q, c, s, dp, o);
    *c2 = o[2] - *c0;
}

/* The member of a family in joint j whose next stage (A cos q' + B sin q' + C = 0, its kernel `probe`) reaches:
 * previous's where it does, else the one with C = 0 from three probes, C = C0 + C1 cos t + C2 sin t in the member t
 * (Python's _family_by_reach says why) */
static void sr_family_by_reach(int j, double *q, double *c, double *s, const double *prev, sr_stage_kernel probe,
                               const double *pose, const double *dp)
{
    double o[6], c0, c1, c2, g, t;
    if (prev) {
        q[j] = prev[j];
        c[j] = cos(prev[j]);
        s[j] = sin(prev[j]);
        probe(pose, q, c, s, dp, o);
        if (fabs(o[2]) <= sqrt(o[0] * o[0] + o[1] * o[1]) * (1.0 + SR_TANGENT_TOL)) return;
    }
    sr_reach_terms(j, q, c, s, probe, pose, dp, &c0, &c1, &c2);
    g = sqrt(c1 * c1 + c2 * c2);
    if (g <= SR_DEGENERATE_EPS) { /* the next stage does not see the family: its usual representative */
        sr_family_member(j, q, c, s, prev);
        return;
    }
    t = atan2(c2, c1) + acos(sr_clamp1(-c0 / g));
    c[j] = cos(t);
    s[j] = sin(t);
    q[j] = atan2(s[j], c[j]);
}

/* Near the family joint j's rounding moves the next stage's target past its band: where that stage does not reach at
 * the joint as read, the joint moves to the nearest member where it does (its reach's edge, from three probes), if
 * within `window` (Python's _near_family_by_reach says why). Returns whether it moved (else q, c, s as read). */
static int sr_near_family_by_reach(int j, double *q, double *c, double *s, sr_stage_kernel probe, const double *pose,
                                   const double *dp, double window)
{
    double o[6], r, c0, c1, c2, g, x, phi, w, t, ta, tb;
    const double rq = q[j], rc = c[j], rs = s[j];
    probe(pose, q, c, s, dp, o);
    r = sqrt(o[0] * o[0] + o[1] * o[1]);
    if (fabs(o[2]) <= r) return 0;
    x = o[2] < 0.0 ? -r : r;
    sr_reach_terms(j, q, c, s, probe, pose, dp, &c0, &c1, &c2);
    g = sqrt(c1 * c1 + c2 * c2);
    x = g > SR_DEGENERATE_EPS ? (x - c0) / g : 2.0;
    if (fabs(x) <= 1.0) {
        phi = atan2(c2, c1);
        w = acos(x);
        ta = fabs(remainder(phi + w - rq, 2.0 * SR_PI));
        tb = fabs(remainder(phi - w - rq, 2.0 * SR_PI));
        t = tb < ta ? phi - w : phi + w;
        if ((tb < ta ? tb : ta) <= window) {
            q[j] = wk_wrap(t);
            c[j] = cos(t);
            s[j] = sin(t);
            return 1;
        }
    }
    q[j] = rq, c[j] = rc, s[j] = rs;
    return 0;
}
#endif

/* Joint j as the angle from (u0, v0) to (u, v) (out = u, v, u0, v0); a family where either vanishes (its member by
 * sr_family_by_reach when the stage has a probe, its next stage's kernel; else NULL) */
static int sr_rotation2d(const double *out, int j, double *q, double *c, double *s, const double *prev,
                         double *amp, unsigned *f, sr_stage_kernel probe, const double *pose, const double *dp)
{
    const double nu = sqrt(out[0] * out[0] + out[1] * out[1]), n0 = sqrt(out[2] * out[2] + out[3] * out[3]);
    /* a family at the rounding of the design's lengths (Python's _rotation2d: above it the pose fixes the angle) */
    const double tol = SR_ON_AXIS_TOL * sr_design_size(dp);
    if (n0 <= tol || nu <= tol) {
#if SR_HAS_FAMILY_PROBE
        if (probe)
            sr_family_by_reach(j, q, c, s, prev, probe, pose, dp);
        else
            sr_family_member(j, q, c, s, prev);
#else
        (void)probe;
        (void)pose;
        (void)dp;
        sr_family_member(j, q, c, s, prev);
#endif
        *f = WK_FLAG_INDETERMINATE | WK_FLAG_SINGULAR_INVERSE;
        amp[j] = 1.0;
    } else {
        const double cu = out[0] / nu, su = out[1] / nu, c0 = out[2] / n0, s0 = out[3] / n0;
        const double shorter = nu < n0 ? nu : n0;
        /* the angle carries the vectors' rounding over the shorter one's length (Python's _rotation2d) */
        amp[j] = shorter < 1.0 ? 1.0 / shorter : 1.0;
        c[j] = cu * c0 + su * s0;
        s[j] = su * c0 - cu * s0;
        q[j] = atan2(s[j], c[j]);
#if SR_HAS_FAMILY_PROBE
        if (probe && SR_STAGE_NOISE * amp[j] > SR_TANGENT_MAX &&
            sr_near_family_by_reach(j, q, c, s, probe, pose, dp, tol / shorter))
            *f = WK_FLAG_INDETERMINATE | WK_FLAG_SINGULAR_INVERSE;
#endif
    }
    return 1;
}
#endif

#if SR_HAS_REVOLUTE_VALUE
/* a revolute joint j given directly (out = q_j), wrapped */
static int sr_revolute_value(const double *out, int j, double *q, double *c, double *s)
{
    q[j] = wk_wrap(out[0]);
    c[j] = cos(q[j]);
    s[j] = sin(q[j]);
    return 1;
}
#endif

#if SR_HAS_PRISMATIC_VALUE
/* a prismatic joint j given directly (out = q_j) */
static int sr_prismatic_value(const double *out, int j, double *q, double *c, double *s)
{
    (void)c;
    (void)s;
    q[j] = out[0];
    return 1;
}
#endif

#if SR_HAS_SLIDE_QUADRATIC
/* A slide from a distance (out = (B, D, E): (q + B)^2 = D, E the scale of D's rounding): q = -B + sgn sqrt(D); D
 * within SR_ROOT_GAP_TOL of E one double root (the + branch reports it), below that no real root (Python's
 * _slide_quadratic). */
static int sr_slide_quadratic(const double *out, int j, double sgn, double *q, double *c, double *s, unsigned *f)
{
    const double band = SR_ROOT_GAP_TOL * out[2];
    (void)c;
    (void)s;
    if (!(out[1] >= -band)) return 0;
    if (out[1] <= band) {
        if (sgn < 0.0) return 0;
        q[j] = -out[0];
        *f = WK_FLAG_DOUBLE_ROOT | WK_FLAG_SINGULAR_INVERSE;
        return 1;
    }
    q[j] = -out[0] + sgn * sqrt(out[1]);
    return 1;
}
#endif

#if SR_WRIST_STAGE >= 0
/* +1 when turning q4 by a moves the end frame as turning q6 by a does at theta5 = 0 (up) or pi (down), else
 * -1: the axes coincide there, so q6 + sigma q4 is what the pose defines (probed on the FK of the geometry the
 * stages solve: a calibrated robot's ideal table, whose axes coincide exactly). */
static double sr_wrist_sigma(int up, const double *dp, const int *w)
{
    double qa[SR_N], qb[SR_N], ta[12], tb[12], scale = 1.0, diff = 0.0;
    int j;
    for (j = 0; j < SR_N; ++j) qa[j] = qb[j] = 0.0;
    qa[w[1]] = qb[w[1]] = up ? 0.0 : SR_PI;
    qa[w[0]] = 0.5;
    qb[w[2]] = 0.5;
#if SR_CALIBRATED
    {
        double ca[SR_N], sa[SR_N], cb[SR_N], sb[SR_N];
        for (j = 0; j < SR_N; ++j) {
            ca[j] = cos(qa[j]);
            sa[j] = sin(qa[j]);
            cb[j] = cos(qb[j]);
            sb[j] = sin(qb[j]);
        }
        sr_k_fk_ideal(qa, ca, sa, dp, ta);
        sr_k_fk_ideal(qb, cb, sb, dp, tb);
    }
#else
    sr_k_fk(qa, dp, ta);
    sr_k_fk(qb, dp, tb);
#endif
    for (j = 0; j < SR_N_LENGTHS; ++j)
        if (fabs(dp[j]) + 1.0 > scale) scale = fabs(dp[j]) + 1.0;
    for (j = 0; j < 12; ++j)
        if (fabs(ta[j] - tb[j]) > diff) diff = fabs(ta[j] - tb[j]);
    return diff <= 1e-9 * scale ? 1.0 : -1.0;
}

/* The shares of the wrist centre's kappa and of amp_before the family bands' factor takes (Python's
 * WRIST_KAPPA_SHARE and WRIST_AMP_SHARE say why) */
#define SR_WRIST_KAPPA_SHARE 0.25
#define SR_WRIST_AMP_SHARE 16.0

/* The factor the wrist's family bands scale by: WRIST_KAPPA_SHARE kappa of the wrist centre's Jacobian in the prefix
 * joints (its kernel `centre`), kappa = size ||adj J||_F / |det J|, capped at WRIST_AMP_SHARE amp_before; amp_before
 * without the kernel, or where |sin theta5| is beyond twice the widest band's reach (Python's _wrist_amp: the same
 * operations) */
static double sr_wrist_amp(double s5, double amp_before, sr_stage_kernel centre, const double *pose, const double *q,
                           const double *c, const double *s, const double *dp)
{
    double m[9], a[9], det, adj, share, cap;
    if (centre == NULL) return amp_before;
    cap = SR_WRIST_AMP_SHARE * amp_before;
    if (!(fabs(s5) <= 2.0 * SR_WRIST_EXACT_TOL * cap)) return amp_before;
    centre(pose, q, c, s, dp, m);
    a[0] = m[4] * m[8] - m[5] * m[7];
    a[1] = m[5] * m[6] - m[3] * m[8];
    a[2] = m[3] * m[7] - m[4] * m[6];
    a[3] = m[2] * m[7] - m[1] * m[8];
    a[4] = m[0] * m[8] - m[2] * m[6];
    a[5] = m[1] * m[6] - m[0] * m[7];
    a[6] = m[1] * m[5] - m[2] * m[4];
    a[7] = m[2] * m[3] - m[0] * m[5];
    a[8] = m[0] * m[4] - m[1] * m[3];
    det = fabs(m[0] * a[0] + m[1] * a[1] + m[2] * a[2]);
    adj = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2] + a[3] * a[3] + a[4] * a[4] + a[5] * a[5] + a[6] * a[6] +
               a[7] * a[7] + a[8] * a[8]);
    share = SR_WRIST_KAPPA_SHARE * fmax(1.0, fmax(fabs(pose[3]), fmax(fabs(pose[7]), fabs(pose[11])))) * adj;
    return share < cap * det ? share / det : cap;
}

#if SR_HAS_WRIST_MIRROR
/* The second wrist branch mirrors the first, computed for the same prefix at set k - 1 (the wrist is the last
 * branching stage): q5 -> -q5, q4 -> q4 + pi, q6 -> q6 + pi. At the singularity the first branch already holds the
 * whole family (its sin theta5 exactly 0), so this one is a duplicate; within SR_WRIST_EXACT_TOL of it (times
 * sr_wrist_amp's factor, as the first branch read it) both are the pose's own reading of a near family (sr_wrist). */
static int sr_wrist_mirror(const int *w, double *q, double *c, double *s, double amp_before, sr_stage_kernel centre,
                           const double *pose, const double *dp, unsigned *f)
{
    if (fabs(s[w[1]]) <= SR_WRIST_FAMILY_TOL) return 0;
    amp_before = sr_wrist_amp(s[w[1]], amp_before, centre, pose, q, c, s, dp);
    if (fabs(s[w[1]]) <= SR_SINGULAR_EPS) *f = WK_FLAG_SINGULAR_INVERSE;
    if (fabs(s[w[1]]) <= SR_WRIST_EXACT_TOL * amp_before)
        *f = WK_FLAG_SINGULAR_INVERSE | WK_FLAG_INDETERMINATE | WK_FLAG_READ_MEMBER;
    q[w[1]] = -q[w[1]];
    s[w[1]] = -s[w[1]];
    q[w[0]] = q[w[0]] > 0.0 ? q[w[0]] - SR_PI : q[w[0]] + SR_PI;
    c[w[0]] = -c[w[0]];
    s[w[0]] = -s[w[0]];
    q[w[2]] = q[w[2]] > 0.0 ? q[w[2]] - SR_PI : q[w[2]] + SR_PI;
    c[w[2]] = -c[w[2]];
    s[w[2]] = -s[w[2]];
    return 1;
}
#endif

/* The spherical wrist (q4, q5, q6 = w[0..2]) from the entries of its rotation (out, 9), branch sgn; e: the DH
 * twists' signs of those entries (e0..e3) and of the singular family's (k00, k10 at theta5 = 0, then pi). */
static int sr_wrist(const double *out, double sgn, const double *e, const int *w, double *q, double *c, double *s,
                    const double *dp, double amp_before, sr_stage_kernel centre, const double *pose, unsigned *f)
{
    const double s5 = sgn * sqrt(out[2] * out[2] + out[5] * out[5]), c5 = e[0] * out[8];
    /* the family bands: the stages before amplified the input's rounding into the wrist's rotation (sr_wrist_amp's
     * factor: the wrist centre's kappa share, capped at WRIST_AMP_SHARE x their product); within the exact band the
     * entries place the member of a near family, flagged indeterminate (Python's _wrist) */
    const double amp = sr_wrist_amp(s5, amp_before, centre, pose, q, c, s, dp), family = SR_WRIST_FAMILY_TOL * amp;
    double x, y, n;
    if (fabs(s5) <= SR_SINGULAR_EPS) *f = WK_FLAG_SINGULAR_INVERSE;
    if (fabs(s5) <= SR_WRIST_EXACT_TOL * amp) *f |= WK_FLAG_INDETERMINATE | WK_FLAG_READ_MEMBER;
    if (fabs(s5) > family && fabs(s5) <= SR_SINGULAR_EPS) {
        /* near the singularity q6 = phi - sigma q4, phi from the well-conditioned entries (see Python) */
        const int up = c5 >= 0.0;
        const double k00 = up ? e[4] : e[6], k10 = up ? e[5] : e[7];
        n = sqrt(s5 * s5 + c5 * c5);
        c[w[1]] = c5 / n;
        s[w[1]] = s5 / n;
        q[w[1]] = atan2(s5, c5);
        x = e[1] * sgn * out[2];
        y = e[1] * sgn * out[5];
        n = sqrt(x * x + y * y);
        c[w[0]] = x / n;
        s[w[0]] = y / n;
        q[w[0]] = atan2(y, x);
        q[w[2]] = wk_wrap(atan2(k10 * out[3], k00 * out[0]) - sr_wrist_sigma(up, dp, w) * q[w[0]]);
        c[w[2]] = cos(q[w[2]]);
        s[w[2]] = sin(q[w[2]]);
        return 1;
    }
    if (fabs(s5) <= family) {
        /* wrist singularity: q4 := 0 (moved to previous's q4 by ik_near), q6 carries q4 +/- q6 */
        const int up = c5 >= 0.0;
        const double k00 = up ? e[4] : e[6], k10 = up ? e[5] : e[7];
        if (sgn < 0.0) return 0;
        q[w[0]] = 0.0;
        c[w[0]] = 1.0;
        s[w[0]] = 0.0;
        q[w[1]] = up ? 0.0 : SR_PI;
        c[w[1]] = up ? 1.0 : -1.0;
        s[w[1]] = 0.0;
        x = k00 * out[0];
        y = k10 * out[3];
        *f = WK_FLAG_SINGULAR_INVERSE | WK_FLAG_INDETERMINATE;
    } else {
        n = sqrt(s5 * s5 + c5 * c5);
        c[w[1]] = c5 / n;
        s[w[1]] = s5 / n;
        q[w[1]] = atan2(s5, c5);
        x = e[1] * sgn * out[2];
        y = e[1] * sgn * out[5];
        n = sqrt(x * x + y * y);
        c[w[0]] = x / n;
        s[w[0]] = y / n;
        q[w[0]] = atan2(y, x);
        x = e[2] * sgn * out[6];
        y = e[3] * sgn * out[7];
    }
    n = sqrt(x * x + y * y);
    if (n <= SR_DEGENERATE_EPS) return 0;
    c[w[2]] = x / n;
    s[w[2]] = y / n;
    q[w[2]] = atan2(y, x);
    return 1;
}
#endif
