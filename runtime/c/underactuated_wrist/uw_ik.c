/* The underactuated wrist's inverse kinematics: every one of the 8 sets, one pose or many.
 * (a wristkin runtime source, inlined whole into the underactuated wrist's generated C after its UW_*
 * constants, the uw_design / uw_ik_solutions / uw_fk_solutions types and the derived kernels uw_k_*;
 * derive/runtime_files.py, tests/test_uw_runtime.py) */
/* ------------------------------------------------------------------ inverse kinematics */
static void uw_ik_clear(uw_ik_solutions *out, int status)
{
    int k, j;
    out->count = 0;
    out->status = status;
    for (k = 0; k < UW_MAX_IK; ++k) {
        out->valid[k] = 0;
        out->flags[k] = 0u;
        for (j = 0; j < UW_N_JOINTS; ++j) out->values[k][j] = NAN;
        for (j = 0; j < UW_N_IK_AUX; ++j) out->aux[k][j] = NAN;
    }
}

static int uw_api_ik(const double pose[3], const uw_design *design,
                     uw_ik_solutions *out)
{
    double rot[9], abc[9], z3[9], z2[2][9], cb[2][3], sb[2][3], roots[3][2], motor[3][2], rows[3][2][3];
    double norms[3][2], cond_inv = 1.0;
    unsigned bflag = 0u;
    int i, b, k, status = WK_STATUS_OK;
    const uw_design *d = uw_design_or_default(design);
    if (!out) return WK_ERR_NULL;
    if (!pose) {
        uw_ik_clear(out, WK_ERR_NULL);
        return WK_ERR_NULL;
    }
    if (!uw_finite3(pose)) {
        uw_ik_clear(out, WK_ERR_NONFINITE);
        return WK_ERR_NONFINITE;
    }
    uw_rotation(pose, rot);
    uw_k_ik_abc(rot, d->c, abc);
    for (i = 0; i < 3; ++i) {
        const double a = abc[3 * i], bb = abc[3 * i + 1], c = abc[3 * i + 2];
        const double r = sqrt(a * a + bb * bb); /* A, B are O(1): no overflow, and cheaper than hypot */
        double u, sg, g, base, ca, sa, ci;
        if (r <= 1e-13) {
            if (fabs(c) <= 1e-13) { /* every theta_i closes this loop: representative theta0 */
                const double t = d->theta0;
                status = WK_STATUS_INDETERMINATE;
                roots[i][0] = roots[i][1] = t;
                cb[0][i] = cb[1][i] = cos(t);
                sb[0][i] = sb[1][i] = sin(t);
                bflag |= WK_FLAG_INDETERMINATE | WK_FLAG_SINGULAR_INVERSE;
                cond_inv = 0.0;
                continue;
            }
            uw_ik_clear(out, WK_STATUS_UNREACHABLE);
            return WK_OK;
        }
        u = -c / r;
        if (fabs(u) > 1.0 + UW_TANGENT_TOL) {
            uw_ik_clear(out, WK_STATUS_UNREACHABLE);
            return WK_OK;
        }
        u = uw_clamp1(u);
        sg = sqrt(1.0 - u * u);
        if (sg <= UW_TANGENT_TOL) bflag |= WK_FLAG_DOUBLE_ROOT;
        ci = r * sg / d->c[1];
        if (ci <= UW_SINGULAR_EPS) bflag |= WK_FLAG_SINGULAR_INVERSE;
        if (ci < cond_inv) cond_inv = ci;
        base = atan2(bb, a);
        g = acos(u);
        roots[i][0] = uw_wrap_root(base + g);
        roots[i][1] = uw_wrap_root(base - g);
        /* cos, sin of base +/- g from (A, B, u) without further trigonometry */
        ca = a / r;
        sa = bb / r;
        cb[0][i] = ca * u - sa * sg;
        sb[0][i] = sa * u + ca * sg;
        cb[1][i] = ca * u + sa * sg;
        sb[1][i] = sa * u - ca * sg;
    }
    /* per (branch, root): motor angle and the row Zi2 x Zi3 of jx; the 8 sets only combine them */
    uw_k_platform_axes(rot, d->c, z3);
    uw_k_middle_axes(cb[0], sb[0], d->c, z2[0]);
    uw_k_middle_axes(cb[1], sb[1], d->c, z2[1]);
    for (i = 0; i < 3; ++i)
        for (b = 0; b < 2; ++b) {
            motor[i][b] = uw_wrap_motor(roots[i][b] - d->theta0);
            uw_cross(z2[b] + 3 * i, z3 + 3 * i, rows[i][b]);
            norms[i][b] = uw_norm(rows[i][b]);
        }
    out->count = UW_MAX_IK;
    out->status = status;
    for (k = 0; k < UW_MAX_IK; ++k) {
        const int b0 = k & 1, b1 = (k >> 1) & 1, b2 = (k >> 2) & 1;
        const double cd = uw_cond_rows(rows[0][b0], rows[1][b1], rows[2][b2],
                                       norms[0][b0] * norms[1][b1] * norms[2][b2]);
        out->values[k][0] = roots[0][b0];
        out->values[k][1] = roots[1][b1];
        out->values[k][2] = roots[2][b2];
        out->aux[k][0] = motor[0][b0];
        out->aux[k][1] = motor[1][b1];
        out->aux[k][2] = motor[2][b2];
        out->aux[k][3] = cond_inv;
        out->aux[k][4] = cd;
        out->valid[k] = 1;
        out->flags[k] = bflag | (cd <= UW_SINGULAR_EPS ? WK_FLAG_SINGULAR_DIRECT : 0u);
    }
    return WK_OK;
}

static int uw_api_ik_batch(size_t n, const double *poses, const uw_design *design,
                           uw_ik_solutions *out)
{
    size_t r;
    int first = WK_OK;
    if (n == 0) return WK_OK;
    if (!poses || !out) return WK_ERR_NULL;
    for (r = 0; r < n; ++r) {
        const int rc = uw_api_ik(poses + 3 * r, design, out + r);
        if (rc != WK_OK && first == WK_OK) first = rc;
    }
    return first;
}
