/* ASan/UBSan driver for the generated 3-RSR wrist and SCARA + 3-RSR hybrid: every entry point, including
 * NULL pointers, non-finite input, degenerate configurations and batches. Exit 0 = no failed expectation. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "rsr_wrist.h"
#include "scara_rsr.h"

static int failures = 0;
#define EXPECT(c)                                                     \
    do {                                                              \
        if (!(c)) {                                                   \
            fprintf(stderr, "%s:%d: expected %s\n", __FILE__, __LINE__, #c); \
            ++failures;                                               \
        }                                                             \
    } while (0)

static double urand(double lo, double hi)
{
    return lo + (hi - lo) * ((double)rand() / (double)RAND_MAX);
}

static void wrist(void)
{
    wk_rsr_wrist_design d;
    wk_rsr_wrist_ik_solutions ik, many[4];
    wk_rsr_wrist_fk_solutions fk;
    double pose[3] = {0.3, 0.5, 0.08}, bad[3] = {NAN, 0.1, 0.08}, poses[12], jq[3], jx[9], span[2], g, a;
    double params[5] = {0.06, 0.4, 1.3, 0.02, 0.1}, badp[5] = {0.06, 1.3, 0.4, 0.02, 0.1};
    int i, k;
    EXPECT(wk_rsr_wrist_design_init(NULL, &d) == WK_OK);
    EXPECT(wk_rsr_wrist_design_init(params, &d) == WK_OK);
    EXPECT(wk_rsr_wrist_design_init(badp, &d) == WK_ERR_DESIGN);
    EXPECT(wk_rsr_wrist_design_init(params, NULL) == WK_ERR_NULL);
    EXPECT(wk_rsr_wrist_ik(pose, NULL, &ik) == WK_OK && ik.count == 8);
    EXPECT(wk_rsr_wrist_ik(bad, NULL, &ik) == WK_ERR_NONFINITE && ik.count == 0);
    EXPECT(wk_rsr_wrist_ik(NULL, NULL, &ik) == WK_ERR_NULL);
    EXPECT(wk_rsr_wrist_ik(pose, NULL, NULL) == WK_ERR_NULL);
    pose[2] = 0.5;
    EXPECT(wk_rsr_wrist_ik(pose, NULL, &ik) == WK_OK && ik.status == WK_STATUS_UNREACHABLE);
    pose[2] = 0.08;
    for (k = 0; k < 2000; ++k) {
        double q[3], p[3];
        for (i = 0; i < 3; ++i) q[i] = urand(-4.0, 4.0);
        EXPECT(wk_rsr_wrist_fk(q, NULL, &fk) == WK_OK);
        if (fk.count) {
            for (i = 0; i < 3; ++i) p[i] = fk.values[0][i];
            if (p[1] <= 3.14159) EXPECT(wk_rsr_wrist_ik(p, NULL, &ik) == WK_OK);
            EXPECT(wk_rsr_wrist_jacobians(q, p, NULL, jq, jx) == WK_OK);
            (void)wk_rsr_wrist_select_ik(&ik, q, NULL, NULL);
        }
    }
    {
        const double q[3] = {1.5707963267948966, 1.5707963267948966, 1.5707963267948966};
        EXPECT(wk_rsr_wrist_fk(q, NULL, &fk) == WK_OK && fk.status == WK_STATUS_NO_ASSEMBLY);
    }
    for (i = 0; i < 12; ++i) poses[i] = i % 3 == 2 ? 0.07 : 0.1 * i;
    EXPECT(wk_rsr_wrist_ik_batch(4, poses, NULL, many) == WK_OK);
    EXPECT(wk_rsr_wrist_ik_batch(0, NULL, NULL, NULL) == WK_OK);
    EXPECT(wk_rsr_wrist_fk_batch(1, NULL, NULL, NULL) == WK_ERR_NULL);
    EXPECT(wk_rsr_wrist_select_ik(NULL, NULL, NULL, NULL) == -1);
    {
        double jac[18];
        const double q[3] = {0.7, 0.8, 0.9}, qc[3] = {1.5707963267948966, 1.5707963267948966, 1.5707963267948966};
        EXPECT(wk_rsr_wrist_jacobian(q, NULL, jac) == WK_OK);
        EXPECT(wk_rsr_wrist_jacobian(qc, NULL, jac) == WK_STATUS_NO_ASSEMBLY);
        EXPECT(wk_rsr_wrist_jacobian(NULL, NULL, jac) == WK_ERR_NULL);
    }
    EXPECT(wk_rsr_wrist_workspace(0.3, 0.4, NULL, span) == WK_OK && span[0] <= span[1]);
    EXPECT(wk_rsr_wrist_workspace(0.3, 3.0, NULL, span) == WK_STATUS_UNREACHABLE);
    EXPECT(wk_rsr_wrist_workspace(NAN, 0.4, NULL, span) == WK_ERR_NONFINITE);
    EXPECT(wk_rsr_wrist_gamma_from_azimuth(0.7, 0.5, &g) == WK_OK);
    EXPECT(wk_rsr_wrist_azimuth_from_gamma(g, 0.5, &a) == WK_OK && fabs(a - 0.7) < 1e-12);
    EXPECT(wk_rsr_wrist_azimuth_from_gamma(g, 1.5707963267948966, &a) == WK_ERR_RANGE);
    { /* the design atlas's block sums and swing profile */
        int64_t sums[WK_ATLAS_MODES + WK_RSR_WRIST_MAX_FK + 1] = {0}, index[72];
        double li_min = HUGE_VAL, joints[12], alpha[72], beta[181];
        for (i = 0; i < 12; ++i) joints[i] = urand(0.4, 1.3);
        EXPECT(wk_rsr_wrist_design_init(params, &d) == WK_OK);
        EXPECT(wk_rsr_wrist_atlas_batch(4, poses, 4, joints, &d, 0.1, sums, &li_min) == WK_OK);
        EXPECT(sums[WK_ATLAS_MODES] + sums[WK_ATLAS_MODES + 1] == 4 && sums[WK_ATLAS_N_REACH] <= 4);
        EXPECT(sums[WK_ATLAS_N_SETS] == 0 || (li_min >= 0.0 && li_min <= 1.0));
        EXPECT(wk_rsr_wrist_atlas_batch(0, NULL, 0, NULL, NULL, 0.1, sums, &li_min) == WK_OK);
        EXPECT(wk_rsr_wrist_atlas_batch(1, NULL, 0, NULL, NULL, 0.1, sums, &li_min) == WK_ERR_NULL);
        EXPECT(wk_rsr_wrist_atlas_batch(1, bad, 0, NULL, NULL, 0.1, sums, &li_min) == WK_ERR_NONFINITE);
        for (i = 0; i < 72; ++i) alpha[i] = 0.08726646259971647 * i;
        for (i = 0; i < 181; ++i) beta[i] = 0.008726646259971647 * i;
        EXPECT(wk_rsr_wrist_max_swing(&d, 72, alpha, 181, beta, index) == WK_OK);
        for (i = 0; i < 72; ++i) EXPECT(index[i] >= -1 && index[i] < 181);
        EXPECT(wk_rsr_wrist_max_swing(&d, 72, alpha, 5000, NULL, index) == WK_ERR_NULL);
        EXPECT(wk_rsr_wrist_max_swing(&d, 1, alpha, 5000, beta, index) == WK_ERR_RANGE);
        EXPECT(wk_rsr_wrist_max_swing(&d, 1, bad, 181, beta, index) == WK_ERR_NONFINITE);
    }
}

static void hybrid(void)
{
    wk_scara_rsr_design d;
    wk_scara_rsr_ik_solutions ik, many[2];
    wk_scara_rsr_fk_solutions fk;
    double q[7] = {0.3, 1.0, 0.1, 0.2, 0.8, 0.9, 1.0}, pose[13], p12[12], lbw, poses[26];
    double w[7] = {1, 0, 0, 0, 0, 0, 0};
    int i, k;
    EXPECT(wk_scara_rsr_design_init(NULL, &d) == WK_OK);
    EXPECT(wk_scara_rsr_fk(q, &d, &fk) == WK_OK && fk.count == 1);
    for (i = 0; i < 13; ++i) pose[i] = fk.values[0][i];
    EXPECT(wk_scara_rsr_ik(pose, NULL, &ik) == WK_OK && ik.count == 16);
    EXPECT(wk_scara_rsr_select_ik(&ik, q, NULL, NULL, w) >= 0);
    EXPECT(wk_scara_rsr_select_ik(NULL, q, NULL, NULL, w) == -1);
    EXPECT(wk_scara_rsr_fk_matrix(q, NULL, p12) == WK_OK);
    EXPECT(wk_scara_rsr_middle_lbw(p12, NULL, &lbw) == WK_OK);
    {
        double jac[42];
        EXPECT(wk_scara_rsr_jacobian(q, NULL, jac) == WK_OK);
        EXPECT(wk_scara_rsr_jacobian(q, NULL, NULL) == WK_ERR_NULL);
    }
    EXPECT(wk_scara_rsr_middle_lbw(NULL, NULL, &lbw) == WK_ERR_NULL);
    pose[3] += 5.0;
    EXPECT(wk_scara_rsr_ik(pose, NULL, &ik) == WK_OK && ik.status == WK_STATUS_UNREACHABLE && ik.count == 0);
    pose[0] = INFINITY;
    EXPECT(wk_scara_rsr_ik(pose, NULL, &ik) == WK_ERR_NONFINITE);
    pose[0] = 2.0;
    EXPECT(wk_scara_rsr_ik(pose, NULL, &ik) == WK_ERR_RANGE);
    for (k = 0; k < 2000; ++k) {
        for (i = 0; i < 7; ++i) q[i] = urand(-4.0, 4.0);
        EXPECT(wk_scara_rsr_fk(q, NULL, &fk) == WK_OK);
        if (fk.count) {
            for (i = 0; i < 13; ++i) pose[i] = fk.values[0][i];
            EXPECT(wk_scara_rsr_ik(pose, NULL, &ik) == WK_OK);
        }
    }
    for (i = 0; i < 26; ++i) poses[i] = pose[i % 13];
    EXPECT(wk_scara_rsr_ik_batch(2, poses, NULL, many) == WK_OK);
    EXPECT(wk_scara_rsr_fk_batch(0, NULL, NULL, NULL) == WK_OK);
}

int main(void)
{
    srand(7);
    wrist();
    hybrid();
    if (failures) fprintf(stderr, "%d expectation(s) failed\n", failures);
    return failures ? 1 : 0;
}
