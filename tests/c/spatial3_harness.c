/* Test harness: the spatial 3R core (runtime/c/wk_spatial3.c) as it is inlined, after the root finder it calls,
 * exported for ctypes (tests/test_spatial3_runtime.py). */
#include <math.h>

#include "wristkin_common.h"

#include "../../runtime/c/poly_real_roots.c"
#include "../../runtime/c/wk_poly_ops.c"
#include "../../runtime/c/wk_geom3.c"
#include "../../runtime/c/wk_spatial3.c"

int wkt_spatial3_lines(const double *h, const double *r, const double *x, const double *y, double scale, double eps,
                       double on_axis, double *q, unsigned *fl);

/* h, r: 3 x 3 row-major (a line per row); q: WK_S3_MAX x 3; fl: WK_S3_MAX */
int wkt_spatial3_lines(const double *h, const double *r, const double *x, const double *y, double scale, double eps,
                       double on_axis, double *q, unsigned *fl)
{
    return wk_spatial3((const double (*)[3])h, (const double (*)[3])r, x, y, scale, eps, on_axis, (double (*)[3])q, fl);
}
