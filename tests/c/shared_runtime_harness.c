/* Test harness for the shared runtime's cores that the serial stages inline: subproblem 6 (runtime/c/wk_sp6.c) and
 * the spatial 3R (runtime/c/wk_spatial3.c), after the root finder, the polynomial operations and the 3-vector
 * helpers they call, compiled as they are with the tolerances the serial stages hand them (sr_sp6.c's SR_SP6_*,
 * the derived DEGENERATE_EPS; a chain of size 1 m), and the dense steps of runtime/c/wristkin_runtime.c (compiled
 * beside it). Built as a shared library by tests/test_shared_runtime.py; exports wkt_* wrappers for ctypes. */
#include <math.h>
#include <stddef.h>

#include "wristkin_common.h"

#define WKT_SCALE 1.0
#define WKT_DEGENERATE_EPS 1e-12
#define WKT_SP6_DOUBLE_ROOT_TOL 1e-12
#define WKT_SP6_TANGENT_TOL 1e-9
#define WKT_SP6_ON_AXIS_TOL 1e-12
#define WKT_SP6_FAMILY_TOL 1.4210854715202004e-14
#define WKT_S3_ON_AXIS_TOL 1e-12

#include "../../runtime/c/poly_real_roots.c"
#include "../../runtime/c/wk_poly_ops.c"
#include "../../runtime/c/wk_geom3.c"
#include "../../runtime/c/wk_spatial3.c"
#include "../../runtime/c/wk_sp6.c"

int wkt_solve_square(const double *a, int n, const double *b, double *x);
int wkt_lu_solve_many(const double *a, int n, const double *b, int m, double *x);
int wkt_sp6(const double *n, const double *h0, const double *p0, const double *h4, const double *p4, double d0,
            const double *g, const double *h5, double *q0, double *q4, unsigned *f, int *ord);
int wkt_sp6_split(const double *n, const double *h0, const double *p0, const double *h4, const double *p4, double d0,
                  const double *g, const double *h5, double q0, double q4, double *s0, double *s4);
int wkt_spatial3(const double *axes, const double *points, const double *x, const double *y, double *qa,
                 double *qb, double *qc, unsigned *f);

/* the serial sp6 stage's tolerances at scale 1 (sr_sp6_candidates) */
static wk_sp6_tols wkt_sp6_tols(void)
{
    wk_sp6_tols t;
    t.scale = WKT_SCALE;
    t.degenerate = WKT_DEGENERATE_EPS;
    t.double_root = WKT_SP6_DOUBLE_ROOT_TOL;
    t.tangent = WKT_SP6_TANGENT_TOL;
    t.on_axis = WKT_SP6_ON_AXIS_TOL;
    t.family = WKT_SP6_FAMILY_TOL;
    return t;
}

/* the polish's square step, the chain's relative pivot threshold */
int wkt_solve_square(const double *a, int n, const double *b, double *x)
{
    return wk_square_solve(a, n, b, 1e-8, x);
}

/* one factorization, then each of the m right-hand sides b (rows of n) solved from it into the rows of x */
int wkt_lu_solve_many(const double *a, int n, const double *b, int m, double *x)
{
    double lu[WK_MAX_DIM * WK_MAX_DIM];
    int perm[WK_MAX_DIM], i;
    if (!wk_lu_factor(a, n, 1e-8, lu, perm)) return 0;
    for (i = 0; i < m; ++i) wk_lu_solve(lu, perm, n, b + i * n, x + i * n);
    return 1;
}

/* (q0, q4, flags, order) of subproblem 6 with e0 = 0, at most WK_SP6_MAX */
int wkt_sp6(const double *n, const double *h0, const double *p0, const double *h4, const double *p4, double d0,
            const double *g, const double *h5, double *q0, double *q4, unsigned *f, int *ord)
{
    const wk_sp6_tols t = wkt_sp6_tols();
    return wk_sp6(n, h0, p0, h4, p4, d0, 0.0, g, h5, &t, q0, q4, f, ord);
}

/* the two roots a merged one near (q0, q4) stands for */
int wkt_sp6_split(const double *n, const double *h0, const double *p0, const double *h4, const double *p4, double d0,
                  const double *g, const double *h5, double q0, double q4, double *s0, double *s4)
{
    const wk_sp6_tols t = wkt_sp6_tols();
    return wk_sp6_split(n, h0, p0, h4, p4, d0, g, h5, q0, q4, &t, s0, s4);
}

/* three revolute lines (axes, points: 3 x 3 row-major) placing x on y; the candidates' joints in qa, qb, qc */
int wkt_spatial3(const double *axes, const double *points, const double *x, const double *y, double *qa,
                 double *qb, double *qc, unsigned *f)
{
    double q[WK_S3_MAX][3];
    int i;
    const int n = wk_spatial3((const double (*)[3])axes, (const double (*)[3])points, x, y, WKT_SCALE,
                              WKT_DEGENERATE_EPS, WKT_S3_ON_AXIS_TOL, q, f);
    for (i = 0; i < n; ++i) {
        qa[i] = q[i][0];
        qb[i] = q[i][1];
        qc[i] = q[i][2];
    }
    return n;
}
