/* Test harness for runtime/c/poly_real_roots.c.
 *
 * Built by tests/test_poly_real_roots.py, which prepends the partial itself
 * (defining WK_POLY_PARTIAL_INLINED) so that the build cache sees its bytes;
 * compiled on its own, the partial is included through the repo-relative path.
 *
 * Shared library: exports wk_test_poly_real_roots{,_tol} for ctypes.
 * With -DWK_POLY_HARNESS_MAIN: an executable for sanitizer runs that reads
 * cases ("n k0 ... kn" per line, %a or decimal) from argv[1], or generates
 * them with a fixed LCG when no file is given, checks the structural
 * contract and prints "n r flags... status" per case.
 */
#include <math.h>
#ifndef WK_POLY_PARTIAL_INLINED
#include "../../runtime/c/poly_real_roots.c"
#endif

int wk_test_poly_real_roots(const double *coef, int n, double *roots, unsigned *flags, int *status);
int wk_test_poly_real_roots_tol(const double *coef, int n, double *roots, unsigned *flags, int *status,
                                double tol_touch);

int wk_test_poly_real_roots(const double *coef, int n, double *roots, unsigned *flags, int *status)
{
    return wk_poly_real_roots(coef, n, roots, flags, status, WK_POLY_TOL_TOUCH);
}

int wk_test_poly_real_roots_tol(const double *coef, int n, double *roots, unsigned *flags, int *status,
                                double tol_touch)
{
    return wk_poly_real_roots(coef, n, roots, flags, status, tol_touch);
}

#ifdef WK_POLY_HARNESS_MAIN
#include <stdio.h>

static unsigned long long lcg_state = 0x9E3779B97F4A7C15ULL;

static double lcg_uniform(void) /* [0, 1) */
{
    lcg_state = lcg_state * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(lcg_state >> 11) * (1.0 / 9007199254740992.0);
}

/* Multiply c[0..*deg] by (x^2 + b x + e) or (x - r). */
static void mul_quad(double *c, int *deg, double b, double e)
{
    int i;
    c[*deg + 2] = 0.0;
    c[*deg + 1] = 0.0;
    for (i = *deg; i >= 0; --i) {
        c[i + 2] += c[i];
        c[i + 1] += b * c[i];
        c[i] *= e;
    }
    *deg += 2;
}

static void mul_lin(double *c, int *deg, double r)
{
    int i;
    c[*deg + 1] = 0.0;
    for (i = *deg; i >= 0; --i) {
        c[i + 1] += c[i];
        c[i] *= -r;
    }
    *deg += 1;
}

/* One generated case: random real roots, complex pairs, clusters, doubles. */
static int gen_case(double *c)
{
    int deg = 0, target = 1 + (int)(lcg_uniform() * 8.0), kind = (int)(lcg_uniform() * 6.0);
    double r, gap;
    c[0] = 0.5 + lcg_uniform();
    while (deg < target) {
        r = (lcg_uniform() * 2.0 - 1.0) * pow(10.0, lcg_uniform() * 4.0 - 2.0);
        if (kind == 0 && deg + 2 <= target) {
            mul_quad(c, &deg, -2.0 * r, r * r + pow(10.0, -2.0 - 12.0 * lcg_uniform()));
        } else if (kind == 1 && deg + 2 <= target) {
            gap = pow(10.0, -3.0 - 5.0 * lcg_uniform());
            mul_lin(c, &deg, r);
            mul_lin(c, &deg, r + gap);
        } else if (kind == 2 && deg + 2 <= target) {
            mul_lin(c, &deg, r);
            mul_lin(c, &deg, r);
        } else if (kind == 3 && deg + 2 <= target) {
            mul_quad(c, &deg, -2.0 * r, r * r + 1.0 + lcg_uniform());
        } else {
            mul_lin(c, &deg, r);
        }
        kind = (int)(lcg_uniform() * 6.0);
    }
    return deg;
}

static int check_case(const double *c, int n, int verbose)
{
    double roots[WK_POLY_MAXDEG];
    unsigned flags[WK_POLY_MAXDEG];
    int status = -1, cnt, i, bad = 0;
    for (i = 0; i < WK_POLY_MAXDEG; ++i) {
        roots[i] = -12345.0;
        flags[i] = 77u;
    }
    cnt = wk_poly_real_roots(c, n, roots, flags, &status, WK_POLY_TOL_TOUCH);
    if (cnt < 0 || (n >= 0 && n <= WK_POLY_MAXDEG && cnt > n) || cnt > WK_POLY_MAXDEG) bad = 1;
    if (status < 0 || status > 15) bad = 1;
    for (i = 0; i < cnt && i < WK_POLY_MAXDEG; ++i) {
        if (!(fabs(roots[i]) <= 1.7976931348623157e308)) bad = 1;
        if (flags[i] > 1u) bad = 1;
        if (i > 0 && !(roots[i] > roots[i - 1])) bad = 1;
    }
    if (verbose) {
        printf("%d %d", cnt, status);
        for (i = 0; i < cnt && i < WK_POLY_MAXDEG; ++i) printf(" %a %u", roots[i], flags[i]);
        printf("\n");
    }
    return bad;
}

int main(int argc, char **argv)
{
    double c[WK_POLY_MAXDEG + 3];
    int n, i, ncase = 0, nbad = 0;
    if (argc > 1) {
        FILE *fp = fopen(argv[1], "r");
        if (!fp) return 2;
        while (fscanf(fp, "%d", &n) == 1) {
            if (n < 0 || n > WK_POLY_MAXDEG) return 3;
            for (i = 0; i <= n; ++i)
                if (fscanf(fp, "%lf", &c[i]) != 1) return 3;
            nbad += check_case(c, n, 1);
            ++ncase;
        }
        fclose(fp);
    } else {
        static const double specials[][9] = {
            {0, 0, 0, 0, 0, 0, 0, 0, 0},
            {1, 0, 0, 0, 0, 0, 0, 0, 0},
            {0, 0, 0, 0, 0, 0, 0, 0, 1},
            {0, 0, 1, 0, 0, 0, 0, 0, 0},
            {1e-300, 1, 0, 0, 0, 0, 0, 0, 1e-300},
            {1e300, -1e300, 1, 0, 0, 0, 0, 0, 1e-20},
            {4.9e-324, 0, 0, 0, 0, 0, 0, 0, -4.9e-324},
            {1, -8, 28, -56, 70, -56, 28, -8, 1},
        };
        for (i = 0; i < (int)(sizeof specials / sizeof specials[0]); ++i) {
            for (n = 0; n <= WK_POLY_MAXDEG; ++n) nbad += check_case(specials[i], n, 0);
        }
        c[0] = 1.0;
        c[1] = NAN;
        nbad += check_case(c, 1, 0);
        c[1] = INFINITY;
        nbad += check_case(c, 1, 0);
        nbad += check_case(c, -1, 0);
        nbad += check_case(c, 9, 0);
        for (ncase = 0; ncase < 20000; ++ncase) {
            n = gen_case(c);
            nbad += check_case(c, n, 0);
        }
    }
    fprintf(stderr, "%d cases, %d bad\n", ncase, nbad);
    return nbad ? 1 : 0;
}
#endif
