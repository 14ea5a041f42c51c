/* Angles and small 3-vector algebra of the underactuated wrist: wraps, the ZXZ rotation and its Euler
 * angles, crosses and the direct-singularity measure of three Jacobian rows.
 * (a wristkin runtime source, inlined whole into the underactuated wrist's generated C after its UW_*
 * constants, the uw_design / uw_ik_solutions / uw_fk_solutions types and the derived kernels uw_k_*;
 * derive/runtime_files.py, tests/test_uw_runtime.py) */
static int uw_finite3(const double *v)
{
    return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
}

static double uw_clamp1(double x)
{
    return x > 1.0 ? 1.0 : (x < -1.0 ? -1.0 : x);
}

/* [0, 2 pi): reduced exactly (wk_wrap), then a turn added to a negative angle */
static double uw_wrap_2pi(double a)
{
    a = wk_wrap(a);
    return a < 0.0 ? a + UW_TWO_PI : a;
}

static double uw_wrap_pi(double a)
{
    return wk_wrap(a);
}

static void uw_rotation(const double *pose, double *r)
{
    const double cp = cos(pose[0]), sp = sin(pose[0]), ct = cos(pose[1]), st = sin(pose[1]);
    const double cf = cos(pose[2]), sf = sin(pose[2]);
    r[0] = cp * cf - sp * ct * sf; r[1] = -cp * sf - sp * ct * cf; r[2] = sp * st;
    r[3] = sp * cf + cp * ct * sf; r[4] = -sp * sf + cp * ct * cf; r[5] = -cp * st;
    r[6] = st * sf; r[7] = st * cf; r[8] = ct;
}

/* ZXZ angles from row-major R; theta in [0, pi]. Returns WK_FLAG_GIMBAL where only psi +/- phi is defined. */
static unsigned uw_euler(const double *r, double *pose)
{
    const double st = sqrt(r[2] * r[2] + r[5] * r[5]);
    pose[1] = atan2(st, r[8]);
    if (st <= UW_GIMBAL_EPS) {
        pose[0] = atan2(r[3], r[0]);
        pose[2] = 0.0;
        return WK_FLAG_GIMBAL;
    }
    /* phi from Rz(phi) = Rx(-theta) Rz(-psi) R: takes psi's eps / sin(theta) error back (see Python _euler);
       psi's cos and sin are the entries atan2 read, normalised (no trigonometry) */
    pose[0] = atan2(r[2], -r[5]);
    {
        const double cp = -r[5] / st, sp = r[2] / st;
        pose[2] = atan2(r[8] * (-sp * r[0] + cp * r[3]) + st * r[6], cp * r[0] + sp * r[3]);
    }
    return 0u;
}

static double uw_det3(const double *a)
{
    return a[0] * (a[4] * a[8] - a[5] * a[7]) - a[1] * (a[3] * a[8] - a[5] * a[6])
         + a[2] * (a[3] * a[7] - a[4] * a[6]);
}

static void uw_cross(const double *a, const double *b, double *out)
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

static double uw_norm(const double *a)
{
    return sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
}

/* |det[r0; r1; r2]| / (n0 n1 n2): the direct-singularity measure in [0, 1] for rows Zi2 x Zi3. */
static double uw_cond_rows(const double *r0, const double *r1, const double *r2, double norm)
{
    const double det = r0[0] * (r1[1] * r2[2] - r1[2] * r2[1]) - r0[1] * (r1[0] * r2[2] - r1[2] * r2[0])
                     + r0[2] * (r1[0] * r2[1] - r1[1] * r2[0]);
    return norm > 0.0 ? fabs(det) / norm : 0.0;
}

/* theta in (-2 pi, 2 pi] -> [0, 2 pi) without fmod (the IK roots never leave that range) */
static double uw_wrap_root(double a)
{
    if (a < 0.0) a += UW_TWO_PI;
    if (a >= UW_TWO_PI) a -= UW_TWO_PI;
    return a;
}

/* theta - theta0 with theta in [0, 2 pi), theta0 in [0, pi] -> (-pi, pi] */
static double uw_wrap_motor(double a)
{
    if (a > UW_PI) a -= UW_TWO_PI;
    if (a <= -UW_PI) a += UW_TWO_PI;
    return a;
}
