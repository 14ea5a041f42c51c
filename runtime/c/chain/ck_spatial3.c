/* Three revolute axes in general position: every real root of their degree-8 polynomial.
 * (a wristkin runtime source, inlined whole into every user robot's generated C, after the robot's CK_*
 * constants; derive/runtime_files.py, tests/test_chain_runtime.py) */
/* Rows of u . R(h2, q2) v_j over a = (1, cos q2, sin q2), for each v_j: (h.u)(h.v), u.v - (h.u)(h.v), u.(h x v) */
static void ck_bilinear(const double *h2, const double *u, const double (*vs)[3], double m[3][3])
{
    const double hu = ck_dot(h2, u);
    int j;
    for (j = 0; j < 3; ++j) {
        double hx[3];
        ck_cross(h2, vs[j], hx);
        m[0][j] = hu * ck_dot(h2, vs[j]);
        m[1][j] = ck_dot(u, vs[j]) - hu * ck_dot(h2, vs[j]);
        m[2][j] = ck_dot(u, hx);
    }
}
/* Newton steps on e_a e_b e_c x = y (Cramer's rule on the columns h_i x (p - r_i); Python's _spatial3_refine):
 * the degree-8 polynomial's roots carry ~1e-10 of its rounding, which a wrist after them would read as a turn off
 * its singular family; two steps bring a simple root to rounding (a step is kept only while the residual shrinks) */
#define CK_SPATIAL3_REFINE_STEPS 2
static double ck_spatial3_point(const ck_chain *ch, const int *js, const double *q, const double *x,
                                const double *y, double *p, double (*h)[3], double (*r)[3])
{
    ck_rt e, s;
    double d[3];
    int i;
    ck_identity(&e);
    for (i = 0; i < 3; ++i) {
        ck_mv(e.r, ch->axis[js[i]], h[i]);
        ck_apply(&e, ch->point[js[i]], r[i]);
        ck_screw(0, ch->axis[js[i]], ch->point[js[i]], q[i], &s);
        ck_compose(&e, &s, &e);
    }
    ck_apply(&e, x, p);
    ck_sub(p, y, d);
    return ck_norm(d);
}

static void ck_spatial3_refine(const ck_chain *ch, int ja, int jb, int jc, const double *x, const double *y,
                               double *qa, double *qb, double *qc)
{
    const int js[3] = {ja, jb, jc};
    double q[3] = {*qa, *qb, *qc}, p[3], h[3][3], r[3][3], err;
    int it, i;
    err = ck_spatial3_point(ch, js, q, x, y, p, h, r);
    for (it = 0; it < CK_SPATIAL3_REFINE_STEPS; ++it) {
        double c[3][3], b[3], x12[3], bx2[3], c1b[3], det, trial[3], p2[3], h2[3][3], r2[3][3], err2;
        for (i = 0; i < 3; ++i) {
            double d[3];
            ck_sub(p, r[i], d);
            ck_cross(h[i], d, c[i]);
        }
        ck_sub(y, p, b);
        ck_cross(c[1], c[2], x12);
        det = ck_dot(c[0], x12);
        if (!(fabs(det) > CK_DEGENERATE_EPS * CK_SCALE * CK_SCALE * CK_SCALE)) break;
        ck_cross(b, c[2], bx2);
        ck_cross(c[1], b, c1b);
        trial[0] = q[0] + ck_dot(b, x12) / det;
        trial[1] = q[1] + ck_dot(c[0], bx2) / det;
        trial[2] = q[2] + ck_dot(c[0], c1b) / det;
        err2 = ck_spatial3_point(ch, js, trial, x, y, p2, h2, r2);
        if (!(err2 < err)) break;
        for (i = 0; i < 3; ++i) {
            q[i] = trial[i];
            p[i] = p2[i];
        }
        for (i = 0; i < 3; ++i) {
            int m;
            for (m = 0; m < 3; ++m) {
                h[i][m] = h2[i][m];
                r[i][m] = r2[i][m];
            }
        }
        err = err2;
    }
    *qa = q[0];
    *qb = q[1];
    *qc = q[2];
}

/* (q_a, q_b, q_c, flags) with e_a e_b e_c x = y for three revolute axes in general position (the Python module's
 * _spatial3): joint a keeps the distance to its axis point and the component along its axis, two equations
 * bilinear in (1, cos q_b, sin q_b) x (1, cos q_c, sin q_c); cos^2 + sin^2 = 1 of the (cos q_c, sin q_c) they give
 * is a degree-8 polynomial in tan(q_b / 2). At most 9 candidates (8 roots and q_b = pi). */
static int ck_spatial3(const ck_chain *ch, int ja, int jb, int jc, const double *x, const double *y, double *qa,
                       double *qb, double *qc, unsigned *fl)
{
    const double *h1 = ch->axis[ja], *r1 = ch->point[ja], *h2 = ch->axis[jb], *r2 = ch->point[jb];
    const double *h3 = ch->axis[jc], *r3 = ch->point[jc];
    static const double apoly[3][3] = { {1.0, 0.0, 1.0}, {1.0, 0.0, -1.0}, {0.0, 2.0, 0.0} };
    double v[3], vb[3][3], u[3], f[3][3], g[3][3], hv, dtarget, htarget, yr[3], tmp[3];
    double p[3][3], q[3][3], dt[3], ht[3], det[5], nc[5], ns[5], a5[5], poly[9], roots[8], ang[9];
    unsigned rf[8], af[9];
    int i, j, nroot, status = 0, na = 0, out = 0;
    ck_sub(x, r3, v);
    hv = ck_dot(h3, v);
    ck_scale(h3, hv, tmp);
    ck_add(r3, tmp, vb[0]);
    ck_sub(vb[0], r2, vb[0]);
    ck_sub(v, tmp, vb[1]);
    ck_cross(h3, v, vb[2]);
    ck_sub(r2, r1, u);
    ck_bilinear(h2, u, (const double (*)[3])vb, f);
    ck_bilinear(h2, h1, (const double (*)[3])vb, g);
    for (i = 0; i < 3; ++i)
        for (j = 0; j < 3; ++j) f[i][j] *= 2.0;
    f[0][0] += ck_dot(vb[0], vb[0]) + ck_dot(vb[1], vb[1]) + ck_dot(u, u);
    f[0][1] += 2.0 * ck_dot(vb[0], vb[1]);
    f[0][2] += 2.0 * ck_dot(vb[0], vb[2]);
    g[0][0] += ck_dot(h1, u);
    ck_sub(y, r1, yr);
    dtarget = ck_dot(yr, yr);
    htarget = ck_dot(h1, yr);
    for (j = 0; j < 3; ++j)
        for (i = 0; i < 3; ++i) {
            p[j][i] = apoly[0][i] * f[0][j] + apoly[1][i] * f[1][j] + apoly[2][i] * f[2][j];
            q[j][i] = apoly[0][i] * g[0][j] + apoly[1][i] * g[1][j] + apoly[2][i] * g[2][j];
        }
    for (i = 0; i < 3; ++i) {
        dt[i] = apoly[0][i] * dtarget - p[0][i];
        ht[i] = apoly[0][i] * htarget - q[0][i];
    }
    ck_poly_mul(p[1], 3, q[2], 3, det);
    ck_poly_mul(p[2], 3, q[1], 3, a5);
    ck_poly_axpy(det, a5, 5, -1.0);
    ck_poly_mul(dt, 3, q[2], 3, nc);
    ck_poly_mul(p[2], 3, ht, 3, a5);
    ck_poly_axpy(nc, a5, 5, -1.0);
    ck_poly_mul(p[1], 3, ht, 3, ns);
    ck_poly_mul(q[1], 3, dt, 3, a5);
    ck_poly_axpy(ns, a5, 5, -1.0);
    ck_poly_mul(nc, 5, nc, 5, poly);
    {
        double sq[9];
        ck_poly_mul(ns, 5, ns, 5, sq);
        ck_poly_axpy(poly, sq, 9, 1.0);
        ck_poly_mul(det, 5, det, 5, sq);
        ck_poly_axpy(poly, sq, 9, -1.0);
    }
    nroot = wk_poly_real_roots(poly, 8, roots, rf, &status);
    for (i = 0; i < nroot; ++i) {
        ang[na] = 2.0 * atan(roots[i]);
        af[na++] = (rf[i] & WK_POLY_FLAG_DOUBLE) ? (WK_FLAG_DOUBLE_ROOT | WK_FLAG_SINGULAR_INVERSE) : 0u;
    }
    ang[na] = CK_PI; /* tan(q_b / 2) = infinity is no root of the polynomial: tried directly */
    af[na++] = 0u;
    for (i = 0; i < na; ++i) {
        const double cb = cos(ang[i]), sb = sin(ang[i]);
        double pv[3], qv[3], dd, cc, ss, w[3], t1 = 0.0;
        ck_rt eb, ec, e;
        for (j = 0; j < 3; ++j) {
            pv[j] = f[0][j] + cb * f[1][j] + sb * f[2][j];
            qv[j] = g[0][j] + cb * g[1][j] + sb * g[2][j];
        }
        dd = pv[1] * qv[2] - pv[2] * qv[1];
        if (fabs(dd) <= CK_DEGENERATE_EPS * CK_SCALE * CK_SCALE * CK_SCALE) continue;
        cc = ((dtarget - pv[0]) * qv[2] - pv[2] * (htarget - qv[0])) / dd;
        ss = (pv[1] * (htarget - qv[0]) - qv[1] * (dtarget - pv[0])) / dd;
        if (fabs(hypot(cc, ss) - 1.0) > 1e-6) continue; /* the root at infinity, or a poorly resolved one */
        qb[out] = ang[i];
        qc[out] = atan2(ss, cc);
        ck_screw(0, h2, r2, qb[out], &eb);
        ck_screw(0, h3, r3, qc[out], &ec);
        ck_compose(&eb, &ec, &e);
        ck_apply(&e, x, w);
        ck_sub(w, r1, w);
        fl[out] = af[i];
        if (ck_sp1(h1, w, yr, CK_SCALE, &t1)) {
            qa[out] = t1;
            if (!(fl[out] & WK_FLAG_DOUBLE_ROOT)) ck_spatial3_refine(ch, ja, jb, jc, x, y, &qa[out], &qb[out], &qc[out]);
        } else {
            qa[out] = 0.0;
            fl[out] |= WK_FLAG_INDETERMINATE | WK_FLAG_SINGULAR_INVERSE;
        }
        ++out;
    }
    return out;
}
