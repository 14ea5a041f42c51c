/* Test harness for the SCARA + 3-RSR hybrid's hand-written sources (runtime/c/rsr/rsr_legs.c, the 3-RSR core, and
 * scara_rsr_api.c, its verbs), compiled as they are where the hybrid's generated C inlines them: after
 * rsr_prelude.h (the generated scara_rsr.c up to the core: header, sizes, types, derived kernels, tolerances) and,
 * before the verbs, rsr_between.h (the default design), which tests/test_rsr_runtime.py cuts from
 * generated/c/scara_rsr.c. Built as a shared library with runtime/c/wristkin_runtime.c. */
#include "rsr_prelude.h"
#include "../../runtime/c/rsr/rsr_legs.c"
#include "rsr_between.h"
#include "../../runtime/c/rsr/scara_rsr_api.c"

int wkt_hy_design_init(const double *params, hy_design *design);
int wkt_hy_ik(const double *pose, const hy_design *design, hy_ik_solutions *out);
int wkt_hy_fk(const double *joints, const hy_design *design, hy_fk_solutions *out);

int wkt_hy_design_init(const double *params, hy_design *design)
{
    return hy_api_design_init(params, design);
}

int wkt_hy_ik(const double *pose, const hy_design *design, hy_ik_solutions *out)
{
    return hy_api_ik(pose, design, out);
}

int wkt_hy_fk(const double *joints, const hy_design *design, hy_fk_solutions *out)
{
    return hy_api_fk(joints, design, out);
}

/* the other verbs (tests/test_scara_rsr.py runs them through the generated binding), the core's functions the
 * hybrid does not call and the prelude's kernels (rsr_kernels.h), referenced so that the strict flags see no
 * unused function */
void (*const wkt_hy_verbs[])(void) = {
    (void (*)(void))hy_api_fk_matrix, (void (*)(void))hy_api_jacobian, (void (*)(void))hy_api_middle_lbw,
    (void (*)(void))hy_api_ik_batch, (void (*)(void))hy_api_fk_batch, (void (*)(void))hy_api_select_ik,
    (void (*)(void))rsr_design_ok, (void (*)(void))rsr_legs, (void (*)(void))rsr_plane,
    (void (*)(void))rsr_plane_of_set, (void (*)(void))rsr_pose_of_plane, (void (*)(void))rsr_leg_cond_inverse,
    (void (*)(void))rsr_workspace};
#include "rsr_kernels.h"
