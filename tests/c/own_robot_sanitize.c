/* Sanitizer driver for a user robot's generated solver whose design is one run-time parameter (a held joint or the
   arm angle: params[1]): random, singular and hostile inputs; every returned set must reproduce the pose. Compile
   with -DMECH=name -DMECH_H='"name.h"' -DN=joints -DMAX_IK=sets (-DFREE=index of the free joint, if any). */
#include <math.h>
#include <stdio.h>
#include MECH_H
#define WK_SANITIZE_SERIAL_TAIL
#include "sanitize.h"

/* a random rotation (unit quaternion) and translation as the top 3x4 of a frame */
static void random_frame(double *f)
{
    double x = uniform(-1, 1), y = uniform(-1, 1), z = uniform(-1, 1), w = uniform(-1, 1);
    const double n = sqrt(x * x + y * y + z * z + w * w);
    x /= n; y /= n; z /= n; w /= n;
    f[0] = 1 - 2 * (y * y + z * z); f[1] = 2 * (x * y - z * w); f[2] = 2 * (x * z + y * w);
    f[4] = 2 * (x * y + z * w); f[5] = 1 - 2 * (x * x + z * z); f[6] = 2 * (y * z - x * w);
    f[8] = 2 * (x * z - y * w); f[9] = 2 * (y * z + x * w); f[10] = 1 - 2 * (x * x + y * y);
    f[3] = uniform(-0.3, 0.3); f[7] = uniform(-0.3, 0.3); f[11] = uniform(-0.3, 0.3);
}

int main(void)
{
    TYPE(MECH, _design) d;
    TYPE(MECH, _ik_solutions) ik, ikb[3];
    TYPE(MECH, _fk_solutions) fk, fkb[3];
    const double special[] = {0.0, 1.5707963267948966, -1.5707963267948966, 3.141592653589793};
    double q[N], jac[6 * N], rows[3 * N], poses[36], t[12], base[12], tool[12], params[1] = {0.4};
    long checksum = 0;
    int i, j, k;
    if (FN(MECH, _design_init)(params, &d) != WK_OK) return 1;
    for (i = 0; i < 1500; ++i) {
        if (i % 100 == 50) {
            random_frame(base);
            random_frame(tool);
            if (FN(MECH, _design_set_frames)(&d, base, i % 200 == 50 ? tool : NULL) != WK_OK) return 2;
        }
        for (j = 0; j < N; ++j) q[j] = (i % 3 == 0) ? special[(i + j) % 4] : uniform(-3.2, 3.2);
#if N > 4
        if (i % 7 == 0) q[4] = 0.0; /* the wrist singularity of a 6R arm */
        else if (i % 11 == 0) q[4] = 1e-6; /* near it: a merged double root's split fallback */
#endif
#ifdef FREE
        q[FREE] = params[0]; /* a redundant chain: its free joint at the design's value */
#endif
        if (FN(MECH, _fk)(q, &d, &fk) != WK_OK) return 3;
        checksum += FN(MECH, _ik)(fk.values[0], &d, &ik) + ik.count;
        /* a generic pose FK made has its solutions (a special or singular one may lose its family: see the
           Python module) */
        if (ik.count > MAX_IK || (ik.count < 1 && i % 3 != 0 && i % 7 != 0)) return 4;
        for (k = 0; k < MAX_IK; ++k) {
            if (!ik.valid[k]) continue;
            if (FN(MECH, _fk_matrix)(ik.values[k], &d, t) != WK_OK) return 5;
            for (j = 0; j < 12; ++j)
                if (!(fabs(t[j] - fk.values[0][j]) <= 1e-8)) return 6;
        }
        checksum += FN(MECH, _ik_near)(fk.values[0], &d, q, &ik) + ik.count;
        checksum += FN(MECH, _select_ik)(&ik, q, NULL, NULL) + FN(MECH, _select_ik)(&ik, NULL, NULL, NULL);
        checksum += FN(MECH, _jacobian)(q, &d, jac);
        if (i % 50 == 0) {
            double bad[12];
            for (j = 0; j < 12; ++j) bad[j] = fk.values[0][j];
            bad[i % 12] = (i % 100 == 0) ? NAN : INFINITY;
            checksum += FN(MECH, _ik)(bad, &d, &ik);
            bad[i % 12] = 0.3; /* not a rotation any more (or a moved position) */
            checksum += FN(MECH, _ik)(bad, &d, &ik) + ik.count;
            for (j = 0; j < 12; ++j) bad[j] = fk.values[0][j];
            bad[3] = 5.0; /* out of reach */
            checksum += FN(MECH, _ik)(bad, &d, &ik) + ik.count + ik.status;
            bad[3] = 3e6; /* beyond the length limit */
            checksum += FN(MECH, _ik)(bad, &d, &ik);
        }
    }
    checksum += batch_and_null_inputs(rows, poses, fkb, ikb, &ik, &fk);
    checksum += FN(MECH, _design_set_frames)(NULL, NULL, NULL) + FN(MECH, _design_set_frames)(&d, NULL, NULL);
    q[0] = NAN;
    checksum += FN(MECH, _ik_near)(poses, NULL, q, &ik) + FN(MECH, _jacobian)(q, NULL, jac);
    printf("checksum %ld\n", checksum);
    return 0;
}
