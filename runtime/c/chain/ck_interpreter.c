/* The decomposition's interpreter (ck_run): each op solves its joints, recurses into every root.
 * (a wristkin runtime source, inlined whole into every user robot's generated C, after the robot's CK_*
 * constants; derive/runtime_files.py, tests/test_chain_runtime.py) */
/* ------------------------------------------------------------------ the decomposition's interpreter */
/* cos and sin of the last full joints a candidate's check, polish or conditioning asked for: its FK and Jacobian
 * at one point read the same (a calibrated robot's polish spent a third of its time recomputing them) */
typedef struct {
    double q[CK_N], c[CK_N], s[CK_N];
    int valid;
} ck_trig_memo;

typedef struct {
    const ck_chain *ideal;   /* the chain the plan reads */
    const ck_chain *truth;   /* the same joints on the true geometry: the check */
    ck_rt g;                 /* the ideal chain's product of exponentials */
    ck_rt target;            /* the end frame of the chain the solver reads */
    ck_rt pose;              /* the input pose (its rotation projected): what the returned sets must reach */
    const ck_design *design;
    const double *prev;      /* the previous solution in the chain's order, or NULL */
    double free_value;
    unsigned projected;
    int indeterminate;
    double noise;            /* 1 / g of the near-singular orientation the current candidate went through, else 1 */
    double amp;              /* how much its trig stages amplified the input's rounding (ck_root_amplification): the
                              * orientation's family band (Python's amp) */
    int probe;               /* a family's existence probed: candidates verified and counted in hits, not stored */
    int raw;                 /* a calibrated robot's compensation (ck_compensated): candidates checked on the ideal
                              * chain only */
    int hits;
    double q[CK_N];
    double theta[CK_N];      /* the angle of a parallel group (orient), by its first joint */
    double spec[CK_N_OPS][3];/* each op's point or direction on the ideal chain */
    ck_ik_solutions *out;
    ck_trig_memo *memo;      /* the candidates' trig (ck_trig_memo_of) */
} ck_ctx;

static int ck_same(const double *a, const double *b)
{
    int i;
    for (i = 0; i < CK_N; ++i) {
        double d = fabs(a[i] - b[i]);
        if (ck_revolute[i] && d > CK_SAME_TOL) {
            if (fabs(d - CK_TWO_PI) > 1e-6) return 0; /* clearly apart: no wrap brings them together */
            d = fabs(wk_wrap(a[i] - b[i]));
        }
        if (!(d <= CK_SAME_TOL)) return 0;
    }
    return 1;
}

/* A singular orientation family's free angle when no `previous` is given: the first of these (every degree, nearest
 * to 0 first) for which the rest of the decomposition has a verified solution (the Python module's FAMILY_ANGLES) */
#define CK_N_FAMILY 360
static double ck_family_angle(int t)
{
    const int k = (t + 1) / 2;
    return t == 0 ? 0.0 : (t % 2 ? 1.0 : -1.0) * k * CK_PI / 180.0;
}

/* The angle of an orientation op's first unit (one joint, or a parallel group turning as one) at prev. */
static double ck_unit_angle(const ck_chain *ch, const ck_op *op, const double *prev)
{
    const double *u = ch->axis[op->units[0][0]];
    double s = 0.0;
    int m;
    for (m = 0; m < op->unit_len[0]; ++m) {
        const int j = op->units[0][m];
        s += copysign(1.0, ck_dot(u, ch->axis[j])) * prev[j];
    }
    return s;
}

/* Store an orientation op's unit angles: a joint's value, or a parallel group's sum (its first joint's slot). */
static void ck_orient_set(ck_ctx *c, const ck_op *op, const double *angles)
{
    int m;
    for (m = 0; m < op->n_units; ++m) {
        if (op->unit_len[m] == 1)
            c->q[op->units[m][0]] = angles[m];
        else
            c->theta[op->units[m][0]] = angles[m];
    }
}

static void ck_fk_full(const double *q, const ck_design *d, ck_rt *o);

/* A solution of the solver's chain (values in its order) as the description's joint values, wrapped */
static void ck_full_joints(const ck_ctx *c, const double *qc, double *full)
{
    int i;
    for (i = 0; i < CK_N; ++i) full[i] = 0.0;
    for (i = 0; i < c->truth->n; ++i) full[c->truth->index[i]] = qc[i];
#if CK_FREE >= 0
    full[CK_FREE] = c->free_value;
#endif
    for (i = 0; i < CK_N; ++i)
        if (ck_revolute[i]) full[i] = wk_wrap(full[i]);
}

/* The noise of the stages after a three-unit orientation root: 1 / g with g = |u0 x R(u1, t2) u2| (how far the middle
 * unit turns the last axis off the first), at least the outer one (Python: the orient op) */
static double ck_orient_noise(const double *const *u, double t2, double outer)
{
    double r[9], w[3], x[3], g;
    ck_rot(u[1], t2, r);
    ck_mv(r, u[2], w);
    ck_cross(u[0], w, x);
    g = ck_norm(x);
    g = 1.0 / (g > 1e-300 ? g : 1e-300);
    return g > outer ? g : outer;
}

#if CK_CALIBRATED
static void ck_run(ck_ctx *c, int k, const double *x, const double *y, unsigned flags);

/* A candidate of the compensation's solve: stored when the ideal chain reaches its target (Python's take) */
static void ck_raw_candidate(ck_ctx *c)
{
    ck_ik_solutions *out = c->out;
    double qc[CK_N], full[CK_N];
    ck_rt t;
    int i, k;
    if (out->count >= CK_MAX_IK) return;
    for (i = 0; i < c->ideal->n; ++i) qc[i] = c->ideal->prismatic[i] ? c->q[i] : wk_wrap(c->q[i]);
    ck_fk_chain(c->ideal, qc, &t);
    if (!(ck_frame_error(&t, &c->target) <= CK_IK_VERIFY_TOL)) return;
    ck_full_joints(c, qc, full);
    for (k = 0; k < out->count; ++k)
        if (ck_same(full, out->values[k])) return;
    for (i = 0; i < CK_N; ++i) out->values[k][i] = full[i];
    out->valid[k] = 1;
    out->count = k + 1;
}

/* A calibrated robot's candidate whose polish failed (near a singularity the ideal geometry's answer is ~1e-7 /
 * sigma_min off, outside Gauss-Newton's reach): replaced by the ideal chain's solution, nearest qc, of the pose it
 * must reach for the true chain to reach the target at the same joints, target E(qc) with E = F_true(qc)^-1
 * F_ideal(qc) (Python's _compensated). 1 when qc was replaced. */
static int ck_compensated(const ck_ctx *c, double *qc)
{
    ck_ctx r = *c;
    ck_ik_solutions raw;
    ck_rt ti, tt, e;
    double full[CK_N], best = INFINITY, zero[3] = {0.0, 0.0, 0.0};
    int i, k, pick = -1;
    ck_fk_chain(c->ideal, qc, &ti);
    ck_fk_chain(c->truth, qc, &tt);
    ck_inverse(&tt, &e);
    ck_compose(&e, &ti, &e);
    ck_compose(&c->target, &e, &r.target);
    ck_inverse(&c->ideal->home, &r.g);
    ck_compose(&r.target, &r.g, &r.g);
    r.raw = 1;
    r.probe = r.hits = 0;
    r.noise = r.amp = 1.0;
    raw.count = 0;
    r.out = &raw;
    for (i = 0; i < CK_N; ++i) r.q[i] = r.theta[i] = 0.0;
    ck_run(&r, 0, zero, zero, 0u);
    ck_full_joints(c, qc, full);
    for (k = 0; k < raw.count; ++k) {
        double gap = 0.0;
        for (i = 0; i < CK_N; ++i) {
            const double d = ck_revolute[i] ? fabs(wk_wrap(raw.values[k][i] - full[i]))
                                            : fabs(raw.values[k][i] - full[i]);
            if (d > gap) gap = d;
        }
        if (gap < best) {
            best = gap;
            pick = k;
        }
    }
    if (pick < 0) return 0;
    for (i = 0; i < c->truth->n; ++i) qc[i] = raw.values[pick][c->truth->index[i]];
    return 1;
}
#endif

static void ck_trig_of(const double *q, double *c, double *s);

/* cos and sin of the full joints q: the memo's when it holds these joints (equal, signed zeros alike), else taken
 * and kept */
static void ck_trig_memo_of(ck_trig_memo *m, const double *q, double *c, double *s)
{
    int j, same = m->valid;
    for (j = 0; j < CK_N && same; ++j) same = m->q[j] == q[j] && signbit(m->q[j]) == signbit(q[j]);
    if (!same) {
        ck_trig_of(q, m->c, m->s);
        for (j = 0; j < CK_N; ++j) m->q[j] = q[j];
        m->valid = 1;
    }
    for (j = 0; j < CK_N; ++j) {
        c[j] = m->c[j];
        s[j] = m->s[j];
    }
}
static void ck_fk_full_cs(const double *q, const double *c, const double *s, const ck_design *d, ck_rt *o);
#if !CK_REVERSED
static void ck_jacobian_held(const double *full, const double *c, const double *s, double *jac);
#endif

/* A candidate of the plan as it stands, when the module's own FK (the robot's derived kernel, base . chain . tool)
 * reproduces the pose with it (err <= CK_IK_VERIFY_TOL; full, its cos and sin and err set). */
static int ck_candidate_exact(const ck_ctx *c, const double *qc, double *full, double *cs, double *sn, double *err)
{
    ck_rt t;
    ck_full_joints(c, qc, full);
    ck_trig_memo_of(c->memo, full, cs, sn);
    ck_fk_full_cs(full, cs, sn, c->design, &t);
    *err = ck_frame_error(&t, &c->pose);
    return *err <= CK_IK_VERIFY_TOL;
}

#if !CK_REVERSED
/* The solver's chain is the description's with the free joint held: its end frame and Jacobian at qc are the
 * robot's derived kernels' at the full joints (no walk along the chain's table) */
static void ck_held_fk(const void *self, const double *qc, ck_rt *t)
{
    double full[CK_N], cs[CK_N], sn[CK_N], v[12];
    ck_full_joints((const ck_ctx *)self, qc, full);
    ck_trig_memo_of(((const ck_ctx *)self)->memo, full, cs, sn);
    ck_k_fk(full, cs, sn, v);
    ck_from12(v, t);
}

static void ck_held_jacobian(const void *self, const double *qc, double *jac)
{
    double full[CK_N], cs[CK_N], sn[CK_N];
    ck_full_joints((const ck_ctx *)self, qc, full);
    ck_trig_memo_of(((const ck_ctx *)self)->memo, full, cs, sn);
    ck_jacobian_held(full, cs, sn, jac);
}
#endif

/* A candidate's polish on the true chain: through the derived kernels where the solver's chain is the held
 * description, on the reversed chain's table otherwise (t0: its end frame at qc when the caller has it, else NULL) */
static double ck_polish_candidate(const ck_ctx *c, double *qc, const ck_rt *t0)
{
#if CK_REVERSED
    (void)t0;
    return ck_polish(c->truth, qc, &c->target);
#else
    ck_reader r;
    r.fk = ck_held_fk;
    r.jacobian = ck_held_jacobian;
    r.self = c;
    r.n = c->truth->n;
    return ck_polish_read(&r, qc, &c->target, t0);
#endif
}

/* The true solver chain's Jacobian at qc (and its end frame when t is not NULL), the same two readings */
static void ck_candidate_jacobian(const ck_ctx *c, const double *qc, double *jac, ck_rt *t)
{
#if CK_REVERSED
    ck_jacobian_chain(c->truth, qc, jac, t);
#else
    if (t) ck_held_fk(c, qc, t);
    ck_held_jacobian(c, qc, jac);
#endif
}

/* A candidate of the plan: verified (and polished) on the true chain, deduplicated, flagged, stored. */
static void ck_candidate(ck_ctx *c, unsigned flags)
{
    ck_ik_solutions *out = c->out;
    const ck_chain *ch = c->truth;
    double qc[CK_N], full[CK_N], cs[CK_N], sn[CK_N], jac[6 * CK_N], err;
    ck_rt t;
    int i, k, have_jac = 0;
#if CK_CALIBRATED
    if (c->raw) {
        ck_raw_candidate(c);
        return;
    }
#endif
    if (out->count >= CK_MAX_IK) return;
    for (i = 0; i < ch->n; ++i) qc[i] = ch->prismatic[i] ? c->q[i] : wk_wrap(c->q[i]);
    /* the common case first: a set at rounding level (CK_POLISH_TOL) by the module's own FK needs neither the solver
     * chain's check nor a polish. Above it the verdicts stay the two checks' (the solver chain's frame, then the
     * module's): a set near the tolerance passes one and fails the other (a reversed chain reads T^-1's entries),
     * and which one decides whether a family's member verifies (Python's accept) */
    if (!(ck_candidate_exact(c, qc, full, cs, sn, &err) && err <= CK_POLISH_TOL)) {
#if CK_REVERSED
        ck_candidate_jacobian(c, qc, jac, &t); /* one walk of the chain's table gives both */
#else
        ck_held_fk(c, qc, &t); /* the Jacobian at the set kept, below (a polish moves it) */
#endif
        err = ck_frame_error(&t, &c->target);
        /* polished to CK_POLISH_TOL, not merely to the tolerance: near a singularity a set within CK_IK_VERIFY_TOL
         * may be residual / sigma_min off (5e-12 / 1e-6: an offset wrist 1e-6 from its singularity came back 2e-6
         * rad off) */
        if (err > CK_POLISH_TOL) {
            err = ck_polish_candidate(c, qc, &t);
#if CK_CALIBRATED
            if (!(err <= CK_IK_VERIFY_TOL) && ck_compensated(c, qc)) /* once per candidate: no retry loop */
                err = ck_polish_candidate(c, qc, NULL);
#endif
            ck_candidate_jacobian(c, qc, jac, NULL);
        }
#if !CK_REVERSED
        else {
            ck_held_jacobian(c, qc, jac);
        }
#endif
        if (!(err <= CK_IK_VERIFY_TOL)) return;
        have_jac = 1;
        /* the residual reported and checked is the module's own FK (fk_matrix) of the returned set: the solver's
         * chain (held, maybe reversed: T^-1's entries) and base . chain . tool round differently, and the tool's
         * lever scales an orientation error, so a set within the tolerance there can miss it here; such a set is
         * polished on to CK_POLISH_TOL and kept only if it then meets CK_IK_VERIFY_TOL */
        if (!ck_candidate_exact(c, qc, full, cs, sn, &err)) {
            ck_polish_candidate(c, qc, NULL);
            ck_candidate_jacobian(c, qc, jac, NULL);
            if (!ck_candidate_exact(c, qc, full, cs, sn, &err)) return;
        }
    }
    for (k = 0; k < out->count; ++k)
        if (ck_same(full, out->values[k])) return;
    if (c->probe) {
        ++c->hits;
        return;
    }
    /* the solver chain's conditioning: read from the kernel where that chain is the description's with the free
     * joint held (same base and end frame), from the reversed chain's table otherwise */
    if (!have_jac) {
#if CK_REVERSED
        ck_jacobian_chain(ch, qc, jac, NULL);
#else
        ck_jacobian_held(full, cs, sn, jac);
#endif
    }
    if (ck_is_singular(jac, ch->n)) flags |= WK_FLAG_SINGULAR_INVERSE;
    k = out->count;
    for (i = 0; i < CK_N; ++i) out->values[k][i] = full[i];
    out->valid[k] = 1;
    out->flags[k] = flags | c->projected;
    out->aux[k][0] = err;
    if (flags & WK_FLAG_INDETERMINATE) c->indeterminate = 1;
    out->count = k + 1;
}

/* Sets stored so far (while probing: sets that would be) */
static int ck_count(const ck_ctx *c)
{
    return c->probe ? c->hits : c->out->count;
}

/* The bands a trig stage runs its roots at, in order (Python's _with_split): the noise-widened one; where that merged
 * two roots into one (wide: 1 root flagged double) that the stage's own band separates (own: 2 roots), that band
 * next, run only when the merged root verified nothing. Returns the number of passes. */
static int ck_stage_bands(const ck_ctx *c, int nr_wide, const unsigned *f_wide, int nr_own, double *bands)
{
    bands[0] = c->noise;
    if (c->noise > 1.0 && nr_wide == 1 && (f_wide[0] & WK_FLAG_DOUBLE_ROOT) && nr_own == 2) {
        bands[1] = 1.0;
        return 2;
    }
    return 1;
}

/* gp = (product of the joints before lo)^-1 g (product of the joints after hi)^-1 */
static void ck_reduced(const ck_ctx *c, int lo, int hi, ck_rt *gp)
{
    ck_rt a;
    ck_product(c->ideal, c->q, 0, lo, &a);
    ck_inverse(&a, &a);
    ck_compose(&a, &c->g, gp);
    ck_product(c->ideal, c->q, hi + 1, c->ideal->n, &a);
    ck_inverse(&a, &a);
    ck_compose(gp, &a, gp);
}

static void ck_run(ck_ctx *c, int k, const double *x, const double *y, unsigned flags);

/* Where a singular family's free angle goes: one joint (subproblem 6's q5), or an orientation op's first unit */
typedef struct {
    int joint;               /* >= 0: that joint; -1: the orientation op below */
    const ck_op *op;
    int nu;
    const double *const *u;
    const double *rd;
    double t2;
} ck_place;

static void ck_place_angle(ck_ctx *c, const ck_place *p, double angle)
{
    double angles[3];
    if (p->joint >= 0) {
        c->q[p->joint] = angle;
        return;
    }
    ck_orient_rest(p->nu, p->u, p->rd, -angle, p->t2, angles);
    ck_orient_set(c, p->op, angles);
}

/* A singular family from op k on (Python's run_family): without `previous`, the first of ck_family_angle(t) with a
 * verified set; with it, the family is kept exactly where it is kept without it (the grid probed first: previous
 * picks the member, never whether the family or the split roots are returned), as previous's member when that
 * verifies, else the grid's. */
static void ck_run_family(ck_ctx *c, int k, const double *x, const double *y, unsigned flags, const ck_place *p,
                          const double *prev_angle)
{
    int t, before;
    if (prev_angle && !c->probe) {
        c->probe = 1;
        c->hits = 0;
        for (t = 0; t < CK_N_FAMILY && c->hits == 0; ++t) {
            ck_place_angle(c, p, ck_family_angle(t));
            ck_run(c, k + 1, x, y, flags);
        }
        c->probe = 0;
        if (c->hits == 0) return;
        before = c->out->count;
        ck_place_angle(c, p, *prev_angle);
        ck_run(c, k + 1, x, y, flags);
        if (c->out->count == before) { /* previous's member verifies nothing: the grid's, found by the probe */
            ck_place_angle(c, p, ck_family_angle(t - 1));
            ck_run(c, k + 1, x, y, flags);
        }
        return;
    }
    for (t = 0; t < CK_N_FAMILY; ++t) {
        before = ck_count(c);
        ck_place_angle(c, p, ck_family_angle(t));
        ck_run(c, k + 1, x, y, flags);
        if (ck_count(c) > before) break;
    }
}
#if CK_HAS_SP6

/* subproblem 6's inputs at one op: its joints, direction, the points and constant of the first equation, g = Rg h5 */
typedef struct {
    int j0, j4, j5;
    const double *n;
    double p0[3], p4[3], d0, g[3];
} ck_sp6_in;

/* One candidate (q0, q4) of subproblem 6: q5 from the group's invariant, then the rest of the plan; a merged
 * near-double root that verified nothing is split into its two roots (may_split: not a split root itself) */
static void ck_sp6_set(ck_ctx *c, int k, const double *x, const double *y, unsigned flags, const ck_sp6_in *in,
                       double q0, double q4, unsigned f, int order, int may_split)
{
    const ck_chain *ch = c->ideal;
    const double *h0 = ch->axis[in->j0], *h4 = ch->axis[in->j4], *h5 = ch->axis[in->j5];
    double r0[9], rt[9], r4[9], m[9], a[3], b[3], t5 = 0.0, s0[2], s4[2];
    const int before = ck_count(c);
    int i, ns;
    /* the group keeps n: n^T R4 R5 = n^T R0^T Rg, so rot(h5, -q5) (R4^T n) = (R0^T Rg)^T n */
    ck_rot(h0, q0, r0);
    ck_transpose(r0, rt);
    ck_mm(rt, c->g.r, m);
    ck_rot(h4, q4, r4);
    ck_mtv(r4, in->n, a);
    ck_mtv(m, in->n, b);
    c->q[in->j0] = q0;
    c->q[in->j4] = q4;
    if (ck_sp1(h5, a, b, 1.0, &t5)) {
        /* near the wrist singularity q5 carries q4's error over g = |h5 x R4^T n|: eps / g^2 after the quartic
         * (order 2), eps / g after the split (order 1); the later stages' bands grow by as much (Python's
         * sp6_set) */
        const double outer = c->noise;
        double cr[3], gg;
        ck_cross(h5, a, cr);
        gg = ck_norm(cr);
        c->q[in->j5] = -t5;
        c->noise = fmax(outer, 1.0 / fmax(order == 1 ? gg : gg * gg, 1e-300));
        ck_run(c, k + 1, x, y, flags | f);
        c->noise = outer;
    } else {
        /* the wrist singularity: joint j5 and the group turn about one direction (a family); its angle from
         * `previous` or the grid (ck_run_family: it moves the position) */
        ck_place p;
        p.joint = in->j5;
        p.op = NULL;
        p.nu = 0;
        p.u = NULL;
        p.rd = NULL;
        p.t2 = 0.0;
        ck_run_family(c, k, x, y, flags | f | WK_FLAG_INDETERMINATE | WK_FLAG_SINGULAR_INVERSE, &p,
                      c->prev ? &c->prev[in->j5] : NULL);
    }
    if (ck_count(c) > before || !may_split || !(f & WK_FLAG_SINGULAR_INVERSE)) return;
    /* a merged near-double root that verified nothing: the two roots it merged */
    ns = ck_sp6_split(in->n, h0, in->p0, h4, in->p4, in->d0, in->g, h5, q0, q4, s0, s4);
    for (i = 0; i < ns; ++i)
        ck_sp6_set(c, k, x, y, flags, in, s0[i], s4[i],
                   (f & ~WK_FLAG_DOUBLE_ROOT) | wk_sp6_merged(ns) | WK_FLAG_SINGULAR_INVERSE, 1, 0);
}
#endif

/* Op k and everything after it, for each root: x the point the joints place (moved by the solved last joints),
 * y its image (moved back by the solved first joints). */
static void ck_run(ck_ctx *c, int k, const double *x, const double *y, unsigned flags)
{
    const ck_chain *ch = c->ideal;
    const ck_op *op;
    if (c->out->count >= CK_MAX_IK) return;
    if (k == CK_N_OPS) {
        ck_candidate(c, flags);
        return;
    }
    op = &ck_plan[k];
    switch (op->op) {
    case CK_BEGIN: {
        ck_rt gp;
        double yy[3];
        ck_reduced(c, op->lo, op->hi, &gp);
        ck_apply(&gp, c->spec[k], yy);
        ck_run(c, k + 1, c->spec[k], yy, flags);
        break;
    }
    case CK_FIRST_PLANE:
    case CK_LAST_PLANE: {
        const int first = op->op == CK_FIRST_PLANE, j = op->j;
        const double *nv = c->spec[k], *h = ch->axis[j], *r = ch->point[j];
        double d[3], d2[3], moved[3], t[2], t2[2], outer, bands[2];
        unsigned f2[2];
        int pass, npass, before;
        unsigned f[2];
        int nr, i;
        if (op->prismatic) {
            const double den = ck_dot(nv, h);
            double v;
            if (!(fabs(den) > 0.0)) return;
            ck_sub(y, x, d);
            v = ck_dot(nv, d) / den;
            c->q[j] = v;
            ck_scale(h, v, d);
            if (first) {
                ck_sub(y, d, moved);
                ck_run(c, k + 1, x, moved, flags);
            } else {
                ck_add(x, d, moved);
                ck_run(c, k + 1, moved, y, flags);
            }
            return;
        }
        if (first) { /* n . rot(h, -q)(y - r) = n . (x - r) */
            ck_sub(y, r, d);
            ck_sub(x, r, d2);
        } else { /* n . rot(h, q)(x - r) = n . (y - r) */
            ck_sub(x, r, d);
            ck_sub(y, r, d2);
        }
        before = ck_count(c);
        nr = ck_sp4(nv, h, d, ck_dot(nv, d2), CK_SCALE, c->noise, t, f);
        npass = ck_stage_bands(c, nr, f, c->noise > 1.0 ? ck_sp4(nv, h, d, ck_dot(nv, d2), CK_SCALE, 1.0, t2, f2) : 0,
                               bands);
        for (pass = 0; pass < npass && !(pass && ck_count(c) > before); ++pass) {
            nr = ck_sp4(nv, h, d, ck_dot(nv, d2), CK_SCALE, bands[pass], t, f);
            if (first)
                for (i = 0; i < nr; ++i) t[i] = -t[i];
            outer = c->amp;
            c->amp = ck_root_amplification(nr, t, f, outer);
            for (i = 0; i < nr; ++i) {
                ck_rt e;
                c->q[j] = t[i];
                ck_screw(0, h, r, t[i], &e);
                if (first) {
                    ck_inverse(&e, &e);
                    ck_apply(&e, y, moved);
                    ck_run(c, k + 1, x, moved, flags | f[i]);
                } else {
                    ck_apply(&e, x, moved);
                    ck_run(c, k + 1, moved, y, flags | f[i]);
                }
            }
            c->amp = outer;
        }
        break;
    }
    case CK_FIRST_DIST:
    case CK_LAST_DIST: {
        const int first = op->op == CK_FIRST_DIST, j = op->j;
        const double *s = c->spec[k], *h = ch->axis[j], *r = ch->point[j];
        const double *moving = first ? y : x, *other = first ? x : y;
        double d3[3], ms[3], sr[3], mr[3], moved[3], dist, t[2], t2[2], outer, bands[2];
        const double *tg;
        unsigned f2[2];
        int pass, npass, before;
        unsigned f[2];
        int nr, i;
        ck_sub(other, s, d3);
        dist = ck_norm(d3);
        if (op->prismatic) { /* |moving -+ v h - s| = d: a quadratic in v */
            double b, cc, disc;
            ck_sub(moving, s, ms);
            b = ck_dot(h, ms) * (first ? -1.0 : 1.0);
            cc = ck_dot(ms, ms) - dist * dist;
            disc = b * b - cc;
            if (disc < -CK_TANGENT_TOL * CK_SCALE * CK_SCALE) return;
            if (disc <= CK_DOUBLE_ROOT_TOL * CK_SCALE * CK_SCALE) {
                t[0] = -b;
                f[0] = WK_FLAG_DOUBLE_ROOT | WK_FLAG_SINGULAR_INVERSE;
                nr = 1;
            } else {
                t[0] = -b + sqrt(disc);
                t[1] = -b - sqrt(disc);
                f[0] = f[1] = 0u;
                nr = 2;
            }
            for (i = 0; i < nr; ++i) {
                double hv[3];
                c->q[j] = t[i];
                ck_scale(h, t[i], hv);
                if (first) {
                    ck_sub(y, hv, moved);
                    ck_run(c, k + 1, x, moved, flags | f[i]);
                } else {
                    ck_add(x, hv, moved);
                    ck_run(c, k + 1, moved, y, flags | f[i]);
                }
            }
            return;
        }
        ck_sub(moving, r, mr);
        ck_sub(s, r, sr);
        before = ck_count(c);
        tg = op->planar ? d3 : NULL; /* the parts normal to h: a sum of squares (ck_sp3) */
        nr = ck_sp3(h, mr, sr, dist, CK_SCALE, c->noise, tg, c->amp, t, f);
        npass = ck_stage_bands(c, nr, f, c->noise > 1.0 ? ck_sp3(h, mr, sr, dist, CK_SCALE, 1.0, tg, c->amp, t2, f2) : 0,
                               bands);
        for (pass = 0; pass < npass && !(pass && ck_count(c) > before); ++pass) {
            nr = ck_sp3(h, mr, sr, dist, CK_SCALE, bands[pass], tg, c->amp, t, f);
            outer = c->amp;
            c->amp = ck_root_amplification(nr, t, f, outer);
            for (i = 0; i < nr; ++i) {
                ck_rt e;
                const double tt = first ? -t[i] : t[i];
                c->q[j] = tt;
                ck_screw(0, h, r, tt, &e);
                if (first) {
                    ck_inverse(&e, &e);
                    ck_apply(&e, y, moved);
                    ck_run(c, k + 1, x, moved, flags | f[i]);
                } else {
                    ck_apply(&e, x, moved);
                    ck_run(c, k + 1, moved, y, flags | f[i]);
                }
            }
            c->amp = outer;
        }
        break;
    }
    case CK_PAIR: { /* rot_j rot_k (x - s) = y - s */
        const double *s = c->spec[k];
        double ys[3], xs[3], t1[2], t2[2];
        unsigned f[2];
        int has1[2], nr, i, split;
        const int before = ck_count(c);
        ck_sub(y, s, ys);
        ck_sub(x, s, xs);
        for (split = 0; split < 2; ++split) { /* a near-double root's two roots when its merged one verified nothing */
            if (split && ck_count(c) > before) break;
            nr = ck_sp2(ys, ch->axis[op->j], xs, ch->axis[op->k], CK_SCALE, split, 1.0, CK_ON_AXIS_TOL, t1, has1, t2,
                        f);
            for (i = 0; i < nr; ++i) {
                c->q[op->j] = has1[i] ? -t1[i] : (c->prev ? c->prev[op->j] : 0.0);
                c->q[op->k] = t2[i];
                ck_run(c, k + 1, x, y, flags | f[i]);
            }
        }
        break;
    }
    case CK_SINGLE: {
        const int j = op->j;
        const double *h = ch->axis[j], *r = ch->point[j];
        double xr[3], yr[3], t;
        if (op->prismatic) {
            ck_sub(y, x, xr);
            c->q[j] = ck_dot(h, xr);
            ck_run(c, k + 1, x, y, flags);
            return;
        }
        ck_sub(x, r, xr);
        ck_sub(y, r, yr);
        /* on the axis (a shoulder family) at CK_ON_AXIS_TOL of the chain's size (Python's "single" op) */
        if (!ck_sp1(h, xr, yr, CK_SCALE * (CK_ON_AXIS_TOL / CK_DEGENERATE_EPS), &t)) {
            c->q[j] = c->prev ? c->prev[j] : 0.0;
            ck_run(c, k + 1, x, y, flags | WK_FLAG_INDETERMINATE | WK_FLAG_SINGULAR_INVERSE);
        } else {
            c->q[j] = t;
            ck_run(c, k + 1, x, y, flags);
        }
        break;
    }
#if CK_HAS_SP6
    case CK_SP6: { /* subproblem 6: joints j and k from the group's invariants, then js[0] about the group's axis */
        const double *n = c->spec[k];
        ck_sp6_in in;
        double q0[CK_SP6_MAX], q4[CK_SP6_MAX];
        unsigned f6[CK_SP6_MAX];
        int i, nr, o6[CK_SP6_MAX];
        in.j0 = op->j;
        in.j4 = op->k;
        in.j5 = op->js[0];
        in.n = n;
        ck_sub(y, ch->point[in.j0], in.p0);
        ck_sub(x, ch->point[in.j4], in.p4);
        in.d0 = ck_dot(n, ch->point[in.j4]) - ck_dot(n, ch->point[in.j0]);
        ck_mv(c->g.r, ch->axis[in.j5], in.g);
        nr = ck_sp6(n, ch->axis[in.j0], in.p0, ch->axis[in.j4], in.p4, in.d0, 0.0, in.g, ch->axis[in.j5], q0, q4,
                    f6, o6);
        for (i = 0; i < nr; ++i) ck_sp6_set(c, k, x, y, flags, &in, q0[i], q4[i], f6[i], o6[i], 1);
        break;
    }
#endif
#if CK_HAS_SPATIAL3
    case CK_SPATIAL3: { /* three revolute axes in general position: every real root of the polynomial */
        double qa[WK_S3_MAX], qb[WK_S3_MAX], qc[WK_S3_MAX];
        unsigned f3[WK_S3_MAX];
        int i, nr = ck_spatial3(ch, op->js[0], op->js[1], op->js[2], x, y, qa, qb, qc, f3);
        for (i = 0; i < nr; ++i) {
            c->q[op->js[0]] = qa[i];
            c->q[op->js[1]] = qb[i];
            c->q[op->js[2]] = qc[i];
            ck_run(c, k + 1, x, y, flags | f3[i]);
        }
        break;
    }
#endif
#if CK_HAS_ARM_ANGLE
    case CK_ARM_ANGLE: { /* the shoulder and the elbow from the wrist centre y and the design's arm angle */
        double sets[4][4];
        unsigned fa[4];
        int i, nr = ck_arm_angle(ch, op, c->spec[k], x, y, c->design->params[0], c->prev, sets, fa);
        for (i = 0; i < nr; ++i) {
            c->q[op->js[0]] = sets[i][0];
            c->q[op->js[1]] = sets[i][1];
            c->q[op->js[2]] = sets[i][2];
            c->q[op->j] = sets[i][3];
            ck_run(c, k + 1, x, y, flags | fa[i]);
        }
        break;
    }
#endif
#if CK_HAS_GENERAL6R
    case CK_GENERAL6R: { /* no decomposition: the general 6R by elimination (wk_general6r.c), every candidate */
        double axes[18], points[18], frames[96], g4[16], cand[WK_G6_MAX_CANDIDATES * 6];
        static const double id4[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
        int i, m, nr;
        for (i = 0; i < 6; ++i)
            for (m = 0; m < 3; ++m) {
                axes[3 * i + m] = ch->axis[i][m];
                points[3 * i + m] = ch->point[i][m];
            }
        wk_g6_z_frames(axes, points, frames);
        for (i = 0; i < 3; ++i) { /* the product of exponentials as a 4 x 4 (the home frame is removed) */
            for (m = 0; m < 3; ++m) g4[4 * i + m] = c->g.r[3 * i + m];
            g4[4 * i + 3] = c->g.t[i];
        }
        g4[12] = g4[13] = g4[14] = 0.0;
        g4[15] = 1.0;
        nr = wk_g6_solve(frames, id4, g4, op->j, op->lo, op->k, cand, WK_G6_MAX_CANDIDATES);
        for (i = 0; i < nr; ++i) {
            for (m = 0; m < 6; ++m) c->q[m] = cand[6 * i + m];
            ck_run(c, k + 1, x, y, flags);
        }
        break;
    }
#endif
    case CK_LINEAR: { /* x + sum q_i h_i = y: least squares over the slides */
        double a[3 * 3], b[3], sol[3];
        int i, r;
        ck_sub(y, x, b);
        for (r = 0; r < 3; ++r)
            for (i = 0; i < op->n_js; ++i) a[r * op->n_js + i] = ch->axis[op->js[i]][r];
        ck_lstsq(a, 3, op->n_js, b, sol);
        for (i = 0; i < op->n_js; ++i) c->q[op->js[i]] = sol[i];
        ck_run(c, k + 1, x, y, flags);
        break;
    }
    case CK_ORIENT: {
        const int nu = op->n_units;
        const double *u[3];
        double t1[2], t2[2], rv[3];
        unsigned f[2];
        int has1[2], ns, i;
        const int before_op = ck_count(c);
        ck_rt gp;
        ck_reduced(c, op->lo, op->hi, &gp);
        for (i = 0; i < nu; ++i) u[i] = ch->axis[op->units[i][0]];
        if (nu == 3) {
            ck_mv(gp.r, u[2], rv);
            ns = ck_sp2(rv, u[0], u[2], u[1], 1.0, 0, c->amp, CK_FAMILY_TOL, t1, has1, t2, f);
        } else if (nu == 2) {
            double a = 0.0;
            ck_mv(gp.r, u[1], rv);
            has1[0] = ck_sp1(u[0], u[1], rv, 1.0, &a);
            t1[0] = has1[0] ? -a : 0.0;
            t2[0] = 0.0;
            f[0] = 0u;
            ns = 1;
        } else {
            t1[0] = t2[0] = 0.0;
            has1[0] = 1;
            f[0] = 0u;
            ns = 1;
        }
        for (i = 0; i < ns; ++i) {
            double angles[3], w[3], rw[3], a = 0.0;
            if (nu == 1) {
                ck_perpendicular(u[0], w);
                ck_mv(gp.r, w, rw);
                angles[0] = ck_sp1(u[0], w, rw, 1.0, &a) ? a : 0.0;
                ck_orient_set(c, op, angles);
                ck_run(c, k + 1, x, y, flags | f[i]);
            } else if (has1[i]) {
                const double outer = c->noise;
                ck_orient_rest(nu, u, gp.r, t1[i], t2[i], angles);
                ck_orient_set(c, op, angles);
                if (nu == 3) c->noise = ck_orient_noise(u, t2[i], outer);
                ck_run(c, k + 1, x, y, flags | f[i]);
                c->noise = outer;
            } else {
                /* a singular family (the first and last axes line up): the first unit's angle is free. With
                 * `previous`, its angle there; else the first of ck_family_angle(t) for which the rest of the
                 * decomposition has a verified solution (the position may depend on it: a parallel group). */
                ck_place p;
                const double prev_angle = c->prev ? ck_unit_angle(ch, op, c->prev) : 0.0;
                p.joint = -1;
                p.op = op;
                p.nu = nu;
                p.u = u;
                p.rd = gp.r;
                p.t2 = t2[i];
                ck_run_family(c, k, x, y, flags | f[i], &p, c->prev ? &prev_angle : NULL);
            }
        }
        if (nu == 3 && ck_count(c) == before_op) {
            /* near (not at) the singular family the merged root is a family that verifies nothing: its two roots
             * are two sets with every angle defined */
            ns = ck_sp2(rv, u[0], u[2], u[1], 1.0, 1, c->amp, CK_FAMILY_TOL, t1, has1, t2, f);
            for (i = 0; i < ns; ++i) {
                double angles[3];
                const double outer = c->noise;
                ck_orient_rest(nu, u, gp.r, t1[i], t2[i], angles);
                ck_orient_set(c, op, angles);
                c->noise = ck_orient_noise(u, t2[i], outer);
                ck_run(c, k + 1, x, y, flags | f[i]);
                c->noise = outer;
            }
        }
        break;
    }
    case CK_GROUP_REST: { /* rotations about parallel axes add: the last is the sum minus the others */
        const double *u = ch->axis[op->js[0]];
        double acc = 0.0, rest;
        int i;
        for (i = 0; i < op->n_js; ++i) {
            const int m = op->js[i];
            if (m != op->j) acc = acc + copysign(1.0, ck_dot(u, ch->axis[m])) * c->q[m];
        }
        rest = c->theta[op->js[0]] - acc;
        c->q[op->j] = rest * copysign(1.0, ck_dot(u, ch->axis[op->j]));
        ck_run(c, k + 1, x, y, flags);
        break;
    }
    default:
        break;
    }
}

