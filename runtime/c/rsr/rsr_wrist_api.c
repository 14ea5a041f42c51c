/* The 3-RSR wrist's verbs: design, IK with every branch, FK, batches, the design atlas's sums, the maximum swing,
 * selection, Jacobians, workspace and the swing-rotation angle.
 * (a wristkin runtime source, inlined whole into the wrist's generated C after its RSR_* sizes and tolerances, the
 * rsr_design / rsr_ik_solutions / rsr_fk_solutions types, its derived kernels rsr_k_*, the 3-RSR core
 * (rsr_legs.c) and the default design; derive/runtime_files.py, tests/test_rsr_runtime.py) */
static int rsr_api_design_init(const double *params, rsr_design *design)
{
    int i;
    if (!design) return WK_ERR_NULL;
    if (!params) {
        *design = rsr_default_design;
        return WK_OK;
    }
    if (!wk_all_finite(params, RSR_N_PARAMS)) return WK_ERR_NONFINITE;
    if (!rsr_design_ok(params)) return WK_ERR_DESIGN;
    for (i = 0; i < RSR_N_PARAMS; ++i) design->params[i] = params[i];
    return WK_OK;
}

static void rsr_ik_clear(rsr_ik_solutions *out, int status)
{
    int k, j;
    out->count = 0;
    out->status = status;
    for (k = 0; k < RSR_MAX_IK; ++k) {
        out->valid[k] = 0;
        out->flags[k] = 0u;
        for (j = 0; j < 3; ++j) out->values[k][j] = NAN;
        for (j = 0; j < RSR_N_IK_AUX; ++j) out->aux[k][j] = NAN;
    }
}

static int rsr_api_ik(const double pose[3], const rsr_design *design, rsr_ik_solutions *out)
{
    const double *w;
    double leg[3][2][4], cond, p[3];
    unsigned lflags[3];
    int k, i;
    if (!out) return WK_ERR_NULL;
    rsr_ik_clear(out, WK_ERR_NULL);
    if (!pose) return WK_ERR_NULL;
    if (!wk_all_finite(pose, 3)) {
        out->status = WK_ERR_NONFINITE;
        return WK_ERR_NONFINITE;
    }
    if (pose[1] < 0.0 || pose[1] > RSR_PI) {
        out->status = WK_ERR_RANGE;
        return WK_ERR_RANGE;
    }
    w = (design ? design : &rsr_default_design)->params;
    out->status = WK_STATUS_OK;
    p[0] = wk_wrap(pose[0]); /* exactly: the kernels add the legs' angles to alpha */
    p[1] = pose[1];
    p[2] = pose[2];
    if (!rsr_legs(p, w, leg, lflags, &cond)) {
        out->status = WK_STATUS_UNREACHABLE;
        return WK_OK;
    }
    for (k = 0; k < RSR_MAX_IK; ++k) {
        double plane[4], cd, res = 0.0;
        unsigned f = lflags[0] | lflags[1] | lflags[2];
        int skip = 0;
        for (i = 0; i < 3; ++i) {
            const int b = (k >> i) & 1;
            if (b && (lflags[i] & (WK_FLAG_DOUBLE_ROOT | WK_FLAG_INDETERMINATE))) skip = 1; /* reported once */
            if (leg[i][b][3] > res) res = leg[i][b][3];
        }
        if (skip || !(res <= RSR_IK_VERIFY_TOL)) continue;
        if (!rsr_plane_of_set(leg, k, w, plane, &cd)) cd = 0.0;
        if (cd <= RSR_SINGULAR_EPS) f |= WK_FLAG_SINGULAR_DIRECT;
        for (i = 0; i < 3; ++i) out->values[k][i] = leg[i][(k >> i) & 1][0];
        out->aux[k][0] = res;
        out->aux[k][1] = cond;
        out->aux[k][2] = cd;
        out->flags[k] = f;
        out->valid[k] = 1;
        out->count++;
        if (f & WK_FLAG_INDETERMINATE) out->status = WK_STATUS_INDETERMINATE;
    }
    return WK_OK;
}

static int rsr_api_fk(const double joints[3], const rsr_design *design, rsr_fk_solutions *out)
{
    const double *w;
    double plane[4], cd, ci, pose[3], tw[12];
    unsigned f = 0u;
    int j;
    if (!out) return WK_ERR_NULL;
    out->count = 0;
    out->valid[0] = 0;
    out->flags[0] = 0u;
    for (j = 0; j < 3; ++j) out->values[0][j] = NAN;
    for (j = 0; j < RSR_N_FK_AUX; ++j) out->aux[0][j] = NAN;
    out->status = WK_ERR_NULL;
    if (!joints) return WK_ERR_NULL;
    if (!wk_all_finite(joints, 3)) {
        out->status = WK_ERR_NONFINITE;
        return WK_ERR_NONFINITE;
    }
    w = (design ? design : &rsr_default_design)->params;
    if (!rsr_plane(joints, w, plane, &cd)) {
        out->status = WK_STATUS_NO_ASSEMBLY;
        return WK_OK;
    }
    if (rsr_pose_of_plane(plane, pose)) f |= WK_FLAG_GIMBAL;
    rsr_k_fk_pose(plane, tw);
    ci = rsr_leg_cond_inverse(joints, pose, w);
    if (cd <= RSR_SINGULAR_EPS) f |= WK_FLAG_SINGULAR_DIRECT;
    if (ci <= RSR_SINGULAR_EPS) f |= WK_FLAG_SINGULAR_INVERSE;
    for (j = 0; j < 3; ++j) out->values[0][j] = pose[j];
    for (j = 0; j < 12; ++j) out->aux[0][j] = tw[j];
    out->aux[0][12] = ci;
    out->aux[0][13] = cd;
    out->flags[0] = f;
    out->valid[0] = 1;
    out->count = 1;
    out->status = WK_STATUS_OK;
    return WK_OK;
}

static int rsr_api_ik_batch(size_t n, const double *poses, const rsr_design *design,
                            rsr_ik_solutions *out)
{
    size_t i;
    int rc = WK_OK;
    if (n == 0) return WK_OK;
    if (!poses || !out) return WK_ERR_NULL;
    for (i = 0; i < n; ++i) {
        const int r = rsr_api_ik(poses + 3 * i, design, out + i);
        if (r != WK_OK && rc == WK_OK) rc = r;
    }
    return rc;
}

static int rsr_api_fk_batch(size_t n, const double *joints, const rsr_design *design,
                            rsr_fk_solutions *out)
{
    size_t i;
    int rc = WK_OK;
    if (n == 0) return WK_OK;
    if (!joints || !out) return WK_ERR_NULL;
    for (i = 0; i < n; ++i) {
        const int r = rsr_api_fk(joints + 3 * i, design, out + i);
        if (r != WK_OK && rc == WK_OK) rc = r;
    }
    return rc;
}

/* 1 if phi lies on the arc [lo, hi] of the leg limits, phi in (-pi, pi] (an IK value, atan2's): off = phi - lo (lo
 * wrapped) lies in (-2 pi, 2 pi], so the arc is off in [0, hi - lo] or off <= hi - lo - 2 pi (wristkin_atlas's
 * numpy path decides the same way). */
static int rsr_within_limits(double phi, double lo_wrapped, double width)
{
    const double off = phi - lo_wrapped;
    return (off >= 0.0 && off <= width) || off <= width - RSR_TWO_PI;
}

static int rsr_api_atlas_batch(size_t n_pose, const double *poses, size_t n_joint, const double *joints,
                               const rsr_design *design, double threshold, int64_t *sums, double *li_min)
{
    const rsr_design *d = design ? design : &rsr_default_design;
    const double *w = d->params;
    const double lo = remainder(w[1], RSR_TWO_PI), width = w[2] - w[1];
    size_t i;
    int k, j;
    if ((n_pose && !poses) || (n_joint && !joints) || !sums || !li_min) return WK_ERR_NULL;
    for (i = 0; i < n_pose; ++i) {
        rsr_ik_solutions s;
        double best = -1.0;
        const int rc = rsr_api_ik(poses + 3 * i, d, &s);
        if (rc < 0) return rc;
        for (k = 0; k < RSR_MAX_IK; ++k) {
            double o[12], li;
            if (!s.valid[k] || !rsr_within_limits(s.values[k][0], lo, width) ||
                !rsr_within_limits(s.values[k][1], lo, width) || !rsr_within_limits(s.values[k][2], lo, width))
                continue;
            rsr_k_atlas_rates(s.values[k], poses + 3 * i, w, o);
            li = wk_inverse_kappa_f(o + 3, o);
            sums[WK_ATLAS_N_SETS] += 1;
            sums[WK_ATLAS_LI_SUM] += (int64_t)llrint(li * WK_ATLAS_FIXED);
            sums[WK_ATLAS_NEAR_INVERSE] += s.aux[k][1] < threshold;
            sums[WK_ATLAS_NEAR_DIRECT] += s.aux[k][2] < threshold;
            if (li > best) best = li;
            if (li < *li_min) *li_min = li;
        }
        if (best >= 0.0) {
            sums[WK_ATLAS_N_REACH] += 1;
            sums[WK_ATLAS_LI_BEST_SUM] += (int64_t)llrint(best * WK_ATLAS_FIXED);
        }
    }
    for (i = 0; i < n_joint; ++i) {
        rsr_fk_solutions s;
        int near = 0;
        const int rc = rsr_api_fk(joints + 3 * i, d, &s);
        if (rc < 0) return rc;
        for (j = 0; j < RSR_MAX_FK; ++j) near |= s.valid[j] && s.aux[j][13] < threshold;
        sums[WK_ATLAS_FK_NEAR_DIRECT] += near;
        sums[WK_ATLAS_MODES + s.count] += 1;
    }
    return WK_OK;
}

/* Whether direction (x, y) lies on the arc from angle lo counter-clockwise to hi (width in (0, 2 pi)), by cross
 * products with the end directions (e_lo, e_hi) instead of atan2 and fmod: for a width <= pi, on the lo side of
 * neither end; above pi, not strictly inside the complementary arc (of width < pi). */
static int rsr_on_arc(double x, double y, const double e_lo[2], const double e_hi[2], double width)
{
    const double c_lo = e_lo[0] * y - e_lo[1] * x, c_hi = x * e_hi[1] - y * e_hi[0];
    return width <= RSR_PI ? (c_lo >= 0.0 && c_hi >= 0.0) : !(c_lo < 0.0 && c_hi < 0.0);
}

/* rsr_workspace's attitude test with its trigonometry hoisted out of the swing profile's loops: the ik_coeffs
 * kernel is A_i = sin(beta/2) s_i(alpha), B = cos(beta/2), so s_i is the kernel at beta = pi (sin(pi/2) = 1) once
 * per azimuth and (sin(beta/2), B) the kernel at alpha = pi/2 once per swing, their products the kernel's own; the
 * limits' cos / sin once per design. Leg i reaches n . S_i / L = A_i cos phi + B sin phi over [phi_min, phi_max]:
 * the end values, or the sinusoid's top (bottom) where its direction (A_i, B) ((-A_i, -B)) lies on the arc. */
static int rsr_swing_reachable(const double s_alpha[3], double sh, double b, const double *w, const double lim[4],
                               const double e_lo[2], const double e_hi[2])
{
    double lo = 0.5 * w[3], hi = 0.5 * w[4];
    int i;
    for (i = 0; i < 3; ++i) {
        const double a = sh * s_alpha[i], rho = w[0] * sqrt(a * a + b * b);
        const double v0 = w[0] * (a * lim[0] + b * lim[1]), v1 = w[0] * (a * lim[2] + b * lim[3]);
        const double top = rsr_on_arc(a, b, e_lo, e_hi, w[2] - w[1]) ? rho : (v0 > v1 ? v0 : v1);
        const double bottom = rsr_on_arc(-a, -b, e_lo, e_hi, w[2] - w[1]) ? -rho : (v0 < v1 ? v0 : v1);
        if (bottom > lo) lo = bottom;
        if (top < hi) hi = top;
    }
    return lo <= hi;
}

#define RSR_SWING_MAX 1024 /* swing grid values per call (the atlas uses at most 361: 0.5 deg up to 180 deg) */

static int rsr_api_max_swing(const rsr_design *design, size_t n_alpha, const double *alpha, size_t n_beta,
                             const double *beta, int64_t *index)
{
    const double *w = (design ? design : &rsr_default_design)->params;
    const double lim[4] = {cos(w[1]), sin(w[1]), cos(w[2]), sin(w[2])};
    const double e_lo[2] = {lim[0], lim[1]}, e_hi[2] = {lim[2], lim[3]};
    double sh[RSR_SWING_MAX], b[RSR_SWING_MAX], k[5];
    size_t i, j;
    if ((n_alpha && (!alpha || !index)) || (n_beta && !beta)) return WK_ERR_NULL;
    if (n_beta > RSR_SWING_MAX) return WK_ERR_RANGE;
    for (j = 0; j < n_beta; ++j) {
        const double pose[3] = {0.5 * RSR_PI, beta[j], 0.0};
        if (!isfinite(beta[j])) return WK_ERR_NONFINITE;
        rsr_k_ik_coeffs(pose, w, k);
        sh[j] = k[0];
        b[j] = k[3];
    }
    for (i = 0; i < n_alpha; ++i)
        if (!isfinite(alpha[i])) return WK_ERR_NONFINITE;
    for (i = 0; i < n_alpha; ++i) {
        const double pose[3] = {alpha[i], RSR_PI, 0.0};
        rsr_k_ik_coeffs(pose, w, k);
        index[i] = -1;
        for (j = n_beta; j-- > 0;) { /* from the top: the first reachable swing is the largest */
            if (rsr_swing_reachable(k, sh[j], b[j], w, lim, e_lo, e_hi)) {
                index[i] = (int64_t)j;
                break;
            }
        }
    }
    return WK_OK;
}

static int rsr_api_select_ik(const rsr_ik_solutions *s, const double *previous, const double *lower,
                             const double *upper)
{
    if (!s) return -1;
    return wk_select(RSR_MAX_IK, 3, s->valid, s->flags, &s->values[0][0], rsr_joint_revolute, previous,
                     lower, upper, NULL);
}

static int rsr_api_jacobians(const double joints[3], const double pose[3], const rsr_design *design,
                             double jq[3], double jx[9])
{
    double o[12];
    int i;
    if (!joints || !pose || !jq || !jx) return WK_ERR_NULL;
    if (!wk_all_finite(joints, 3) || !wk_all_finite(pose, 3)) return WK_ERR_NONFINITE;
    rsr_k_jacobians(joints, pose, (design ? design : &rsr_default_design)->params, o);
    for (i = 0; i < 3; ++i) jq[i] = o[i];
    for (i = 0; i < 9; ++i) jx[i] = o[3 + i];
    return WK_OK;
}

static int rsr_api_jacobian(const double joints[3], const rsr_design *design, double jac[18])
{
    const double *w;
    double plane[4], cd;
    if (!joints || !jac) return WK_ERR_NULL;
    if (!wk_all_finite(joints, 3)) return WK_ERR_NONFINITE;
    w = (design ? design : &rsr_default_design)->params;
    if (!rsr_plane(joints, w, plane, &cd)) return WK_STATUS_NO_ASSEMBLY;
    rsr_k_geometric_jacobian(joints, w, jac);
    return WK_OK;
}

static int rsr_api_workspace(double alpha, double beta, const rsr_design *design, double span[2])
{
    if (!span) return WK_ERR_NULL;
    if (!isfinite(alpha) || !isfinite(beta)) return WK_ERR_NONFINITE;
    return rsr_workspace(alpha, beta, (design ? design : &rsr_default_design)->params, span) ? WK_OK
                                                                                           : WK_STATUS_UNREACHABLE;
}

static int rsr_api_gamma_from_azimuth(double alpha1, double beta, double *gamma)
{
    if (!gamma) return WK_ERR_NULL;
    if (!isfinite(alpha1) || !isfinite(beta)) return WK_ERR_NONFINITE;
    *gamma = atan2(sin(alpha1), cos(beta) * cos(alpha1));
    return WK_OK;
}

static int rsr_api_azimuth_from_gamma(double gamma, double beta, double *alpha1)
{
    double c;
    if (!alpha1) return WK_ERR_NULL;
    if (!isfinite(gamma) || !isfinite(beta)) return WK_ERR_NONFINITE;
    c = cos(beta);
    if (fabs(c) <= RSR_GIMBAL_EPS) return WK_ERR_RANGE;
    *alpha1 = atan2(fabs(c) * sin(gamma), (c > 0.0 ? 1.0 : -1.0) * cos(gamma));
    return WK_OK;
}
