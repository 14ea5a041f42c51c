/* A serial arm's inputs: the joints as the solver uses them and the design, validated.
 * (a wristkin runtime source, inlined whole into every serial arm's generated C after its SR_* constants and
 * switches, the sr_design / sr_ik_solutions / sr_fk_solutions types, its derived kernels sr_k_* and stage
 * functions; derive/runtime_files.py, derive/families/serial/views.py, tests/test_serial_runtime.py) */
#if SR_HAS_PRISMATIC
/* 1 if every prismatic value is within SR_LENGTH_MAX: IK returns only sets that FK accepts */
static int sr_prismatic_in_range(const double *q)
{
    int j;
    for (j = 0; j < SR_N; ++j)
        if (!sr_revolute[j] && !(fabs(q[j]) <= SR_LENGTH_MAX)) return 0;
    return 1;
}
#endif

/* Joints as the solver uses them: revolute angles wrapped exactly (wk_wrap reduces against 2 pi itself),
 * prismatic offsets within SR_LENGTH_MAX. Returns WK_OK or a negative code. */
static int sr_joints(const double *joints, double *q)
{
    int j;
    if (!wk_all_finite(joints, SR_N)) return WK_ERR_NONFINITE;
    for (j = 0; j < SR_N; ++j) {
        if (sr_revolute[j]) {
            q[j] = wk_wrap(joints[j]);
        } else {
            if (!(fabs(joints[j]) <= SR_LENGTH_MAX)) return WK_ERR_RANGE;
            q[j] = joints[j];
        }
    }
    return WK_OK;
}

static const sr_design *sr_design_or_default(const sr_design *d)
{
    return d ? d : &sr_default_design;
}

static int sr_api_design_init(const double *params, sr_design *design)
{
    int i;
    if (!design) return WK_ERR_NULL;
    if (!params) {
        *design = sr_default_design;
        return WK_OK;
    }
    if (!wk_all_finite(params, SR_N_PARAMS)) return WK_ERR_NONFINITE;
    {
        /* every length within SR_LENGTH_MAX; the largest 0 or at least SR_DESIGN_SCALE_MIN (see DESIGN_SCALE_MIN);
         * a held joint's angle after the lengths is any finite value (its stage wraps it) */
        double scale = 0.0;
        for (i = 0; i < SR_N_LENGTHS; ++i)
            if (fabs(params[i]) > scale) scale = fabs(params[i]);
        if (scale > SR_LENGTH_MAX || (scale > 0.0 && scale < SR_DESIGN_SCALE_MIN)) return WK_ERR_DESIGN;
#if SR_LENGTHS_FLOOR
        /* DH lengths: each 0 or at least SR_LENGTH_MIN in magnitude (Python LENGTH_MIN) */
        for (i = 0; i < SR_N_LENGTHS; ++i)
            if (params[i] != 0.0 && fabs(params[i]) < SR_LENGTH_MIN) return WK_ERR_DESIGN;
#endif
    }
#if SR_N_DESIGN_CHECKS > 0
    {
        /* design conditions (Python DESIGN_CHECKS): zero = |v| <= tol required, nonzero = |v| > tol required */
        double v[SR_N_DESIGN_CHECKS];
        sr_k_design_check(params, v);
        for (i = 0; i < SR_N_DESIGN_CHECKS; ++i) {
            if (sr_check_zero[i] == 2) continue; /* a held joint's value: ik refuses it (sr_ik.c), fk takes it */
            if (sr_check_zero[i] ? !(fabs(v[i]) <= sr_check_tol[i]) : !(fabs(v[i]) > sr_check_tol[i]))
                return WK_ERR_DESIGN;
        }
    }
#endif
    for (i = 0; i < SR_N_PARAMS; ++i) design->params[i] = params[i];
    return sr_api_design_set_frames(design, NULL, NULL); /* the chain's own frames */
}
