/* Test harness for a serial arm's hand-written numerics (runtime/c/serial/sr_*.c), compiled as they are where a
 * generated solver inlines them: after serial_prelude.h (the robot's constants, switches, types, derived kernels
 * and data) and, for sr_ik.c, serial_stages.h (its stage functions), both of which tests/test_serial_runtime.py
 * cuts from the robot's generated C (SymPy's output and printed data, not hand-written). Built as a shared
 * library with runtime/c/wristkin_runtime.c; exports wkt_sr_* wrappers for ctypes (every sr_api_* is called, so
 * the strict flags see no unused function). */
#include "serial_prelude.h"
#include "../../runtime/c/serial/sr_frames.c"
#include "../../runtime/c/serial/sr_input.c"
#include "../../runtime/c/serial/sr_fk.c"
#include "../../runtime/c/serial/sr_stages.c"
#include "../../runtime/c/serial/sr_verify.c"
#include "serial_stages.h"
#include "../../runtime/c/serial/sr_ik.c"

int wkt_sr_sizes(int *n, int *max_ik);
int wkt_sr_design_init(const double *params, sr_design *design);
int wkt_sr_design_set_frames(sr_design *design, const double *base, const double *tool);
int wkt_sr_ik(const double *pose, const double *previous, double *values, int *valid, unsigned *flags, double *aux);
int wkt_sr_ik_batch(size_t n, const double *poses, sr_ik_solutions *out);
int wkt_sr_fk(const double *joints, double *pose, double *jac, double *man, unsigned *flags);
int wkt_sr_fk_batch(size_t n, const double *joints, sr_fk_solutions *out);
int wkt_sr_select_ik(const sr_ik_solutions *s, const double *previous);
int wkt_sr_atlas(size_t n, const double *joints, double length, double threshold, int64_t *sums, double *li_min);
int wkt_sr_has_wrist(void);
double wkt_sr_wrist_amp(double s5, double amp_before, sr_stage_kernel centre, const double *pose);

int wkt_sr_sizes(int *n, int *max_ik)
{
    *n = SR_N;
    *max_ik = SR_MAX_IK;
    return (int)sizeof(sr_design);
}

int wkt_sr_design_init(const double *params, sr_design *design)
{
    return sr_api_design_init(params, design);
}

int wkt_sr_design_set_frames(sr_design *design, const double *base, const double *tool)
{
    return sr_api_design_set_frames(design, base, tool);
}

/* IK near `previous` (NULL: none) with the default design, the sets copied out flat */
int wkt_sr_ik(const double *pose, const double *previous, double *values, int *valid, unsigned *flags, double *aux)
{
    sr_ik_solutions out;
    int k, j;
    const int rc = previous ? sr_api_ik_near(pose, NULL, previous, &out) : sr_api_ik(pose, NULL, &out);
    for (k = 0; k < SR_MAX_IK; ++k) {
        valid[k] = out.valid[k];
        flags[k] = out.flags[k];
        aux[k] = out.aux[k][0];
        for (j = 0; j < SR_N; ++j) values[k * SR_N + j] = out.values[k][j];
    }
    return rc < 0 ? rc : out.status;
}

int wkt_sr_ik_batch(size_t n, const double *poses, sr_ik_solutions *out)
{
    return sr_api_ik_batch(n, poses, NULL, out);
}

int wkt_sr_fk(const double *joints, double *pose, double *jac, double *man, unsigned *flags)
{
    sr_fk_solutions out;
    int rc = sr_api_fk_matrix(joints, NULL, pose);
    if (rc == WK_OK) rc = sr_api_jacobian(joints, NULL, jac);
    if (rc == WK_OK) rc = sr_api_fk(joints, NULL, &out);
    *man = out.aux[0][0];
    *flags = out.flags[0];
    return rc;
}

int wkt_sr_fk_batch(size_t n, const double *joints, sr_fk_solutions *out)
{
    return sr_api_fk_batch(n, joints, NULL, out);
}

int wkt_sr_select_ik(const sr_ik_solutions *s, const double *previous)
{
    return sr_api_select_ik(s, previous, NULL, NULL);
}

int wkt_sr_atlas(size_t n, const double *joints, double length, double threshold, int64_t *sums, double *li_min)
{
    return sr_api_atlas_conditioning(n, joints, NULL, length, threshold, sums, li_min);
}

int wkt_sr_has_wrist(void)
{
    return SR_WRIST_STAGE >= 0;
}

/* The wrist's band factor from a centre kernel the caller gives (the prefix joints all zero: its own matter) */
double wkt_sr_wrist_amp(double s5, double amp_before, sr_stage_kernel centre, const double *pose)
{
#if SR_WRIST_STAGE >= 0
    double q[SR_N] = { 0.0 }, c[SR_N] = { 0.0 }, s[SR_N] = { 0.0 };
    return sr_wrist_amp(s5, amp_before, centre, pose, q, c, s, NULL);
#else
    (void)s5;
    (void)centre;
    (void)pose;
    return amp_before;
#endif
}
