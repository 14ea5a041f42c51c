/* wristkin: 3-vector helpers, subproblem 1 and a trig equation for the chain-free cores (wk_spatial3.c, wk_sp6.c,
 * wk_arm_angle.c) (C99, libm only; the runtime's flags before it).
 * Included verbatim into generated C99 sources before them (static inline: a core that does not use one of them
 * leaves no unused function behind). Python's twin: runtime/python/geom3.py, step for step. */
static inline double wk_g3_dot(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* o = a x b (o may alias a or b) */
static inline void wk_g3_cross(const double *a, const double *b, double *o)
{
    const double x = a[1] * b[2] - a[2] * b[1], y = a[2] * b[0] - a[0] * b[2], z = a[0] * b[1] - a[1] * b[0];
    o[0] = x;
    o[1] = y;
    o[2] = z;
}

/* o = a + s b */
static inline void wk_g3_axpy(const double *a, double s, const double *b, double *o)
{
    o[0] = a[0] + s * b[0];
    o[1] = a[1] + s * b[1];
    o[2] = a[2] + s * b[2];
}

static inline double wk_g3_norm(const double *a)
{
    return sqrt(wk_g3_dot(a, a));
}

/* p turned by q about the line (h, r): r + R (p - r), R by Rodrigues (o may alias p) */
static inline void wk_g3_turn_cs(const double *h, const double *r, double c, double s, const double *p, double *o)
{
    double d[3], hx[3], hd;
    d[0] = p[0] - r[0];
    d[1] = p[1] - r[1];
    d[2] = p[2] - r[2];
    hd = wk_g3_dot(h, d) * (1.0 - c);
    wk_g3_cross(h, d, hx);
    o[0] = r[0] + c * d[0] + s * hx[0] + hd * h[0];
    o[1] = r[1] + c * d[1] + s * hx[1] + hd * h[1];
    o[2] = r[2] + c * d[2] + s * hx[2] + hd * h[2];
}

static inline void wk_g3_turn(const double *h, const double *r, double q, const double *p, double *o)
{
    wk_g3_turn_cs(h, r, cos(q), sin(q), p, o);
}

/* the direction v turned by q about h: rot(h, q) v (o may alias v) */
static inline void wk_g3_turn_dir_cs(const double *h, double c, double s, const double *v, double *o)
{
    static const double origin[3] = {0.0, 0.0, 0.0};
    wk_g3_turn_cs(h, origin, c, s, v, o);
}

static inline void wk_g3_turn_dir(const double *h, double q, const double *v, double *o)
{
    wk_g3_turn_dir_cs(h, cos(q), sin(q), v, o);
}

/* t with rot(k, t) p = q seen normal to k (subproblem 1); 0 when either is within eps_scale of the axis */
static inline int wk_g3_sp1(const double *k, const double *p, const double *q, double eps_scale, double *t)
{
    double pp[3], qq[3], c[3];
    wk_g3_axpy(p, -wk_g3_dot(k, p), k, pp);
    wk_g3_axpy(q, -wk_g3_dot(k, q), k, qq);
    if (wk_g3_norm(pp) <= eps_scale || wk_g3_norm(qq) <= eps_scale) return 0;
    wk_g3_cross(pp, qq, c);
    *t = atan2(wk_g3_dot(k, c), wk_g3_dot(pp, qq));
    return 1;
}

/* Roots t of a cos t + b sin t = c (at most 2): a double root once (flagged), where 1 - u^2 is within double_root; a
 * vanishing equation (|(a, b)| and |c| within on_axis of `scale`) one representative t = 0, flagged indeterminate;
 * |u| = |c| / |(a, b)| up to 1 + tangent counts as a root */
static inline int wk_g3_trig(double a, double b, double c, double scale, double on_axis, double tangent,
                             double double_root, double *t, unsigned *f)
{
    const double r = hypot(a, b);
    double u, phi, w;
    if (r <= on_axis * scale) {
        if (!(fabs(c) <= on_axis * scale)) return 0;
        t[0] = 0.0;
        f[0] = WK_FLAG_INDETERMINATE | WK_FLAG_SINGULAR_INVERSE;
        return 1;
    }
    u = c / r;
    if (!(fabs(u) <= 1.0 + tangent)) return 0;
    u = u > 1.0 ? 1.0 : (u < -1.0 ? -1.0 : u);
    phi = atan2(b, a);
    if (1.0 - u * u <= double_root) {
        t[0] = phi + (u > 0.0 ? 0.0 : 3.141592653589793);
        f[0] = WK_FLAG_DOUBLE_ROOT | WK_FLAG_SINGULAR_INVERSE;
        return 1;
    }
    w = acos(u);
    t[0] = phi + w;
    t[1] = phi - w;
    f[0] = f[1] = 0u;
    return 2;
}
