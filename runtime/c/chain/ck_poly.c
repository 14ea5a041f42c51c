/* Polynomial helpers of the spatial-3 and subproblem-6 kernels (ascending coefficients).
 * (a wristkin runtime source, inlined whole into every user robot's generated C, after the robot's CK_*
 * constants; derive/runtime_files.py, tests/test_chain_runtime.py) */
/* out = out + s * p for polynomials in t (ascending coefficients, degree <= 8) */
static void ck_poly_axpy(double *out, const double *p, int np, double s)
{
    int i;
    for (i = 0; i < np; ++i) out[i] += s * p[i];
}

/* out = a * b (degrees na - 1, nb - 1) */
static void ck_poly_mul(const double *a, int na, const double *b, int nb, double *out)
{
    int i, j;
    for (i = 0; i < na + nb - 1; ++i) out[i] = 0.0;
    for (i = 0; i < na; ++i)
        for (j = 0; j < nb; ++j) out[i + j] += a[i] * b[j];
}

