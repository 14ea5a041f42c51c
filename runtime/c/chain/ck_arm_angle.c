/* The arm angle of a 7R arm with a spherical shoulder and a spherical wrist (an S-R-S arm: the iiwa's) as the
 * redundancy parameter: the op CK_ARM_ANGLE sets the shoulder joints js[0..2] and the elbow j for the wrist
 * centre the previous op placed and the design's arm angle psi (Python: chain_arm_angle.py, step for step).
 * psi is where the elbow is on its circle about the shoulder-wrist line: 0 in the plane of that line and the first
 * joint's axis, on the side the axis points to; positive turning about the line from the shoulder to the wrist.
 * (a wristkin runtime source, inlined into a user robot's generated C when its plan has the op, after the robot's
 * CK_* constants; derive/runtime_files.py, tests/test_chain_runtime.py) */
/* ------------------------------------------------------------------ the arm angle (an S-R-S arm) */
/* u: the unit from the shoulder centre s to the wrist centre w; n1: the first axis h1's part normal to u, unit
 * (psi = 0 there); n2 = u x n1. Returns WK_FLAG_INDETERMINATE when w lies on the first axis (any n1 normal to u),
 * 0 otherwise, -1 when w = s. */
static int ck_arm_plane(const double *h1, const double *s, const double *w, double *u, double *n1, double *n2)
{
    double sw[3], m;
    int flags = 0;
    ck_sub(w, s, sw);
    m = ck_norm(sw);
    if (!(m > 0.0)) return -1;
    ck_scale(sw, 1.0 / m, u);
    ck_scale(u, ck_dot(h1, u), n1);
    ck_sub(h1, n1, n1);
    m = ck_norm(n1);
    if (!(m > CK_ON_AXIS_TOL)) {
        ck_perpendicular(u, n1);
        flags = (int)WK_FLAG_INDETERMINATE;
    } else {
        ck_scale(n1, 1.0 / m, n1);
    }
    ck_cross(u, n1, n2);
    return flags;
}

/* psi of an elbow point e (shoulder s, wrist w, first axis h1; axis: the elbow axis's direction there). With the
 * elbow on the line (stretched or folded) the side is axis x u, as the stage reads it there (Python's
 * _arm_angle_of) */
static double ck_arm_angle_of(const double *h1, const double *s, const double *e, const double *w,
                              const double *axis)
{
    double u[3], n1[3], n2[3], side[3], along[3];
    if (ck_arm_plane(h1, s, w, u, n1, n2) < 0) return 0.0;
    ck_sub(e, s, side);
    ck_scale(u, ck_dot(side, u), along);
    ck_sub(side, along, side);
    if (!(ck_norm(side) > CK_DOUBLE_ROOT_TOL * CK_SCALE)) ck_cross(axis, u, side);
    return atan2(ck_dot(side, n2), ck_dot(side, n1));
}

/* The elbow point: on the elbow axis je, nearest the shoulder centre s (Python's _elbow_point) */
static void ck_elbow_point(const ck_chain *ch, int je, const double *s, double *o)
{
    double se[3];
    ck_sub(s, ch->point[je], se);
    ck_scale(ch->axis[je], ck_dot(ch->axis[je], se), o);
    ck_add(ch->point[je], o, o);
}

/* r = the rotation with columns a, b, a x b (row-major) */
static void ck_frame_of(const double *a, const double *b, double *r)
{
    double c[3];
    int i;
    ck_cross(a, b, c);
    for (i = 0; i < 3; ++i) {
        r[3 * i] = a[i];
        r[3 * i + 1] = b[i];
        r[3 * i + 2] = c[i];
    }
}

/* The op's sets: out[m] = (q_a, q_b, q_c, q_e) with flags[m], at most 4 (two elbows x two shoulders); x the wrist
 * centre at home, w its target, s the shoulder centre. The elbow from |e_e x - s| = |w - s| (subproblem 3); the
 * shoulder's rotation about s maps the home side's frame (s -> the turned wrist centre, and that line's unit to
 * the elbow point) onto the target's (s -> w, the side psi gives); subproblem 2 then 1 read the shoulder from it
 * (q_b = 0 lines up a and c: a family, q_a from prev else 0). */
static int ck_arm_angle(const ck_chain *ch, const ck_op *op, const double *s, const double *x, const double *w,
                        double psi, const double *prev, double out[4][4], unsigned *flags)
{
    const int ja = op->js[0], jb = op->js[1], jc = op->js[2], je = op->j;
    const double *ha = ch->axis[ja], *hb = ch->axis[jb], *hc = ch->axis[jc], *he = ch->axis[je], *pe = ch->point[je];
    const double *const units[3] = {ha, hb, hc};
    double u[3], n1[3], n2[3], side[3], target[9], elbow[3], xe[3], se[3], sw[3], te[2], length, tmp[3];
    unsigned fe[2];
    int plane, ne, i, count = 0;
    ck_sub(w, s, sw);
    length = ck_norm(sw);
    plane = ck_arm_plane(ha, s, w, u, n1, n2);
    if (plane < 0) return 0;
    ck_scale(n1, cos(psi), side);
    ck_scale(n2, sin(psi), tmp);
    ck_add(side, tmp, side);
    ck_frame_of(u, side, target);
    ck_elbow_point(ch, je, s, elbow);
    ck_sub(s, pe, se);
    ck_sub(x, pe, xe);
    ne = ck_sp3(he, xe, se, length, CK_SCALE, 1.0, NULL, 1.0, te, fe);
    if (ne == 1 && (fe[0] & WK_FLAG_DOUBLE_ROOT)) {
        /* the arm (nearly) stretched or folded: the merged roots are the elbow bent to either side of the line,
         * where the shoulder and wrist differ by a half turn: both sides, a band's width off the line (Python's
         * _arm_angle_stage) */
        const double band = sqrt(CK_DOUBLE_ROOT_TOL);
        te[1] = te[0] - band;
        te[0] += band;
        fe[1] = fe[0];
        ne = 2;
    }
    for (i = 0; i < ne; ++i) {
        ck_rt e;
        double v[3], off[3], home_side[3], home[9], r[9], rc[3], t1[2], t2[2];
        unsigned f = fe[i], f2[2];
        int has1[2], ns, m;
        ck_screw(0, he, pe, te[i], &e);
        ck_apply(&e, x, v);
        ck_sub(v, s, v);
        ck_scale(v, 1.0 / ck_norm(v), v);
        ck_sub(elbow, s, off);
        ck_scale(v, ck_dot(off, v), tmp);
        ck_sub(off, tmp, off);
        if (ck_norm(off) > CK_DOUBLE_ROOT_TOL * CK_SCALE) {
            ck_scale(off, 1.0 / ck_norm(off), home_side);
        } else { /* stretched or folded: the elbow on the line, any turn about it the same pose */
            ck_cross(he, v, home_side);
            ck_scale(home_side, 1.0 / ck_norm(home_side), home_side);
            f |= WK_FLAG_DOUBLE_ROOT | WK_FLAG_SINGULAR_INVERSE;
        }
        /* r = target home^T: home's transpose has rows v, home_side, v x home_side */
        ck_cross(v, home_side, home + 6);
        for (m = 0; m < 3; ++m) {
            home[m] = v[m];
            home[3 + m] = home_side[m];
        }
        ck_mm(target, home, r);
        ck_mv(r, hc, rc);
        ns = ck_sp2(rc, ha, hc, hb, 1.0, 0, 1.0, CK_FAMILY_TOL, t1, has1, t2, f2);
        for (m = 0; m < ns && count < 4; ++m) {
            unsigned g = f2[m];
            if (!has1[m]) { /* a and c line up: the family's q_a from prev, else 0 */
                t1[m] = -(prev ? prev[ja] : 0.0);
                g |= WK_FLAG_INDETERMINATE | WK_FLAG_SINGULAR_INVERSE;
            }
            ck_orient_rest(3, units, r, t1[m], t2[m], out[count]); /* as the orientation op reads its units */
            out[count][3] = te[i];
            flags[count] = f | g | (unsigned)plane;
            ++count;
        }
    }
    return count;
}

/* The arm angle of joint values (Python's arm_angle), on the ideal chain the op reads: where the joints put the
 * elbow point on its circle about the shoulder-wrist line. */
static int ck_api_arm_angle(const double *joints, const void *design, double *psi)
{
    const ck_chain *ch = &ck_ideal_chain;
    const ck_op *op = &ck_plan[1]; /* arm_angle_plan: begin, arm_angle, orient */
    const int wrist[3] = {op->j + 1, op->j + 2, op->j + 3};
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
    *psi = ck_arm_angle_of(ch->axis[op->js[0]], s, e, w, axis);
    return WK_OK;
}
