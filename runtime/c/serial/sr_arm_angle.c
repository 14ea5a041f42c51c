/* An S-R-S arm's arm_angle stage (the shoulder's three joints and the elbow for the wrist centre's target and the
 * arm angle psi, the design's; wk_arm_angle.c, inlined before it), or its held_elbow stage (the elbow held: the
 * shoulder at previous's arm angle), on the axes, centres and points its derived kernel gives. The sets are computed
 * once per prefix of the set index above the stage's bits and kept in the call's scratch (sr_ws); set k takes set
 * (k >> shift) & 3 (two elbows x two shoulders; the held elbow's (k >> shift) & 1). The wrist's stage follows; the FK check
 * verifies each set. And the module's arm_angle verb: the arm angle of joint values, read on the points its derived
 * reader kernel (sr_k_arm_angle_parts) places.
 * (a wristkin runtime source, inlined whole into a serial arm's generated C that has an arm_angle stage, after
 * sr_verify.c; Python's serial_arm_angle.py; derive/serial_core/views.py, tests/test_arm_angle.py) */
#if SR_HAS_ARM_ANGLE || SR_HAS_HELD_ELBOW
/* the core's bands (wk_arm_angle.c's WK_AA_*), on the robot's size sr_scale */
static wk_aa_tols sr_aa_tols(void)
{
    wk_aa_tols t;
    t.scale = sr_scale;
    t.degenerate = SR_DEGENERATE_EPS;
    t.double_root = WK_AA_DOUBLE_ROOT;
    t.tangent = WK_AA_TANGENT;
    t.on_axis = WK_AA_ON_AXIS;
    t.family = WK_AA_FAMILY;
    return t;
}

#if SR_HAS_ARM_ANGLE
/* Set k's set: `kernel` the stage's (h_a, h_b, h_c, s, h_e, p_e, x, y, psi), `parent` the set index's prefix above
 * the stage's bits (the sets are recomputed when it changes), `idx` the set; 0 when there is no such set */
static int sr_arm_angle(sr_stage_kernel kernel, long parent, int idx, const int *joints, double *q, double *c,
                        double *s, const double *pose, const double *dp, const double *prev, sr_ws *ws, unsigned *f)
{
    if (ws->key != parent) {
        const wk_aa_tols t = sr_aa_tols();
        double out[25];
        kernel(pose, q, c, s, dp, out);
        ws->key = parent;
        ws->n = wk_arm_angle(out, out + 3, out + 6, out + 9, out + 12, out + 15, out + 18, out + 21, out[24],
                             prev ? &prev[joints[0]] : NULL, NULL, &t, ws->q, ws->f);
        sr_ws_mark_near(ws);
    }
    return sr_ws_take(ws, idx, joints, q, c, s, f);
}
#endif

/* The arm angle of joint values q under the design's parameters dp, read on the points the reader kernel places */
static double sr_arm_angle_at(const double *q, const double *dp)
{
    const wk_aa_tols t = sr_aa_tols();
    double out[15];
    sr_k_arm_angle_parts(q, dp, out);
    return wk_aa_angle_of(out, out + 3, out + 6, out + 9, out + 12, &t);
}

#if SR_HAS_HELD_ELBOW
/* Set k's set of an S-R-S arm with its elbow held (a self-motion): `kernel` the stage's (h_a, h_b, h_c, s, h_e, p_e, x,
 * y), x where the held elbow puts the wrist centre; the core with the elbow held at 0 about h_e (x has its turn): no
 * set unless |y - s| = |x - s| within its tangent band, else the shoulder's sets at previous's arm angle (else 0),
 * flagged indeterminate. `parent`, `idx` as sr_arm_angle's. */
static int sr_held_elbow(sr_stage_kernel kernel, long parent, int idx, const int *joints, double *q, double *c,
                         double *s, const double *pose, const double *dp, const double *prev, sr_ws *ws, unsigned *f)
{
    if (ws->key != parent) {
        const wk_aa_tols t = sr_aa_tols();
        const double held = 0.0;
        double out[24], sets[4][4];
        int m, j;
        kernel(pose, q, c, s, dp, out);
        ws->key = parent;
        ws->n = wk_arm_angle(out, out + 3, out + 6, out + 9, out + 12, out + 15, out + 18, out + 21,
                             prev ? sr_arm_angle_at(prev, dp) : 0.0, prev ? &prev[joints[0]] : NULL, &held, &t, sets,
                             ws->f);
        for (m = 0; m < ws->n; ++m)
            for (j = 0; j < 3; ++j) ws->q[m][j] = sets[m][j];
        sr_ws_mark_near(ws);
    }
    return sr_ws_take(ws, idx, joints, q, c, s, f);
}
#endif

/* The arm angle of joint values (Python's arm_angle): where they put the elbow point on its circle about the
 * shoulder-wrist line (0 in the plane of the first axis and that line, on the side the axis points to) */
static int sr_api_arm_angle(const double *joints, const sr_design *design, double *psi)
{
    const sr_design *d = sr_design_or_default(design);
    if (!joints || !psi) return WK_ERR_NULL;
    if (!wk_all_finite(joints, SR_N)) return WK_ERR_NONFINITE;
    *psi = sr_arm_angle_at(joints, d->params);
    return WK_OK;
}
#endif
