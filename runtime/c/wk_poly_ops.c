/* wristkin: polynomial helpers of the spatial 3R (wk_spatial3.c) and subproblem-6 (wk_sp6.c) cores,
 * ascending coefficients, degree <= 8. Included verbatim into generated C99 sources (static functions). */
/* out += s p (polynomials in t, ascending coefficients) */
static void wk_poly_axpy(double *out, const double *p, int np, double s)
{
    int i;
    for (i = 0; i < np; ++i) out[i] += s * p[i];
}

/* out = a b (degrees na - 1, nb - 1) */
static void wk_poly_mul(const double *a, int na, const double *b, int nb, double *out)
{
    int i, j;
    for (i = 0; i < na + nb - 1; ++i) out[i] = 0.0;
    for (i = 0; i < na; ++i)
        for (j = 0; j < nb; ++j) out[i + j] += a[i] * b[j];
}
