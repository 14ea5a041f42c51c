/* The underactuated wrist's design: validation of the four link angles and the derived constants.
 * (a wristkin runtime source, inlined whole into the underactuated wrist's generated C after its UW_*
 * constants, the uw_design / uw_ik_solutions / uw_fk_solutions types and the derived kernels uw_k_*;
 * derive/runtime_files.py, tests/test_uw_runtime.py) */
static const uw_design *uw_design_or_default(const uw_design *d)
{
    return d ? d : &uw_default_design;
}

/* ------------------------------------------------------------------ design */
static int uw_api_design_init(const double *params, uw_design *design)
{
    double p[4], cth0;
    int i;
    if (!design) return WK_ERR_NULL;
    if (!params) {
        *design = uw_default_design;
        return WK_OK;
    }
    for (i = 0; i < 4; ++i) {
        if (!isfinite(params[i])) return WK_ERR_NONFINITE;
        p[i] = params[i];
    }
    /* link angles at least UW_DESIGN_MARGIN from 0 and pi (Python DESIGN_MARGIN): the constants divide by sines */
    if (!(p[0] >= UW_DESIGN_MARGIN && p[0] <= UW_PI - UW_DESIGN_MARGIN && p[1] >= UW_DESIGN_MARGIN &&
          p[1] <= UW_PI - UW_DESIGN_MARGIN))
        return WK_ERR_DESIGN;
    if (!(p[2] >= 0.0 && p[2] <= 0.5 * UW_PI && p[3] >= UW_DESIGN_MARGIN && p[3] <= 0.5 * UW_PI)) return WK_ERR_DESIGN;
    /* the home loop -sin(alpha1) sin(beta1 + beta2) (cos theta - cos theta0) fixes no theta0 as beta1 + beta2 -> pi */
    if (!(p[2] + p[3] <= UW_PI - UW_DESIGN_MARGIN)) return WK_ERR_DESIGN;
    uw_k_design_constants(p, design->c);
    for (i = 0; i < UW_N_CONSTANTS; ++i)
        if (!isfinite(design->c[i])) return WK_ERR_DESIGN;
    cth0 = design->c[UW_N_CONSTANTS - 1];
    if (!isfinite(cth0) || fabs(cth0) > 1.0 + UW_TANGENT_TOL) return WK_ERR_DESIGN;
    for (i = 0; i < 4; ++i) design->params[i] = p[i];
    design->theta0 = acos(uw_clamp1(cth0));
    return WK_OK;
}
