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

#endif
