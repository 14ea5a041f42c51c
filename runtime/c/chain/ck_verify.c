/* Verification and Gauss-Newton polish of a candidate on the true chain.
 * (a wristkin runtime source, inlined whole into every user robot's generated C, after the robot's CK_*
 * constants; derive/runtime_files.py, tests/test_chain_runtime.py) */
/* ------------------------------------------------------------------ verification on the true chain */
/* max |t - target| over the entries of [R | p] */
static double ck_frame_error(const ck_rt *t, const ck_rt *target)
{
    double err = 0.0;
    int i;
    for (i = 0; i < 9; ++i) {
        const double e = fabs(t->r[i] - target->r[i]);
        if (!(e <= err)) err = e; /* a NaN propagates (and fails the check) */
    }
    for (i = 0; i < 3; ++i) {
        const double e = fabs(t->t[i] - target->t[i]);
        if (!(e <= err)) err = e;
    }
    return err;
}

/* 6-vector (position error, 1/2 sum of column crosses) from t to target */
static void ck_twist_error(const ck_rt *t, const ck_rt *target, double *e)
{
    int i;
    e[0] = target->t[0] - t->t[0];
    e[1] = target->t[1] - t->t[1];
    e[2] = target->t[2] - t->t[2];
    e[3] = e[4] = e[5] = 0.0;
    for (i = 0; i < 3; ++i) {
        const double a[3] = {t->r[i], t->r[3 + i], t->r[6 + i]};
        const double b[3] = {target->r[i], target->r[3 + i], target->r[6 + i]};
        double c[3];
        ck_cross(a, b, c);
        e[3] = e[3] + 0.5 * c[0];
        e[4] = e[4] + 0.5 * c[1];
        e[5] = e[5] + 0.5 * c[2];
    }
}

/* How a polish reads the chain it drives: its end frame and its Jacobian (6 x n) at q. */
typedef struct {
    void (*fk)(const void *self, const double *q, ck_rt *t);
    void (*jacobian)(const void *self, const double *q, double *jac);
    const void *self;
    int n;
} ck_reader;

/* Gauss-Newton on the chain `r` reads: removes the error of the ideal geometry and of a tangent root. q in place;
 * returns the pose error. A square step is J^-1 e by elimination, else (or near rank deficiency) least squares. */
static double ck_polish_read(const ck_reader *r, double *q, const ck_rt *target, const ck_rt *t0)
{
    ck_rt t, t2;
    double err;
    int it, j, n = r->n;
    if (t0) /* the caller's reading of r at q */
        t = *t0;
    else
        r->fk(r->self, q, &t);
    err = ck_frame_error(&t, target);
    for (it = 0; it < CK_POLISH_STEPS; ++it) {
        double jac[6 * CK_N], e[6], step[CK_N], trial[CK_N], err2;
        if (err <= CK_POLISH_TOL) break;
        r->jacobian(r->self, q, jac);
        ck_twist_error(&t, target, e);
        if (n != 6 || !wk_square_solve(jac, 6, e, 1e-8, step)) ck_lstsq(jac, 6, n, e, step);
        for (j = 0; j < n; ++j) trial[j] = q[j] + step[j];
        r->fk(r->self, trial, &t2);
        err2 = ck_frame_error(&t2, target);
        if (!(err2 < err)) break;
        for (j = 0; j < n; ++j) q[j] = trial[j];
        err = err2;
        t = t2;
    }
    return err;
}

static void ck_table_fk(const void *self, const double *q, ck_rt *t)
{
    ck_fk_chain((const ck_chain *)self, q, t);
}

static void ck_table_jacobian(const void *self, const double *q, double *jac)
{
    ck_jacobian_chain((const ck_chain *)self, q, jac, NULL);
}

/* The polish on a chain's table (the solver's chains: reversed, ideal; inline: a robot whose candidates the
 * kernels polish has no call) */
static inline double ck_polish(const ck_chain *ch, double *q, const ck_rt *target)
{
    ck_reader r;
    r.fk = ck_table_fk;
    r.jacobian = ck_table_jacobian;
    r.self = ch;
    r.n = ch->n;
    return ck_polish_read(&r, q, target, NULL);
}

