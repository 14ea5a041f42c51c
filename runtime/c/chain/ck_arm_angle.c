/* The arm angle of an S-R-S arm (the iiwa's) as the redundancy parameter, for the interpreted plan's op
 * CK_ARM_ANGLE: the chain-free core wk_arm_angle.c (inlined before it) on the chain's axes with the chain's
 * tolerances; it sets the shoulder joints js[0..2] and the elbow j for the wrist centre the previous op placed and
 * the design's arm angle psi (Python: chain_arm_angle.py).
 * (a wristkin runtime source, inlined into a user robot's generated C when its plan has the op, after the robot's
 * CK_* constants; derive/families/chain/views.py, tests/test_arm_angle.py) */
/* the core's tolerances: the chain's */
static wk_aa_tols ck_aa_tols(void)
{
    wk_aa_tols t;
    t.scale = CK_SCALE;
    t.degenerate = CK_DEGENERATE_EPS;
    t.double_root = CK_DOUBLE_ROOT_TOL;
    t.tangent = CK_TANGENT_TOL;
    t.on_axis = CK_ON_AXIS_TOL;
    t.family = CK_FAMILY_TOL;
    return t;
}

/* The elbow point: on the elbow axis je, nearest the shoulder centre s (Python's _elbow_point) */
static void ck_elbow_point(const ck_chain *ch, int je, const double *s, double *o)
{
    double se[3];
    ck_sub(s, ch->point[je], se);
    ck_scale(ch->axis[je], ck_dot(ch->axis[je], se), o);
    ck_add(ch->point[je], o, o);
}

/* The op's sets: out[m] = (q_a, q_b, q_c, q_e) with flags[m], at most 4 (wk_arm_angle); x the wrist centre at home,
 * w its target, s the shoulder centre */
static int ck_arm_angle(const ck_chain *ch, const ck_op *op, const double *s, const double *x, const double *w,
                        double psi, const double *prev, double out[4][4], unsigned *flags)
{
    const wk_aa_tols t = ck_aa_tols();
    const int ja = op->js[0];
    return wk_arm_angle(ch->axis[ja], ch->axis[op->js[1]], ch->axis[op->js[2]], s, ch->axis[op->j], ch->point[op->j],
                        x, w, psi, prev ? &prev[ja] : NULL, NULL, &t, out, flags);
}

/* The arm angle of joint values (Python's arm_angle), on the ideal chain the op reads: where the joints put the
 * elbow point on its circle about the shoulder-wrist line. */
static int ck_api_arm_angle(const double *joints, const void *design, double *psi)
{
    const ck_chain *ch = &ck_ideal_chain;
    const ck_op *op = &ck_plan[1]; /* arm_angle_plan: begin, arm_angle, orient */
    const int wrist[3] = {op->j + 1, op->j + 2, op->j + 3};
    const wk_aa_tols tol = ck_aa_tols();
    double s[3], w0[3], elbow[3], e[3], w[3], axis[3];
    ck_rt shoulder, t;
    int i;
    (void)design;
    if (!joints || !psi) return WK_ERR_NULL;
    if (!wk_all_finite(joints, CK_N)) return WK_ERR_NONFINITE;
    ck_point(ch, op, s);
    ck_meet(ch, wrist, 3, w0);
    ck_elbow_point(ch, op->j, s, elbow);
    ck_identity(&shoulder);
    for (i = 0; i < 3; ++i) {
        ck_screw(0, ch->axis[op->js[i]], ch->point[op->js[i]], joints[op->js[i]], &t);
        ck_compose(&shoulder, &t, &shoulder);
    }
    ck_apply(&shoulder, elbow, e);
    ck_mv(shoulder.r, ch->axis[op->j], axis);
    ck_screw(0, ch->axis[op->j], ch->point[op->j], joints[op->j], &t);
    ck_compose(&shoulder, &t, &t);
    ck_apply(&t, w0, w);
    *psi = wk_aa_angle_of(ch->axis[op->js[0]], s, e, w, axis, &tol);
    return WK_OK;
}
