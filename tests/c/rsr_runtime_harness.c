/* Test harness for the 3-RSR wrist's hand-written sources (runtime/c/rsr/rsr_legs.c, the core it shares with the
 * SCARA hybrid, and rsr_wrist_api.c, its verbs), compiled as they are where the wrist's generated C inlines them:
 * after rsr_prelude.h (the generated rsr_wrist.c up to the core: its header, sizes, types, derived kernels rsr_k_*
 * and RSR_* tolerances) and, before the verbs, rsr_between.h (the default design), which tests/test_rsr_runtime.py
 * cuts from generated/c/rsr_wrist.c. Built as a shared library with runtime/c/wristkin_runtime.c; exports wkt_rsr_*
 * wrappers for ctypes. */
#include "rsr_prelude.h"
#include "../../runtime/c/rsr/rsr_legs.c"
#include "rsr_between.h"
#include "../../runtime/c/rsr/rsr_wrist_api.c"

int wkt_rsr_design_ok(const double *w);
int wkt_rsr_legs(const double *pose, const double *w, double *leg, unsigned *flags, double *cond);
int wkt_rsr_plane(const double *q, const double *w, double *plane, double *cond);
int wkt_rsr_plane_of_set(const double *leg, int word, const double *w, double *plane, double *cond);
int wkt_rsr_pose_of_plane(const double *plane, double *pose);
double wkt_rsr_leg_cond_inverse(const double *q, const double *pose, const double *w);
int wkt_rsr_workspace(double alpha, double beta, const double *w, double *span);

int wkt_rsr_design_ok(const double *w)
{
    return rsr_design_ok(w);
}

/* leg: 3 x 2 x 4 (phi, cos, sin, residual per leg and root) */
int wkt_rsr_legs(const double *pose, const double *w, double *leg, unsigned *flags, double *cond)
{
    double l[3][2][4];
    int i, b, k;
    const int ok = rsr_legs(pose, w, l, flags, cond);
    for (i = 0; i < 3; ++i)
        for (b = 0; b < 2; ++b)
            for (k = 0; k < 4; ++k) leg[(i * 2 + b) * 4 + k] = l[i][b][k];
    return ok;
}

int wkt_rsr_plane(const double *q, const double *w, double *plane, double *cond)
{
    return rsr_plane(q, w, plane, cond);
}

int wkt_rsr_plane_of_set(const double *leg, int word, const double *w, double *plane, double *cond)
{
    double l[3][2][4];
    int i, b, k;
    for (i = 0; i < 3; ++i)
        for (b = 0; b < 2; ++b)
            for (k = 0; k < 4; ++k) l[i][b][k] = leg[(i * 2 + b) * 4 + k];
    return rsr_plane_of_set(l, word, w, plane, cond);
}

int wkt_rsr_pose_of_plane(const double *plane, double *pose)
{
    return rsr_pose_of_plane(plane, pose);
}

double wkt_rsr_leg_cond_inverse(const double *q, const double *pose, const double *w)
{
    return rsr_leg_cond_inverse(q, pose, w);
}

int wkt_rsr_workspace(double alpha, double beta, const double *w, double *span)
{
    return rsr_workspace(alpha, beta, w, span);
}

int wkt_rsr_design_init(const double *params, rsr_design *design);
int wkt_rsr_ik(const double *pose, const rsr_design *design, rsr_ik_solutions *out);
int wkt_rsr_fk(const double *joints, const rsr_design *design, rsr_fk_solutions *out);

int wkt_rsr_design_init(const double *params, rsr_design *design)
{
    return rsr_api_design_init(params, design);
}

int wkt_rsr_ik(const double *pose, const rsr_design *design, rsr_ik_solutions *out)
{
    return rsr_api_ik(pose, design, out);
}

int wkt_rsr_fk(const double *joints, const rsr_design *design, rsr_fk_solutions *out)
{
    return rsr_api_fk(joints, design, out);
}

/* the other verbs (tests/test_rsr_wrist.py runs them through the generated binding) and the prelude's kernels the
 * sources do not call, referenced so that the strict flags see no unused function (rsr_kernels.h: the kernels'
 * names, written by the test) */
void (*const wkt_rsr_verbs[])(void) = {
    (void (*)(void))rsr_api_ik_batch, (void (*)(void))rsr_api_fk_batch, (void (*)(void))rsr_api_atlas_batch,
    (void (*)(void))rsr_api_max_swing, (void (*)(void))rsr_api_select_ik, (void (*)(void))rsr_api_jacobians,
    (void (*)(void))rsr_api_jacobian, (void (*)(void))rsr_api_workspace, (void (*)(void))rsr_api_gamma_from_azimuth,
    (void (*)(void))rsr_api_azimuth_from_gamma};
#include "rsr_kernels.h"
