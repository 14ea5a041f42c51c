/* Test harness for the 3-RSR core (runtime/c/rsr/rsr_legs.c), compiled as it is where the wrist's generated C
 * inlines it: after rsr_prelude.h (the generated rsr_wrist.c up to the source: its header, derived kernels rsr_k_*
 * and RSR_* tolerances), which tests/test_rsr_runtime.py cuts from generated/c/rsr_wrist.c. Built as a shared
 * library with runtime/c/wristkin_runtime.c; exports wkt_rsr_* wrappers for ctypes. */
#include "rsr_prelude.h"
#include "../../runtime/c/rsr/rsr_legs.c"

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

/* the prelude's kernels the core does not call, referenced (rsr_kernels.h, written by the test from their names) */
#include "rsr_kernels.h"
