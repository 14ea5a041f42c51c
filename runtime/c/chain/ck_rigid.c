/* Rigid-body algebra of the user-robot solver: 3-vectors, rotations, transforms, screws.
 * (a wristkin runtime source, inlined whole into every user robot's generated C, after the robot's CK_*
 * constants; derive/runtime_files.py, tests/test_chain_runtime.py) */
/* ------------------------------------------------------------------ rigid-body algebra */
typedef struct {
    double r[9]; /* rotation, row-major */
    double t[3];
} ck_rt;

static double ck_dot(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void ck_cross(const double *a, const double *b, double *o)
{
    const double x = a[1] * b[2] - a[2] * b[1], y = a[2] * b[0] - a[0] * b[2], z = a[0] * b[1] - a[1] * b[0];
    o[0] = x;
    o[1] = y;
    o[2] = z;
}

static void ck_sub(const double *a, const double *b, double *o)
{
    o[0] = a[0] - b[0];
    o[1] = a[1] - b[1];
    o[2] = a[2] - b[2];
}

static void ck_add(const double *a, const double *b, double *o)
{
    o[0] = a[0] + b[0];
    o[1] = a[1] + b[1];
    o[2] = a[2] + b[2];
}

static void ck_scale(const double *a, double s, double *o)
{
    o[0] = a[0] * s;
    o[1] = a[1] * s;
    o[2] = a[2] * s;
}

static double ck_norm(const double *a)
{
    return sqrt(ck_dot(a, a));
}

/* Rotation about the unit axis k by t (Rodrigues), row-major. */
static void ck_rot(const double *k, double t, double *r)
{
    const double c = cos(t), s = sin(t), v = 1.0 - c, x = k[0], y = k[1], z = k[2];
    r[0] = c + x * x * v;
    r[1] = x * y * v - z * s;
    r[2] = x * z * v + y * s;
    r[3] = y * x * v + z * s;
    r[4] = c + y * y * v;
    r[5] = y * z * v - x * s;
    r[6] = z * x * v - y * s;
    r[7] = z * y * v + x * s;
    r[8] = c + z * z * v;
}

/* o = r v (o may alias v) */
static void ck_mv(const double *r, const double *v, double *o)
{
    const double x = ck_dot(r, v), y = ck_dot(r + 3, v), z = ck_dot(r + 6, v);
    o[0] = x;
    o[1] = y;
    o[2] = z;
}

/* o = r^T v (o may alias v) */
static void ck_mtv(const double *r, const double *v, double *o)
{
    const double x = r[0] * v[0] + r[3] * v[1] + r[6] * v[2], y = r[1] * v[0] + r[4] * v[1] + r[7] * v[2],
                 z = r[2] * v[0] + r[5] * v[1] + r[8] * v[2];
    o[0] = x;
    o[1] = y;
    o[2] = z;
}

/* o = a b (o may alias a or b) */
static void ck_mm(const double *a, const double *b, double *o)
{
    double m[9];
    int i, j;
    for (i = 0; i < 3; ++i)
        for (j = 0; j < 3; ++j) m[3 * i + j] = a[3 * i] * b[j] + a[3 * i + 1] * b[3 + j] + a[3 * i + 2] * b[6 + j];
    for (i = 0; i < 9; ++i) o[i] = m[i];
}

static void ck_identity(ck_rt *o)
{
    int i;
    for (i = 0; i < 9; ++i) o->r[i] = (i % 4 == 0) ? 1.0 : 0.0;
    o->t[0] = o->t[1] = o->t[2] = 0.0;
}

/* o = a b (o may alias a or b) */
static void ck_compose(const ck_rt *a, const ck_rt *b, ck_rt *o)
{
    ck_rt m;
    ck_mm(a->r, b->r, m.r);
    ck_mv(a->r, b->t, m.t);
    ck_add(m.t, a->t, m.t);
    *o = m;
}

/* o = a^-1 (o may alias a) */
static void ck_inverse(const ck_rt *a, ck_rt *o)
{
    ck_rt m;
    int i, j;
    for (i = 0; i < 3; ++i)
        for (j = 0; j < 3; ++j) m.r[3 * i + j] = a->r[3 * j + i];
    ck_mv(m.r, a->t, m.t);
    ck_scale(m.t, -1.0, m.t);
    *o = m;
}

/* o = a x (o may alias x) */
static void ck_apply(const ck_rt *a, const double *x, double *o)
{
    double m[3];
    ck_mv(a->r, x, m);
    ck_add(m, a->t, o);
}

/* exp(S q): rotation about the line (h, p), or translation along h */
static void ck_screw(int prismatic, const double *h, const double *p, double q, ck_rt *o)
{
    if (prismatic) {
        ck_identity(o);
        ck_scale(h, q, o->t);
        return;
    }
    ck_rot(h, q, o->r);
    ck_mv(o->r, p, o->t);
    ck_sub(p, o->t, o->t);
}

/* A pose's top 3x4 (row-major) as a transform */
static void ck_from12(const double *p, ck_rt *o)
{
    int i;
    for (i = 0; i < 3; ++i) {
        o->r[3 * i] = p[4 * i];
        o->r[3 * i + 1] = p[4 * i + 1];
        o->r[3 * i + 2] = p[4 * i + 2];
        o->t[i] = p[4 * i + 3];
    }
}

static void ck_to12(const ck_rt *a, double *p)
{
    int i;
    for (i = 0; i < 3; ++i) {
        p[4 * i] = a->r[3 * i];
        p[4 * i + 1] = a->r[3 * i + 1];
        p[4 * i + 2] = a->r[3 * i + 2];
        p[4 * i + 3] = a->t[i];
    }
}

