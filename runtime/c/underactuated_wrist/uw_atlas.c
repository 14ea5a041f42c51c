/* The design atlas's sums over one block of the underactuated wrist's poses and joint triples
 * (docs/atlas.md).
 * (a wristkin runtime source, inlined whole into the underactuated wrist's generated C after its UW_*
 * constants, the uw_design / uw_ik_solutions / uw_fk_solutions types and the derived kernels uw_k_*;
 * derive/runtime_files.py, tests/test_uw_runtime.py) */
static int uw_api_atlas_home_batch(size_t n_pose, const double *poses, size_t n_joint, const double *joints,
                                   const uw_design *design, double threshold, const int64_t home[3],
                                   int64_t *sums, double *li_min, double phi_lo[3], double phi_hi[3])
{
    const uw_design *d = uw_design_or_default(design);
    size_t i;
    int k, j;
    if ((n_pose && !poses) || (n_joint && !joints) || !home || !sums || !li_min || !phi_lo || !phi_hi)
        return WK_ERR_NULL;
    for (i = 0; i < n_pose; ++i) {
        uw_ik_solutions s;
        double rot[9], best = -1.0;
        const int rc = uw_api_ik(poses + 3 * i, d, &s);
        if (rc < 0) return rc;
        uw_rotation(poses + 3 * i, rot);
        for (k = 0; k < UW_MAX_IK; ++k) {
            double o[12], li;
            if (!s.valid[k]) continue;
            uw_k_jacobians(s.values[k], rot, d->c, o); /* g_i = det[Zi1, Zi2, Zi3], x_i = Zi2 x Zi3 */
            li = wk_inverse_kappa_f(o + 3, o);
            sums[WK_ATLAS_N_SETS] += 1;
            sums[WK_ATLAS_LI_SUM] += (int64_t)llrint(li * WK_ATLAS_FIXED);
            sums[WK_ATLAS_NEAR_INVERSE] += s.aux[k][3] < threshold;
            sums[WK_ATLAS_NEAR_DIRECT] += s.aux[k][4] < threshold;
            if (li > best) best = li;
            if (li < *li_min) *li_min = li;
            if ((o[0] > 0.0) == (home[0] != 0) && (o[1] > 0.0) == (home[1] != 0) && (o[2] > 0.0) == (home[2] != 0))
                for (j = 0; j < 3; ++j) { /* the home working mode's motor / sensor angles, degrees */
                    const double phi = s.aux[k][j] * (180.0 / UW_PI);
                    if (phi < phi_lo[j]) phi_lo[j] = phi;
                    if (phi > phi_hi[j]) phi_hi[j] = phi;
                }
        }
        if (best >= 0.0) {
            sums[WK_ATLAS_N_REACH] += 1;
            sums[WK_ATLAS_LI_BEST_SUM] += (int64_t)llrint(best * WK_ATLAS_FIXED);
        }
    }
    for (i = 0; i < n_joint; ++i) {
        uw_fk_solutions s;
        int near = 0;
        const int rc = uw_api_fk(joints + 3 * i, d, &s);
        if (rc < 0) return rc;
        for (k = 0; k < UW_MAX_FK; ++k)
            near |= s.valid[k] && s.aux[k][UW_N_FK_AUX - 1] < threshold; /* cond_direct */
        sums[WK_ATLAS_FK_NEAR_DIRECT] += near;
        sums[WK_ATLAS_MODES + s.count] += 1;
    }
    return WK_OK;
}
