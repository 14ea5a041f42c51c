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

/* The modes found so far: (zeta, eta, cos zeta, sin zeta, cos eta, sin eta), flags, the eliminant root each came
 * from, and whether it was accepted in the fold band (resolved only to sqrt(UW_FK_FOLD_TOL)). */
typedef struct {
    double modes[16][6];
    unsigned flags[16];
    int root[16], fold[16], n;
} uw_mode_table;

/* Add a polished mode (z, e, cs: cos, sin of both; flags tf) of eliminant root r, or merge it into one it duplicates
 * (Python's _add_mode). */
static void uw_add_mode(uw_mode_table *t, double z, double e, const double *cs, unsigned tf, int r)
{
    int m, dup = -1;
    z = uw_wrap_2pi(z);
    e = uw_wrap_2pi(e);
    /* a touching root's modes closer than the fold's resolution sqrt(UW_FK_FOLD_TOL) are one double root; two
       modes polished to regular residuals are distinct beyond UW_FK_DUPLICATE_TOL (see Python) */
    for (m = 0; m < t->n; ++m) {
        const double near = (tf || t->fold[m]) ? sqrt(UW_FK_FOLD_TOL) : UW_FK_DUPLICATE_TOL;
        if (fabs(uw_wrap_pi(t->modes[m][0] - z)) < near && fabs(uw_wrap_pi(t->modes[m][1] - e)) < near) {
            dup = m;
            break;
        }
    }
    if (dup >= 0) {
        if (t->root[dup] != r) {
            t->flags[dup] |= WK_FLAG_DOUBLE_ROOT | tf; /* two roots, one mode: merged */
        } else if (fabs(uw_wrap_pi(t->modes[dup][0] - z)) >= UW_FK_DUPLICATE_TOL ||
                   fabs(uw_wrap_pi(t->modes[dup][1] - e)) >= UW_FK_DUPLICATE_TOL) {
            t->flags[dup] |= WK_FLAG_DOUBLE_ROOT | WK_FLAG_SINGULAR_DIRECT; /* a fold pair, merged */
        }
    } else if (t->n < 16) {
        t->modes[t->n][0] = z;
        t->modes[t->n][1] = e;
        for (m = 0; m < 4; ++m) t->modes[t->n][2 + m] = cs[m]; /* cos, sin of zeta, eta (the wrap keeps them) */
        t->flags[t->n] = tf;
        t->fold[t->n] = tf != 0u;
        t->root[t->n] = r;
        ++t->n;
    }
}

/* Two regular modes on either side of (zeta, eta), a point polished only into the fold band (Python's
 * _split_fold): polished from (zeta, eta) +- s v, v the near-null direction of the loop equations' Jacobian, s =
 * 1e-6, 1e-5, 1e-4; 1 with pair[k] = (zeta, eta, cos zeta, sin zeta, cos eta, sin eta) when both reach a regular
 * residual UW_FK_DUPLICATE_TOL apart, else 0. */
static int uw_split_fold(const uw_fk_coef *cf, double zeta, double eta, const double *cs, double pair[2][6])
{
    static const double steps[3] = {1e-6, 1e-5, 1e-4};
    double g[2], jac[4], p, q, rr, lam, v0, v1, nv;
    int k, side;
    (void)uw_residual(cf, cs, g, jac);
    p = jac[0] * jac[0] + jac[2] * jac[2];
    q = jac[0] * jac[1] + jac[2] * jac[3];
    rr = jac[1] * jac[1] + jac[3] * jac[3];
    lam = 0.5 * (p + rr) - hypot(0.5 * (p - rr), q); /* J^T J's smaller eigenvalue: its vector is v */
    if (fabs(q) + fabs(lam - p) >= fabs(lam - rr) + fabs(q)) {
        v0 = q;
        v1 = lam - p;
    } else {
        v0 = lam - rr;
        v1 = q;
    }
    nv = hypot(v0, v1);
    if (!(nv > 0.0)) return 0;
    v0 /= nv;
    v1 /= nv;
    for (k = 0; k < 3; ++k) {
        double err[2];
        for (side = 0; side < 2; ++side) {
            const double s = side ? -steps[k] : steps[k];
            double z = zeta + s * v0, e = eta + s * v1;
            pair[side][2] = cos(z);
            pair[side][3] = sin(z);
            pair[side][4] = cos(e);
            pair[side][5] = sin(e);
            err[side] = uw_polish(cf, &z, &e, pair[side] + 2);
            pair[side][0] = z;
            pair[side][1] = e;
        }
        if (err[0] <= UW_FK_RESIDUAL_TOL && err[1] <= UW_FK_RESIDUAL_TOL &&
            (fabs(uw_wrap_pi(pair[0][0] - pair[1][0])) >= UW_FK_DUPLICATE_TOL ||
             fabs(uw_wrap_pi(pair[0][1] - pair[1][1])) >= UW_FK_DUPLICATE_TOL))
            return 1;
    }
    return 0;
}

static int uw_api_fk(const double joints[3], const uw_design *design,
                     uw_fk_solutions *out)
{
    const uw_design *d = uw_design_or_default(design);
    uw_fk_coef cf;
    double raw[18], kpoly[9], roots[8], best = -1.0, eta_c, cq[3], sq[3], z1[9], z2[9];
    unsigned rflags[8];
    uw_mode_table t;
    int nroots, pstatus = 0, nm = 0, r, j, k, kbest = 0;
    t.n = 0;
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
    nroots = wk_poly_real_roots(kpoly, 8, roots, rflags, &pstatus, WK_POLY_TOL_TOUCH);
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
            double err, pair[2][6];
            int fold_only;
            cs[0] = zcs[2 * j];
            cs[1] = zcs[2 * j + 1];
            cs[2] = ce0;
            cs[3] = se0;
            err = uw_polish(&cf, &z, &e, cs);
            if (!(err <= (touching ? UW_FK_FOLD_TOL : UW_FK_RESIDUAL_TOL))) continue;
            fold_only = touching && !(err <= UW_FK_RESIDUAL_TOL);
            if (fold_only && uw_split_fold(&cf, z, e, cs, pair)) { /* in the fold band only: two modes after all */
                uw_add_mode(&t, pair[0][0], pair[0][1], pair[0] + 2, 0u, r);
                uw_add_mode(&t, pair[1][0], pair[1][1], pair[1] + 2, 0u, r);
                continue;
            }
            /* a merge is confirmed, not assumed: a regular residual is a regular mode (see Python) */
            uw_add_mode(&t, z, e, cs, fold_only ? (WK_FLAG_DOUBLE_ROOT | WK_FLAG_SINGULAR_DIRECT) : 0u, r);
        }
    }
    nm = t.n;
    /* stable order: by eta, then zeta (insertion sort, nm <= 16) */
    for (j = 1; j < nm; ++j) {
        double mode[6];
        unsigned f = t.flags[j];
        int i = j - 1, c;
        for (c = 0; c < 6; ++c) mode[c] = t.modes[j][c];
        while (i >= 0 && (t.modes[i][1] > mode[1] || (t.modes[i][1] == mode[1] && t.modes[i][0] > mode[0]))) {
            for (c = 0; c < 6; ++c) t.modes[i + 1][c] = t.modes[i][c];
            t.flags[i + 1] = t.flags[i];
            --i;
        }
        for (c = 0; c < 6; ++c) t.modes[i + 1][c] = mode[c];
        t.flags[i + 1] = f;
    }
    if (nm > UW_MAX_FK) nm = UW_MAX_FK;
    uw_k_base_axes(d->c, z1);
    uw_k_middle_axes(cq, sq, d->c, z2);
    for (k = 0; k < nm; ++k) {
        const double c3[3] = {cq[0], t.modes[k][2], t.modes[k][4]}, s3[3] = {sq[0], t.modes[k][3], t.modes[k][5]};
        double rot[9], z3[9], rows[3][3], n12[3], ci = 1.0, cd;
        unsigned f = t.flags[k];
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
        out->aux[k][9] = t.modes[k][0];
        out->aux[k][10] = t.modes[k][1];
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
