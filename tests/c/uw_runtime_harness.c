/* Test harness for the underactuated wrist's hand-written numerics (runtime/c/underactuated_wrist/uw_*.c),
 * compiled as they are with the names the generated solver defines before inlining them: the catalogue wrist's
 * tolerances, its generated header's types and its derived kernels uw_k_* (uw_kernels.h, which
 * tests/test_uw_runtime.py cuts from generated/c/underactuated_wrist.c: SymPy's output, not hand-written).
 * Built as a shared library with runtime/c/wristkin_runtime.c; exports wkt_uw_* wrappers for ctypes. */
#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "underactuated_wrist.h"

#define UW_PI 3.14159265358979323846
#define UW_TWO_PI 6.28318530717958647692
#define UW_SINGULAR_EPS 1e-6
#define UW_GIMBAL_EPS 1e-10
#define UW_TANGENT_TOL 1e-12
#define UW_DESIGN_MARGIN 1e-3
#define UW_FK_RESIDUAL_TOL 1e-10
#define UW_FK_DUPLICATE_TOL 1e-7
#define UW_FK_FOLD_TOL 1e-8
#define UW_POLISH_ITERS 40
/* the generated header's sizes and types, named as the runtime sources read them (as the template does) */
#define UW_N_JOINTS WK_UNDERACTUATED_WRIST_N_JOINTS
#define UW_N_POSE WK_UNDERACTUATED_WRIST_N_POSE
#define UW_MAX_IK WK_UNDERACTUATED_WRIST_MAX_IK
#define UW_MAX_FK WK_UNDERACTUATED_WRIST_MAX_FK
#define UW_N_IK_AUX WK_UNDERACTUATED_WRIST_N_IK_AUX
#define UW_N_FK_AUX WK_UNDERACTUATED_WRIST_N_FK_AUX
#define UW_N_CONSTANTS WK_UNDERACTUATED_WRIST_N_CONSTANTS
typedef wk_underactuated_wrist_design uw_design;
typedef wk_underactuated_wrist_ik_solutions uw_ik_solutions;
typedef wk_underactuated_wrist_fk_solutions uw_fk_solutions;

#include "uw_kernels.h"

#define WK_POLY_TOL_TOUCH 1e-8
#include "../../runtime/c/poly_real_roots.c"

/* the tests always pass a design (wkt_uw_design_init): the generated file's default is its printed data */
static const uw_design uw_default_design;

#include "../../runtime/c/underactuated_wrist/uw_geometry.c"
#include "../../runtime/c/underactuated_wrist/uw_design.c"
#include "../../runtime/c/underactuated_wrist/uw_ik.c"
#include "../../runtime/c/underactuated_wrist/uw_fk_modes.c"
#include "../../runtime/c/underactuated_wrist/uw_fk.c"
#include "../../runtime/c/underactuated_wrist/uw_select.c"
#include "../../runtime/c/underactuated_wrist/uw_rates.c"
#include "../../runtime/c/underactuated_wrist/uw_atlas.c"

int wkt_uw_design_init(const double *params, uw_design *design);
int wkt_uw_ik(const double *pose, const uw_design *design, uw_ik_solutions *out);
int wkt_uw_fk(const double *joints, const uw_design *design, uw_fk_solutions *out);
int wkt_uw_select_ik(const uw_ik_solutions *s, const double *previous, const double *lower, const double *upper);
int wkt_uw_select_fk(const uw_fk_solutions *s, const double *previous, const double *lower, const double *upper);
int wkt_uw_batches(size_t n, const double *poses, const double *joints, const uw_design *design,
                   uw_ik_solutions *ik, uw_fk_solutions *fk);
int wkt_uw_angular_acceleration(const double *joints, const double *pose, const double *qdot,
                                const double *qddot, const uw_design *design, double *wdot);
int wkt_uw_omega_from_euler_rates(const double *pose, const double *rates, double *w);
int wkt_uw_atlas(size_t n_pose, const double *poses, size_t n_joint, const double *joints, const uw_design *design,
                 double threshold, const int64_t *home, int64_t *sums, double *li_min, double *lo, double *hi);
void wkt_uw_euler(const double *pose, double *r, double *back, unsigned *flags);
void wkt_uw_polynomial(const double *trip, double ce, double se, double *kpoly);
double wkt_uw_polish(const double *trip, double *zeta, double *eta);

int wkt_uw_design_init(const double *params, uw_design *design)
{
    return uw_api_design_init(params, design);
}

int wkt_uw_ik(const double *pose, const uw_design *design, uw_ik_solutions *out)
{
    return uw_api_ik(pose, design, out);
}

int wkt_uw_fk(const double *joints, const uw_design *design, uw_fk_solutions *out)
{
    return uw_api_fk(joints, design, out);
}

int wkt_uw_select_ik(const uw_ik_solutions *s, const double *previous, const double *lower, const double *upper)
{
    return uw_api_select_ik(s, previous, lower, upper);
}

int wkt_uw_select_fk(const uw_fk_solutions *s, const double *previous, const double *lower, const double *upper)
{
    return uw_api_select_fk(s, previous, lower, upper);
}

int wkt_uw_batches(size_t n, const double *poses, const double *joints, const uw_design *design,
                   uw_ik_solutions *ik, uw_fk_solutions *fk)
{
    const int a = uw_api_ik_batch(n, poses, design, ik), b = uw_api_fk_batch(n, joints, design, fk);
    return a != WK_OK ? a : b;
}

int wkt_uw_angular_acceleration(const double *joints, const double *pose, const double *qdot,
                                const double *qddot, const uw_design *design, double *wdot)
{
    return uw_api_angular_acceleration(joints, pose, qdot, qddot, design, wdot);
}

int wkt_uw_omega_from_euler_rates(const double *pose, const double *rates, double *w)
{
    return uw_api_omega_from_euler_rates(pose, rates, w);
}

int wkt_uw_atlas(size_t n_pose, const double *poses, size_t n_joint, const double *joints, const uw_design *design,
                 double threshold, const int64_t *home, int64_t *sums, double *li_min, double *lo, double *hi)
{
    return uw_api_atlas_home_batch(n_pose, poses, n_joint, joints, design, threshold, home, sums, li_min, lo, hi);
}

/* R of a ZXZ pose, the angles read back from R, and the gimbal flag */
void wkt_uw_euler(const double *pose, double *r, double *back, unsigned *flags)
{
    uw_rotation(pose, r);
    *flags = uw_euler(r, back);
}

/* K0..K8 of the eliminant for loop coefficients trip[18] (D1, E1, F1, D2, E2, F2 as const, cos, sin) */
void wkt_uw_polynomial(const double *trip, double ce, double se, double *kpoly)
{
    uw_fk_coef cf;
    int j;
    for (j = 0; j < 18; ++j) cf.trip[j / 3][j % 3] = trip[j];
    uw_k_polynomial(&cf, ce, se, kpoly);
}

/* the polish from (zeta, eta); returns the final max |residual| */
double wkt_uw_polish(const double *trip, double *zeta, double *eta)
{
    uw_fk_coef cf;
    double cs[4];
    int j;
    for (j = 0; j < 18; ++j) cf.trip[j / 3][j % 3] = trip[j];
    cs[0] = cos(*zeta);
    cs[1] = sin(*zeta);
    cs[2] = cos(*eta);
    cs[3] = sin(*eta);
    return uw_polish(&cf, zeta, eta, cs);
}
