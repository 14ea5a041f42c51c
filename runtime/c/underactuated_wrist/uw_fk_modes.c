/* The underactuated wrist's FK numerics for one joint triple: the degree-8 eliminant in
 * x = tan((eta - eta_c) / 2), zeta at a root, and a damped Gauss-Newton polish on the two loop equations.
 * (a wristkin runtime source, inlined whole into the underactuated wrist's generated C after its UW_*
 * constants, the uw_design / uw_ik_solutions / uw_fk_solutions types and the derived kernels uw_k_*;
 * derive/runtime_files.py, tests/test_uw_runtime.py) */
/* ------------------------------------------------------------------ forward kinematics */
typedef struct {
    double trip[6][3]; /* D1, E1, F1, D2, E2, F2 as (const, cos eta, sin eta) */
} uw_fk_coef;

/* cos, sin of 2 pi k / 16: the sampling ring used to place eta_c */
static const double uw_ring[16][2] = {
    {1.0, 0.0}, {0.92387953251128674, 0.38268343236508978}, {0.70710678118654757, 0.70710678118654757},
    {0.38268343236508984, 0.92387953251128674}, {0.0, 1.0}, {-0.38268343236508973, 0.92387953251128674},
    {-0.70710678118654746, 0.70710678118654757}, {-0.92387953251128674, 0.38268343236508989}, {-1.0, 0.0},
    {-0.92387953251128685, -0.38268343236508967}, {-0.70710678118654768, -0.70710678118654746},
    {-0.38268343236509, -0.92387953251128663}, {0.0, -1.0}, {0.38268343236508956, -0.92387953251128685},
    {0.70710678118654735, -0.70710678118654768}, {0.92387953251128652, -0.38268343236509034}};

static void uw_def_cs(const uw_fk_coef *cf, double ce, double se, double *v, double *dv)
{
    int j;
    for (j = 0; j < 6; ++j) {
        v[j] = cf->trip[j][0] + cf->trip[j][1] * ce + cf->trip[j][2] * se;
        if (dv) dv[j] = -cf->trip[j][1] * se + cf->trip[j][2] * ce;
    }
}

static double uw_elimination(const double *v)
{
    const double a = v[1] * v[5] - v[4] * v[2], b = v[3] * v[2] - v[0] * v[5], c = v[0] * v[4] - v[3] * v[1];
    return a * a + b * b - c * c;
}

static void uw_pmul2(const double *a, const double *b, double *out) /* quadratic x quadratic */
{
    out[0] = a[0] * b[0];
    out[1] = a[0] * b[1] + a[1] * b[0];
    out[2] = a[0] * b[2] + a[1] * b[1] + a[2] * b[0];
    out[3] = a[1] * b[2] + a[2] * b[1];
    out[4] = a[2] * b[2];
}

static void uw_psq4(const double *a, double *out) /* quartic squared */
{
    int i, j;
    for (i = 0; i < 9; ++i) out[i] = 0.0;
    for (i = 0; i < 5; ++i)
        for (j = 0; j < 5; ++j) out[i + j] += a[i] * a[j];
}

/* K0..K8 of (1 + x^2)^4 * identity, x = tan((eta - eta_c)/2). */
static void uw_k_polynomial(const uw_fk_coef *cf, double ce, double se, double *kpoly)
{
    double q[6][3], p1[5], p2[5], t1[5], t2[5], t3[5], s1[9], s2[9], s3[9];
    int j;
    for (j = 0; j < 6; ++j) {
        const double rc = cf->trip[j][1] * ce + cf->trip[j][2] * se;
        const double rs = -cf->trip[j][1] * se + cf->trip[j][2] * ce;
        q[j][0] = cf->trip[j][0] + rc;
        q[j][1] = 2.0 * rs;
        q[j][2] = cf->trip[j][0] - rc;
    }
    uw_pmul2(q[1], q[5], p1); uw_pmul2(q[4], q[2], p2);
    for (j = 0; j < 5; ++j) t1[j] = p1[j] - p2[j];
    uw_pmul2(q[3], q[2], p1); uw_pmul2(q[0], q[5], p2);
    for (j = 0; j < 5; ++j) t2[j] = p1[j] - p2[j];
    uw_pmul2(q[0], q[4], p1); uw_pmul2(q[3], q[1], p2);
    for (j = 0; j < 5; ++j) t3[j] = p1[j] - p2[j];
    uw_psq4(t1, s1); uw_psq4(t2, s2); uw_psq4(t3, s3);
    for (j = 0; j < 9; ++j) kpoly[j] = s1[j] + s2[j] - s3[j];
}

/* The loop equations' residual and Jacobian at (zeta, eta) given their cosines and sines. */
static double uw_residual(const uw_fk_coef *cf, const double *cs, double *g, double *jac)
{
    double v[6], dv[6];
    const double cz = cs[0], sz = cs[1];
    uw_def_cs(cf, cs[2], cs[3], v, dv);
    g[0] = v[0] * cz + v[1] * sz + v[2];
    g[1] = v[3] * cz + v[4] * sz + v[5];
    jac[0] = -v[0] * sz + v[1] * cz;
    jac[1] = dv[0] * cz + dv[1] * sz + dv[2];
    jac[2] = -v[3] * sz + v[4] * cz;
    jac[3] = dv[3] * cz + dv[4] * sz + dv[5];
    return fmax(fabs(g[0]), fabs(g[1]));
}

/* cos and sin of t + d from those of t (c, s): the rotation by d, its cos and sin from their series when
 * |d| <= 1e-2 (truncation below 3e-18, under the rounding of the product), else from libm at t + d. A Newton step's
 * turn is small, and the trial points' libm calls were most of the FK's time in sincos (17 % of it). */
static void uw_turn(double t, double c, double s, double d, double *co, double *so)
{
    if (fabs(d) <= 1e-2) {
        const double d2 = d * d;
        const double cd = 1.0 - d2 * (0.5 - d2 * (1.0 / 24.0 - d2 * (1.0 / 720.0)));
        const double sd = d * (1.0 - d2 * (1.0 / 6.0 - d2 * (1.0 / 120.0)));
        *co = c * cd - s * sd;
        *so = s * cd + c * sd;
    } else {
        *co = cos(t + d);
        *so = sin(t + d);
    }
}

/* Damped Gauss-Newton on the two loop equations from (zeta, eta) with cs = (cos zeta, sin zeta, cos eta,
 * sin eta); returns the final max |residual|. */
static double uw_polish(const uw_fk_coef *cf, double *zeta, double *eta, double *cs)
{
    double g[2], jac[4], err = uw_residual(cf, cs, g, jac);
    int it;
    for (it = 0; it < UW_POLISH_ITERS && err > 1e-16; ++it) {
        const double a = jac[0], b = jac[1], c = jac[2], dd = jac[3];
        const double j00 = a * a + c * c, j01 = a * b + c * dd, j11 = b * b + dd * dd;
        const double mu = 1e-14 * (j00 + j11) + 1e-300;
        const double r0 = -(a * g[0] + c * g[1]), r1 = -(b * g[0] + dd * g[1]);
        const double det = (j00 + mu) * (j11 + mu) - j01 * j01;
        const double dz = (r0 * (j11 + mu) - j01 * r1) / det, de = ((j00 + mu) * r1 - j01 * r0) / det;
        double g2[2], jac2[4], cs2[4], err2;
        uw_turn(*zeta, cs[0], cs[1], dz, &cs2[0], &cs2[1]);
        uw_turn(*eta, cs[2], cs[3], de, &cs2[2], &cs2[3]);
        err2 = uw_residual(cf, cs2, g2, jac2);
        if (!(err2 < err)) break;
        *zeta += dz;
        *eta += de;
        err = err2;
        g[0] = g2[0]; g[1] = g2[1];
        jac[0] = jac2[0]; jac[1] = jac2[1]; jac[2] = jac2[2]; jac[3] = jac2[3];
        cs[0] = cs2[0]; cs[1] = cs2[1]; cs[2] = cs2[2]; cs[3] = cs2[3];
    }
    return err;
}

/* zeta = base +/- acos(u) and its cos, sin (zcs) from those of base and u: no trigonometry but the angles'. */
static int uw_zeta_pair(double base, double cb, double sb, double u, double *zeta, double *zcs)
{
    const double g = acos(u), sg = sqrt((1.0 - u) * (1.0 + u));
    zeta[0] = base + g;
    zeta[1] = base - g;
    zcs[0] = cb * u - sb * sg;
    zcs[1] = sb * u + cb * sg;
    zcs[2] = cb * u + sb * sg;
    zcs[3] = sb * u - cb * sg;
    return 2;
}

/* zeta candidates at eta, with their cos and sin in zcs: Cramer's rule, or one equation when the two are
 * proportional. */
static int uw_zeta_candidates(const uw_fk_coef *cf, double ce, double se, double *zeta, double *zcs)
{
    double v[6], den, nc, ns, n1, n2;
    uw_def_cs(cf, ce, se, v, 0);
    den = v[0] * v[4] - v[3] * v[1];
    nc = v[1] * v[5] - v[4] * v[2];
    ns = v[3] * v[2] - v[0] * v[5];
    n1 = sqrt(v[0] * v[0] + v[1] * v[1]);
    n2 = sqrt(v[3] * v[3] + v[4] * v[4]);
    if (fabs(den) > 1e-8 * n1 * n2) {
        const double sgn = den > 0.0 ? 1.0 : -1.0, h = sqrt(nc * nc + ns * ns);
        zeta[0] = atan2(sgn * ns, sgn * nc);
        zcs[0] = h > 0.0 ? sgn * nc / h : cos(zeta[0]);
        zcs[1] = h > 0.0 ? sgn * ns / h : sin(zeta[0]);
        return 1;
    } else {
        const double d = n1 >= n2 ? v[0] : v[3], e = n1 >= n2 ? v[1] : v[4], f = n1 >= n2 ? v[2] : v[5];
        const double r = sqrt(d * d + e * e);
        if (r == 0.0 || fabs(f) > r * (1.0 + 1e-6)) return 0;
        return uw_zeta_pair(atan2(e, d), d / r, e / r, uw_clamp1(-f / r), zeta, zcs);
    }
}

/* Every zeta candidate at an unresolved (double) root: Cramer's rule and both roots of each equation alone (two
 * modes can share eta where the equations are nearly proportional; see Python _zeta_all). Up to 5. */
static int uw_zeta_all(const uw_fk_coef *cf, double ce, double se, double *zeta, double *zcs)
{
    double v[6];
    int n = uw_zeta_candidates(cf, ce, se, zeta, zcs), i;
    uw_def_cs(cf, ce, se, v, 0);
    for (i = 0; i < 2 && n <= 3; ++i) {
        const double d = v[3 * i], e = v[3 * i + 1], f = v[3 * i + 2], r = sqrt(d * d + e * e);
        if (r > 0.0 && fabs(f) <= r * (1.0 + 1e-6)) {
            n += uw_zeta_pair(atan2(e, d), d / r, e / r, uw_clamp1(-f / r), zeta + n, zcs + 2 * n);
        }
    }
    return n;
}
