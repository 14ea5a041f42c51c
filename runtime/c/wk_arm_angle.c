/* wristkin: the arm angle of a 7R arm with a spherical shoulder and a spherical wrist (an S-R-S arm: the iiwa's) as
 * its redundancy parameter: the shoulder's three joints and the elbow for a wrist centre and an arm angle psi, every
 * set (C99, libm only). Included verbatim into generated C99 sources (static functions, no allocation).
 *
 * psi is where the elbow is on its circle about the shoulder-wrist line: 0 in the plane of that line and the first
 * joint's axis, on the side the axis points to; positive turning about the line from the shoulder to the wrist
 * (derive/kinematics/arm_angle.py derives and checks it). The elbow from the distance (subproblem 3: bent either
 * way); the shoulder's rotation about s maps the home side's frame (s -> the turned wrist centre, and that line's unit
 * to the elbow point) onto the target's (s -> w, the side psi gives); subproblem 2 then 1 read the three shoulder
 * joints from it (two sets; q_b = 0 lines up a and c: a family, q_a from previous else 0). Python's twin:
 * runtime/python/arm_angle.py, step for step.
 * Needs wk_geom3.c and wristkin_runtime's flags before it. The serial arm's arm_angle
 * stage (serial/sr_arm_angle.c) calls it with its tolerances; tests/test_arm_angle.py tests it through it. */

/* The bands (double_root, tangent, on_axis, family) on the closed-form stages' inputs of an S-R-S arm, which the serial
 * stage runs the core at (arm_angle.py's
 * AA_BANDS) */
#define WK_AA_DOUBLE_ROOT (32.0 * DBL_EPSILON)
#define WK_AA_TANGENT 1e-9
#define WK_AA_ON_AXIS (64.0 * DBL_EPSILON)
#define WK_AA_FAMILY 1e-12

/* the caller's tolerances (the serial stage's) */
typedef struct {
    double scale;       /* the chain's size: the distance equation's and the elbow's offset bands scale with it */
    double degenerate;  /* subproblem 1's band on a unit vector's part normal to its axis */
    double double_root; /* 1 - u^2 of the elbow's equation, g^2 of the shoulder's (over its rounding): a double root */
    double tangent;     /* |u| up to 1 + this counts as a root (and g^2 down to -this of its scale) */
    double on_axis;     /* a vanishing equation, and the wrist centre on the first axis, within this */
    double family;      /* the shoulder's family band: p1 within this of k1 (q_b = 0 lines up a and c) */
} wk_aa_tols;

/* o = v / |v| */
static void wk_aa_unit(const double *v, double *o)
{
    const double n = wk_g3_norm(v);
    o[0] = v[0] / n;
    o[1] = v[1] / n;
    o[2] = v[2] / n;
}

/* A unit vector normal to k */
static void wk_aa_perpendicular(const double *k, double *o)
{
    double e[3] = {0.0, 0.0, 0.0};
    if (fabs(k[0]) <= fmin(fabs(k[1]), fabs(k[2])))
        e[0] = 1.0;
    else if (fabs(k[1]) <= fabs(k[2]))
        e[1] = 1.0;
    else
        e[2] = 1.0;
    wk_g3_cross(k, e, o);
    wk_aa_unit(o, o);
}

/* u: the unit from the shoulder centre s to the wrist centre w; n1: the first axis h1's part normal to u, unit
 * (psi = 0 there); n2 = u x n1. Returns WK_FLAG_INDETERMINATE when w lies on the first axis (any n1 normal to u),
 * 0 otherwise, -1 when w = s. */
static int wk_aa_plane(const double *h1, const double *s, const double *w, double on_axis, double *u, double *n1,
                       double *n2)
{
    double sw[3], m;
    int flags = 0;
    wk_g3_axpy(w, -1.0, s, sw);
    m = wk_g3_norm(sw);
    if (!(m > 0.0)) return -1;
    u[0] = sw[0] / m;
    u[1] = sw[1] / m;
    u[2] = sw[2] / m;
    wk_g3_axpy(h1, -wk_g3_dot(h1, u), u, n1);
    m = wk_g3_norm(n1);
    if (!(m > on_axis)) {
        wk_aa_perpendicular(u, n1);
        flags = (int)WK_FLAG_INDETERMINATE;
    } else {
        n1[0] /= m;
        n1[1] /= m;
        n1[2] /= m;
    }
    wk_g3_cross(u, n1, n2);
    return flags;
}

/* psi of an elbow point e (shoulder s, wrist w, first axis h1; axis: the elbow axis's direction there). With the
 * elbow on the line (stretched or folded) the side is axis x u, as the stage reads it there */
static double wk_aa_angle_of(const double *h1, const double *s, const double *e, const double *w, const double *axis,
                             const wk_aa_tols *tol)
{
    double u[3], n1[3], n2[3], se[3], side[3];
    if (wk_aa_plane(h1, s, w, tol->on_axis, u, n1, n2) < 0) return 0.0;
    wk_g3_axpy(e, -1.0, s, se);
    wk_g3_axpy(se, -wk_g3_dot(se, u), u, side);
    if (!(wk_g3_norm(side) > tol->double_root * tol->scale)) wk_g3_cross(axis, u, side);
    return atan2(wk_g3_dot(side, n2), wk_g3_dot(side, n1));
}

/* t with |rot(k, t) p1 - p2| = d (subproblem 3) */
static int wk_aa_sp3(const double *k, const double *p1, const double *p2, double d, const wk_aa_tols *tol, double *t,
                     unsigned *f)
{
    const double kp1 = wk_g3_dot(k, p1);
    const double c = 0.5 * (wk_g3_dot(p1, p1) + wk_g3_dot(p2, p2) - d * d) - kp1 * wk_g3_dot(k, p2);
    double perp[3], kx[3];
    wk_g3_axpy(p1, -kp1, k, perp);
    wk_g3_cross(k, p1, kx);
    return wk_g3_trig(wk_g3_dot(p2, perp), wk_g3_dot(p2, kx), c, tol->scale * tol->scale, tol->on_axis,
                      tol->tangent, tol->double_root, t, f);
}

/* (t1, t2) with rot(k1, t1) p1 = rot(k2, t2) p2 for unit vectors (subproblem 2), at most 2: the common vector
 * w = alpha k1 + beta k2 +- g k1 x k2, g^2 read on the circle of the smaller radius; has1 0 where p1 lies on k1 (any
 * t1: a family) */
static int wk_aa_sp2(const double *p1, const double *k1, const double *p2, const double *k2, const wk_aa_tols *tol,
                     double *t1, int *has1, double *t2, unsigned *f)
{
    const double c = wk_g3_dot(k1, k2), a1 = wk_g3_dot(k1, p1), a2 = wk_g3_dot(k2, p2), den = 1.0 - c * c;
    double alpha, beta, kk[3], base[3], ws[2][3], r1[3], r2[3], n1, n2, n, e, g2, res2, size, scale2;
    unsigned flag;
    int nw, i, out = 0;
    if (!(den > 0.0)) return 0;
    alpha = (a1 - c * a2) / den;
    beta = (a2 - c * a1) / den;
    wk_g3_cross(k1, k2, kk);
    base[0] = base[1] = base[2] = 0.0;
    wk_g3_axpy(base, alpha, k1, base);
    wk_g3_axpy(base, beta, k2, base);
    wk_g3_cross(k1, p1, r1);
    wk_g3_cross(k2, p2, r2);
    n1 = wk_g3_dot(r1, r1);
    n2 = wk_g3_dot(r2, r2);
    if (n1 <= n2) {
        n = n1;
        e = a2 - c * a1;
    } else {
        n = n2;
        e = a1 - c * a2;
    }
    g2 = (den * n - e * e) / (den * den);
    size = sqrt(0.5 * (wk_g3_dot(p1, p1) + wk_g3_dot(p2, p2)));
    if (!(size >= 1.0)) size = 1.0;
    res2 = size * (sqrt(n) + fabs(e)) / den;
    scale2 = wk_g3_dot(p1, p1) + wk_g3_dot(p2, p2);
    if (g2 < -tol->tangent * scale2) return 0;
    if (g2 <= tol->double_root * res2 || g2 <= tol->family * tol->family * scale2) {
        ws[0][0] = base[0];
        ws[0][1] = base[1];
        ws[0][2] = base[2];
        nw = 1;
        flag = WK_FLAG_DOUBLE_ROOT | WK_FLAG_SINGULAR_INVERSE;
    } else {
        const double g = sqrt(g2);
        wk_g3_axpy(base, g, kk, ws[0]);
        wk_g3_axpy(base, -g, kk, ws[1]);
        nw = 2;
        flag = 0u;
    }
    for (i = 0; i < nw; ++i) {
        double a = 0.0, b = 0.0;
        /* p1 on the axis k1 (the family) at the family band, as g above (unit vectors: the band is the distance) */
        const int ok1 = wk_g3_sp1(k1, p1, ws[i], tol->family, &a);
        if (!wk_g3_sp1(k2, p2, ws[i], tol->family, &b)) continue;
        t1[out] = ok1 ? a : 0.0;
        has1[out] = ok1;
        t2[out] = b;
        f[out] = ok1 ? flag : (flag | WK_FLAG_INDETERMINATE | WK_FLAG_SINGULAR_INVERSE);
        ++out;
        if (!ok1) break; /* p1 on the axis k1: both w coincide (one family) */
    }
    return out;
}

/* r (row-major): the rotation that maps the frame (c, d, c x d) onto (a, b, a x b) */
static void wk_aa_rotation(const double *a, const double *b, const double *c, const double *d, double *r)
{
    double ab[3], cd[3];
    int i, j;
    wk_g3_cross(a, b, ab);
    wk_g3_cross(c, d, cd);
    for (i = 0; i < 3; ++i)
        for (j = 0; j < 3; ++j) r[3 * i + j] = a[i] * c[j] + b[i] * d[j] + ab[i] * cd[j];
}

/* o = r v (r row-major) */
static void wk_aa_mv(const double *r, const double *v, double *o)
{
    int i;
    for (i = 0; i < 3; ++i) o[i] = r[3 * i] * v[0] + r[3 * i + 1] * v[1] + r[3 * i + 2] * v[2];
}

/* The shoulder's angles of rot(h_a, q_a) rot(h_b, q_b) rot(h_c, q_c) = r given q_a = -t1, q_b = t2: q_c by
 * subproblem 1 on a unit w normal to h_c */
static void wk_aa_orient_rest(const double *ha, const double *hb, const double *hc, const double *r, double t1,
                              double t2, const wk_aa_tols *tol, double *angles)
{
    double w[3], v[3], t3 = 0.0;
    wk_aa_perpendicular(hc, w);
    wk_aa_mv(r, w, v);
    wk_g3_turn_dir(ha, t1, v, v);
    wk_g3_turn_dir(hb, -t2, v, v);
    angles[0] = -t1;
    angles[1] = t2;
    angles[2] = wk_g3_sp1(hc, w, v, tol->degenerate, &t3) ? t3 : 0.0;
}

/* The sets out[m] = (q_a, q_b, q_c, q_e) with flags[m], at most 4 (two elbows x two shoulders): h_a, h_b, h_c the
 * shoulder's axes (meeting at s), h_e / p_e the elbow's axis and a point on it, x the wrist centre at home, w its
 * target, psi the arm angle; prev_a: previous's q_a (a shoulder family's member), or NULL. held_e: the elbow held at
 * this value (NULL: solved), the arm a self-motion: w within the tangent band of the distance it leaves the wrist
 * centre from s, else no set; the sets at psi, flagged indeterminate (every psi reaches the pose). */
static int wk_arm_angle(const double *ha, const double *hb, const double *hc, const double *s, const double *he,
                        const double *pe, const double *x, const double *w, double psi, const double *prev_a,
                        const double *held_e, const wk_aa_tols *tol, double out[4][4], unsigned *flags)
{
    double u[3], n1[3], n2[3], side[3], elbow[3], xe[3], se[3], sw[3], te[2];
    unsigned fe[2];
    int plane, ne, i, count = 0;
    plane = wk_aa_plane(ha, s, w, tol->on_axis, u, n1, n2);
    if (plane < 0) return 0;
    side[0] = side[1] = side[2] = 0.0;
    wk_g3_axpy(side, cos(psi), n1, side); /* the elbow's side of the line s -> w */
    wk_g3_axpy(side, sin(psi), n2, side);
    wk_g3_axpy(s, -1.0, pe, se);
    wk_g3_axpy(pe, wk_g3_dot(he, se), he, elbow); /* the elbow axis's point nearest s */
    wk_g3_axpy(x, -1.0, pe, xe);
    wk_g3_axpy(w, -1.0, s, sw);
    if (held_e) {
        double xh[3];
        wk_g3_turn(he, pe, *held_e, x, xh);
        wk_g3_axpy(xh, -1.0, s, xh);
        if (!(fabs(wk_g3_norm(xh) - wk_g3_norm(sw)) <= tol->tangent * tol->scale)) return 0;
        te[0] = *held_e;
        fe[0] = WK_FLAG_INDETERMINATE | WK_FLAG_SINGULAR_INVERSE;
        ne = 1;
    } else {
        ne = wk_aa_sp3(he, xe, se, wk_g3_norm(sw), tol, te, fe);
    }
    if (!held_e && ne == 1 && (fe[0] & WK_FLAG_DOUBLE_ROOT)) {
        /* the arm (nearly) stretched or folded: the merged roots are the elbow bent to either side of the line,
         * where the shoulder and wrist differ by a half turn: both sides, a band's width off the line */
        const double band = sqrt(tol->double_root);
        te[1] = te[0] - band;
        te[0] += band;
        fe[1] = fe[0];
        ne = 2;
    }
    for (i = 0; i < ne; ++i) {
        double v[3], off[3], home_side[3], r[9], rc[3], t1[2], t2[2];
        unsigned f = fe[i], f2[2];
        int has1[2], ns, m;
        wk_g3_turn(he, pe, te[i], x, v); /* the wrist centre with the elbow turned, shoulder at home */
        wk_g3_axpy(v, -1.0, s, v);
        wk_aa_unit(v, v);
        wk_g3_axpy(elbow, -1.0, s, off);
        wk_g3_axpy(off, -wk_g3_dot(off, v), v, off);
        if (wk_g3_norm(off) > tol->double_root * tol->scale) {
            wk_aa_unit(off, home_side);
        } else { /* stretched or folded: the elbow on the line, any turn about it the same pose */
            wk_g3_cross(he, v, home_side);
            wk_aa_unit(home_side, home_side);
            f |= WK_FLAG_DOUBLE_ROOT | WK_FLAG_SINGULAR_INVERSE;
        }
        wk_aa_rotation(u, side, v, home_side, r);
        wk_aa_mv(r, hc, rc);
        ns = wk_aa_sp2(rc, ha, hc, hb, tol, t1, has1, t2, f2);
        for (m = 0; m < ns && count < 4; ++m) {
            unsigned g = f2[m];
            if (!has1[m]) { /* a and c line up: the family's q_a from previous, else 0 */
                t1[m] = -(prev_a ? *prev_a : 0.0);
                g |= WK_FLAG_INDETERMINATE | WK_FLAG_SINGULAR_INVERSE;
            }
            wk_aa_orient_rest(ha, hb, hc, r, t1[m], t2[m], tol, out[count]);
            out[count][3] = te[i];
            flags[count] = f | g | (unsigned)plane;
            ++count;
        }
    }
    return count;
}
