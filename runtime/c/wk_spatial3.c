/* wristkin: three revolute axes in general position placing a point, every real solution (C99, libm only).
 * Included verbatim into generated C99 sources (static functions, no allocation).
 *
 * The position problem rot_a rot_b rot_c x = y of three lines (unit direction h_i through point r_i), none of the
 * invariants of subproblems 1-4 applying (subproblem 5 in effect). Joint a keeps the distance of the point to its
 * axis point r_a and its component along h_a: two equations bilinear in (1, cos q_b, sin q_b) x (1, cos q_c,
 * sin q_c). For each q_b they are linear in (cos q_c, sin q_c), and cos^2 + sin^2 = 1 of their solution is a degree-8
 * polynomial in tan(q_b / 2) (with the extraneous (1 + t^2)^2 of the half-angle substitution: at most four real
 * roots, Pieper's bound), whose real roots wk_poly_real_roots isolates; q_a then by subproblem 1, and Newton steps
 * on the point bring a simple root to rounding. A double root of the polynomial with the target off axis a is
 * split into the pair it merged (wk_s3_split): near that axis the pair differs by ~ the distance, below the
 * polynomial's sqrt(eps). Python's twin: runtime/python/spatial3.py, step for step.
 * Needs poly_real_roots.c, wk_poly_ops.c, wk_geom3.c and wristkin_runtime's flags before it. The serial arm's
 * spatial3 stage (sr_spatial3.c) calls it; tests/test_spatial3_runtime.py tests it
 * as it is (tests/c/spatial3_harness.c). */
#define WK_S3_MAX 12            /* candidates: eight roots, q_b = pi, and the pairs split from merged ones */
#define WK_S3_REFINE_STEPS 8    /* Newton steps at most (spatial3.py's S3_REFINE_STEPS says why) */
#define WK_S3_SPLIT_STEPS 8     /* Newton steps from each of a merged pair's two starts */
#define WK_S3_SPLIT_TOL 1e-10   /* a split root's point residual (relative to the lengths' size) at most this */
#define WK_S3_SPLIT_APART 0.25  /* the two split roots at least this part of their starts' gap apart: a pair */
#define WK_S3_SPLIT_HALVINGS 10 /* a split's Newton step halved up to this many times until the residual shrinks */
#define WK_S3_SPLIT_STEP_MAX 0.5 /* rad: a split's Newton step at most this in any joint before it is halved */
#define WK_S3_SPLIT_NEAR 1e-3   /* rad: a split root keeps the merged root's q_b, q_c to this */
#define WK_S3_CURVATURE_STEP 1e-3 /* rad: the central difference of the point's second derivative */
#define WK_S3_ROUNDING 32.0     /* the polynomial's rounding: at most this many eps of its terms' sizes (spatial3.py) */
#define WK_S3_CIRCLE_TOL 1e-6   /* |(cos, sin)| of q_c off 1 by more: the root at infinity, or a poorly resolved one */

/* Rows of u . R(h2, q2) v_j over (1, cos q2, sin q2), for each v_j: (h.u)(h.v), u.v - (h.u)(h.v), u.(h x v) */
static void wk_s3_bilinear(const double *h2, const double *u, const double (*vs)[3], double m[3][3])
{
    const double hu = wk_g3_dot(h2, u);
    int j;
    for (j = 0; j < 3; ++j) {
        double hx[3];
        wk_g3_cross(h2, vs[j], hx);
        m[0][j] = hu * wk_g3_dot(h2, vs[j]);
        m[1][j] = wk_g3_dot(u, vs[j]) - hu * wk_g3_dot(h2, vs[j]);
        m[2][j] = wk_g3_dot(u, hx);
    }
}

/* The point rot_a rot_b rot_c x at q (p), the lines of b and c moved by the joints before them (h, r), and
 * |p - y| */
static double wk_s3_point(const double (*h0)[3], const double (*r0)[3], const double *q, const double *x,
                          const double *y, double *p, double h[3][3], double r[3][3])
{
    double d[3];
    int i, m;
    for (m = 0; m < 3; ++m) {
        p[m] = x[m];
        for (i = 0; i < 3; ++i) {
            h[i][m] = h0[i][m];
            r[i][m] = r0[i][m];
        }
    }
    /* the last joint first: each turn moves the point and the lines after it; the lines before keep theirs (one
     * cos and sin per joint: libm's may set errno, so the compiler does not share them between the turns) */
    for (i = 2; i >= 0; --i) {
        const double c = cos(q[i]), s = sin(q[i]);
        int k;
        wk_g3_turn_cs(h0[i], r0[i], c, s, p, p);
        for (k = i + 1; k < 3; ++k) {
            wk_g3_turn_cs(h0[i], r0[i], c, s, r[k], r[k]);
            wk_g3_turn_dir_cs(h0[i], c, s, h[k], h[k]);
        }
    }
    wk_g3_axpy(p, -1.0, y, d);
    return sqrt(wk_g3_dot(d, d));
}

/* Newton steps on rot_a rot_b rot_c x = y (Cramer's rule on the columns h_i x (p - r_i)): a step is kept only while
 * the residual shrinks, halved up to `halvings` times until it does (a split's starts, where J is near-singular and
 * the full step overshoots). Returns the residual. */
static double wk_s3_refine(const double (*h0)[3], const double (*r0)[3], const double *x, const double *y,
                           double eps3, double *q, int steps, int halvings)
{
    double p[3], h[3][3], r[3][3], err;
    int it, i;
    err = wk_s3_point(h0, r0, q, x, y, p, h, r);
    for (it = 0; it < steps; ++it) {
        double c[3][3], b[3], x12[3], bx2[3], c1b[3], det, dq[3], trial[3], p2[3], h2[3][3], r2[3][3], err2 = err;
        int m, half;
        for (i = 0; i < 3; ++i) {
            double d[3];
            wk_g3_axpy(p, -1.0, r[i], d);
            wk_g3_cross(h[i], d, c[i]);
        }
        wk_g3_axpy(y, -1.0, p, b);
        wk_g3_cross(c[1], c[2], x12);
        det = wk_g3_dot(c[0], x12);
        if (!(fabs(det) > eps3)) break;
        wk_g3_cross(b, c[2], bx2);
        wk_g3_cross(c[1], b, c1b);
        dq[0] = wk_g3_dot(b, x12) / det;
        dq[1] = wk_g3_dot(c[0], bx2) / det;
        dq[2] = wk_g3_dot(c[0], c1b) / det;
        if (halvings > 0) { /* damped: at most WK_S3_SPLIT_STEP_MAX in any joint (a near-singular J's step is huge) */
            const double big = fmax(fabs(dq[0]), fmax(fabs(dq[1]), fabs(dq[2])));
            if (big > WK_S3_SPLIT_STEP_MAX)
                for (i = 0; i < 3; ++i) dq[i] *= WK_S3_SPLIT_STEP_MAX / big;
        }
        for (half = 0; half <= halvings; ++half) {
            for (i = 0; i < 3; ++i) trial[i] = q[i] + dq[i];
            err2 = wk_s3_point(h0, r0, trial, x, y, p2, h2, r2);
            if (err2 < err) break;
            for (i = 0; i < 3; ++i) dq[i] *= 0.5;
        }
        if (!(err2 < err)) break;
        for (i = 0; i < 3; ++i) {
            q[i] = trial[i];
            p[i] = p2[i];
            for (m = 0; m < 3; ++m) {
                h[i][m] = h2[i][m];
                r[i][m] = r2[i][m];
            }
        }
        err = err2;
    }
    return err;
}

/* The largest joint difference of two sets (wrapped) */
static double wk_s3_gap(const double *a, const double *b)
{
    double far = 0.0;
    int m;
    for (m = 0; m < 3; ++m) {
        const double g = fabs(wk_wrap(a[m] - b[m]));
        if (g > far) far = g;
    }
    return far;
}

/* Damped Newton on the point from each of a split's two starts (the rows of q; any step that lowers the residual: J is
 * near-singular near a pair): 1, the pair in q, when both reach WK_S3_SPLIT_TOL x scale, keep the merged root's q_b
 * and q_c to WK_S3_SPLIT_NEAR (the pair it merged, not roots elsewhere) and stay WK_S3_SPLIT_APART of their starts'
 * gap apart (not one root twice); else 0 */
static int wk_s3_pair_converges(const double (*h)[3], const double (*r)[3], const double *x, const double *y,
                                double scale, double qb, double qc, double q[2][3])
{
    const double start_gap = wk_s3_gap(q[0], q[1]);
    int k;
    for (k = 0; k < 2; ++k) {
        if (!(wk_s3_refine(h, r, x, y, 0.0, q[k], WK_S3_SPLIT_STEPS, WK_S3_SPLIT_HALVINGS) <= WK_S3_SPLIT_TOL * scale))
            return 0;
        if (!(fmax(fabs(wk_wrap(q[k][1] - qb)), fabs(wk_wrap(q[k][2] - qc))) <= WK_S3_SPLIT_NEAR)) return 0;
    }
    return wk_s3_gap(q[0], q[1]) > WK_S3_SPLIT_APART * start_gap;
}

/* The pair a merged double root of the polynomial stands for, where the target is near axis a (distance rho): the
 * point's image w = rot_b rot_c x must lie on the circle of radius rho about axis a, which the surface w(q_b, q_c)
 * crosses twice. Near the merged root the surface meets the circle's plane along the line through w in the direction
 * d = n x h_a (n its normal there): its two points on the circle (the line's centre-nearest point +-rho along d where
 * rounding hides the gap) give q_a by subproblem 1 and (q_b, q_c) moved along the surface to them, then Newton on the
 * point from each. The two roots separate at eps / rho, not the polynomial's sqrt(eps). Returns 1 with the pair in q,
 * or 0 (the merged root stands). */
static int wk_s3_split(const double (*h)[3], const double (*r)[3], const double *x, const double *y,
                       const double *yr, double rho, double scale, double qb, double qc, double q[2][3])
{
    double w[3], hc[3], rc[3], jb[3], jc[3], normal[3], d[3], v0[3], size, mid, disc, half, gbb, gbc, gcc, det, db, dc;
    int k, m;
    wk_g3_turn(h[2], r[2], qc, x, w);
    wk_g3_turn(h[1], r[1], qb, w, w);
    wk_g3_turn_dir(h[1], qb, h[2], hc);
    wk_g3_turn(h[1], r[1], qb, r[2], rc);
    wk_g3_axpy(w, -1.0, r[1], jb);
    wk_g3_cross(h[1], jb, jb);
    wk_g3_axpy(w, -1.0, rc, jc);
    wk_g3_cross(hc, jc, jc);
    wk_g3_cross(jb, jc, normal);
    wk_g3_cross(normal, h[0], d);
    size = sqrt(wk_g3_dot(d, d));
    if (!(size > 0.0)) return 0;
    for (m = 0; m < 3; ++m) d[m] /= size;
    wk_g3_axpy(w, -1.0, r[0], v0);
    wk_g3_axpy(v0, -wk_g3_dot(h[0], v0), h[0], v0); /* w's offset from axis a, normal to it */
    mid = -wk_g3_dot(v0, d);
    disc = mid * mid - wk_g3_dot(v0, v0) + rho * rho;
    half = disc > 0.0 ? sqrt(disc) : rho;
    /* (q_b, q_c) per unit of d on the surface: jb db + jc dc = d (|jb x jc|^2 = the 2 x 2 system's determinant) */
    gbb = wk_g3_dot(jb, jb);
    gbc = wk_g3_dot(jb, jc);
    gcc = wk_g3_dot(jc, jc);
    det = wk_g3_dot(normal, normal);
    db = (gcc * wk_g3_dot(jb, d) - gbc * wk_g3_dot(jc, d)) / det;
    dc = (gbb * wk_g3_dot(jc, d) - gbc * wk_g3_dot(jb, d)) / det;
    for (k = 0; k < 2; ++k) {
        const double t = k == 0 ? mid + half : mid - half;
        double p[3];
        wk_g3_axpy(v0, t, d, p);
        if (!wk_g3_sp1(h[0], p, yr, 0.0, &q[k][0])) return 0;
        /* the start on the surface, off axis a as the root is: from w itself (on the axis when the pair is
         * symmetric about it) J's column of q_a vanishes and Newton's step is noise */
        q[k][1] = qb + t * db;
        q[k][2] = qc + t * dc;
    }
    return wk_s3_pair_converges(h, r, x, y, scale, qb, qc, q);
}

/* The largest cross product of vs[i], vs[j] (i < j), unit, into o; 0 when all vanish */
static int wk_s3_largest_cross(const double (*vs)[3], double *o)
{
    static const int pairs[3][2] = { {0, 1}, {0, 2}, {1, 2} };
    double best = -1.0, c[3], size;
    int k, m;
    for (k = 0; k < 3; ++k) {
        double n2;
        wk_g3_cross(vs[pairs[k][0]], vs[pairs[k][1]], c);
        n2 = wk_g3_dot(c, c);
        if (n2 > best) {
            best = n2;
            for (m = 0; m < 3; ++m) o[m] = c[m];
        }
    }
    size = sqrt(best);
    if (!(size > 0.0)) return 0;
    for (m = 0; m < 3; ++m) o[m] /= size;
    return 1;
}

/* The pair a merged double root q0 of the point equations stands for (the surface w(q_b, q_c) near-tangent to the
 * target's circle about axis a): at q0 the Jacobian J is singular, right and left null vectors v, u (the largest cross
 * products of its rows, of its columns); along v the residual's part on u is quadratic, u.(y - p) = s^2 u.H / 2 with
 * H the point's second derivative along v (central differences), so the pair starts at q0 +- s v and Newton takes each
 * to its root. Returns 1 with the pair in q, or 0 (s^2 <= 0: a complex pair; or no convergence to distinct roots). */
static int wk_s3_pair(const double (*h)[3], const double (*r)[3], const double *x, const double *y, double scale,
                      const double *q0, double q[2][3])
{
    double p0[3], hh[3][3], rr[3][3], cols[3][3], rows[3][3], v[3], u[3], qs[3], plus[3], minus[3], hm[3], res[3];
    double curv, s2, half;
    int i, m, k;
    (void)wk_s3_point(h, r, q0, x, y, p0, hh, rr);
    for (i = 0; i < 3; ++i) {
        double d[3];
        wk_g3_axpy(p0, -1.0, rr[i], d);
        wk_g3_cross(hh[i], d, cols[i]);
    }
    for (i = 0; i < 3; ++i)
        for (m = 0; m < 3; ++m) rows[i][m] = cols[m][i];
    if (!wk_s3_largest_cross((const double (*)[3])rows, v) || !wk_s3_largest_cross((const double (*)[3])cols, u))
        return 0;
    for (m = 0; m < 3; ++m) qs[m] = q0[m] + WK_S3_CURVATURE_STEP * v[m];
    (void)wk_s3_point(h, r, qs, x, y, plus, hh, rr);
    for (m = 0; m < 3; ++m) qs[m] = q0[m] - WK_S3_CURVATURE_STEP * v[m];
    (void)wk_s3_point(h, r, qs, x, y, minus, hh, rr);
    for (m = 0; m < 3; ++m)
        hm[m] = (plus[m] - 2.0 * p0[m] + minus[m]) / (WK_S3_CURVATURE_STEP * WK_S3_CURVATURE_STEP);
    curv = wk_g3_dot(u, hm);
    if (!(fabs(curv) > 0.0)) return 0;
    wk_g3_axpy(y, -1.0, p0, res);
    s2 = 2.0 * wk_g3_dot(u, res) / curv;
    if (!(s2 > 0.0)) return 0;
    half = sqrt(s2);
    for (k = 0; k < 2; ++k)
        for (m = 0; m < 3; ++m) q[k][m] = q0[m] + (k == 0 ? half : -half) * v[m];
    return wk_s3_pair_converges(h, r, x, y, scale, q0[1], q0[2], q);
}

/* q_c of the root q_b: the two equations (rows f, g over (1, cos q_c, sin q_c) at q_b's (1, cos, sin)) are linear in
 * its cos and sin; 0 where they do not fix it (a vanishing determinant, or (cos, sin) off the unit circle) */
static int wk_s3_qc(double f[3][3], double g[3][3], double dtarget, double htarget, double eps3, double qb, double *qc)
{
    const double cb = cos(qb), sb = sin(qb);
    double pv[3], qv[3], dd, cc, ss;
    int j;
    for (j = 0; j < 3; ++j) {
        pv[j] = f[0][j] + cb * f[1][j] + sb * f[2][j];
        qv[j] = g[0][j] + cb * g[1][j] + sb * g[2][j];
    }
    dd = pv[1] * qv[2] - pv[2] * qv[1];
    if (fabs(dd) <= eps3) return 0;
    cc = ((dtarget - pv[0]) * qv[2] - pv[2] * (htarget - qv[0])) / dd;
    ss = (pv[1] * (htarget - qv[0]) - qv[1] * (dtarget - pv[0])) / dd;
    if (fabs(hypot(cc, ss) - 1.0) > WK_S3_CIRCLE_TOL) return 0;
    *qc = atan2(ss, cc);
    return 1;
}

/* Axes a and c parallel: the distance and component equations at a root q_b (rows f, g at q_b's (1, cos, sin)) are
 * one equation in q_c, their (cos, sin) parts parallel. The better conditioned of them, A cos + B sin = C, gives
 * q_c = atan2(B, A) +- acos(C / |(A, B)|): the count of roots into qc (one at a tangency) where the other equation
 * holds too, 0 where none does, the point is on axis c (A = B = 0) or C / |(A, B)| is past 1 beyond the circle's
 * tolerance (Python's _s3_qc_dependent) */
static int wk_s3_qc_dependent(double f[3][3], double g[3][3], double dtarget, double htarget, double scale,
                              double eps, double qb, double qc[2])
{
    const double cb = cos(qb), sb = sin(qb);
    double pv[3], qv[3], dist[3], comp[3], norm, u, phi, gap, size;
    const double *use, *other;
    int j, n = 0;
    for (j = 0; j < 3; ++j) {
        pv[j] = f[0][j] + cb * f[1][j] + sb * f[2][j];
        qv[j] = g[0][j] + cb * g[1][j] + sb * g[2][j];
    }
    dist[0] = pv[1];
    dist[1] = pv[2];
    dist[2] = dtarget - pv[0];
    comp[0] = qv[1];
    comp[1] = qv[2];
    comp[2] = htarget - qv[0];
    use = hypot(pv[1], pv[2]) >= scale * hypot(qv[1], qv[2]) ? dist : comp;
    other = use == dist ? comp : dist;
    norm = hypot(use[0], use[1]);
    if (!(norm > eps * scale * scale)) return 0;
    u = use[2] / norm;
    if (!(fabs(u) <= 1.0 + WK_S3_CIRCLE_TOL)) return 0;
    phi = atan2(use[1], use[0]);
    gap = acos(u > 1.0 ? 1.0 : (u < -1.0 ? -1.0 : u));
    /* the other equation holds too where q_b is the eliminant's root (not at the q_b = pi tried beside them) */
    size = fabs(other[0]) + fabs(other[1]) + fabs(other[2]);
    for (j = 0; j < (gap > 0.0 ? 2 : 1); ++j) {
        const double t = j == 0 ? phi + gap : phi - gap;
        if (fabs(other[0] * cos(t) + other[1] * sin(t) - other[2]) <= WK_S3_CIRCLE_TOL * size) qc[n++] = t;
    }
    return n;
}

/* out += |a| |b| coefficientwise: the size of the terms of a b, which bounds its rounding */
static void wk_s3_mul_abs(const double *a, int na, const double *b, int nb, double *out)
{
    int i, j;
    for (i = 0; i < na; ++i)
        for (j = 0; j < nb; ++j) out[i + j] += fabs(a[i]) * fabs(b[j]);
}

/* The root finder's touch tolerance for `poly` (n coefficients) whose coefficients sum terms of sizes `terms`: its
 * rounding relative to its largest coefficient, at least the finder's own (Python's _s3_touch_tol says why) */
static double wk_s3_touch_tol(const double *poly, const double *terms, int n)
{
    double big = 0.0, size = 0.0, tol;
    int i;
    for (i = 0; i < n; ++i) {
        if (fabs(poly[i]) > big) big = fabs(poly[i]);
        if (terms[i] > size) size = terms[i];
    }
    if (!(big > 0.0)) return WK_POLY_TOL_TOUCH;
    tol = WK_S3_ROUNDING * WK_POLY_EPS * size / big;
    return tol > WK_POLY_TOL_TOUCH ? tol : WK_POLY_TOL_TOUCH;
}

/* A split pair into the candidates from row `out` on, flagged singular (the pair meets where J is): the next row */
static int wk_s3_put_pair(double pair[2][3], double q[WK_S3_MAX][3], unsigned *fl, int out)
{
    int k, m;
    for (k = 0; k < 2; ++k) {
        for (m = 0; m < 3; ++m) q[out][m] = pair[k][m];
        fl[out++] = WK_FLAG_SINGULAR_INVERSE;
    }
    return out;
}

/* The candidates (q_a, q_b, q_c) of rot_a rot_b rot_c x = y, h[i] / r[i] the lines of a, b, c at the joints' zero,
 * into q (rows of 3) with their flags (a double root of the polynomial: WK_FLAG_DOUBLE_ROOT; q_a undetermined, the
 * point on axis a: WK_FLAG_INDETERMINATE with q_a = 0). `scale` the lengths' size, `eps` the relative size below
 * which a coefficient is degenerate, `on_axis` the relative distance from axis a within which the point is on it
 * (the caller's rounding band: farther off, q_a is read from the point's offset, accurate to ~eps scale / rho, as
 * the pose determines it). Returns the count (<= WK_S3_MAX); the caller verifies them. */
static int wk_spatial3(const double (*h)[3], const double (*r)[3], const double *x, const double *y, double scale,
                       double eps, double on_axis, double q[WK_S3_MAX][3], unsigned *fl)
{
    const double *h1 = h[0], *r1 = r[0], *h2 = h[1], *r2 = r[1], *h3 = h[2], *r3 = r[2];
    static const double apoly[3][3] = { {1.0, 0.0, 1.0}, {1.0, 0.0, -1.0}, {0.0, 2.0, 0.0} };
    const double eps3 = eps * scale * scale * scale;
    double v[3], vb[3][3], u[3], f[3][3], g[3][3], hv, dtarget, htarget, yr[3], yr_perp[3], rho;
    double p[3][3], pq[3][3], dt[3], ht[3], det[5], nc[5], ns[5], a5[5], poly[9], roots[8], ang[9];
    double sdt[3], sht[3], snc[5] = {0.0}, sns[5] = {0.0}, terms[9] = {0.0};
    unsigned rf[8], af[9];
    int i, j, nroot, status = 0, na = 0, out = 0, near_axis, dependent;
    wk_g3_axpy(x, -1.0, r3, v);
    hv = wk_g3_dot(h3, v);
    wk_g3_axpy(r3, hv, h3, vb[0]); /* z - r2 over (1, cos q_c, sin q_c) */
    wk_g3_axpy(vb[0], -1.0, r2, vb[0]);
    wk_g3_axpy(v, -hv, h3, vb[1]);
    wk_g3_cross(h3, v, vb[2]);
    wk_g3_axpy(r2, -1.0, r1, u);
    wk_s3_bilinear(h2, u, (const double (*)[3])vb, f);
    wk_s3_bilinear(h2, h1, (const double (*)[3])vb, g);
    for (i = 0; i < 3; ++i)
        for (j = 0; j < 3; ++j) f[i][j] *= 2.0;
    f[0][0] += wk_g3_dot(vb[0], vb[0]) + wk_g3_dot(vb[1], vb[1]) + wk_g3_dot(u, u);
    f[0][1] += 2.0 * wk_g3_dot(vb[0], vb[1]);
    f[0][2] += 2.0 * wk_g3_dot(vb[0], vb[2]);
    g[0][0] += wk_g3_dot(h1, u);
    wk_g3_axpy(y, -1.0, r1, yr);
    dtarget = wk_g3_dot(yr, yr);
    htarget = wk_g3_dot(h1, yr);
    /* (1, cos q_b, sin q_b) times (1 + t^2): (1 + t^2, 1 - t^2, 2 t), polynomials in t = tan(q_b / 2) */
    for (j = 0; j < 3; ++j)
        for (i = 0; i < 3; ++i) {
            p[j][i] = apoly[0][i] * f[0][j] + apoly[1][i] * f[1][j] + apoly[2][i] * f[2][j];
            pq[j][i] = apoly[0][i] * g[0][j] + apoly[1][i] * g[1][j] + apoly[2][i] * g[2][j];
        }
    for (i = 0; i < 3; ++i) {
        dt[i] = apoly[0][i] * dtarget - p[0][i];
        ht[i] = apoly[0][i] * htarget - pq[0][i];
    }
    wk_poly_mul(p[1], 3, pq[2], 3, det);
    wk_poly_mul(p[2], 3, pq[1], 3, a5);
    wk_poly_axpy(det, a5, 5, -1.0);
    wk_poly_mul(dt, 3, pq[2], 3, nc);
    wk_poly_mul(p[2], 3, ht, 3, a5);
    wk_poly_axpy(nc, a5, 5, -1.0);
    wk_poly_mul(p[1], 3, ht, 3, ns);
    wk_poly_mul(pq[1], 3, dt, 3, a5);
    wk_poly_axpy(ns, a5, 5, -1.0);
    /* axes a and c parallel: det vanishes identically, the degree-8 polynomial is nc^2 + ns^2 (every root double,
     * q_c not read from the singular system); the eliminant is Q_2 nc - Q_1 ns, degree 6 (spatial3.py says why) */
    for (i = 0; i < 5; ++i)
        if (fabs(det[i]) > eps3) break;
    dependent = i == 5;
    /* the sizes of nc's, ns's and det's terms (dt's and ht's before their cancellation): their rounding's scale */
    for (i = 0; i < 3; ++i) {
        sdt[i] = fabs(apoly[0][i]) * dtarget + fabs(p[0][i]);
        sht[i] = fabs(apoly[0][i] * htarget) + fabs(pq[0][i]);
    }
    wk_s3_mul_abs(sdt, 3, pq[2], 3, snc);
    wk_s3_mul_abs(p[2], 3, sht, 3, snc);
    wk_s3_mul_abs(p[1], 3, sht, 3, sns);
    wk_s3_mul_abs(pq[1], 3, sdt, 3, sns);
    if (dependent) {
        double part[7];
        wk_poly_mul(pq[2], 3, nc, 5, poly);
        wk_poly_mul(pq[1], 3, ns, 5, part);
        wk_poly_axpy(poly, part, 7, -1.0);
        wk_s3_mul_abs(pq[2], 3, snc, 5, terms);
        wk_s3_mul_abs(pq[1], 3, sns, 5, terms);
        nroot = wk_poly_real_roots(poly, 6, roots, rf, &status, wk_s3_touch_tol(poly, terms, 7));
    } else {
        double sdet[5] = {0.0};
        wk_s3_mul_abs(p[1], 3, pq[2], 3, sdet);
        wk_s3_mul_abs(p[2], 3, pq[1], 3, sdet);
        wk_s3_mul_abs(nc, 5, snc, 5, terms);
        wk_s3_mul_abs(ns, 5, sns, 5, terms);
        wk_s3_mul_abs(det, 5, sdet, 5, terms);
        wk_poly_mul(nc, 5, nc, 5, poly);
        {
            double sq[9];
            wk_poly_mul(ns, 5, ns, 5, sq);
            wk_poly_axpy(poly, sq, 9, 1.0);
            wk_poly_mul(det, 5, det, 5, sq);
            wk_poly_axpy(poly, sq, 9, -1.0);
        }
        nroot = wk_poly_real_roots(poly, 8, roots, rf, &status, wk_s3_touch_tol(poly, terms, 9));
    }
    for (i = 0; i < nroot; ++i) {
        ang[na] = 2.0 * atan(roots[i]);
        af[na++] = (rf[i] & WK_POLY_FLAG_DOUBLE) ? (WK_FLAG_DOUBLE_ROOT | WK_FLAG_SINGULAR_INVERSE) : 0u;
    }
    ang[na] = 3.14159265358979323846; /* tan(q_b / 2) = infinity is no root of the polynomial: tried directly */
    af[na++] = 0u;
    wk_g3_axpy(yr, -htarget, h1, yr_perp);
    rho = sqrt(wk_g3_dot(yr_perp, yr_perp)); /* the target's distance from axis a (|yr|^2 - (h.yr)^2 cancels) */
    near_axis = on_axis * scale < rho && rho <= WK_S3_SPLIT_NEAR * scale;
    for (i = 0; i < na && out < WK_S3_MAX; ++i) {
        double w[3], qb = ang[i], qc = 0.0, t1 = 0.0;
        if (near_axis && !dependent && !(af[i] & WK_FLAG_DOUBLE_ROOT) && i + 2 < na && !(af[i + 1] & WK_FLAG_DOUBLE_ROOT)) {
            /* two simple roots a hair apart near axis a: a pair the polynomial resolved only to its sqrt(eps), whose
             * images sit near the axis, where q_a is noise: split from their midpoint */
            const double gap = wk_wrap(ang[i + 1] - qb), mid = qb + 0.5 * gap;
            double pair[2][3];
            if (fabs(gap) <= WK_S3_SPLIT_NEAR && out + 2 <= WK_S3_MAX &&
                wk_s3_qc(f, g, dtarget, htarget, eps3, mid, &qc) &&
                wk_s3_split(h, r, x, y, yr, rho, scale, mid, qc, pair)) {
                out = wk_s3_put_pair(pair, q, fl, out);
                ++i;
                continue;
            }
        }
        if (dependent) { /* a and c parallel: no merged pairs to split (the eliminant's roots are simple) */
            double qcs[2];
            const int nqc = wk_s3_qc_dependent(f, g, dtarget, htarget, scale, eps, qb, qcs);
            for (j = 0; j < nqc && out < WK_S3_MAX; ++j) {
                q[out][1] = qb;
                q[out][2] = qcs[j];
                wk_g3_turn(h3, r3, qcs[j], x, w);
                wk_g3_turn(h2, r2, qb, w, w);
                wk_g3_axpy(w, -1.0, r1, w);
                fl[out] = af[i];
                if (wk_g3_sp1(h1, w, yr, on_axis * scale, &t1)) {
                    q[out][0] = t1;
                    (void)wk_s3_refine(h, r, x, y, eps3, q[out], WK_S3_REFINE_STEPS, 0);
                } else {
                    q[out][0] = 0.0;
                    fl[out] |= WK_FLAG_INDETERMINATE | WK_FLAG_SINGULAR_INVERSE;
                }
                ++out;
            }
            continue;
        }
        if (!wk_s3_qc(f, g, dtarget, htarget, eps3, qb, &qc)) continue;
        q[out][1] = qb;
        q[out][2] = qc;
        if ((af[i] & WK_FLAG_DOUBLE_ROOT) && rho > on_axis * scale && out + 2 <= WK_S3_MAX) {
            /* a merged pair: near axis a its two roots differ by ~rho, below the polynomial's resolution */
            double pair[2][3];
            if (wk_s3_split(h, r, x, y, yr, rho, scale, q[out][1], q[out][2], pair)) {
                out = wk_s3_put_pair(pair, q, fl, out);
                continue;
            }
        }
        wk_g3_turn(h3, r3, q[out][2], x, w);
        wk_g3_turn(h2, r2, q[out][1], w, w);
        wk_g3_axpy(w, -1.0, r1, w);
        fl[out] = af[i];
        if (wk_g3_sp1(h1, w, yr, on_axis * scale, &t1)) {
            q[out][0] = t1;
            if ((fl[out] & WK_FLAG_DOUBLE_ROOT) && out + 2 <= WK_S3_MAX) {
                /* a merged pair elsewhere: the surface near-tangent to the target's circle, split along J's null
                 * vector */
                double pair[2][3];
                if (wk_s3_pair(h, r, x, y, scale, q[out], pair)) {
                    out = wk_s3_put_pair(pair, q, fl, out);
                    continue;
                }
            }
            if (!(fl[out] & WK_FLAG_DOUBLE_ROOT)) (void)wk_s3_refine(h, r, x, y, eps3, q[out], WK_S3_REFINE_STEPS, 0);
        } else {
            q[out][0] = 0.0;
            fl[out] |= WK_FLAG_INDETERMINATE | WK_FLAG_SINGULAR_INVERSE;
        }
        ++out;
    }
    return out;
}
