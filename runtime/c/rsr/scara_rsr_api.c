/* The SCARA + 3-RSR hybrid's verbs: design, FK, IK with every branch, batches, selection, Jacobian, the middle
 * l_bw of a pose.
 * (a wristkin runtime source, inlined whole into the hybrid's generated C after its HY_* sizes and constants, the
 * hy_design / hy_ik_solutions / hy_fk_solutions types, its derived kernels rsr_k_*, the 3-RSR core (rsr_legs.c)
 * and the default design; derive/runtime_files.py, tests/test_rsr_runtime.py) */
static int hy_api_design_init(const double *params, hy_design *design)
{
    int i;
    if (!design) return WK_ERR_NULL;
    if (!params) {
        *design = hy_default_design;
        return WK_OK;
    }
    if (!wk_all_finite(params, HY_N_PARAMS)) return WK_ERR_NONFINITE;
    if (!(params[0] > 0.0 && params[1] > 0.0) || !rsr_design_ok(params + 4)) return WK_ERR_DESIGN;
    {
        int i;
        const double lo = params[0] < params[1] ? params[0] : params[1], hi = params[0] + params[1] - lo;
        for (i = 0; i < 4; ++i) /* SCARA lengths within HY_LENGTH_MAX, as Python's make_design */
            if (!(fabs(params[i]) <= HY_LENGTH_MAX)) return WK_ERR_DESIGN;
        /* a vanishing link leaves an elbow that moves nothing: a singular design */
        if (hi < HY_DESIGN_SCALE_MIN || lo < HY_LINK_RATIO_MIN * hi) return WK_ERR_DESIGN;
    }
    for (i = 0; i < HY_N_PARAMS; ++i) design->params[i] = params[i];
    return WK_OK;
}

/* (theta, alpha1, beta) of R = Rz(theta) C Rz(alpha1) Ry(beta) Rz(-alpha1); returns 1 at beta = 0 (alpha1 := 0) */
static int hy_split(const double *p, double *theta, double *alpha1, double *beta)
{
    const double ax = p[2], ay = p[6], az = p[10], sb = hypot(ax, ay);
    double ca, sa;
    *beta = atan2(sb, -az);
    if (sb <= RSR_GIMBAL_EPS) {
        /* beta = 0: R = Rz(theta) C; beta = pi: R = Rz(theta - 2 alpha1 + pi) (C Rz(a) = Rz(-a) C): alpha1 := 0
         * either way */
        *theta = az <= 0.0 ? atan2(p[4], -p[5]) : atan2(-p[4], -p[0]);
        *alpha1 = 0.0;
        return 1;
    }
    ca = ax / sb;
    sa = ay / sb;
    *alpha1 = atan2(-sa * p[0] + ca * p[4], sa * p[1] - ca * p[5]);
    *theta = wk_wrap(atan2(ay, ax) + *alpha1);
    return 0;
}

/* FK core: pose13 and aux6; 0 if the wrist's mirror plane is undefined */
static int hy_fk(const double *q, const double *dp, double *pose13, double *aux, unsigned *flags)
{
    const double *w = dp + 4;
    double plane[4], cd, ci, wpose[3], tw[12], theta, alpha1, beta;
    int gimbal;
    if (!rsr_plane(q + 4, w, plane, &cd)) return 0;
    gimbal = rsr_pose_of_plane(plane, wpose);
    rsr_k_fk_pose(plane, tw);
    rsr_k_fk_compose(q, tw, dp, pose13);
    pose13[12] = wpose[2];
    ci = rsr_leg_cond_inverse(q + 4, wpose, w);
    (void)hy_split(pose13, &theta, &alpha1, &beta);
    alpha1 = gimbal ? 0.0 : wpose[0];
    *flags = (gimbal ? WK_FLAG_GIMBAL : 0u) | (cd <= RSR_SINGULAR_EPS ? WK_FLAG_SINGULAR_DIRECT : 0u) |
             (ci <= RSR_SINGULAR_EPS ? WK_FLAG_SINGULAR_INVERSE : 0u);
    if (aux) {
        aux[0] = wk_wrap(theta - alpha1);
        aux[1] = beta;
        aux[2] = atan2(sin(alpha1), cos(beta) * cos(alpha1));
        aux[3] = alpha1;
        aux[4] = ci;
        aux[5] = cd;
    }
    return 1;
}


/* A pose with its rotation projected onto SO(3) (within WK_ROTATION_PROJECT_TOL): 0 if farther. */
static int hy_projected_pose(const double *p, double *out, double *deviation)
{
    double r[9];
    int i;
    if (!wk_input_rotation(p, r, deviation)) return 0;
    for (i = 0; i < 3; ++i) {
        out[4 * i] = r[3 * i];
        out[4 * i + 1] = r[3 * i + 1];
        out[4 * i + 2] = r[3 * i + 2];
        out[4 * i + 3] = p[4 * i + 3];
    }
    return 1;
}

/* Joints as the solver uses them: angles wrapped exactly (wk_wrap reduces against 2 pi itself), the
 * stroke d3 within HY_LENGTH_MAX: WK_OK, WK_ERR_NONFINITE or WK_ERR_RANGE. */
static int hy_joints(const double *joints, double *q)
{
    int j;
    if (!wk_all_finite(joints, 7)) return WK_ERR_NONFINITE;
    for (j = 0; j < 7; ++j) q[j] = j == 2 ? joints[j] : wk_wrap(joints[j]);
    return fabs(q[2]) <= HY_LENGTH_MAX ? WK_OK : WK_ERR_RANGE;
}

static int hy_api_fk(const double joints[7], const hy_design *design, hy_fk_solutions *out)
{
    double qw[7];
    int j;
    if (!out) return WK_ERR_NULL;
    out->count = 0;
    out->valid[0] = 0;
    out->flags[0] = 0u;
    for (j = 0; j < HY_N_POSE; ++j) out->values[0][j] = NAN;
    for (j = 0; j < HY_N_FK_AUX; ++j) out->aux[0][j] = NAN;
    out->status = WK_ERR_NULL;
    if (!joints) return WK_ERR_NULL;
    {
        const int rc = hy_joints(joints, qw);
        if (rc != WK_OK) {
            out->status = rc;
            return rc;
        }
    }
    if (!hy_fk(qw, (design ? design : &hy_default_design)->params, out->values[0], out->aux[0],
               &out->flags[0])) {
        for (j = 0; j < HY_N_POSE; ++j) out->values[0][j] = NAN;
        out->status = WK_STATUS_NO_ASSEMBLY;
        return WK_OK;
    }
    out->valid[0] = 1;
    out->count = 1;
    out->status = WK_STATUS_OK;
    return WK_OK;
}

static int hy_api_fk_matrix(const double joints[7], const hy_design *design, double pose12[12])
{
    double p13[13], qw[7];
    unsigned f;
    int j;
    if (!joints || !pose12) return WK_ERR_NULL;
    if ((j = hy_joints(joints, qw)) != WK_OK) return j;
    if (!hy_fk(qw, (design ? design : &hy_default_design)->params, p13, NULL, &f)) return WK_STATUS_NO_ASSEMBLY;
    for (j = 0; j < 12; ++j) pose12[j] = p13[j];
    return WK_OK;
}

static int hy_api_jacobian(const double joints[7], const hy_design *design, double jac[42])
{
    const double *dp;
    double plane[4], cd, qw[7];
    int rc;
    if (!joints || !jac) return WK_ERR_NULL;
    if ((rc = hy_joints(joints, qw)) != WK_OK) return rc;
    dp = (design ? design : &hy_default_design)->params;
    if (!rsr_plane(qw + 4, dp + 4, plane, &cd)) return WK_STATUS_NO_ASSEMBLY;
    rsr_k_jacobian(qw, dp, jac);
    return WK_OK;
}

static int hy_api_middle_lbw(const double pose12[12], const hy_design *design, double *lbw)
{
    double theta, alpha1, beta, span[2], p[12], dev;
    if (!pose12 || !lbw) return WK_ERR_NULL;
    if (!wk_all_finite(pose12, 12)) return WK_ERR_NONFINITE;
    if (!hy_projected_pose(pose12, p, &dev)) return WK_ERR_RANGE;
    if (hy_split(p, &theta, &alpha1, &beta) && beta > 0.5 * RSR_PI) {
        /* the family's members every 30 degrees at beta = pi, the split's 0 first (hy_api_ik) */
        int k;
        for (k = 0; k < 6; ++k)
            if (rsr_workspace(k * RSR_PI / 6.0, beta, (design ? design : &hy_default_design)->params + 4, span)) {
                *lbw = 0.5 * (span[0] + span[1]);
                return WK_OK;
            }
        return WK_STATUS_UNREACHABLE;
    }
    if (!rsr_workspace(alpha1, beta, (design ? design : &hy_default_design)->params + 4, span))
        return WK_STATUS_UNREACHABLE;
    *lbw = 0.5 * (span[0] + span[1]);
    return WK_OK;
}

static void hy_ik_clear(hy_ik_solutions *out, int status)
{
    int k, j;
    out->count = 0;
    out->status = status;
    for (k = 0; k < HY_MAX_IK; ++k) {
        out->valid[k] = 0;
        out->flags[k] = 0u;
        for (j = 0; j < 7; ++j) out->values[k][j] = NAN;
        for (j = 0; j < HY_N_IK_AUX; ++j) out->aux[k][j] = NAN;
    }
}

static int hy_api_ik(const double pose_in[13], const hy_design *design, hy_ik_solutions *out)
{
    const double *dp;
    double pose[13], deviation = 0.0;
    double theta, alpha1, beta, wpose[3], leg[3][2][4], lcond, off[4], x4, y4, z4, c2, ctol, sg, kc, gamma, el[2][2];
    unsigned lflags[3], eflag = 0u, f0;
    int word, e, i, gimbal;
    if (!out) return WK_ERR_NULL;
    hy_ik_clear(out, WK_ERR_NULL);
    if (!pose_in) return WK_ERR_NULL;
    if (!wk_all_finite(pose_in, 13)) {
        out->status = WK_ERR_NONFINITE;
        return WK_ERR_NONFINITE;
    }
    if (!hy_projected_pose(pose_in, pose, &deviation)) {
        out->status = WK_ERR_RANGE;
        return WK_ERR_RANGE;
    }
    pose[12] = pose_in[12];
    dp = (design ? design : &hy_default_design)->params;
    out->status = WK_STATUS_UNREACHABLE;
    gimbal = hy_split(pose, &theta, &alpha1, &beta);
    wpose[0] = alpha1;
    wpose[1] = beta;
    wpose[2] = pose[12];
    if (!rsr_legs(wpose, dp + 4, leg, lflags, &lcond)) {
        /* at beta = pi only theta - 2 alpha1 is fixed (a family): the split's member alpha1 = 0 may leave a leg short
         * (its coefficient sin(alpha1 - a_i) is 0 for a leg at azimuth 0); the family's other members, every 30
         * degrees, each moving theta by 2 alpha1 (Python's GIMBAL_ALPHAS) */
        int k, ok = 0;
        if (!(gimbal && beta > 0.5 * RSR_PI)) return WK_OK;
        for (k = 1; k < 6 && !ok; ++k) {
            wpose[0] = k * RSR_PI / 6.0;
            ok = rsr_legs(wpose, dp + 4, leg, lflags, &lcond);
        }
        if (!ok) return WK_OK;
        theta = wk_wrap(theta + 2.0 * (wpose[0] - alpha1));
        alpha1 = wpose[0];
    }
    off[0] = theta;
    off[1] = alpha1;
    off[2] = beta;
    off[3] = pose[12];
    {
        double o[3];
        rsr_k_wrist_offset(off, dp, o);
        x4 = pose[3] - o[0];
        y4 = pose[7] - o[1];
        z4 = pose[11] - o[2];
    }
    {
        /* 1 + cos theta2 and 1 - cos theta2 from factored differences of squares: neither fold cancels (see Python) */
        const double r = hypot(x4, y4), dl = fabs(dp[0] - dp[1]);
        double opc, omc;
        if (!(r <= 2.0 * (dp[0] + dp[1]))) return WK_OK; /* far out of reach (the products below could overflow) */
        opc = (r - dl) * (r + dl) / (2.0 * dp[0] * dp[1]);
        omc = (dp[0] + dp[1] - r) * (dp[0] + dp[1] + r) / (2.0 * dp[0] * dp[1]);
        /* the tangent band scales with the rounding error of c2 (relative to its terms, >= 1 x RSR_TANGENT_TOL) */
        ctol = RSR_TANGENT_TOL * (x4 * x4 + y4 * y4 + dp[0] * dp[0] + dp[1] * dp[1]) / (2.0 * dp[0] * dp[1]);
        if (!(opc >= -ctol && omc >= -ctol)) return WK_OK;
        opc = opc > 0.0 ? opc : 0.0;
        omc = omc > 0.0 ? omc : 0.0;
        c2 = opc <= omc ? opc - 1.0 : 1.0 - omc;
        sg = sqrt(opc * omc);
        kc = (dp[0] - dp[1]) + dp[1] * opc; /* L1 + L2 c2 */
        if (sg <= sqrt(ctol)) {
            eflag |= WK_FLAG_SINGULAR_INVERSE; /* stretched or folded */
            if (dp[1] * sg <= sqrt(ctol) * fabs(kc)) eflag |= WK_FLAG_DOUBLE_ROOT; /* the elbows coincide in theta1 too */
        }
        if (r <= RSR_DEGENERATE_EPS) eflag |= WK_FLAG_INDETERMINATE | WK_FLAG_SINGULAR_INVERSE;
    }
    if (!(fabs(dp[2] - z4) <= HY_LENGTH_MAX)) return WK_OK; /* a stroke FK rejects: unreachable */
    for (i = 0; i < 2; ++i) {
        const double s2 = i ? -sg : sg;
        el[i][0] = wk_wrap(atan2(y4, x4) - atan2(dp[1] * s2, kc));
        el[i][1] = atan2(s2, c2);
    }
    gamma = atan2(sin(alpha1), cos(beta) * cos(alpha1));
    out->status = WK_STATUS_OK;
    f0 = eflag | lflags[0] | lflags[1] | lflags[2] | (gimbal ? WK_FLAG_GIMBAL : 0u);
    for (word = 0; word < 8; ++word) {
        double plane[4], cd, wp[3], tw[12];
        int skip = 0, have_plane;
        for (i = 0; i < 3; ++i)
            if (((word >> i) & 1) && (lflags[i] & (WK_FLAG_DOUBLE_ROOT | WK_FLAG_INDETERMINATE))) skip = 1; /* once */
        if (skip) continue;
        have_plane = rsr_plane_of_set(leg, word, dp + 4, plane, &cd);
        if (!have_plane || cd <= RSR_SINGULAR_EPS) {
            /* S1, S2, S3 (nearly) collinear (direct singularity): the legs do not fix the mirror plane (its rounding
               error grows as 1 / cond_direct), the target does: the set is kept, flagged singular_direct (as
               rsr_wrist does), with the target's plane */
            plane[0] = sin(0.5 * beta) * cos(alpha1);
            plane[1] = sin(0.5 * beta) * sin(alpha1);
            plane[2] = cos(0.5 * beta);
            plane[3] = 0.5 * pose[12];
            if (!have_plane) cd = 0.0;
        }
        (void)rsr_pose_of_plane(plane, wp);
        rsr_k_fk_pose(plane, tw);
        for (e = 0; e < 2; ++e) {
            const int k = 8 * e + word;
            double q[4], t[12], res = fabs(wp[2] - pose[12]);
            /* one elbow at full stretch / fold; on axis 1 (folded, L1 = L2) theta2 = +pi and -pi are one angle and
               theta1 is free: the other elbow is a member of the same family (Python says so too) */
            if (e && (eflag & (WK_FLAG_DOUBLE_ROOT | WK_FLAG_INDETERMINATE))) continue;
            q[0] = el[e][0];
            q[1] = el[e][1];
            q[2] = dp[2] - z4;
            q[3] = wk_wrap(theta - q[0] - q[1]);
            rsr_k_fk_compose(q, tw, dp, t);
            for (i = 0; i < 12; ++i) {
                const double d = fabs(t[i] - pose[i]);
                if (d > res) res = d;
            }
            if (!(res <= RSR_IK_VERIFY_TOL)) continue;
            for (i = 0; i < 4; ++i) out->values[k][i] = q[i];
            for (i = 0; i < 3; ++i) out->values[k][4 + i] = leg[i][(word >> i) & 1][0];
            out->aux[k][0] = res;
            out->aux[k][1] = alpha1;
            out->aux[k][2] = beta;
            out->aux[k][3] = gamma;
            out->aux[k][4] = lcond;
            out->aux[k][5] = cd;
            out->flags[k] = f0 | (cd <= RSR_SINGULAR_EPS ? WK_FLAG_SINGULAR_DIRECT : 0u) |
                            (deviation > 0.0 ? WK_FLAG_PROJECTED : 0u);
            out->valid[k] = 1;
            out->count++;
            if (out->flags[k] & WK_FLAG_INDETERMINATE) out->status = WK_STATUS_INDETERMINATE;
        }
    }
    if (out->count == 0) out->status = WK_STATUS_UNREACHABLE;
    return WK_OK;
}

static int hy_api_ik_batch(size_t n, const double *poses, const hy_design *design,
                           hy_ik_solutions *out)
{
    size_t i;
    int rc = WK_OK;
    if (n == 0) return WK_OK;
    if (!poses || !out) return WK_ERR_NULL;
    for (i = 0; i < n; ++i) {
        const int r = hy_api_ik(poses + 13 * i, design, out + i);
        if (r != WK_OK && rc == WK_OK) rc = r;
    }
    return rc;
}

static int hy_api_fk_batch(size_t n, const double *joints, const hy_design *design,
                           hy_fk_solutions *out)
{
    size_t i;
    int rc = WK_OK;
    if (n == 0) return WK_OK;
    if (!joints || !out) return WK_ERR_NULL;
    for (i = 0; i < n; ++i) {
        const int r = hy_api_fk(joints + 7 * i, design, out + i);
        if (r != WK_OK && rc == WK_OK) rc = r;
    }
    return rc;
}

static int hy_api_select_ik(const hy_ik_solutions *s, const double *previous, const double *lower,
                            const double *upper, const double *weights)
{
    if (!s) return -1;
    return wk_select(HY_MAX_IK, 7, s->valid, s->flags, &s->values[0][0], rsr_joint_revolute, previous,
                     lower, upper, weights);
}
