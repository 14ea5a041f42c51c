/* Small dense numerics: one-sided Jacobi SVD, least squares, the Jacobian's spectrum and conditioning.
 * (a wristkin runtime source, inlined whole into every user robot's generated C, after the robot's CK_*
 * constants; derive/runtime_files.py, tests/test_chain_runtime.py) */
/* ------------------------------------------------------------------ small dense numerics */
/* One-sided Jacobi SVD (Hestenes) of the m x n matrix a (m >= n, both <= CK_DIM): rotates column pairs until
 * they are orthogonal, so a becomes U S; v (n x n, or NULL) accumulates the rotations; s = the column norms. */
static void ck_svd(double a[CK_DIM][CK_DIM], int m, int n, double *s, double v[CK_DIM][CK_DIM])
{
    int i, p, q, sweep;
    if (v)
        for (i = 0; i < n; ++i)
            for (p = 0; p < n; ++p) v[i][p] = i == p ? 1.0 : 0.0;
    for (sweep = 0; sweep < 60; ++sweep) {
        int rotated = 0;
        for (p = 0; p < n; ++p)
            for (q = p + 1; q < n; ++q) {
                double alpha = 0.0, beta = 0.0, gamma = 0.0, zeta, t, c, sn;
                for (i = 0; i < m; ++i) {
                    alpha += a[i][p] * a[i][p];
                    beta += a[i][q] * a[i][q];
                    gamma += a[i][p] * a[i][q];
                }
                if (!(fabs(gamma) > 1e-15 * sqrt(alpha * beta))) continue; /* orthogonal to rounding (or 0) */
                rotated = 1;
                zeta = (beta - alpha) / (2.0 * gamma);
                if (fabs(zeta) > 1e100)
                    t = 0.5 / zeta;
                else
                    t = (zeta >= 0.0 ? 1.0 : -1.0) / (fabs(zeta) + sqrt(1.0 + zeta * zeta));
                c = 1.0 / sqrt(1.0 + t * t);
                sn = c * t;
                for (i = 0; i < m; ++i) {
                    const double ap = a[i][p], aq = a[i][q];
                    a[i][p] = c * ap - sn * aq;
                    a[i][q] = sn * ap + c * aq;
                }
                for (i = 0; v && i < n; ++i) {
                    const double vp = v[i][p], vq = v[i][q];
                    v[i][p] = c * vp - sn * vq;
                    v[i][q] = sn * vp + c * vq;
                }
            }
        if (!rotated) break;
    }
    for (p = 0; p < n; ++p) {
        double acc = 0.0;
        for (i = 0; i < m; ++i) acc += a[i][p] * a[i][p];
        s[p] = sqrt(acc);
    }
}

/* x = the least-squares solution of A x = b (A: m x n row-major, m >= n) of least norm: singular values at or
 * below eps max(m, n) s_max count as zero (numpy's lstsq with rcond=None). */
static void ck_lstsq(const double *a_in, int m, int n, const double *b, double *x)
{
    double a[CK_DIM][CK_DIM], v[CK_DIM][CK_DIM], s[CK_DIM], smax = 0.0, cut;
    int i, j;
    for (i = 0; i < m; ++i)
        for (j = 0; j < n; ++j) a[i][j] = a_in[i * n + j];
    ck_svd(a, m, n, s, v);
    for (j = 0; j < n; ++j) {
        if (s[j] > smax) smax = s[j];
        x[j] = 0.0;
    }
    cut = CK_EPS * (m > n ? m : n) * smax;
    for (j = 0; j < n; ++j) {
        double ub = 0.0, c;
        if (!(s[j] > cut)) continue;
        for (i = 0; i < m; ++i) ub += a[i][j] * b[i]; /* (U S)_j . b */
        c = ub / (s[j] * s[j]);
        for (i = 0; i < n; ++i) x[i] += c * v[i][j];
    }
}

/* The singular values of the 6 x n matrix jac (min(6, n) of them): *ratio = s_min / s_max (0 when s_max is 0);
 * returns their product (the manipulability). */
static double ck_spectrum(const double *jac, int n, double *ratio)
{
    double a[CK_DIM][CK_DIM], s[CK_DIM], lo, hi, prod = 1.0;
    int i, j, k = n <= 6 ? n : 6;
    for (i = 0; i < 6; ++i)
        for (j = 0; j < n; ++j) {
            if (n <= 6)
                a[i][j] = jac[i * n + j];
            else
                a[j][i] = jac[i * n + j]; /* more columns than rows: the transpose's columns */
        }
    if (n <= 6)
        ck_svd(a, 6, n, s, NULL);
    else
        ck_svd(a, n, 6, s, NULL);
    lo = hi = s[0];
    for (j = 0; j < k; ++j) {
        prod *= s[j];
        if (s[j] < lo) lo = s[j];
        if (s[j] > hi) hi = s[j];
    }
    *ratio = hi > 0.0 ? lo / hi : 0.0;
    return prod;
}

/* 1 when sigma_min / sigma_max of the 6 x n matrix jac is at or below CK_SINGULAR_EPS (Python: the SVD's ratio):
 * proven either way by the runtime's Cholesky bounds (wk_conditioning_bound), else the SVD decides. */
static int ck_is_singular(const double *jac, int n)
{
    double ratio;
    const int bound = wk_conditioning_bound(jac, n, CK_SINGULAR_EPS, NULL);
    if (bound) return bound < 0;
    ck_spectrum(jac, n, &ratio);
    return ratio <= CK_SINGULAR_EPS;
}

/* The manipulability (the product of J's nonzero singular values) and whether J is singular (ratio at or below
 * CK_SINGULAR_EPS): a well-conditioned J by the runtime's Cholesky bounds, else the SVD. */
static double ck_conditioning(const double *jac, int n, int *singular)
{
    double man, ratio;
    if (wk_conditioning_bound(jac, n, CK_SINGULAR_EPS, &man) == 1) {
        *singular = 0;
        return man;
    }
    man = ck_spectrum(jac, n, &ratio);
    *singular = ratio <= CK_SINGULAR_EPS;
    return man;
}

