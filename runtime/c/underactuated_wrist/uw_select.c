/* Which of the underactuated wrist's solution sets to use (the seed's rule).
 * (a wristkin runtime source, inlined whole into the underactuated wrist's generated C after its UW_*
 * constants, the uw_design / uw_ik_solutions / uw_fk_solutions types and the derived kernels uw_k_*;
 * derive/runtime_files.py, tests/test_uw_runtime.py) */
/* ------------------------------------------------------------------ selection */
static int uw_select(int nsol, int width, const int *valid, const unsigned *flags, const double *values,
                     const double *aux, int naux, const double *previous, const double *lower, const double *upper)
{
    int k, j, best = -1, best_regular = 0;
    double best_score = 0.0;
    for (k = 0; k < nsol; ++k) {
        const double *v = values + (size_t)k * (size_t)width;
        const int regular = !(flags[k] & (WK_FLAG_SINGULAR_INVERSE | WK_FLAG_SINGULAR_DIRECT));
        double score = 0.0;
        int in_range = 1;
        if (!valid[k]) continue;
        if (lower && upper)
            for (j = 0; j < width; ++j)
                if (uw_wrap_2pi(v[j] - lower[j]) > upper[j] - lower[j]) in_range = 0;
        if (!in_range) continue;
        if (previous) {
            for (j = 0; j < width; ++j) score -= fabs(uw_wrap_pi(v[j] - uw_wrap_pi(previous[j])));
        } else {
            const double *a = aux + (size_t)k * (size_t)naux;
            score = fmin(a[naux - 2], a[naux - 1]);
        }
        /* with previous: nearest, whatever the flags (information, not a reason to jump); without: regular
           first, then best conditioned */
        if (best < 0 || (previous ? score > best_score
                                  : ((regular && !best_regular) || (regular == best_regular && score > best_score)))) {
            best = k;
            best_score = score;
            best_regular = regular;
        }
    }
    return best;
}

static int uw_api_select_ik(const uw_ik_solutions *s, const double *previous,
                            const double *lower, const double *upper)
{
    if (!s) return -1;
    return uw_select(UW_MAX_IK, 3, s->valid, s->flags, &s->values[0][0], &s->aux[0][0],
                     UW_N_IK_AUX, previous, lower, upper);
}

static int uw_api_select_fk(const uw_fk_solutions *s, const double *previous,
                            const double *lower, const double *upper)
{
    if (!s) return -1;
    return uw_select(UW_MAX_FK, 3, s->valid, s->flags, &s->values[0][0], &s->aux[0][0],
                     UW_N_FK_AUX, previous, lower, upper);
}
