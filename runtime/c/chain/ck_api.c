/* Input handling, FK, Jacobian and IK entry points (the generated public functions call these).
 * (a wristkin runtime source, inlined whole into every user robot's generated C, after the robot's CK_*
 * constants; derive/runtime_files.py, tests/test_chain_runtime.py) */
/* ------------------------------------------------------------------ input handling */
static const ck_design *ck_design_or_default(const ck_design *d)
{
    return d ? d : &ck_default_design;
}

/* Joints as the solver uses them: finite, revolute angles wrapped (exactly), prismatic offsets within
 * CK_LENGTH_MAX. Returns WK_OK or a negative code. */
static int ck_joints(const double *joints, double *q)
{
    int j;
    if (!wk_all_finite(joints, CK_N)) return WK_ERR_NONFINITE;
    for (j = 0; j < CK_N; ++j) {
        if (ck_revolute[j]) {
            q[j] = wk_wrap(joints[j]);
        } else {
            if (!(fabs(joints[j]) <= CK_LENGTH_MAX)) return WK_ERR_RANGE;
            q[j] = joints[j];
        }
    }
    return WK_OK;
}

/* A design's values are finite (design_init makes them so; a hand-filled struct is checked too) */
static int ck_design_ok(const ck_design *d)
{
    return wk_all_finite(d->params, CK_N_PARAMS_STORED) && wk_all_finite(d->base, 12) &&
           wk_all_finite(d->tool, 12);
}

static int ck_api_design_init(const double *params, ck_design *design)
{
    if (!design) return WK_ERR_NULL;
    if (params && !wk_all_finite(params, CK_N_PARAMS)) return WK_ERR_NONFINITE;
    *design = ck_default_design;
#if CK_N_PARAMS > 0
    if (params) design->params[0] = params[0]; /* the free joint's value, or the arm angle */
#endif
    return WK_OK;
}

/* one frame: finite, its rotation within WK_ROTATION_PROJECT_TOL of SO(3) (projected) */
static int ck_api_design_set_frames(ck_design *design, const double base[12], const double tool[12])
{
    double b[12], t[12];
    int i, rc;
    if (!design) return WK_ERR_NULL;
    for (i = 0; i < 12; ++i) {
        b[i] = ck_default_design.base[i];
        t[i] = ck_default_design.tool[i];
    }
    if (base && (rc = wk_input_frame(base, b)) != WK_OK) return rc;
    if (tool && (rc = wk_input_frame(tool, t)) != WK_OK) return rc;
    for (i = 0; i < 12; ++i) {
        design->base[i] = b[i];
        design->tool[i] = t[i];
    }
    return WK_OK;
}

/* ------------------------------------------------------------------ forward kinematics */
/* The robot's derived kernels (ck_k_fk, ck_k_jacobian: its product of exponentials with the constants folded,
 * printed before the runtime by derive/families/chain/kernels.py) answer FK and the Jacobian; the chain's table
 * (ck_fk_chain) serves the solver's own chains (held, reversed, ideal). */
/* cos and sin of the revolute joints (a prismatic joint's are unused: 1, 0), taken once for every kernel */
static void ck_trig_of(const double *q, double *c, double *s)
{
    int j;
    for (j = 0; j < CK_N; ++j) {
        c[j] = ck_revolute[j] ? cos(q[j]) : 1.0;
        s[j] = ck_revolute[j] ? sin(q[j]) : 0.0;
    }
}

/* base . chain . tool, from the joints and their cos and sin */
static void ck_fk_full_cs(const double *q, const double *c, const double *s, const ck_design *d, ck_rt *o)
{
    ck_rt base, tool;
    double v[12];
    ck_from12(d->base, &base);
    ck_from12(d->tool, &tool);
    ck_k_fk(q, c, s, v);
    ck_from12(v, o);
    ck_compose(&base, o, o);
    ck_compose(o, &tool, o);
}

static void ck_fk_full(const double *q, const ck_design *d, ck_rt *o)
{
    double c[CK_N], s[CK_N];
    ck_trig_of(q, c, s);
    ck_fk_full_cs(q, c, s, d, o);
}

#if !CK_REVERSED /* a reversed chain reads its conditioning off its own table (ck_interpreter.c) */
/* The chain's Jacobian (6 x n) in the solver's joints: the kernel's columns without the free joint's (held, the
 * solver's chain has the description's base and end frame, so its Jacobian is these columns). */
static void ck_jacobian_held(const double *full, const double *c, const double *s, double *jac)
{
    double v[6 * CK_N];
    int i, j, m;
    ck_k_jacobian(full, c, s, v);
    for (i = 0; i < 6; ++i)
        for (j = 0, m = 0; j < CK_N; ++j) {
            if (j == CK_FREE) continue;
            jac[i * (CK_N - (CK_FREE >= 0)) + m] = v[i * CK_N + j];
            ++m;
        }
}
#endif

/* Jacobian of base . chain . tool: the chain's columns with the tool's offset in the linear rows, rotated into
 * the base frame */
static void ck_jacobian_full(const double *q, const ck_design *d, double *jac)
{
    ck_rt base, tool, t, te;
    double c[CK_N], s[CK_N], v[12], jc[6 * CK_N], off[3];
    int i, j;
    ck_from12(d->base, &base);
    ck_from12(d->tool, &tool);
    ck_trig_of(q, c, s);
    ck_k_fk(q, c, s, v);
    ck_k_jacobian(q, c, s, jc);
    ck_from12(v, &t);
    ck_compose(&t, &tool, &te);
    ck_sub(te.t, t.t, off);
    for (j = 0; j < CK_N; ++j) {
        double lin[3], ang[3], extra[3];
        for (i = 0; i < 3; ++i) {
            lin[i] = jc[i * CK_N + j];
            ang[i] = jc[(3 + i) * CK_N + j];
        }
        ck_cross(ang, off, extra);
        ck_add(lin, extra, lin);
        ck_mv(base.r, lin, lin);
        ck_mv(base.r, ang, ang);
        for (i = 0; i < 3; ++i) {
            jac[i * CK_N + j] = lin[i];
            jac[(3 + i) * CK_N + j] = ang[i];
        }
    }
}

static int ck_api_fk(const double *joints, const ck_design *design, ck_fk_solutions *out)
{
    const ck_design *d = ck_design_or_default(design);
    double q[CK_N], jac[6 * CK_N], man;
    ck_rt t;
    int j, rc, singular;
    if (!out) return WK_ERR_NULL;
    out->count = 0;
    out->valid[0] = 0;
    out->flags[0] = 0u;
    for (j = 0; j < 12; ++j) out->values[0][j] = NAN;
    out->aux[0][0] = NAN;
    if (!joints) {
        out->status = WK_ERR_NULL;
        return WK_ERR_NULL;
    }
    rc = ck_design_ok(d) ? ck_joints(joints, q) : WK_ERR_NONFINITE;
    if (rc != WK_OK) {
        out->status = rc;
        return rc;
    }
    ck_fk_full(q, d, &t);
    ck_to12(&t, out->values[0]);
    ck_jacobian_full(q, d, jac);
    man = ck_conditioning(jac, CK_N, &singular);
    out->aux[0][0] = man;
    out->flags[0] = singular ? WK_FLAG_SINGULAR_INVERSE : 0u;
    out->valid[0] = 1;
    out->count = 1;
    out->status = WK_STATUS_OK;
    return WK_OK;
}

static int ck_api_fk_matrix(const double *joints, const ck_design *design, double *pose)
{
    const ck_design *d = ck_design_or_default(design);
    double q[CK_N];
    ck_rt t;
    int rc;
    if (!joints || !pose) return WK_ERR_NULL;
    if (!ck_design_ok(d)) return WK_ERR_NONFINITE;
    rc = ck_joints(joints, q);
    if (rc != WK_OK) return rc;
    ck_fk_full(q, d, &t);
    ck_to12(&t, pose);
    return WK_OK;
}

static int ck_api_jacobian(const double *joints, const ck_design *design, double *jac)
{
    const ck_design *d = ck_design_or_default(design);
    double q[CK_N];
    int rc;
    if (!joints || !jac) return WK_ERR_NULL;
    if (!ck_design_ok(d)) return WK_ERR_NONFINITE;
    rc = ck_joints(joints, q);
    if (rc != WK_OK) return rc;
    ck_jacobian_full(q, d, jac);
    return WK_OK;
}

/* ------------------------------------------------------------------ inverse kinematics */
static int ck_api_ik_near(const double pose_in[12], const ck_design *design, const double *previous,
                          ck_ik_solutions *out);

static int ck_api_ik(const double pose[12], const ck_design *design, ck_ik_solutions *out)
{
    return ck_api_ik_near(pose, design, NULL, out);
}

static int ck_api_ik_near(const double pose_in[12], const ck_design *design, const double *previous,
                          ck_ik_solutions *out)
{
    const ck_design *d = ck_design_or_default(design);
    ck_chain ideal, truth;
    ck_ctx c;
    ck_trig_memo memo;
    ck_rt target, base, tool, g_chain;
    double rot[9], deviation = 0.0, prev[CK_N], prev_c[CK_N], zero[3] = {0.0, 0.0, 0.0};
    int k, j;
    if (!out) return WK_ERR_NULL;
    out->count = 0;
    for (k = 0; k < CK_MAX_IK; ++k) {
        out->valid[k] = 0;
        out->flags[k] = 0u;
        out->aux[k][0] = NAN;
        for (j = 0; j < CK_N; ++j) out->values[k][j] = NAN;
    }
    if (!pose_in) {
        out->status = WK_ERR_NULL;
        return WK_ERR_NULL;
    }
    if (!wk_all_finite(pose_in, 12) || (previous && !wk_all_finite(previous, CK_N)) || !ck_design_ok(d)) {
        out->status = WK_ERR_NONFINITE;
        return WK_ERR_NONFINITE;
    }
    /* the rotation within WK_ROTATION_PROJECT_TOL of SO(3) (projected), the translation within CK_LENGTH_MAX */
    if (!wk_input_rotation(pose_in, rot, &deviation) || !(fabs(pose_in[3]) <= CK_LENGTH_MAX) ||
        !(fabs(pose_in[7]) <= CK_LENGTH_MAX) || !(fabs(pose_in[11]) <= CK_LENGTH_MAX)) {
        out->status = WK_ERR_RANGE;
        return WK_ERR_RANGE;
    }
    if (previous && ck_joints(previous, prev) != WK_OK) {
        out->status = WK_ERR_RANGE;
        return WK_ERR_RANGE;
    }
#if CK_FREE >= 0 && CK_N_DEGENERATE_HELD > 0
    { /* a held value where the other six joints are a self-motion: every pose has infinitely many solutions
         (Python's _DEGENERATE_HELD) */
        static const double held[] = CK_DEGENERATE_HELD;
        for (k = 0; k < CK_N_DEGENERATE_HELD; ++k)
            if (fabs(wk_wrap(d->params[0] - held[k])) <= CK_GEOMETRY_TOL) {
                out->status = WK_ERR_DESIGN;
                return WK_ERR_DESIGN;
            }
    }
#endif
    for (j = 0; j < 3; ++j) {
        target.r[3 * j] = rot[3 * j];
        target.r[3 * j + 1] = rot[3 * j + 1];
        target.r[3 * j + 2] = rot[3 * j + 2];
        target.t[j] = pose_in[4 * j + 3];
    }
    /* the chain's end frame: base^-1 . pose . tool^-1 */
    ck_from12(d->base, &base);
    ck_from12(d->tool, &tool);
    ck_inverse(&base, &base);
    ck_inverse(&tool, &tool);
    ck_compose(&base, &target, &g_chain);
    ck_compose(&g_chain, &tool, &g_chain);
    /* the chains the decomposition reads (the free joint held, read from the tool: as the robot's CK_FREE, CK_REVERSED) */
#if CK_FREE >= 0
    ck_held(&ck_ideal_chain, CK_FREE, d->params[0], &ideal);
    ck_held(&ck_true_chain, CK_FREE, d->params[0], &truth);
#else
    ideal = ck_ideal_chain;
    truth = ck_true_chain;
#endif
#if CK_REVERSED
    {
        ck_chain tmp = ideal;
        ck_reversed(&tmp, &ideal);
        tmp = truth;
        ck_reversed(&tmp, &truth);
    }
    ck_inverse(&g_chain, &c.target);
#else
    c.target = g_chain;
#endif
    c.ideal = &ideal;
    c.truth = &truth;
    c.pose = target;
    c.design = d;
    ck_inverse(&ideal.home, &c.g);
    ck_compose(&c.target, &c.g, &c.g);
    if (previous)
        for (j = 0; j < ideal.n; ++j) prev_c[j] = prev[ideal.index[j]];
    c.prev = previous ? prev_c : NULL;
    c.free_value = d->params[0];
    c.projected = deviation > 0.0 ? WK_FLAG_PROJECTED : 0u;
    c.indeterminate = 0;
    c.noise = 1.0;
    c.amp = 1.0;
    c.probe = c.hits = 0;
    c.raw = 0;
    c.out = out;
    memo.valid = 0;
    c.memo = &memo;
    for (j = 0; j < CK_N; ++j) c.q[j] = c.theta[j] = 0.0;
    for (k = 0; k < CK_N_OPS; ++k) ck_point(&ideal, &ck_plan[k], c.spec[k]);
    ck_run(&c, 0, zero, zero, 0u);
    out->status = out->count == 0 ? WK_STATUS_UNREACHABLE
                                  : (c.indeterminate ? WK_STATUS_INDETERMINATE : WK_STATUS_OK);
    return WK_OK;
}

static int ck_api_ik_batch(size_t n, const double *poses, const ck_design *design,
                           ck_ik_solutions *out)
{
    size_t r;
    int first = WK_OK;
    if (n == 0) return WK_OK;
    if (!poses || !out) return WK_ERR_NULL;
    for (r = 0; r < n; ++r) {
        const int rc = ck_api_ik(poses + 12 * r, design, out + r);
        if (rc != WK_OK && first == WK_OK) first = rc;
    }
    return first;
}

static int ck_api_fk_batch(size_t n, const double *joints, const ck_design *design,
                           ck_fk_solutions *out)
{
    size_t r;
    int first = WK_OK;
    if (n == 0) return WK_OK;
    if (!joints || !out) return WK_ERR_NULL;
    for (r = 0; r < n; ++r) {
        const int rc = ck_api_fk(joints + CK_N * r, design, out + r);
        if (rc != WK_OK && first == WK_OK) first = rc;
    }
    return first;
}

static int ck_api_select_ik(const ck_ik_solutions *s, const double *previous, const double *lower,
                            const double *upper)
{
    /* the contract of every select (the runtime's wk_select); NULL limits are the description's (Python LOWER /
       UPPER) */
    if (!s) return -1;
    return wk_select(CK_MAX_IK, CK_N, s->valid, s->flags, &s->values[0][0], ck_revolute, previous,
                     lower ? lower : ck_lower, upper ? upper : ck_upper, NULL);
}
