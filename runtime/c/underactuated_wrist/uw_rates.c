/* The underactuated wrist's rates: loop Jacobians, angular velocity and acceleration, Euler-angle rates.
 * (a wristkin runtime source, inlined whole into the underactuated wrist's generated C after its UW_*
 * constants, the uw_design / uw_ik_solutions / uw_fk_solutions types and the derived kernels uw_k_*;
 * derive/runtime_files.py, tests/test_uw_runtime.py) */
/* ------------------------------------------------------------------ rates */
static int uw_api_jacobians(const double joints[3], const double pose[3],
                            const uw_design *design, double jq[3], double jx[9])
{
    const uw_design *d = uw_design_or_default(design);
    double rot[9], jac[12];
    int j;
    if (!joints || !pose || !jq || !jx) return WK_ERR_NULL;
    if (!uw_finite3(joints) || !uw_finite3(pose)) return WK_ERR_NONFINITE;
    uw_rotation(pose, rot);
    uw_k_jacobians(joints, rot, d->c, jac);
    for (j = 0; j < 3; ++j) jq[j] = jac[j];
    for (j = 0; j < 9; ++j) jx[j] = jac[3 + j];
    return WK_OK;
}

#define UW_RATE_MAX 1e6 /* rates beyond this are WK_ERR_RANGE (Python RATE_MAX): products stay finite */

static int uw_rates_ok(const double *v)
{
    return fabs(v[0]) <= UW_RATE_MAX && fabs(v[1]) <= UW_RATE_MAX && fabs(v[2]) <= UW_RATE_MAX;
}

/* Solve a x = b for 3x3 a (Cramer); WK_ERR_RANGE when singular or the result is not finite. */
static int uw_solve3(const double *a, const double *b, double *x)
{
    const double det = uw_det3(a);
    double m[9];
    int col, j;
    double scale = 0.0;
    for (j = 0; j < 9; ++j) scale = fmax(scale, fabs(a[j]));
    if (!(fabs(det) > UW_SINGULAR_EPS * scale * scale * scale)) return WK_ERR_RANGE;
    for (col = 0; col < 3; ++col) {
        for (j = 0; j < 9; ++j) m[j] = a[j];
        m[col] = b[0];
        m[3 + col] = b[1];
        m[6 + col] = b[2];
        x[col] = uw_det3(m) / det;
    }
    return uw_finite3(x) ? WK_OK : WK_ERR_RANGE;
}

static int uw_api_angular_velocity(const double joints[3], const double pose[3], const double qdot[3],
                                   const uw_design *design, double w[3])
{
    double jq[3], jx[9], rhs[3];
    int rc, j;
    if (!qdot || !w) return WK_ERR_NULL;
    rc = uw_api_jacobians(joints, pose, design, jq, jx);
    if (rc != WK_OK) return rc;
    if (!uw_finite3(qdot)) return WK_ERR_NONFINITE;
    if (!uw_rates_ok(qdot)) return WK_ERR_RANGE;
    for (j = 0; j < 3; ++j) rhs[j] = jq[j] * qdot[j];
    return uw_solve3(jx, rhs, w);
}

static int uw_api_angular_acceleration(const double joints[3], const double pose[3],
                                       const double qdot[3], const double qddot[3],
                                       const uw_design *design, double wdot[3])
{
    const uw_design *d = uw_design_or_default(design);
    double jq[3], jx[9], w[3], rot[9], rates[12], rhs[3];
    int rc, j;
    if (!qddot || !wdot) return WK_ERR_NULL;
    rc = uw_api_angular_velocity(joints, pose, qdot, design, w);
    if (rc != WK_OK) return rc;
    if (!uw_finite3(qddot)) return WK_ERR_NONFINITE;
    if (!uw_rates_ok(qddot)) return WK_ERR_RANGE;
    uw_api_jacobians(joints, pose, design, jq, jx);
    uw_rotation(pose, rot);
    uw_k_jacobian_rates(joints, rot, qdot, w, d->c, rates);
    for (j = 0; j < 3; ++j)
        rhs[j] = jq[j] * qddot[j] + rates[j] * qdot[j]
               - (rates[3 + 3 * j] * w[0] + rates[4 + 3 * j] * w[1] + rates[5 + 3 * j] * w[2]);
    return uw_solve3(jx, rhs, wdot);
}

static int uw_api_omega_from_euler_rates(const double pose[3], const double euler_rates[3], double w[3])
{
    double e[9];
    int i;
    if (!pose || !euler_rates || !w) return WK_ERR_NULL;
    if (!uw_finite3(pose) || !uw_finite3(euler_rates)) return WK_ERR_NONFINITE;
    if (!uw_rates_ok(euler_rates)) return WK_ERR_RANGE;
    uw_k_euler_rate_matrix(pose, e);
    for (i = 0; i < 3; ++i) w[i] = e[3 * i] * euler_rates[0] + e[3 * i + 1] * euler_rates[1] + e[3 * i + 2] * euler_rates[2];
    return uw_finite3(w) ? WK_OK : WK_ERR_RANGE;
}
