/* An S-R-S arm's arm_angle stage (the shoulder's three joints and the elbow for the wrist centre's target and the
 * arm angle psi, the design's; wk_arm_angle.c, inlined before it), on the axes, centres and points its derived kernel
 * gives. The sets are computed once per prefix of the set index above the stage's bits and kept in the call's scratch
 * (sr_ws); set k takes set (k >> shift) & 3 (two elbows x two shoulders). The wrist's stage follows; the FK check
 * verifies each set. And the module's arm_angle verb: the arm angle of joint values, read on the points its derived
 * reader kernel (sr_k_arm_angle_parts) places.
 * (a wristkin runtime source, inlined whole into a serial arm's generated C that has an arm_angle stage, after
 * sr_verify.c; Python's serial_arm_angle.py; derive/serial_core/views.py, tests/test_arm_angle.py) */
#if SR_HAS_ARM_ANGLE
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
                             prev ? &prev[joints[0]] : NULL, &t, ws->q, ws->f);
    }
    return sr_ws_take(ws, idx, joints, q, c, s, f);
}

/* The arm angle of joint values (Python's arm_angle): where they put the elbow point on its circle about the
 * shoulder-wrist line (0 in the plane of the first axis and that line, on the side the axis points to) */
static int sr_api_arm_angle(const double *joints, const sr_design *design, double *psi)
{
    const sr_design *d = sr_design_or_default(design);
    const wk_aa_tols t = sr_aa_tols();
    double out[15];
    if (!joints || !psi) return WK_ERR_NULL;
    if (!wk_all_finite(joints, SR_N)) return WK_ERR_NONFINITE;
    sr_k_arm_angle_parts(joints, d->params, out);
    *psi = wk_aa_angle_of(out, out + 3, out + 6, out + 9, out + 12, &t);
    return WK_OK;
}
#endif
