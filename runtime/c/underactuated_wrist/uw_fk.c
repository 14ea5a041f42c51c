/* The underactuated wrist's forward kinematics: every real assembly mode, one joint triple or many.
 * (a wristkin runtime source, inlined whole into the underactuated wrist's generated C after its UW_*
 * constants, the uw_design / uw_ik_solutions / uw_fk_solutions types and the derived kernels uw_k_*;
 * derive/runtime_files.py, tests/test_uw_runtime.py) */
static void uw_fk_clear(uw_fk_solutions *out, int status)
{
    int k, j;
    out->count = 0;
    out->status = status;
    for (k = 0; k < UW_MAX_FK; ++k) {
        out->valid[k] = 0;
        out->flags[k] = 0u;
        for (j = 0; j < UW_N_POSE; ++j) out->values[k][j] = NAN;
        for (j = 0; j < UW_N_FK_AUX; ++j) out->aux[k][j] = NAN;
    }
}

static int uw_api_fk(const double joints[3], const uw_design *design,
                     uw_fk_solutions *out)
{
    const uw_design *d = uw_design_or_default(design);
    uw_fk_coef cf;
    double raw[18], kpoly[9], roots[8], best = -1.0, eta_c, modes[16][6], cq[3], sq[3], z1[9], z2[9];
    unsigned rflags[8], mflags[16];
    int mroot[16]; /* the eliminant root each mode came from */
    int mfold[16]; /* the mode was accepted in the fold band (resolved only to sqrt(UW_FK_FOLD_TOL)) */
    int nroots, pstatus = 0, nm = 0, r, j, k, kbest = 0;
    if (!out) return WK_ERR_NULL;
    if (!joints) {
        uw_fk_clear(out, WK_ERR_NULL);
        return WK_ERR_NULL;
    }
    if (!uw_finite3(joints)) {
        uw_fk_clear(out, WK_ERR_NONFINITE);
        return WK_ERR_NONFINITE;
    }
    uw_fk_clear(out, WK_STATUS_OK);
    for (j = 0; j < 3; ++j) {
        cq[j] = cos(joints[j]);
        sq[j] = sin(joints[j]);
    }
    uw_k_fk_def(cq, sq, d->c, raw);
    for (j = 0; j < 6; ++j) {
        cf.trip[j][0] = raw[3 * j];
        cf.trip[j][1] = raw[3 * j + 1];
        cf.trip[j][2] = raw[3 * j + 2];
    }
    /* eta_c: the sampled eta with the largest |identity| goes to x = infinity, so no root is lost there */
    for (k = 0; k < 16; ++k) {
        double v[6], f;
        uw_def_cs(&cf, uw_ring[k][0], uw_ring[k][1], v, 0);
        f = fabs(uw_elimination(v));
        if (f > best) {
            best = f;
            kbest = k;
        }
    }
    /* eta_c = sample angle - pi: its cos, sin are the sample's negated */
    eta_c = UW_TWO_PI * kbest / 16.0 - UW_PI;
    uw_k_polynomial(&cf, -uw_ring[kbest][0], -uw_ring[kbest][1], kpoly);
    nroots = wk_poly_real_roots(kpoly, 8, roots, rflags, &pstatus);
    if (pstatus & WK_POLY_STATUS_ZERO) {
        out->status = WK_STATUS_INDETERMINATE;
        return WK_OK;
    }
    for (r = 0; r < nroots; ++r) {
        /* cos, sin of eta0 - eta_c from x = tan((eta0 - eta_c) / 2) (in 1/x past 1: no overflow), then turned by
           eta_c: no trigonometry but eta0's */
        const double x = roots[r], y = fabs(x) > 1.0 ? 1.0 / x : x, y2 = y * y, ch = (1.0 - y2) / (1.0 + y2);
        const double sh = 2.0 * y / (1.0 + y2), chx = fabs(x) > 1.0 ? -ch : ch;
        const double eta0 = eta_c + 2.0 * atan(x);
        const double ce0 = -uw_ring[kbest][0] * chx + uw_ring[kbest][1] * sh;
        const double se0 = -uw_ring[kbest][1] * chx - uw_ring[kbest][0] * sh;
        const int touching = (rflags[r] & WK_POLY_FLAG_DOUBLE) != 0u;
        double zc[6], zcs[12];
        const int nz = touching ? uw_zeta_all(&cf, ce0, se0, zc, zcs) : uw_zeta_candidates(&cf, ce0, se0, zc, zcs);
        for (j = 0; j < nz; ++j) {
            double z = zc[j], e = eta0, cs[4];
            double err;
            cs[0] = zcs[2 * j];
            cs[1] = zcs[2 * j + 1];
            cs[2] = ce0;
            cs[3] = se0;
            err = uw_polish(&cf, &z, &e, cs);
            /* a merge is confirmed, not assumed: a regular residual is a regular mode (see Python) */
            const unsigned tf = (touching && !(err <= UW_FK_RESIDUAL_TOL)) ? (WK_FLAG_DOUBLE_ROOT | WK_FLAG_SINGULAR_DIRECT) : 0u;
            int m, dup = -1;
            if (!(err <= (touching ? UW_FK_FOLD_TOL : UW_FK_RESIDUAL_TOL))) continue;
            z = uw_wrap_2pi(z);
            e = uw_wrap_2pi(e);
            {
                /* a touching root's modes closer than the fold's resolution sqrt(UW_FK_FOLD_TOL) are one double
                   root (see Python) */
                /* two modes polished to regular residuals are distinct beyond UW_FK_DUPLICATE_TOL (see Python) */
                for (m = 0; m < nm; ++m) {
                    const double near = (tf || mfold[m]) ? sqrt(UW_FK_FOLD_TOL) : UW_FK_DUPLICATE_TOL;
                    if (fabs(uw_wrap_pi(modes[m][0] - z)) < near && fabs(uw_wrap_pi(modes[m][1] - e)) < near) dup = m;
                }
            }
            if (dup >= 0) {
                if (mroot[dup] != r) {
                    mflags[dup] |= WK_FLAG_DOUBLE_ROOT | tf; /* two roots, one mode: merged */
                } else if (fabs(uw_wrap_pi(modes[dup][0] - z)) >= UW_FK_DUPLICATE_TOL ||
                           fabs(uw_wrap_pi(modes[dup][1] - e)) >= UW_FK_DUPLICATE_TOL) {
                    mflags[dup] |= WK_FLAG_DOUBLE_ROOT | WK_FLAG_SINGULAR_DIRECT; /* a fold pair, merged */
                }
            } else if (nm < 16) {
                modes[nm][0] = z;
                modes[nm][1] = e;
                for (m = 0; m < 4; ++m) modes[nm][2 + m] = cs[m]; /* cos, sin of zeta, eta (the wrap keeps them) */
                mflags[nm] = tf;
                mfold[nm] = tf != 0u;
                mroot[nm] = r;
                ++nm;
            }
        }
    }
    /* stable order: by eta, then zeta (insertion sort, nm <= 16) */
    for (j = 1; j < nm; ++j) {
        double mode[6];
        unsigned f = mflags[j];
        int i = j - 1, c;
        for (c = 0; c < 6; ++c) mode[c] = modes[j][c];
        while (i >= 0 && (modes[i][1] > mode[1] || (modes[i][1] == mode[1] && modes[i][0] > mode[0]))) {
            for (c = 0; c < 6; ++c) modes[i + 1][c] = modes[i][c];
            mflags[i + 1] = mflags[i];
            --i;
        }
        for (c = 0; c < 6; ++c) modes[i + 1][c] = mode[c];
        mflags[i + 1] = f;
    }
    if (nm > UW_MAX_FK) nm = UW_MAX_FK;
    uw_k_base_axes(d->c, z1);
    uw_k_middle_axes(cq, sq, d->c, z2);
    for (k = 0; k < nm; ++k) {
        const double c3[3] = {cq[0], modes[k][2], modes[k][4]}, s3[3] = {sq[0], modes[k][3], modes[k][5]};
        double rot[9], z3[9], rows[3][3], n12[3], ci = 1.0, cd;
        unsigned f = mflags[k];
        uw_k_fk_rotation(c3, s3, d->c, rot);
        f |= uw_euler(rot, out->values[k]);
        uw_k_platform_axes(rot, d->c, z3);
        for (j = 0; j < 3; ++j) {
            uw_cross(z1 + 3 * j, z2 + 3 * j, n12);
            ci = fmin(ci, fabs(n12[0] * z3[3 * j] + n12[1] * z3[3 * j + 1] + n12[2] * z3[3 * j + 2]) / d->c[1]);
            uw_cross(z2 + 3 * j, z3 + 3 * j, rows[j]);
        }
        cd = uw_cond_rows(rows[0], rows[1], rows[2], uw_norm(rows[0]) * uw_norm(rows[1]) * uw_norm(rows[2]));
        if (ci <= UW_SINGULAR_EPS) f |= WK_FLAG_SINGULAR_INVERSE;
        if (cd <= UW_SINGULAR_EPS) f |= WK_FLAG_SINGULAR_DIRECT;
        for (j = 0; j < 9; ++j) out->aux[k][j] = rot[j];
        out->aux[k][9] = modes[k][0];
        out->aux[k][10] = modes[k][1];
        out->aux[k][11] = ci;
        out->aux[k][12] = cd;
        out->valid[k] = 1;
        out->flags[k] = f;
    }
    out->count = nm;
    out->status = nm > 0 ? WK_STATUS_OK : WK_STATUS_NO_ASSEMBLY;
    return WK_OK;
}

static int uw_api_fk_batch(size_t n, const double *joints, const uw_design *design,
                           uw_fk_solutions *out)
{
    size_t r;
    int first = WK_OK;
    if (n == 0) return WK_OK;
    if (!joints || !out) return WK_ERR_NULL;
    for (r = 0; r < n; ++r) {
        const int rc = uw_api_fk(joints + 3 * r, design, out + r);
        if (rc != WK_OK && first == WK_OK) first = rc;
    }
    return first;
}
