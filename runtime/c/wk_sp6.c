/* wristkin: subproblem 6, two joints from two invariants, every real solution (C99, libm only).
 * Included verbatim into generated C99 sources (static functions, no allocation).
 *
 * (q0, q4) with n.rot(h0, -q0) p0 - n.rot(h4, q4) p4 = d0 and n.rot(h0, -q0) g - n.rot(h4, q4) h5 = e0: a UR-type
 * arm with an offset wrist, whose parallel group keeps the component along its direction n of a point and of the
 * last axis. (cos q4, sin q4) is affine in (cos q0, sin q0) by Cramer's rule, and cos^2 + sin^2 = 1 a quartic in
 * tan(q0 / 2) whose real roots wk_poly_real_roots isolates; Newton on the equations brings each to rounding. Near
 * the wrist singularity (rot(h4, q4) h5 = +-n: the second equation holds for every q0) a merged pair is split and
 * refined on the second equation's parts normal to n (its roots to eps / delta, not sqrt(eps)), and the singular
 * configurations are tried directly. Python's twin: runtime/python/sp6.py, step for step.
 * Needs poly_real_roots.c, wk_poly_ops.c, wk_geom3.c and wristkin_runtime's flags before it. The serial arm's sp6
 * stage (serial/sr_sp6.c) calls it with its tolerances; tests/test_shared_runtime.py tests it as it is
 * (tests/c/shared_runtime_harness.c). */

/* the caller's tolerances (the serial stage's SR_SP6_*) */
typedef struct {
    double scale;       /* the lengths' size: p0, p4 and d0's rounding scales with it */
    double degenerate;  /* a coefficient norm (relative to scale) at or below this: degenerate (DEGENERATE_EPS) */
    double double_root; /* 1 - u^2 of the wrist's subproblem 4, and 1 - (n.w)^2 there: one double root */
    double tangent;     /* |u| of that subproblem 4 up to 1 + this counts as a root */
    double on_axis;     /* the wrist's subproblem 4: a vanishing equation there (p0 on h0) within this */
    /* the pose's axis on n to rounding (|n x w| within this): the singular family; above it the split's two roots,
       each to ~eps (a band of 1e-12 took poses 1e-13 .. 1e-12 rad from the singularity for the family: the
       generating joints missed on 129 of 200 random poses at 1e-13) */
    double family;
} wk_sp6_tols;

/* q0 = pi (tan(q0 / 2) infinite) is a candidate when cos^2 + sin^2 of the q4 it gives is 1 within this: rounding of
 * the 2 x 2 solve (a root of the quartic near pi would pass a looser test and be found twice) */
#define WK_SP6_AT_PI_TOL 1e-9
/* at most 4 roots (each split in two when merged near the wrist singularity) and q0 = pi, and 2 x 2 singular
 * candidates, each split in two near the singularity */
#define WK_SP6_MAX 17
/* |n . rot(h4, q4) h5| at or above this: the wrist near its singularity (|n . z5| = 1 there), where a root of the
 * quartic is refined on the second equation's parts normal to n (wk_sp6_newton_perp); below it their difference
 * |n x w0|^2 - |n x z5|^2 = (n.z5 - n.w0)(n.z5 + n.w0) loses the factor n.z5 + n.w0 ~ 2 n.z5 */
#define WK_SP6_NEAR_WRIST 0.5
/* a regular root within this of a split root near the wrist singularity is that root found twice (both are refined
 * to ~eps; two distinct roots there are ~delta apart and both the split's) */
#define WK_SP6_SAME_ROOT 1e-9
/* Newton steps on the equations from a root (quadratic convergence from a root of the quartic or of the local
 * model: 3 suffice) */
#define WK_SP6_NEWTON_STEPS 3

/* (cos t, sin t, const) coefficients of n . rot(k, sign t) p */
static void wk_sp6_trig_coef(const double *n, const double *k, const double *p, double sign, double *o)
{
    const double kp = wk_g3_dot(k, p);
    double perp[3], kx[3];
    wk_g3_axpy(p, -kp, k, perp);
    wk_g3_cross(k, p, kx);
    o[0] = wk_g3_dot(n, perp);
    o[1] = sign * wk_g3_dot(n, kx);
    o[2] = kp * wk_g3_dot(n, k);
}

/* f = (F1, F2) without the constants, jac their gradients (row-major) */
static void wk_sp6_eval(const double *n, const double *h0, const double *p0, const double *h4, const double *p4,
                        const double *g, const double *h5, double q0, double q4, double *f, double *jac)
{
    /* one cos and sin per angle (libm's may set errno: the compiler does not share them between the turns) */
    const double c0 = cos(-q0), s0 = sin(-q0), c4 = cos(q4), s4 = sin(q4);
    double w[4][3], a[3], b[3];
    int i;
    wk_g3_turn_dir_cs(h0, c0, s0, p0, w[0]);
    wk_g3_turn_dir_cs(h0, c0, s0, g, w[1]);
    wk_g3_turn_dir_cs(h4, c4, s4, p4, w[2]);
    wk_g3_turn_dir_cs(h4, c4, s4, h5, w[3]);
    for (i = 0; i < 2; ++i) { /* i = 0: F1 (p0, p4), i = 1: F2 (g, h5) */
        const double *wa = w[i], *wb = w[2 + i];
        f[i] = wk_g3_dot(n, wa) - wk_g3_dot(n, wb);
        wk_g3_cross(h0, wa, a);
        wk_g3_cross(h4, wb, b);
        jac[2 * i] = -wk_g3_dot(n, a);
        jac[2 * i + 1] = -wk_g3_dot(n, b);
    }
}

/* (q0, q4) after Newton steps on both equations, each kept only when it lowers the residual: the quartic resolves
 * two roots ~delta apart only to ~sqrt(eps) in tan(q0 / 2), the equations to eps / delta in the angles */
static void wk_sp6_newton(const double *n, const double *h0, const double *p0, const double *h4, const double *p4,
                          double d0, double e0, const double *g, const double *h5, double *q0, double *q4)
{
    double f[2], jac[4], res;
    int it;
    wk_sp6_eval(n, h0, p0, h4, p4, g, h5, *q0, *q4, f, jac);
    res = fmax(fabs(f[0] - d0), fabs(f[1] - e0));
    for (it = 0; it < WK_SP6_NEWTON_STEPS; ++it) {
        const double dt = jac[0] * jac[3] - jac[1] * jac[2];
        const double r1 = f[0] - d0, r2 = f[1] - e0;
        double n0, n4, nres;
        if (res == 0.0 || dt == 0.0) break;
        n0 = *q0 - (jac[3] * r1 - jac[1] * r2) / dt;
        n4 = *q4 - (jac[0] * r2 - jac[2] * r1) / dt;
        wk_sp6_eval(n, h0, p0, h4, p4, g, h5, n0, n4, f, jac);
        nres = fmax(fabs(f[0] - d0), fabs(f[1] - e0));
        if (!(nres < res)) break;
        *q0 = n0;
        *q4 = n4;
        res = nres;
    }
}

/* The second equation's parts normal to n at (q0, q4): u = n x w0, rz = n x z5 (w0 = rot(h0, -q0) g,
 * z5 = rot(h4, q4) h5) and their derivatives -n x (h0 x w0) along q0, n x (h4 x z5) along q4 (as du0, dr4 without
 * the sign) */
static void wk_sp6_normal_parts(const double *n, const double *h0, const double *h4, const double *g,
                                const double *h5, double q0, double q4, double *u, double *rz, double *du0,
                                double *dr4)
{
    double w0[3], z5[3], x[3];
    wk_g3_turn_dir(h0, -q0, g, w0);
    wk_g3_turn_dir(h4, q4, h5, z5);
    wk_g3_cross(n, w0, u);
    wk_g3_cross(n, z5, rz);
    wk_g3_cross(h0, w0, x);
    wk_g3_cross(n, x, du0);
    wk_g3_cross(h4, z5, x);
    wk_g3_cross(n, x, dr4);
}

/* Residuals and Jacobian of the first equation and of the second read as |n x w0|^2 - |n x z5|^2 (its parts
 * normal to n) at (q0, q4) */
static void wk_sp6_perp_eval(const double *n, const double *h0, const double *p0, const double *h4, const double *p4,
                             double d0, const double *g, const double *h5, double q0, double q4, double *f,
                             double *jac)
{
    double w[3], z4[3], u[3], rz[3], du0[3], dr4[3], x[3];
    wk_sp6_normal_parts(n, h0, h4, g, h5, q0, q4, u, rz, du0, dr4);
    wk_g3_turn_dir(h0, -q0, p0, w);
    wk_g3_turn_dir(h4, q4, p4, z4);
    f[0] = wk_g3_dot(n, w) - wk_g3_dot(n, z4) - d0;
    f[1] = wk_g3_dot(u, u) - wk_g3_dot(rz, rz);
    wk_g3_cross(h0, w, x);
    jac[0] = -wk_g3_dot(n, x);
    wk_g3_cross(h4, z4, x);
    jac[1] = -wk_g3_dot(n, x);
    jac[2] = -2.0 * wk_g3_dot(u, du0);
    jac[3] = -2.0 * wk_g3_dot(rz, dr4);
}

/* each residual over its gradient: a distance in radians (metres and a squared sine compared raw stopped the steps
 * on the first's rounding) */
static double wk_sp6_perp_size(const double *f, const double *jac)
{
    return fmax(fabs(f[0]) / fmax(hypot(jac[0], jac[1]), 1e-300), fabs(f[1]) / fmax(hypot(jac[2], jac[3]), 1e-300));
}

/* (q0, q4) after Newton steps on the first equation and the second's normal parts, each kept only when it lowers the
 * residual: near the wrist singularity the n-components are stationary and Newton on them moves q4 by eps / delta
 * (3.8e-10 at delta = 3e-7, which turned q5's angle 1e-4 off); the normal parts' residual is eps delta against a
 * gradient ~delta: q4 to ~eps */
static void wk_sp6_newton_perp(const double *n, const double *h0, const double *p0, const double *h4,
                               const double *p4, double d0, const double *g, const double *h5, double *q0,
                               double *q4)
{
    double f[2], jac[4], res;
    int it;
    wk_sp6_perp_eval(n, h0, p0, h4, p4, d0, g, h5, *q0, *q4, f, jac);
    res = wk_sp6_perp_size(f, jac);
    for (it = 0; it < WK_SP6_NEWTON_STEPS; ++it) {
        const double dt = jac[0] * jac[3] - jac[1] * jac[2];
        const double r1 = f[0], r2 = f[1];
        double n0, n4, nres;
        if (res == 0.0 || dt == 0.0) break;
        n0 = *q0 - (jac[3] * r1 - jac[1] * r2) / dt;
        n4 = *q4 - (jac[0] * r2 - jac[2] * r1) / dt;
        wk_sp6_perp_eval(n, h0, p0, h4, p4, d0, g, h5, n0, n4, f, jac);
        nres = wk_sp6_perp_size(f, jac);
        if (!(nres < res)) break;
        *q0 = n0;
        *q4 = n4;
        res = nres;
    }
}

/* The two roots near (q0, q4), a merged near-double root (a double root of the quartic, or the wrist singularity's
 * candidate near, not at, it): along the first equation's solution curve (tangent t, arc s) the second is read as
 * |n x w0|^2 = |n x z5|^2, its parts normal to n (~delta, each read to eps) instead of its n-components (stationary
 * at +-1, their difference read to eps and so its roots to sqrt(eps)); to second order in s a quadratic, its two
 * roots polished by Newton on the same parts. Returns 0, 2, or 1 where the two curves are near tangent and the pair
 * merges (a double root: wk_sp6_merged). */
static int wk_sp6_split(const double *n, const double *h0, const double *p0, const double *h4, const double *p4,
                        double d0, const double *g, const double *h5, double q0, double q4, const wk_sp6_tols *tol,
                        double *s0, double *s4)
{
    double f[2], jac[4], gn, r, t0, t4, u[3], rz[3], du[3], dr[3];
    double qa, qb, qc, disc, qq, s[2];
    int i, ns;
    wk_sp6_eval(n, h0, p0, h4, p4, g, h5, q0, q4, f, jac);
    gn = hypot(jac[0], jac[1]);
    if (gn <= tol->degenerate * tol->scale) return 0;
    /* onto the first equation's curve, then along its tangent */
    r = -(f[0] - d0) / gn;
    q0 += r * jac[0] / gn;
    q4 += r * jac[1] / gn;
    t0 = -jac[1] / gn;
    t4 = jac[0] / gn;
    wk_sp6_normal_parts(n, h0, h4, g, h5, q0, q4, u, rz, du, dr);
    for (i = 0; i < 3; ++i) { /* along the tangent: d w0 / d q0 = -h0 x w0, d z5 / d q4 = h4 x z5 */
        du[i] *= -t0;
        dr[i] *= t4;
    }
    qa = wk_g3_dot(du, du) - wk_g3_dot(dr, dr);
    qb = 2.0 * (wk_g3_dot(u, du) - wk_g3_dot(rz, dr));
    qc = wk_g3_dot(u, u) - wk_g3_dot(rz, rz);
    disc = qb * qb - 4.0 * qa * qc;
    if (qa == 0.0 || !isfinite(disc)) return 0;
    if (disc > 0.0) {
        qq = -0.5 * (qb + copysign(sqrt(disc), qb)); /* the larger root's numerator: no cancellation */
        s[0] = qq / qa;
        s[1] = qc / qq;
        ns = 2;
    } else { /* the curve's tangent touches the second's pair of lines: one double root at the vertex */
        s[0] = -0.5 * qb / qa;
        ns = 1;
    }
    for (i = 0; i < ns; ++i) {
        s0[i] = q0 + s[i] * t0;
        s4[i] = q4 + s[i] * t4;
        wk_sp6_newton_perp(n, h0, p0, h4, p4, d0, g, h5, &s0[i], &s4[i]);
        s0[i] = wk_wrap(s0[i]);
        s4[i] = wk_wrap(s4[i]);
    }
    return ns;
}

/* WK_FLAG_DOUBLE_ROOT when the split returned its pair merged (one root), else 0 */
static unsigned wk_sp6_merged(int ns)
{
    return ns == 1 ? WK_FLAG_DOUBLE_ROOT : 0u;
}

/* 1 when (q0, q4) is within tol of one of the n points (aq0, aq4) in both angles */
static int wk_sp6_within(double q0, double q4, const double *aq0, const double *aq4, int n, double tol)
{
    int j;
    for (j = 0; j < n; ++j)
        if (fabs(wk_wrap(q0 - aq0[j])) <= tol && fabs(wk_wrap(q4 - aq4[j])) <= tol) return 1;
    return 0;
}

/* 1 when a regular root (q0, q4) is a configuration the wrist singularity's candidates already give: within 1e-6
 * of a candidate (at or near it), or within WK_SP6_SAME_ROOT of one of its split roots (one 1.03e-6 from its
 * candidate was returned twice, and the generating set fell past the solver's set count) */
static int wk_sp6_taken(double q0, double q4, const double *aq0, const double *aq4, int nanchor, const double *pq0,
                        const double *pq4, int nsplit)
{
    return wk_sp6_within(q0, q4, aq0, aq4, nanchor, 1e-6) ||
           wk_sp6_within(q0, q4, pq0, pq4, nsplit, WK_SP6_SAME_ROOT);
}

/* t with n . rot(h0, t) p0 = d (subproblem 4): A cos t + B sin t = C, a double root once (flagged), a vanishing
 * equation one representative t = 0 (flagged indeterminate) */
static int wk_sp6_sp4(const double *n, const double *h0, const double *p0, double d, const wk_sp6_tols *tol, double *t,
                      unsigned *f)
{
    const double kp = wk_g3_dot(h0, p0);
    double perp[3], kx[3];
    wk_g3_axpy(p0, -kp, h0, perp);
    wk_g3_cross(h0, p0, kx);
    return wk_g3_trig(wk_g3_dot(n, perp), wk_g3_dot(n, kx), d - kp * wk_g3_dot(n, h0), tol->scale, tol->on_axis,
                      tol->tangent, tol->double_root, t, f);
}

/* The candidates (q0, q4, flags, order) of subproblem 6, at most WK_SP6_MAX, the regular ones first. `order`: how
 * q4's error grows near the wrist singularity (g = |h5 x rot(h4, q4)^T n| small): 2 from the quartic and Newton on
 * its equations (eps / g), 1 from the split or the normal parts' Newton (~eps), which the caller's later stages read
 * their bands by. A merged double root far from the wrist stays, flagged (Newton is ill-conditioned there). */
static int wk_sp6(const double *n, const double *h0, const double *p0, const double *h4, const double *p4, double d0,
                  double e0, const double *gv, const double *h5, const wk_sp6_tols *tol, double *q0, double *q4,
                  unsigned *fl, int *ord)
{
    static const double apoly[3][3] = { {1.0, 0.0, 1.0}, {1.0, 0.0, -1.0}, {0.0, 2.0, 0.0} };
    double k1[3], m1[3], k2[3], m2[3], e1, e2, det, al[3], be[3], pa[3], pb[3], pd[3], poly[5], sq[5];
    double roots[8], ang[5], atol[5], sq0[4], sq4[4], aq0[4], aq4[4], pq0[8], pq4[8], t4 = 0.0;
    unsigned rf[8], af[5], sfl[4], pfl[8];
    int i, j, nroot, status = 0, na = 0, out = 0, ns = 0, nanchor = 0, nsplit = 0;
    wk_sp6_trig_coef(n, h0, p0, -1.0, k1);
    wk_sp6_trig_coef(n, h4, p4, 1.0, m1);
    wk_sp6_trig_coef(n, h0, gv, -1.0, k2);
    wk_sp6_trig_coef(n, h4, h5, 1.0, m2);
    e1 = d0 - k1[2] + m1[2];
    e2 = e0 - k2[2] + m2[2];
    det = m1[0] * m2[1] - m1[1] * m2[0];
    if (fabs(det) <= tol->degenerate * tol->scale) return 0;
    /* c4 det = (a1 c0 + b1 s0 - e1) d2 - d1 (a2 c0 + b2 s0 - e2); s4 det = c1 (a2 c0 + b2 s0 - e2) - c2 (...1) */
    al[0] = -e1 * m2[1] + m1[1] * e2;
    al[1] = k1[0] * m2[1] - m1[1] * k2[0];
    al[2] = k1[1] * m2[1] - m1[1] * k2[1];
    be[0] = -m1[0] * e2 + m2[0] * e1;
    be[1] = m1[0] * k2[0] - m2[0] * k1[0];
    be[2] = m1[0] * k2[1] - m2[0] * k1[1];
    for (i = 0; i < 3; ++i) {
        pa[i] = apoly[0][i] * al[0] + apoly[1][i] * al[1] + apoly[2][i] * al[2];
        pb[i] = apoly[0][i] * be[0] + apoly[1][i] * be[1] + apoly[2][i] * be[2];
        pd[i] = apoly[0][i] * det;
    }
    wk_poly_mul(pa, 3, pa, 3, poly);
    wk_poly_mul(pb, 3, pb, 3, sq);
    wk_poly_axpy(poly, sq, 5, 1.0);
    wk_poly_mul(pd, 3, pd, 3, sq);
    wk_poly_axpy(poly, sq, 5, -1.0);
    nroot = wk_poly_real_roots(poly, 4, roots, rf, &status, WK_POLY_TOL_TOUCH);
    for (i = 0; i < nroot && na < 4; ++i) {
        ang[na] = 2.0 * atan(roots[i]);
        atol[na] = 1e-6;
        af[na++] = (rf[i] & WK_POLY_FLAG_DOUBLE) ? (WK_FLAG_DOUBLE_ROOT | WK_FLAG_SINGULAR_INVERSE) : 0u;
    }
    ang[na] = 3.141592653589793; /* tan(q0 / 2) = infinity is no root of the polynomial: tried directly */
    atol[na] = WK_SP6_AT_PI_TOL;
    af[na++] = 0u;
    /* the wrist singularity: where rot(h4, q4) h5 = +-n the second equation holds for every q0 (its quartic has a
     * double root there, which rounding may hide), so those q4 are tried with q0 from the first equation alone: the
     * singular family where the second then holds to rounding (|n x w| within on_axis), the two roots from the split
     * where it holds within the double-root tolerance (near the singularity: each to ~eps, where the quartic
     * resolves them to sqrt(eps)) */
    if (wk_g3_sp1(h4, h5, n, tol->degenerate, &t4)) {
        for (j = 0; j < 2; ++j) {
            const double a4 = t4 + (j ? 3.141592653589793 : 0.0);
            double v[3], side, t0[2];
            unsigned f0[2];
            int m, n0;
            wk_g3_turn_dir(h4, a4, h5, v);
            side = wk_g3_dot(n, v);
            if (fabs(fabs(side) - 1.0) > 1e-12) continue;
            wk_g3_turn_dir(h4, a4, p4, v);
            n0 = wk_sp6_sp4(n, h0, p0, d0 + wk_g3_dot(n, v), tol, t0, f0);
            for (m = 0; m < n0; ++m) {
                double w[3], x[3], dn, b0[2], b4[2];
                int nb, b;
                wk_g3_turn_dir(h0, t0[m], gv, w); /* the second equation at q0 = -t0: n . w must be side (+-1) */
                dn = wk_g3_dot(n, w);
                if (!(dn * side > 0.0 && 1.0 - dn * dn <= tol->double_root)) continue;
                aq0[nanchor] = -t0[m];
                aq4[nanchor++] = a4;
                wk_g3_cross(n, w, x);
                if (wk_g3_norm(x) <= tol->family) { /* closed-form inputs: rounding, not a family band's noise */
                    sq0[ns] = -t0[m];
                    sq4[ns] = wk_wrap(a4);
                    sfl[ns++] = f0[m] | WK_FLAG_SINGULAR_INVERSE;
                    continue;
                }
                nb = wk_sp6_split(n, h0, p0, h4, p4, d0, gv, h5, -t0[m], a4, tol, b0, b4);
                for (b = 0; b < nb; ++b) {
                    pq0[nsplit] = b0[b];
                    pq4[nsplit] = b4[b];
                    pfl[nsplit++] = f0[m] | wk_sp6_merged(nb) | WK_FLAG_SINGULAR_INVERSE;
                }
            }
        }
    }
    for (i = 0; i < na; ++i) {
        const double c0 = cos(ang[i]), s0 = sin(ang[i]);
        const double cc = (al[0] + al[1] * c0 + al[2] * s0) / det, ss = (be[0] + be[1] * c0 + be[2] * s0) / det;
        double a0 = ang[i], a4 = atan2(ss, cc), z5[3];
        int order = 2, near;
        if (fabs(hypot(cc, ss) - 1.0) > atol[i]) continue; /* the root at infinity, or a poorly resolved one */
        wk_g3_turn_dir(h4, a4, h5, z5);
        near = fabs(wk_g3_dot(n, z5)) >= WK_SP6_NEAR_WRIST;
        if (af[i] && near) { /* a merged double root near the wrist singularity: its two roots */
            double b0[2], b4[2];
            const int nb = wk_sp6_split(n, h0, p0, h4, p4, d0, gv, h5, a0, a4, tol, b0, b4);
            for (j = 0; j < nb; ++j)
                if (!wk_sp6_taken(b0[j], b4[j], aq0, aq4, nanchor, pq0, pq4, nsplit)) {
                    q0[out] = b0[j];
                    q4[out] = b4[j];
                    fl[out] = (af[i] & ~WK_FLAG_DOUBLE_ROOT) | wk_sp6_merged(nb) | WK_FLAG_SINGULAR_INVERSE;
                    ord[out] = 1;
                    ++out;
                }
            if (nb) continue;
        }
        /* a merged double root far from the wrist stays (Newton is ill-conditioned there); near the wrist a root is
         * refined on the second equation's normal parts */
        if (!af[i]) {
            if (near) {
                wk_sp6_newton_perp(n, h0, p0, h4, p4, d0, gv, h5, &a0, &a4);
                order = 1;
            } else {
                wk_sp6_newton(n, h0, p0, h4, p4, d0, e0, gv, h5, &a0, &a4);
            }
        }
        if (wk_sp6_taken(a0, a4, aq0, aq4, nanchor, pq0, pq4, nsplit)) continue;
        q0[out] = a0;
        q4[out] = a4;
        fl[out] = af[i];
        ord[out] = order;
        ++out;
    }
    for (j = 0; j < nsplit; ++j) {
        q0[out] = pq0[j];
        q4[out] = pq4[j];
        fl[out] = pfl[j];
        ord[out] = 1;
        ++out;
    }
    for (j = 0; j < ns; ++j) {
        q0[out] = sq0[j];
        q4[out] = sq4[j];
        fl[out] = sfl[j];
        ord[out] = 2;
        ++out;
    }
    return out;
}
