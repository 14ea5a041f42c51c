/* The Paden-Kahan subproblems 1-4 (and subproblem 2's height), a trig equation, a 3x3 solve.
 * (a wristkin runtime source, inlined whole into every user robot's generated C, after the robot's CK_*
 * constants; derive/runtime_files.py, tests/test_chain_runtime.py) */
/* ------------------------------------------------------------------ subproblems */
/* Roots t of a cos t + b sin t = c (at most 2), gap: NULL, or a planar distance stage's (Dm, Dp, narrow): 1 - u^2
 * read as Dm Dp / (4 R^2) and its double-root band times narrow (Python's _trig) */
static int ck_trig_gap(double a, double b, double c, double scale, double noise, const double *gap, double *t,
                       unsigned *f)
{
    const double r = hypot(a, b);
    const double tangent = fmax(CK_TANGENT_TOL, CK_STAGE_NOISE * noise);
    const double dbl = fmax(CK_DOUBLE_ROOT_TOL, 2.0 * CK_STAGE_NOISE * noise);
    double u, phi, w, s2;
    if (r <= CK_ON_AXIS_TOL * scale) {
        if (fabs(c) <= CK_ON_AXIS_TOL * scale) {
            t[0] = 0.0;
            f[0] = WK_FLAG_INDETERMINATE | WK_FLAG_SINGULAR_INVERSE;
            return 1;
        }
        return 0;
    }
    u = c / r;
    if (!(fabs(u) <= 1.0 + tangent)) return 0;
    u = u > 1.0 ? 1.0 : (u < -1.0 ? -1.0 : u);
    phi = atan2(b, a);
    s2 = gap ? fmax(gap[0] * gap[1], 0.0) / (4.0 * r * r) : 1.0 - u * u;
    if (s2 <= dbl * (gap ? gap[2] : 1.0)) {
        t[0] = phi + (u > 0.0 ? 0.0 : CK_PI);
        f[0] = WK_FLAG_DOUBLE_ROOT | WK_FLAG_SINGULAR_INVERSE;
        return 1;
    }
    w = gap ? atan2(sqrt(s2), u) : acos(u);
    t[0] = phi + w;
    t[1] = phi - w;
    f[0] = f[1] = 0u;
    return 2;
}

/* Roots t of a cos t + b sin t = c (Python's _trig): a double root once (flagged), a vanishing equation one
 * representative t = 0 (flagged indeterminate); noise: 1 / g of an upstream near-singular orientation, else 1 */
static int ck_trig(double a, double b, double c, double scale, double noise, double *t, unsigned *f)
{
    return ck_trig_gap(a, b, c, scale, noise, NULL, t, f);
}

/* t with rot(k, t) p = q (least squares); 0 when p or q is on the axis (within CK_DEGENERATE_EPS of `scale`:
 * CK_SCALE for points, 1 for directions) */
static int ck_sp1(const double *k, const double *p, const double *q, double scale, double *t)
{
    double pp[3], qq[3], c[3];
    ck_scale(k, ck_dot(k, p), pp);
    ck_sub(p, pp, pp);
    ck_scale(k, ck_dot(k, q), qq);
    ck_sub(q, qq, qq);
    if (ck_norm(pp) <= CK_DEGENERATE_EPS * scale || ck_norm(qq) <= CK_DEGENERATE_EPS * scale) return 0;
    ck_cross(pp, qq, c);
    *t = atan2(ck_dot(k, c), ck_dot(pp, qq));
    return 1;
}

/* t with |rot(k, t) p1 - p2| = d */
static int ck_sp3(const double *k, const double *p1, const double *p2, double d, double scale, double noise,
                  const double *target, double amp, double *t, unsigned *f)
{
    const double kp1 = ck_dot(k, p1);
    double perp[3], kx[3], c, a, b, gap[3];
    ck_scale(k, kp1, perp);
    ck_sub(p1, perp, perp);
    c = 0.5 * (ck_dot(p1, p1) + ck_dot(p2, p2) - d * d) - kp1 * ck_dot(k, p2);
    ck_cross(k, p1, kx);
    a = ck_dot(p2, perp);
    b = ck_dot(p2, kx);
    if (target) { /* planar: 1 - u^2 from its factors (Python's _sp3) */
        double p2n[3], tn[3];
        double l1, l2, e, diff, em;
        ck_scale(k, ck_dot(k, p2), p2n);
        ck_sub(p2, p2n, p2n);
        ck_scale(k, ck_dot(k, target), tn);
        ck_sub(target, tn, tn);
        l1 = ck_norm(perp);
        l2 = ck_norm(p2n);
        e = ck_norm(tn);
        diff = fabs(l1 - l2);
        gap[0] = (e - diff) * (e + diff);
        gap[1] = (l1 + l2 - e) * (l1 + l2 + e);
        em = e * e + diff * diff + 2.0 * (e + diff) * scale;
        gap[2] = fabs(gap[0]) <= fabs(gap[1]) ? fmin(1.0, em * amp / (2.0 * hypot(a, b))) : 1.0;
        return ck_trig_gap(a, b, c, scale * scale, noise, gap, t, f);
    }
    return ck_trig(a, b, c, scale * scale, noise, t, f);
}

/* t with h . rot(k, t) p = d */
static int ck_sp4(const double *h, const double *k, const double *p, double d, double scale, double noise, double *t,
                  unsigned *f)
{
    const double kp = ck_dot(k, p);
    double perp[3], kx[3];
    ck_scale(k, kp, perp);
    ck_sub(p, perp, perp);
    ck_cross(k, p, kx);
    return ck_trig(ck_dot(h, perp), ck_dot(h, kx), d - kp * ck_dot(h, k), scale, noise, t, f);
}

/* g^2 of subproblem 2's common vector w = alpha k1 + beta k2 + g k1 x k2, read on the circle of the smaller radius
 * (p1's about k1 or p2's about k2) so that near a singular family it has no cancellation, and (*res2) the scale at
 * which the inputs' rounding enters it (see Python's _sp2_height2) */
static double ck_sp2_height2(const double *p1, const double *k1, const double *p2, const double *k2, double c,
                             double a1, double a2, double den, double scale, double *res2)
{
    double r1[3], r2[3], n1, n2, n, e, size;
    ck_cross(k1, p1, r1);
    ck_cross(k2, p2, r2);
    n1 = ck_dot(r1, r1);
    n2 = ck_dot(r2, r2);
    if (n1 <= n2) {
        n = n1;
        e = a2 - c * a1;
    } else {
        n = n2;
        e = a1 - c * a2;
    }
    size = sqrt(0.5 * (ck_dot(p1, p1) + ck_dot(p2, p2)));
    if (!(size >= scale)) size = scale;
    *res2 = size * (sqrt(n) + fabs(e)) / den;
    return (den * n - e * e) / (den * den);
}

/* How much a trig stage's nr roots t amplify the rounding of its inputs: 1 / |sin w| for roots phi +- w, a double
 * root 1 / sqrt(CK_DOUBLE_ROOT_TOL), times `outer` (the stages before: each reads the joints they solved, so the
 * errors compound, as the serial runtime's wrist band has them; Python's _root_amplification) */
static double ck_root_amplification(int nr, const double *t, const unsigned *f, double outer)
{
    if (nr == 2) {
        const double s = fabs(sin(0.5 * (t[0] - t[1])));
        return outer / (s > 1e-300 ? s : 1e-300);
    }
    if (nr == 1 && (f[0] & WK_FLAG_DOUBLE_ROOT)) return outer / sqrt(CK_DOUBLE_ROOT_TOL);
    return outer;
}

/* (t1, t2, flags) with rot(k1, t1) p1 = rot(k2, t2) p2, k1 not parallel to k2 (at most 2). has1[i] = 0 when p1
 * lies on k1 (any t1: a singular family, returned once). `amp`: the stages before's amplification of the input's
 * rounding (ck_root_amplification): the bands grow with it; `family_tol`: CK_FAMILY_TOL for a rotation's unit
 * vectors, CK_ON_AXIS_TOL for a position pair (Python's _sp2). */
static int ck_sp2(const double *p1, const double *k1, const double *p2, const double *k2, double scale, int split,
                  double amp, double family_tol, double *t1, int *has1, double *t2, unsigned *f)
{
    const double c = ck_dot(k1, k2), a1 = ck_dot(k1, p1), a2 = ck_dot(k2, p2), den = 1.0 - c * c;
    const double family = family_tol * amp, axis_scale = scale * (family / CK_DEGENERATE_EPS);
    double alpha, beta, kk[3], base[3], tmp[3], ws[2][3], g2, scale2, res2;
    unsigned flag;
    int nw, i, near, out = 0;
    if (!(den > 0.0)) return 0;
    alpha = (a1 - c * a2) / den;
    beta = (a2 - c * a1) / den;
    ck_cross(k1, k2, kk);
    ck_scale(k1, alpha, base);
    ck_scale(k2, beta, tmp);
    ck_add(base, tmp, base);
    g2 = ck_sp2_height2(p1, k1, p2, k2, c, a1, a2, den, scale, &res2);
    scale2 = ck_dot(p1, p1) + ck_dot(p2, p2);
    if (g2 < -CK_TANGENT_TOL * scale2) return 0;
    /* one double root where g^2 is within CK_DOUBLE_ROOT_TOL of what rounding leaves in it (Python's _sp2) */
    /* `split`: only the two roots of a near-double root (see Python's _sp2), for a caller whose merged root
       verified nothing */
    near = g2 <= CK_DOUBLE_ROOT_TOL * amp * res2 || g2 <= family * family * scale2;
    if (split && !(near && g2 > 0.0)) return 0;
    if (!split && near) {
        ws[0][0] = base[0];
        ws[0][1] = base[1];
        ws[0][2] = base[2];
        nw = 1;
        flag = WK_FLAG_DOUBLE_ROOT | WK_FLAG_SINGULAR_INVERSE;
    } else {
        const double g = sqrt(g2);
        ck_scale(kk, g, tmp);
        ck_add(base, tmp, ws[0]);
        ck_scale(kk, -g, tmp);
        ck_add(base, tmp, ws[1]);
        nw = 2;
        flag = split ? WK_FLAG_SINGULAR_INVERSE : 0u;
    }
    for (i = 0; i < nw; ++i) {
        double a = 0.0, b = 0.0;
        /* p1 on the axis k1 (the family) at CK_FAMILY_TOL, as g above (Python's _sp2) */
        const int ok1 = ck_sp1(k1, p1, ws[i], axis_scale, &a);
        if (!ck_sp1(k2, p2, ws[i], axis_scale, &b) || (split && !ok1)) continue;
        t1[out] = ok1 ? a : 0.0;
        has1[out] = ok1;
        t2[out] = b;
        f[out] = ok1 ? flag : (flag | WK_FLAG_INDETERMINATE | WK_FLAG_SINGULAR_INVERSE);
        ++out;
        if (!ok1) break; /* p1 on the axis k1: both w coincide (one family) */
    }
    return out;
}

/* A unit vector normal to k */
static void ck_perpendicular(const double *k, double *o)
{
    double e[3] = {0.0, 0.0, 0.0};
    if (fabs(k[0]) <= fmin(fabs(k[1]), fabs(k[2])))
        e[0] = 1.0;
    else if (fabs(k[1]) <= fabs(k[2]))
        e[1] = 1.0;
    else
        e[2] = 1.0;
    ck_cross(k, e, o);
    ck_scale(o, 1.0 / ck_norm(o), o);
}

/* The unit angles of R(u0, a0) R(u1, a1) [R(u2, a2)] = rd given a0 = -t1 (and a1 = t2 for three units). */
static void ck_orient_rest(int nu, const double *const *u, const double *rd, double t1, double t2, double *angles)
{
    double r1[9], w[3], rw[3], a = 0.0;
    ck_rot(u[0], -t1, r1);
    angles[0] = -t1;
    if (nu == 3) {
        double r2[9];
        ck_rot(u[1], t2, r2);
        ck_mm(r1, r2, r2);
        ck_perpendicular(u[2], w);
        ck_mv(rd, w, rw);
        ck_mtv(r2, rw, rw);
        angles[1] = t2;
        angles[2] = ck_sp1(u[2], w, rw, 1.0, &a) ? a : 0.0;
    } else {
        ck_perpendicular(u[1], w);
        ck_mv(rd, w, rw);
        ck_mtv(r1, rw, rw);
        angles[1] = ck_sp1(u[1], w, rw, 1.0, &a) ? a : 0.0;
    }
}

/* x with m x = v (3 x 3, row-major) by Gaussian elimination with partial pivoting; 0 when a pivot is below
 * 1e-12 of the largest entry (then the caller takes the least-squares path) */
static int ck_solve3(const double *m_in, const double *v_in, double *x)
{
    double m[3][4], big = 0.0;
    int i, j, k;
    for (i = 0; i < 3; ++i) {
        for (j = 0; j < 3; ++j) {
            m[i][j] = m_in[3 * i + j];
            if (fabs(m[i][j]) > big) big = fabs(m[i][j]);
        }
        m[i][3] = v_in[i];
    }
    for (i = 0; i < 3; ++i) {
        int piv = i;
        for (k = i + 1; k < 3; ++k)
            if (fabs(m[k][i]) > fabs(m[piv][i])) piv = k;
        if (!(fabs(m[piv][i]) > 1e-12 * big)) return 0;
        for (j = 0; j < 4; ++j) {
            const double t = m[i][j];
            m[i][j] = m[piv][j];
            m[piv][j] = t;
        }
        for (k = i + 1; k < 3; ++k) {
            const double f = m[k][i] / m[i][i];
            for (j = i; j < 4; ++j) m[k][j] -= f * m[i][j];
        }
    }
    for (i = 2; i >= 0; --i) {
        double acc = m[i][3];
        for (j = i + 1; j < 3; ++j) acc -= m[i][j] * x[j];
        x[i] = acc / m[i][i];
    }
    return 1;
}

/* The point nearest to the axes js (their common point), by least squares */
