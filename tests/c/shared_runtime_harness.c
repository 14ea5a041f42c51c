/* Test harness for the user-robot solver's kernels (runtime/c/chain/ck_*.c), compiled as they are with the
 * constants a generated solver defines before inlining them (here: a 6-joint chain of size 1 m, the default
 * tolerances). Built as a shared library by tests/test_chain_runtime.py (with runtime/c/wristkin_runtime.c);
 * exports wkt_* wrappers for ctypes. */
#include <math.h>
#include <stddef.h>

#include "wristkin_common.h"

#define CK_N 6
#define CK_DIM 8
#define CK_PI 3.14159265358979323846
#define CK_TWO_PI 6.28318530717958647692
#define CK_EPS 2.220446049250313e-16
#define CK_TANGENT_TOL 1e-9
#define CK_DOUBLE_ROOT_TOL 1e-12
#define CK_STAGE_NOISE (16.0 * CK_EPS)
#define CK_IK_VERIFY_TOL 1e-9
#define CK_LENGTH_MAX 1e6
#define CK_SINGULAR_EPS 1e-6
#define CK_SCALE 1.0
#define CK_DEGENERATE_EPS 1e-12
#define CK_FAMILY_TOL 1e-10 /* the bands of a robot with a polynomial stage (views.stage_tolerances) */
#define CK_ON_AXIS_TOL 1e-12
#define CK_POLISH_STEPS 8
#define CK_POLISH_TOL (1e-12 * (CK_SCALE > 1.0 ? CK_SCALE : 1.0))
#define CK_SAME_TOL 1e-9
/* the variants a robot with a held joint read from the tool compiles (ck_held, ck_reversed) */
#define CK_FREE 2
#define CK_REVERSED 1

#include "../../runtime/c/chain/ck_rigid.c"
#include "../../runtime/c/chain/ck_types.h"
#include "../../runtime/c/chain/ck_chain.c"
#include "../../runtime/c/chain/ck_dense.c"
#include "../../runtime/c/chain/ck_subproblems.c"
#include "../../runtime/c/chain/ck_points.c"
#include "../../runtime/c/chain/ck_verify.c"
#include "../../runtime/c/poly_real_roots.c"
#include "../../runtime/c/wk_poly_ops.c"
#include "../../runtime/c/wk_geom3.c"
#include "../../runtime/c/wk_spatial3.c"
#include "../../runtime/c/chain/ck_spatial3.c"
#include "../../runtime/c/wk_sp6.c"
#include "../../runtime/c/chain/ck_sp6.c"

/* ck_chain from flat arrays: kinds[n] (1 = slide), axes[3n], points[3n], home[12] (top 3x4 row-major) */
static void wkt_chain(int n, const int *kinds, const double *axes, const double *points, const double *home,
                      ck_chain *o)
{
    int i, j;
    o->n = n;
    for (i = 0; i < n; ++i) {
        o->prismatic[i] = kinds[i];
        o->index[i] = i;
        for (j = 0; j < 3; ++j) {
            o->axis[i][j] = axes[3 * i + j];
            o->point[i][j] = points[3 * i + j];
        }
    }
    ck_from12(home, &o->home);
}

int wkt_trig(double a, double b, double c, double *t, unsigned *f);
int wkt_conditioning(const double *jac, int n, double *man);
void wkt_perpendicular(const double *k, double *o);
void wkt_orient_rest(const double *u, const double *rd, double t1, double t2, double *angles);
void wkt_transpose(const double *r, double *o);
int wkt_sp6_split(const double *n, const double *h0, const double *p0, const double *h4, const double *p4, double d0,
                  const double *g, const double *h5, double q0, double q4, double *s0, double *s4);
void wkt_meet_point(const double *axes, const double *points, int spec, int j0, int j1, double *o);
double wkt_root_amplification(int nr, const double *t, const unsigned *f, double outer);
int wkt_sp1(const double *k, const double *p, const double *q, double *t);
int wkt_sp2(const double *p1, const double *k1, const double *p2, const double *k2, int split, double *t1, int *has1,
            double *t2, unsigned *f);
int wkt_sp3(const double *k, const double *p1, const double *p2, double d, double *t, unsigned *f);
int wkt_sp4(const double *h, const double *k, const double *p, double d, double *t, unsigned *f);
int wkt_sp6(const double *n, const double *h0, const double *p0, const double *h4, const double *p4, double d0,
            const double *g, const double *h5, double *q0, double *q4, unsigned *f);
void wkt_lstsq(const double *a, int m, int n, const double *b, double *x);
int wkt_solve_square(const double *a, int n, const double *b, double *x);
double wkt_spectrum(const double *jac, int n, double *ratio);
void wkt_fk(int n, const int *kinds, const double *axes, const double *points, const double *home, const double *q,
            double *pose);
void wkt_jacobian(int n, const int *kinds, const double *axes, const double *points, const double *home,
                  const double *q, double *jac);
double wkt_polish(int n, const int *kinds, const double *axes, const double *points, const double *home, double *q,
                  const double *target);
void wkt_held_reversed_fk(int n, const int *kinds, const double *axes, const double *points, const double *home,
                          double held, const double *q, double *pose);
int wkt_spatial3(const double *axes, const double *points, const double *x, const double *y, double *qa,
                 double *qb, double *qc, unsigned *f);

int wkt_trig(double a, double b, double c, double *t, unsigned *f)
{
    return ck_trig(a, b, c, 1.0, 1.0, t, f);
}

double wkt_root_amplification(int nr, const double *t, const unsigned *f, double outer)
{
    return ck_root_amplification(nr, t, f, outer);
}

int wkt_sp1(const double *k, const double *p, const double *q, double *t)
{
    return ck_sp1(k, p, q, CK_SCALE, t);
}

int wkt_sp2(const double *p1, const double *k1, const double *p2, const double *k2, int split, double *t1, int *has1,
            double *t2, unsigned *f)
{
    return ck_sp2(p1, k1, p2, k2, CK_SCALE, split, 1.0, CK_FAMILY_TOL, t1, has1, t2, f);
}

int wkt_sp3(const double *k, const double *p1, const double *p2, double d, double *t, unsigned *f)
{
    return ck_sp3(k, p1, p2, d, CK_SCALE, 1.0, NULL, 1.0, t, f);
}

int wkt_sp4(const double *h, const double *k, const double *p, double d, double *t, unsigned *f)
{
    return ck_sp4(h, k, p, d, CK_SCALE, 1.0, t, f);
}

int wkt_sp6(const double *n, const double *h0, const double *p0, const double *h4, const double *p4, double d0,
            const double *g, const double *h5, double *q0, double *q4, unsigned *f)
{
    int ord[CK_SP6_MAX];
    return ck_sp6(n, h0, p0, h4, p4, d0, 0.0, g, h5, q0, q4, f, ord);
}

void wkt_lstsq(const double *a, int m, int n, const double *b, double *x)
{
    ck_lstsq(a, m, n, b, x);
}

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

double wkt_spectrum(const double *jac, int n, double *ratio)
{
    return ck_spectrum(jac, n, ratio);
}

void wkt_fk(int n, const int *kinds, const double *axes, const double *points, const double *home, const double *q,
            double *pose)
{
    ck_chain ch;
    ck_rt t;
    wkt_chain(n, kinds, axes, points, home, &ch);
    ck_fk_chain(&ch, q, &t);
    ck_to12(&t, pose);
}

void wkt_jacobian(int n, const int *kinds, const double *axes, const double *points, const double *home,
                  const double *q, double *jac)
{
    ck_chain ch;
    ck_rt t;
    wkt_chain(n, kinds, axes, points, home, &ch);
    ck_jacobian_chain(&ch, q, jac, &t);
}

double wkt_polish(int n, const int *kinds, const double *axes, const double *points, const double *home, double *q,
                  const double *target)
{
    ck_chain ch;
    ck_rt t;
    wkt_chain(n, kinds, axes, points, home, &ch);
    ck_from12(target, &t);
    return ck_polish(&ch, q, &t);
}

/* FK of the chain with joint CK_FREE held at `held`, read from the tool (q: the n - 1 remaining joints in the
 * reversed chain's order): the inverse of the end frame */
void wkt_held_reversed_fk(int n, const int *kinds, const double *axes, const double *points, const double *home,
                          double held, const double *q, double *pose)
{
    ck_chain ch, h, r;
    ck_rt t;
    wkt_chain(n, kinds, axes, points, home, &ch);
    ck_held(&ch, CK_FREE, held, &h);
    ck_reversed(&h, &r);
    ck_fk_chain(&r, q, &t);
    ck_to12(&t, pose);
}

/* the first three joints of a 3-joint chain (home unused) */
int wkt_spatial3(const double *axes, const double *points, const double *x, const double *y, double *qa,
                 double *qb, double *qc, unsigned *f)
{
    static const int kinds[3] = {0, 0, 0};
    static const double home[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    ck_chain ch;
    wkt_chain(3, kinds, axes, points, home, &ch);
    return ck_spatial3(&ch, 0, 1, 2, x, y, qa, qb, qc, f);
}

/* 1 when J (6 x n) is flagged singular (sigma_min / sigma_max <= CK_SINGULAR_EPS); man = its manipulability */
int wkt_conditioning(const double *jac, int n, double *man)
{
    int singular = 0;
    *man = ck_conditioning(jac, n, &singular);
    return singular * 2 + ck_is_singular(jac, n); /* both readings of the same test: 3 or 0 */
}

void wkt_perpendicular(const double *k, double *o)
{
    ck_perpendicular(k, o);
}

void wkt_orient_rest(const double *u, const double *rd, double t1, double t2, double *angles)
{
    const double *const units[3] = {u, u + 3, u + 6};
    ck_orient_rest(3, units, rd, t1, t2, angles);
}

void wkt_transpose(const double *r, double *o)
{
    ck_transpose(r, o);
}

int wkt_sp6_split(const double *n, const double *h0, const double *p0, const double *h4, const double *p4, double d0,
                  const double *g, const double *h5, double q0, double q4, double *s0, double *s4)
{
    return ck_sp6_split(n, h0, p0, h4, p4, d0, g, h5, q0, q4, s0, s4);
}

/* the point (CK_MEET, CK_ON) or direction (CK_DIR, CK_CROSS) an op's spec names on a 3-joint chain, joints j0, j1 */
void wkt_meet_point(const double *axes, const double *points, int spec, int j0, int j1, double *o)
{
    static const int kinds[3] = {0, 0, 0};
    static const double home[12] = {1, 0, 0, 0.5, 0, 1, 0, 0.25, 0, 0, 1, 0.125};
    ck_chain ch;
    ck_op op;
    wkt_chain(3, kinds, axes, points, home, &ch);
    op.spec = spec;
    op.n_spec = spec == CK_MEET || spec == CK_CROSS ? 2 : 1;
    op.spec_js[0] = j0;
    op.spec_js[1] = j1;
    ck_point(&ch, &op, o);
}
