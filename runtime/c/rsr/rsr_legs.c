/* The 3-RSR wrist's leg roots, mirror plane and workspace, shared by the wrist and the SCARA hybrid built on it.
 * (a wristkin runtime source, inlined whole into both mechanisms' generated C after their derived kernels rsr_k_*
 * and the RSR_* tolerances; derive/runtime_files.py, tests/test_rsr_runtime.py) */
#define RSR_PI 3.14159265358979323846
#define RSR_TWO_PI 6.28318530717958647692
#define RSR_DIRECT_SCALE 2.598076211353315940 /* 1.5 sqrt(3): max |S1S2 x S1S3| / L^2 */

/* w = (L, phi_min, phi_max, lbw_min, lbw_max): 1 if valid */
/* Wrist design (L, phi_min, phi_max, lbw_min, lbw_max): 0 < L <= RSR_LENGTH_MAX (products of lengths stay
 * finite), ordered limits; the same rule as Python's _wrist_design_error. */
#define RSR_LENGTH_MAX 1e6
static int rsr_design_ok(const double *w)
{
    return wk_all_finite(w, 5) && w[0] > 0.0 && w[0] <= RSR_LENGTH_MAX && w[1] < w[2] && w[2] - w[1] < RSR_TWO_PI &&
           w[3] >= 0.0 && w[3] < w[4] && w[4] <= 2.0 * w[0];
}

/* Both roots per leg of A_i cos phi + B sin phi = C, with cos, sin (algebraic: no trigonometry) and residual:
 * leg[i][b] = {phi, c, s, residual}, b = 0 the + root. Returns 1 if every leg reaches. */
static int rsr_legs(const double *pose, const double *w, double leg[3][2][4], unsigned flags[3], double *cond)
{
    double k[5];
    int i, b;
    rsr_k_ik_coeffs(pose, w, k);
    *cond = 1.0;
    for (i = 0; i < 3; ++i) {
        const double rho = hypot(k[i], k[3]);
        double u, sg, ca, sa;
        flags[i] = 0u;
        if (rho <= RSR_DEGENERATE_EPS) {
            if (fabs(k[4]) > RSR_DEGENERATE_EPS) return 0;
            for (b = 0; b < 2; ++b) {
                leg[i][b][0] = 0.0;
                leg[i][b][1] = 1.0;
                leg[i][b][2] = 0.0;
                leg[i][b][3] = fabs(k[4]);
            }
            flags[i] = WK_FLAG_INDETERMINATE | WK_FLAG_SINGULAR_INVERSE;
            *cond = 0.0;
            continue;
        }
        u = k[4] / rho;
        if (fabs(u) > 1.0 + RSR_TANGENT_TOL) return 0;
        u = u > 1.0 ? 1.0 : (u < -1.0 ? -1.0 : u);
        sg = sqrt(1.0 - u * u);
        ca = k[i] / rho;
        sa = k[3] / rho;
        for (b = 0; b < 2; ++b) {
            const double sgn = b ? -1.0 : 1.0, c = ca * u - sgn * sa * sg, s = sa * u + sgn * ca * sg;
            leg[i][b][0] = atan2(s, c);
            leg[i][b][1] = c;
            leg[i][b][2] = s;
            leg[i][b][3] = fabs(k[i] * c + k[3] * s - k[4]);
        }
        if (sg <= sqrt(RSR_TANGENT_TOL)) flags[i] = WK_FLAG_DOUBLE_ROOT | WK_FLAG_SINGULAR_INVERSE;
        if (rho * sg <= RSR_SINGULAR_EPS) flags[i] |= WK_FLAG_SINGULAR_INVERSE; /* a near-free leg (rho -> 0), as FK flags it */
        if (rho * sg < *cond) *cond = rho * sg; /* |dF_i/dphi_i| / L, as in Python */
    }
    return 1;
}

/* Unit mirror plane (n, h) with n_z >= 0 from raw (N, S1) and its direct conditioning; 0 if S1, S2, S3 are
 * collinear. */
static int rsr_unit_plane(const double o[6], const double *w, double plane[4], double *cond)
{
    const double norm = sqrt(o[0] * o[0] + o[1] * o[1] + o[2] * o[2]);
    *cond = norm / (RSR_DIRECT_SCALE * w[0] * w[0]);
    if (!(*cond > RSR_DEGENERATE_EPS)) return 0;
    if (*cond > 1.0) *cond = 1.0;
    plane[0] = o[0] / norm;
    plane[1] = o[1] / norm;
    plane[2] = o[2] / norm;
    if (plane[2] < 0.0 || (plane[2] == 0.0 && plane[0] * o[3] + plane[1] * o[4] < 0.0)) {
        plane[0] = -plane[0];
        plane[1] = -plane[1];
        plane[2] = -plane[2];
    }
    plane[3] = plane[0] * o[3] + plane[1] * o[4] + plane[2] * o[5];
    return 1;
}

static int rsr_plane(const double *q, const double *w, double plane[4], double *cond)
{
    double o[6];
    rsr_k_fk_plane(q, w, o);
    return rsr_unit_plane(o, w, plane, cond);
}

/* Plane of one leg-root set (leg word bits select the roots), from the roots' cos and sin. */
static int rsr_plane_of_set(double leg[3][2][4], int word, const double *w, double plane[4], double *cond)
{
    double cs[6], o[6];
    int i;
    for (i = 0; i < 3; ++i) {
        cs[i] = leg[i][(word >> i) & 1][1];
        cs[3 + i] = leg[i][(word >> i) & 1][2];
    }
    rsr_k_fk_plane_cs(cs, w, o);
    return rsr_unit_plane(o, w, plane, cond);
}

/* (alpha, beta, l_bw) of a unit plane; returns 1 at the gimbal (beta = 0: alpha := 0). */
static int rsr_pose_of_plane(const double plane[4], double pose[3])
{
    const double sxy = hypot(plane[0], plane[1]);
    const int gimbal = sxy <= RSR_GIMBAL_EPS;
    pose[0] = gimbal ? 0.0 : atan2(plane[1], plane[0]);
    pose[1] = 2.0 * atan2(sxy, plane[2]);
    pose[2] = 2.0 * plane[3];
    return gimbal;
}

static double rsr_leg_cond_inverse(const double *q, const double *pose, const double *w)
{
    double k[5], worst = 1.0;
    int i;
    rsr_k_ik_coeffs(pose, w, k);
    for (i = 0; i < 3; ++i) {
        /* |dF_i/dphi_i| / L in [0, 1]: 0 at a tangent root and for a free leg (A = B = 0) */
        const double c = fabs(-k[i] * sin(q[i]) + k[3] * cos(q[i]));
        if (!(c >= worst)) worst = c;
    }
    return worst;
}

static int rsr_in_arc(double t, double lo, double hi)
{
    double d = fmod(t - lo, RSR_TWO_PI);
    if (d < 0.0) d += RSR_TWO_PI;
    return lo + d <= hi;
}

/* Reachable l_bw interval at (alpha, beta) within the limits; 0 if empty. */
static int rsr_workspace(double alpha, double beta, const double *w, double span[2])
{
    const double pose[3] = {alpha, beta, 0.0};
    double k[5], lo = 0.5 * w[3], hi = 0.5 * w[4];
    int i, j;
    rsr_k_ik_coeffs(pose, w, k);
    for (i = 0; i < 3; ++i) {
        const double t0 = atan2(k[3], k[i]), rho = w[0] * hypot(k[i], k[3]);
        double top = -HUGE_VAL, bottom = HUGE_VAL;
        for (j = 1; j <= 2; ++j) {
            const double v = w[0] * (k[i] * cos(w[j]) + k[3] * sin(w[j]));
            if (v > top) top = v;
            if (v < bottom) bottom = v;
        }
        if (rsr_in_arc(t0, w[1], w[2])) top = rho;
        if (rsr_in_arc(t0 + RSR_PI, w[1], w[2])) bottom = -rho;
        if (bottom > lo) lo = bottom;
        if (top < hi) hi = top;
    }
    span[0] = 2.0 * lo;
    span[1] = 2.0 * hi;
    return lo <= hi;
}
