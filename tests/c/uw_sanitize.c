/* Sanitizer driver: hammers the generated underactuated-wrist C API with random, degenerate and
   hostile inputs (NaN, inf, NULL, huge angles) under ASan/UBSan. Exit 0 = clean. */
#include <math.h>
#include <stdio.h>
#include "underactuated_wrist.h"
#include "sanitize.h"

int main(void)
{
    wk_underactuated_wrist_ik_solutions ik, ikb[4];
    wk_underactuated_wrist_fk_solutions fk, fkb[4];
    wk_underactuated_wrist_design d;
    const double special[] = {0.0, 3.14159265358979323846, -3.14159265358979323846, 1e300, -1e300, 1e-300};
    double v[3], jq[3], jx[9], w[3], rows[12];
    long checksum = 0;
    int i, j, rc;
    if (wk_underactuated_wrist_design_init(NULL, &d) != WK_OK) return 1;
    for (i = 0; i < 20000; ++i) {
        for (j = 0; j < 3; ++j) v[j] = (i % 7 == 0) ? special[(i / 7 + j) % 6] : uniform(-7.0, 7.0);
        if (i % 97 == 0) v[i % 3] = NAN;
        if (i % 101 == 0) v[(i + 1) % 3] = INFINITY;
        rc = wk_underactuated_wrist_ik(v, &d, &ik);
        checksum += rc + ik.count + wk_underactuated_wrist_select_ik(&ik, v, NULL, NULL);
        rc = wk_underactuated_wrist_fk(v, NULL, &fk);
        checksum += rc + fk.count + wk_underactuated_wrist_select_fk(&fk, NULL, NULL, NULL);
        if (rc == WK_OK && fk.count > 0) {
            double qd[3] = {0.1, -0.2, 0.3};
            wk_underactuated_wrist_jacobians(v, fk.values[0], &d, jq, jx);
            wk_underactuated_wrist_angular_velocity(v, fk.values[0], qd, &d, w);
            wk_underactuated_wrist_angular_acceleration(v, fk.values[0], qd, qd, &d, w);
        }
    }
    for (i = 0; i < 12; ++i) rows[i] = uniform(0.0, 6.0);
    checksum += wk_underactuated_wrist_ik_batch(4, rows, &d, ikb) + wk_underactuated_wrist_fk_batch(4, rows, &d, fkb);
    checksum += wk_underactuated_wrist_ik(NULL, &d, &ik) + wk_underactuated_wrist_ik(v, &d, NULL);
    checksum += wk_underactuated_wrist_fk(NULL, NULL, &fk) + wk_underactuated_wrist_ik_batch(0, NULL, NULL, NULL);
    { /* the design atlas's block sums: a valid block, then NULL and non-finite input */
        int64_t sums[WK_ATLAS_MODES + WK_UNDERACTUATED_WRIST_MAX_FK + 1] = {0};
        const int64_t home[3] = {1, 0, 1};
        double li_min = HUGE_VAL, lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
        const double bad[3] = {NAN, 0.1, 0.2};
        if (wk_underactuated_wrist_atlas_home_batch(4, rows, 4, rows, &d, 0.1, home, sums, &li_min, lo, hi) != WK_OK)
            return 1;
        for (i = 0; i <= WK_UNDERACTUATED_WRIST_MAX_FK; ++i) checksum += (long)sums[WK_ATLAS_MODES + i];
        if (checksum < 0 || sums[WK_ATLAS_N_REACH] > 4 || (sums[WK_ATLAS_N_SETS] && !(li_min >= 0.0 && li_min <= 1.0)))
            return 1;
        if (wk_underactuated_wrist_atlas_home_batch(1, NULL, 0, NULL, &d, 0.1, home, sums, &li_min, lo, hi) !=
            WK_ERR_NULL)
            return 1;
        if (wk_underactuated_wrist_atlas_home_batch(1, bad, 0, NULL, &d, 0.1, home, sums, &li_min, lo, hi) !=
            WK_ERR_NONFINITE)
            return 1;
    }
    {
        const double bad[4] = {NAN, 1.0, 0.5, 0.5};
        const double noclosure[4] = {0.2, 0.2, 1.5, 0.1};
        checksum += wk_underactuated_wrist_design_init(bad, &d) + wk_underactuated_wrist_design_init(noclosure, &d);
        checksum += wk_underactuated_wrist_design_init(NULL, NULL);
    }
    printf("checksum %ld\n", checksum);
    return 0;
}
