/* Subproblem 6 for the interpreted plan's sp6 op, on the chain-free core wk_sp6.c (inlined before it) with the
 * chain's tolerances. (a wristkin runtime source, inlined whole into every user robot's generated C whose plan has an
 * sp6 op, after the robot's CK_* constants; derive/families/chain/views.py, tests/test_chain_runtime.py) */
#define CK_SP6_MAX WK_SP6_MAX

/* o = r^T */
static void ck_transpose(const double *r, double *o)
{
    int i, j;
    for (i = 0; i < 3; ++i)
        for (j = 0; j < 3; ++j) o[3 * i + j] = r[3 * j + i];
}

/* the core's tolerances: the chain's, with subproblem 4's bands as ck_trig widens them for noise 1 */
static wk_sp6_tols ck_sp6_tols(void)
{
    wk_sp6_tols t;
    t.scale = CK_SCALE;
    t.degenerate = CK_DEGENERATE_EPS;
    t.double_root = fmax(CK_DOUBLE_ROOT_TOL, 2.0 * CK_STAGE_NOISE);
    t.tangent = fmax(CK_TANGENT_TOL, CK_STAGE_NOISE);
    t.on_axis = CK_ON_AXIS_TOL;
    return t;
}

/* (q0, q4, flags, order) of subproblem 6 (wk_sp6), at most CK_SP6_MAX */
static int ck_sp6(const double *n, const double *h0, const double *p0, const double *h4, const double *p4, double d0,
                  double e0, const double *gv, const double *h5, double *q0, double *q4, unsigned *fl, int *ord)
{
    const wk_sp6_tols t = ck_sp6_tols();
    return wk_sp6(n, h0, p0, h4, p4, d0, e0, gv, h5, &t, q0, q4, fl, ord);
}

/* the two roots a merged one near (q0, q4) stands for (wk_sp6_split) */
static int ck_sp6_split(const double *n, const double *h0, const double *p0, const double *h4, const double *p4,
                        double d0, const double *g, const double *h5, double q0, double q4, double *s0, double *s4)
{
    const wk_sp6_tols t = ck_sp6_tols();
    return wk_sp6_split(n, h0, p0, h4, p4, d0, g, h5, q0, q4, &t, s0, s4);
}
