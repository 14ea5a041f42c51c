/* What the sanitizer drivers share: one xorshift stream of uniform doubles (the same sequence in each) and the
   name pasting for a generated mechanism's functions and types (FN(MECH, _ik) = wk_<MECH>_ik). */
#ifndef WK_TEST_SANITIZE_H
#define WK_TEST_SANITIZE_H

#define CAT3(a, b, c) a##b##c
#define FN(mech, verb) CAT3(wk_, mech, verb)
#define TYPE(mech, suffix) CAT3(wk_, mech, suffix)

static unsigned long long state = 88172645463325252ULL;
static double uniform(double lo, double hi)
{
    state ^= state << 13; state ^= state >> 7; state ^= state << 17;
    return lo + (hi - lo) * (double)(state >> 11) / 9007199254740992.0;
}

#ifdef WK_SANITIZE_SERIAL_TAIL
/* A serial (or user robot) driver's tail (it defines WK_SANITIZE_SERIAL_TAIL, and MECH and N, first): the batch
   verbs on three random joint rows and their poses, then NULL and empty inputs, which must be refused without a
   read or write. */
static long batch_and_null_inputs(double *rows, double *poses, TYPE(MECH, _fk_solutions) *fkb,
                                  TYPE(MECH, _ik_solutions) *ikb, TYPE(MECH, _ik_solutions) *ik,
                                  TYPE(MECH, _fk_solutions) *fk)
{
    long checksum = 0;
    int i, j;
    for (i = 0; i < 3 * N; ++i) rows[i] = uniform(-1.0, 1.0);
    checksum += FN(MECH, _fk_batch)(3, rows, NULL, fkb);
    for (i = 0; i < 3; ++i)
        for (j = 0; j < 12; ++j) poses[12 * i + j] = fkb[i].values[0][j];
    checksum += FN(MECH, _ik_batch)(3, poses, NULL, ikb);
    checksum += FN(MECH, _ik)(NULL, NULL, ik) + FN(MECH, _fk)(NULL, NULL, fk) + FN(MECH, _ik)(poses, NULL, NULL);
    checksum += FN(MECH, _ik_batch)(0, NULL, NULL, NULL) + FN(MECH, _design_init)(NULL, NULL);
    return checksum;
}
#endif

#endif
