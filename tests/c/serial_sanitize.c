/* Sanitizer driver for a generated serial chain; compile with -DMECH=name -DMECH_H='"name.h"' -DN=joints.
   Random, special (0, +/-pi/2, pi) and hostile (NaN, inf, NULL, non-rotation) inputs under ASan/UBSan. */
#include <math.h>
#include <stdio.h>
#include MECH_H
#define WK_SANITIZE_SERIAL_TAIL
#include "sanitize.h"

int main(void)
{
    TYPE(MECH, _ik_solutions) ik, ikb[3];
    TYPE(MECH, _fk_solutions) fk, fkb[3];
    const double special[] = {0.0, 1.5707963267948966, -1.5707963267948966, 3.141592653589793};
    double q[N], jac[6 * N], rows[3 * N], poses[36];
    long checksum = 0;
    int i, j;
    for (i = 0; i < 3000; ++i) {
        for (j = 0; j < N; ++j) q[j] = (i % 3 == 0) ? special[(i + j) % 4] : uniform(-3.2, 3.2);
        if (FN(MECH, _fk)(q, NULL, &fk) != WK_OK) return 1;
        checksum += FN(MECH, _ik)(fk.values[0], NULL, &ik) + ik.count;
        checksum += FN(MECH, _select_ik)(&ik, q, NULL, NULL) + FN(MECH, _jacobian)(q, NULL, jac);
        if (i % 50 == 0) {
            double bad[12];
            for (j = 0; j < 12; ++j) bad[j] = fk.values[0][j];
            bad[i % 12] = (i % 100 == 0) ? NAN : INFINITY;
            checksum += FN(MECH, _ik)(bad, NULL, &ik);
            bad[i % 12] = 0.3; /* not a rotation any more (or a moved position) */
            checksum += FN(MECH, _ik)(bad, NULL, &ik) + ik.count;
        }
    }
    checksum += batch_and_null_inputs(rows, poses, fkb, ikb, &ik, &fk);
    { /* the design atlas's conditioning batch: a valid batch, then NULL, a bad length and NaN joints */
        int64_t sums[2] = {0, 0};
        double li_min = HUGE_VAL;
        if (FN(MECH, _atlas_conditioning)(3, rows, NULL, 0.5, 0.1, sums, &li_min) != WK_OK) return 1;
        if (!(li_min >= 0.0 && li_min <= 1.0) || sums[1] < 0 || sums[1] > 3) return 1;
        if (FN(MECH, _atlas_conditioning)(1, NULL, NULL, 0.5, 0.1, sums, &li_min) != WK_ERR_NULL) return 1;
        if (FN(MECH, _atlas_conditioning)(1, rows, NULL, 0.0, 0.1, sums, &li_min) != WK_ERR_RANGE) return 1;
        rows[0] = NAN;
        if (FN(MECH, _atlas_conditioning)(1, rows, NULL, 0.5, 0.1, sums, &li_min) != WK_ERR_NONFINITE) return 1;
        checksum += (long)sums[1];
    }
    { /* base and tool frames: a framed design's FK -> IK round trip, and hostile frames refused */
        TYPE(MECH, _design) d;
        const double c = cos(0.7), s = sin(0.7);
        const double base[12] = {c, -s, 0.0, 0.1, s, c, 0.0, -0.2, 0.0, 0.0, 1.0, 0.3};
        const double tool[12] = {1.0, 0.0, 0.0, 0.0, 0.0, c, -s, 0.05, 0.0, s, c, 0.1};
        double bad[12];
        if (FN(MECH, _design_init)(NULL, &d) != WK_OK || FN(MECH, _design_set_frames)(&d, base, tool) != WK_OK)
            return 1;
        for (j = 0; j < N; ++j) q[j] = uniform(-3.2, 3.2);
        if (FN(MECH, _fk)(q, &d, &fk) != WK_OK || FN(MECH, _jacobian)(q, &d, jac) != WK_OK) return 1;
        checksum += FN(MECH, _ik)(fk.values[0], &d, &ik) + ik.count;
        for (j = 0; j < 12; ++j) bad[j] = base[j];
        bad[0] = 1.5; /* not a rotation */
        if (FN(MECH, _design_set_frames)(&d, bad, NULL) != WK_ERR_DESIGN) return 1;
        bad[0] = NAN;
        if (FN(MECH, _design_set_frames)(&d, NULL, bad) != WK_ERR_NONFINITE) return 1;
        if (FN(MECH, _design_set_frames)(NULL, base, tool) != WK_ERR_NULL) return 1;
    }
    printf("checksum %ld\n", checksum);
    return 0;
}
