/* A serial arm's forward kinematics, Jacobian and conditioning (one joint vector or many) and the design
 * atlas's conditioning sums.
 * (a wristkin runtime source, inlined whole into every serial arm's generated C after its SR_* constants and
 * switches, the sr_design / sr_ik_solutions / sr_fk_solutions types, its derived kernels sr_k_* and stage
 * functions; derive/runtime_files.py, derive/families/serial/views.py, tests/test_serial_runtime.py) */
/* The manipulability sqrt(det J^T J) (J J^T past 6 joints) of the geometric Jacobian; *singular: sigma_min /
 * sigma_max of J at or below SR_SINGULAR_EPS. A well-conditioned J is proven so by Cholesky factors (the runtime's
 * wk_conditioning_bound); else the Jacobi eigenvalues of J^T J (J J^T past 6 joints) decide (Python's eigvalsh). */
/* the Jacobian in the design's base and tool frames (sr_frames.c); pose0: the kernels' end pose at q when the caller
 * has it, else NULL */
static void sr_jacobian_in_frames(const double *q, const sr_design *d, const double *pose0, double *jac)
{
    sr_k_jacobian(q, d->params, jac);
    if (d->framed) {
        double own[12];
        if (!pose0) {
            sr_k_fk(q, d->params, own);
            pose0 = own;
        }
        sr_reframe_jacobian(d, pose0, jac);
    }
}

/* g = J^T J (cols x cols) of a 6 x cols Jacobian (row-major) */
static void sr_gram(const double *jac, int cols, double *g)
{
    int i, j, k;
    for (i = 0; i < cols; ++i)
        for (j = 0; j < cols; ++j) {
            g[i * cols + j] = 0.0;
            for (k = 0; k < 6; ++k) g[i * cols + j] += jac[k * cols + i] * jac[k * cols + j];
        }
}

/* The manipulability of a 6 x cols Jacobian (row-major) and *ratio = sigma_min / sigma_max, from the Jacobi
 * eigenvalues of J^T J (J J^T past 6 columns: a held joint's 7, whose nonzero sigma^2 it holds); the FK's and the
 * general 6R stage's conditioning where no Cholesky bound proved them regular */
static double sr_gram_spectrum(const double *jac, int cols, double *ratio)
{
    double g[36];
    int i, j, k;
    if (cols <= 6) {
        sr_gram(jac, cols, g);
        return wk_jacobi_spectrum(g, cols, ratio);
    }
    for (i = 0; i < 6; ++i)
        for (j = 0; j < 6; ++j) {
            g[i * 6 + j] = 0.0;
            for (k = 0; k < cols; ++k) g[i * 6 + j] += jac[i * cols + k] * jac[j * cols + k];
        }
    return wk_jacobi_spectrum(g, 6, ratio);
}

/* The manipulability and whether sigma_min / sigma_max <= SR_SINGULAR_EPS of a 6 x cols Jacobian (row-major): a
 * Cholesky bound proves most regular, sr_gram_spectrum decides the rest */
static double sr_spectrum(const double *jac, int cols, int *singular)
{
    double man, ratio;
    if (wk_conditioning_bound(jac, cols, SR_SINGULAR_EPS, &man) == 1) {
        *singular = 0;
        return man;
    }
    man = sr_gram_spectrum(jac, cols, &ratio);
    *singular = ratio <= SR_SINGULAR_EPS;
    return man;
}

static double sr_conditioning(const double *q, const sr_design *d, const double *pose0, int *singular)
{
    double jac[6 * SR_N];
    sr_jacobian_in_frames(q, d, pose0, jac);
    return sr_spectrum(jac, SR_N, singular);
}



/* ------------------------------------------------------------------ forward kinematics */
static int sr_api_fk(const double *joints, const sr_design *design, sr_fk_solutions *out)
{
    const sr_design *d = sr_design_or_default(design);
    double man, q[SR_N], pose0[12];
    int j, singular;
    if (!out) return WK_ERR_NULL;
    out->count = 0;
    out->valid[0] = 0;
    out->flags[0] = 0u;
    for (j = 0; j < 12; ++j) out->values[0][j] = NAN;
    out->aux[0][0] = NAN;
    if (!joints) {
        out->status = WK_ERR_NULL;
        return WK_ERR_NULL;
    }
    {
        const int rc = sr_joints(joints, q);
        if (rc != WK_OK) {
            out->status = rc;
            return rc;
        }
    }
    sr_k_fk(q, d->params, pose0);
    if (d->framed)
        sr_reframe(d, pose0, out->values[0]);
    else
        for (j = 0; j < 12; ++j) out->values[0][j] = pose0[j];
    man = sr_conditioning(q, d, pose0, &singular);
    out->aux[0][0] = man;
    out->flags[0] = singular ? WK_FLAG_SINGULAR_INVERSE : 0u;
    out->valid[0] = 1;
    out->count = 1;
    out->status = WK_STATUS_OK;
    return WK_OK;
}

static int sr_api_fk_matrix(const double *joints, const sr_design *design, double *pose)
{
    const sr_design *d = sr_design_or_default(design);
    double q[SR_N];
    int rc;
    if (!joints || !pose) return WK_ERR_NULL;
    rc = sr_joints(joints, q);
    if (rc != WK_OK) return rc;
    if (!d->framed) {
        sr_k_fk(q, d->params, pose);
    } else {
        double pose0[12];
        sr_k_fk(q, d->params, pose0);
        sr_reframe(d, pose0, pose);
    }
    return WK_OK;
}

static int sr_api_jacobian(const double *joints, const sr_design *design, double *jac)
{
    const sr_design *d = sr_design_or_default(design);
    double q[SR_N];
    int rc;
    if (!joints || !jac) return WK_ERR_NULL;
    rc = sr_joints(joints, q);
    if (rc != WK_OK) return rc;
    sr_jacobian_in_frames(q, d, NULL, jac);
    return WK_OK;
}

/* the design atlas reads the chain's own Jacobian (its base and tool frames, not the design's: the atlas sweeps
 * the chain's lengths, for which frames change no conditioning but the tool's lever) */
static int sr_api_atlas_conditioning(size_t n, const double *joints, const sr_design *design,
                                     double length, double threshold, int64_t sums[2], double *li_min)
{
    const sr_design *d = sr_design_or_default(design);
    size_t s;
    int k;
    if ((n && !joints) || !sums || !li_min) return WK_ERR_NULL;
    if (!(length > 0.0) || !isfinite(length)) return WK_ERR_RANGE;
    for (s = 0; s < n; ++s) {
        double q[SR_N], jac[6 * SR_N], g[SR_N * SR_N], ratio;
        const int rc = sr_joints(joints + SR_N * s, q);
        if (rc != WK_OK) return rc;
        sr_k_jacobian(q, d->params, jac);
        for (k = 0; k < 3 * SR_N; ++k) jac[k] /= length; /* the linear rows, in lengths per rad (or per length) */
        sr_gram(jac, SR_N, g);
        (void)wk_jacobi_spectrum(g, SR_N, &ratio);
        /* sigma_min / sigma_max from the eigenvalues of J^T J: within ~sqrt(eps) of 0 at a singularity (the Gram
         * matrix squares the condition number); rounding can give NaN there (a tiny negative lambda_min) or a few
         * ulps above 1 at an isotropic J */
        ratio = ratio > 0.0 ? (ratio < 1.0 ? ratio : 1.0) : 0.0;
        sums[0] += (int64_t)llrint(ratio * WK_ATLAS_FIXED);
        sums[1] += ratio < threshold;
        if (ratio < *li_min) *li_min = ratio;
    }
    return WK_OK;
}

static int sr_api_fk_batch(size_t n, const double *joints, const sr_design *design,
                           sr_fk_solutions *out)
{
    size_t r;
    int first = WK_OK;
    if (n == 0) return WK_OK;
    if (!joints || !out) return WK_ERR_NULL;
    for (r = 0; r < n; ++r) {
        const int rc = sr_api_fk(joints + SR_N * r, design, out + r);
        if (rc != WK_OK && first == WK_OK) first = rc;
    }
    return first;
}
