/* A serial arm's inverse kinematics: the stage tree run over every branch word, each candidate verified by FK
 * (polished where a tangent root left it sqrt(eps) off), families placed near previous, indistinct pairs merged;
 * and selection.
 * (a wristkin runtime source, inlined whole into every serial arm's generated C after its SR_* constants and
 * switches, the sr_design / sr_ik_solutions / sr_fk_solutions types, its derived kernels sr_k_* and stage
 * functions; derive/runtime_files.py, derive/families/serial/views.py, tests/test_serial_runtime.py) */
#if SR_CALIBRATED
/* Python's CALIBRATED_WRIST_SEARCH says why */
#define SR_CALIBRATED_WRIST_SEARCH 1e-4

/* whether a set's wrist bend is within SR_CALIBRATED_WRIST_SEARCH of singular (|sin q5|; 0 without a wrist) */
static int sr_wrist_bent(const double *q)
{
#if SR_WRIST_J5 >= 0
    return fabs(sin(q[SR_WRIST_J5])) <= SR_CALIBRATED_WRIST_SEARCH;
#else
    (void)q;
    return 0;
#endif
}

/* A calibrated robot's set k whose polish on the true chain failed (the ideal stages' answer outside Gauss-Newton's
 * basin: near a singularity the ideal geometry's 1e-7 moves it by 1e-7 / sigma_min), solved again by the ideal
 * stages for the pose the ideal chain must reach so that the true one reaches `pose`, T_c = pose true(q)^-1
 * ideal(q), then polished: the residual, qk replaced when it improves on err (Python's _compensated). */
static double sr_compensated(int k, const double *pose, double *qk, const double *dp, const double *prev,
                             double target, double err)
{
    double q[SR_N], c[SR_N], s[SR_N], amp[SR_N], ideal[12], truth[12], inv[12], rel[12], tc[12], err2;
    long key[SR_N_STAGES];
    int stage_ok[SR_N_STAGES], j;
    unsigned stage_flags[SR_N_STAGES], f = 0u;
    sr_ws ws;
    sr_ws_init(&ws);
    for (j = 0; j < SR_N; ++j) {
        c[j] = sr_revolute[j] ? cos(qk[j]) : 1.0;
        s[j] = sr_revolute[j] ? sin(qk[j]) : 0.0;
    }
    sr_k_fk_ideal(qk, c, s, dp, ideal);
    sr_k_fk_cs(qk, c, s, dp, truth);
    sr_invert(truth, inv);
    sr_compose(inv, ideal, rel);
    sr_compose(pose, rel, tc);
    for (j = 0; j < SR_N_STAGES; ++j) key[j] = -1;
    for (j = 0; j < SR_N; ++j) {
        q[j] = 0.0;
        c[j] = 1.0;
        s[j] = 0.0;
        amp[j] = 1.0;
    }
    /* an odd set's wrist mirrors the even one's: its prefix first */
    if ((k & 1) && !sr_run_stages(k - 1, tc, q, c, s, dp, prev, amp, &ws, key, stage_ok, stage_flags, &f))
        return err;
    if (!sr_run_stages(k, tc, q, c, s, dp, prev, amp, &ws, key, stage_ok, stage_flags, &f)) return err;
    err2 = sr_polish(q, pose, dp, target);
    if (!(err2 < err)) return err;
    for (j = 0; j < SR_N; ++j) qk[j] = sr_revolute[j] ? wk_wrap(q[j]) : q[j];
    return err2;
}
#endif

#if SR_FAMILY_SCAN
/* Python's CALIBRATED_SHOULDER_SEARCH says why */
#define SR_CALIBRATED_SHOULDER_SEARCH 1e-4

/* whether the pose puts the ideal geometry's wrist centre within SR_CALIBRATED_SHOULDER_SEARCH (times the design's
 * size) of axis 1: the first stage's A, B (the centre's y, x; it reads no joints; Python's _shoulder_near) */
static int sr_shoulder_near(const double *pose, const double *dp)
{
#if SR_SHOULDER_JOINT >= 0
    double q[SR_N], c[SR_N], s[SR_N], out[3];
    int j;
    for (j = 0; j < SR_N; ++j) {
        q[j] = s[j] = 0.0;
        c[j] = 1.0;
    }
    sr_k_stage1(pose, q, c, s, dp, out);
    return hypot(out[0], out[1]) <= SR_CALIBRATED_SHOULDER_SEARCH * sr_design_size(dp);
#else
    (void)pose;
    (void)dp;
    return 0;
#endif
}

/* A calibrated arm's families near a self-motion of its ideal geometry (Python's _scan_families says why): where set
 * 2P or 2P + 1 is within SR_CALIBRATED_WRIST_SEARCH of the wrist's singularity, the family is scanned from it along
 * q4, and where the pose is near the shoulder's (sr_shoulder_near), from the first valid one along q1; each solution
 * that is none of the sets kept (sr_indistinct) takes the family's next free slot of 2P, 2P + 1, SR_STAGE_SETS + 2P
 * and + 1 (flagged as Python's, and `projected`). Returns the sets added. */
static int sr_scan_families(const double *pose, const double *dp, double rounding, unsigned projected,
                            sr_ik_solutions *out)
{
    double found[SR_FAMILY_SCAN_POINTS][SR_N], res[SR_FAMILY_SCAN_POINTS];
    const double floor_ = wk_fk_rounding(fmax(fabs(pose[3]), fmax(fabs(pose[7]), fabs(pose[11]))));
    const int shoulder = sr_shoulder_near(pose, dp);
    sr_fit fit;
    int fam, added = 0;
    fit.pose = pose;
    fit.dp = dp;
    for (fam = 0; fam < SR_STAGE_SETS / 2; ++fam) {
        const int own[4] = { 2 * fam, 2 * fam + 1, SR_STAGE_SETS + 2 * fam, SR_STAGE_SETS + 2 * fam + 1 };
        int starts[2], holds[2], n_starts = 0, slots[4], n_slots = 0, slot = 0, i, j, k, n, t;
        for (k = 2 * fam; k <= 2 * fam + 1; ++k)
            if (out->valid[k] && sr_wrist_bent(out->values[k])) {
                starts[n_starts] = k;
                holds[n_starts++] = SR_WRIST_J4;
                break;
            }
#if SR_SHOULDER_JOINT >= 0
        for (k = 2 * fam; k <= 2 * fam + 1 && shoulder; ++k)
            if (out->valid[k]) {
                starts[n_starts] = k;
                holds[n_starts++] = SR_SHOULDER_JOINT;
                break;
            }
#else
        (void)shoulder;
#endif
        for (i = 0; i < 4; ++i)
            if (!out->valid[own[i]]) slots[n_slots++] = own[i];
        for (t = 0; t < n_starts && slot < n_slots; ++t) {
            n = sr_family_scan(out->values[starts[t]], holds[t], pose, dp, rounding, SR_FAMILY_SCAN_POINTS, found,
                               res);
            for (i = 0; i < n && slot < n_slots; ++i) {
                int same = 0;
                for (k = 0; k < SR_MAX_IK && !same; ++k)
                    same = out->valid[k] &&
                           sr_indistinct(found[i], res[i], out->values[k], out->aux[k][0], &fit, floor_);
                if (same) continue;
                k = slots[slot++];
                for (j = 0; j < SR_N; ++j) out->values[k][j] = found[i][j];
                out->aux[k][0] = res[i];
                out->valid[k] = 1;
                out->flags[k] = (fabs(sin(found[i][SR_WRIST_J5])) <= SR_SINGULAR_EPS ? WK_FLAG_SINGULAR_INVERSE : 0u) |
                                projected;
                ++added;
            }
        }
    }
    return added;
}
#endif

static int sr_api_ik_near(const double pose_in[12], const sr_design *design, const double *previous,
                          sr_ik_solutions *out)
{
    const sr_design *d = sr_design_or_default(design);
    double q[SR_N], c[SR_N], s[SR_N], amp[SR_N], pose[12], rot[9], deviation = 0.0, rounding, size, polish_double;
    long key[SR_N_STAGES];
    int stage_ok[SR_N_STAGES];
    unsigned stage_flags[SR_N_STAGES], projected;
    double prev_w[SR_N];
    const double *prev = NULL;
    sr_ws ws; /* the multi-candidate stages' scratch (sr_stages.c) */
    int k, j, indeterminate = 0;
    unsigned char carried[SR_MAX_IK]; /* sets the checks moved beyond WK_CARRIED_MOVE (wk_drop_carried) */
    sr_chord chord; /* the LU an even set's polish factored, for its wrist mirror (sr_polish_cs) */
#if SR_REUSE_MIRROR_CHECK
    double base_err = -1.0; /* the FK check of the last even set, when it passed unpolished */
#endif
    if (!out) return WK_ERR_NULL;
    out->count = 0;
    chord.ok = 0;
    for (k = 0; k < SR_MAX_IK; ++k) {
        carried[k] = 0;
        out->valid[k] = 0;
        out->flags[k] = 0u;
        out->aux[k][0] = NAN;
        for (j = 0; j < SR_N; ++j) out->values[k][j] = NAN;
    }
    if (!pose_in) {
        out->status = WK_ERR_NULL;
        return WK_ERR_NULL;
    }
#if SR_N_DESIGN_CHECKS > 0 && SR_HELD >= 0
    { /* a held joint's values ik refuses (kind 2: nonzero required; design_init takes them, as fk does) */
        double v[SR_N_DESIGN_CHECKS];
        sr_k_design_check(d->params, v);
        for (k = 0; k < SR_N_DESIGN_CHECKS; ++k)
            if (sr_check_zero[k] == 2 && !(fabs(v[k]) > sr_check_tol[k])) {
                out->status = WK_ERR_DESIGN;
                return WK_ERR_DESIGN;
            }
    }
#endif
    if (!wk_all_finite(pose_in, 12) || (previous && !wk_all_finite(previous, SR_N))) {
        out->status = WK_ERR_NONFINITE;
        return WK_ERR_NONFINITE;
    }
    /* the rotation within WK_ROTATION_PROJECT_TOL of SO(3) (projected), the translation within SR_LENGTH_MAX */
    if (!wk_input_rotation(pose_in, rot, &deviation) || !(fabs(pose_in[3]) <= SR_LENGTH_MAX) ||
        !(fabs(pose_in[7]) <= SR_LENGTH_MAX) || !(fabs(pose_in[11]) <= SR_LENGTH_MAX)) {
        out->status = WK_ERR_RANGE;
        return WK_ERR_RANGE;
    }
    for (j = 0; j < 3; ++j) {
        pose[4 * j] = rot[3 * j];
        pose[4 * j + 1] = rot[3 * j + 1];
        pose[4 * j + 2] = rot[3 * j + 2];
        pose[4 * j + 3] = pose_in[4 * j + 3];
    }
    projected = deviation > 0.0 ? WK_FLAG_PROJECTED : 0u;
    if (d->framed) { /* the design's base and tool frames: the pose the kernels answer (sr_frames.c) */
        double given[12];
        for (j = 0; j < 12; ++j) given[j] = pose[j];
        sr_unframe(d, given, pose);
    }
    if (previous) { /* wrapped as the joints are: a family's representative is taken from it */
        for (j = 0; j < SR_N; ++j) prev_w[j] = sr_revolute[j] ? wk_wrap(previous[j]) : previous[j];
        prev = prev_w;
    }
#if SR_N_IMAGE_CHECKS > 0
    {
        /* a < 6-DOF chain reaches only its image: residuals above SR_IK_VERIFY_TOL -> unreachable */
        double e[SR_N_IMAGE_CHECKS];
        sr_k_image_check(pose, d->params, e);
        for (j = 0; j < SR_N_IMAGE_CHECKS; ++j)
            if (!(fabs(e[j]) <= SR_IK_VERIFY_TOL)) {
                out->status = WK_STATUS_UNREACHABLE;
                return WK_OK;
            }
    }
#endif
    for (j = 0; j < SR_N_STAGES; ++j) {
        key[j] = -1;
        stage_ok[j] = 0;
        stage_flags[j] = 0u;
    }
    sr_ws_init(&ws);
    for (j = 0; j < SR_N; ++j) {
        q[j] = 0.0;
        c[j] = 1.0;
        s[j] = 0.0;
        amp[j] = 1.0;
    }
    /* the FK's own rounding of a pose of this size (wk_merge_indistinct's floor) */
    size = fmax(fabs(pose[3]), fmax(fabs(pose[7]), fabs(pose[11])));
    rounding = wk_fk_rounding(size);
    polish_double = SR_DOUBLE_ROOT_POLISH_TOL * fmax(1.0, size);
    for (k = 0; k < SR_STAGE_SETS; ++k) { /* the stages' sets (a calibrated arm's family scan adds its own after) */
        double t[12], err = 0.0;
        unsigned f = 0u;
        int alive = 1, have_t = 1, moved_by_checks, placed = 0; /* placed: the pose's own set (a calibrated arm's) */
        (void)placed;
        /* the stages (sr_run_stages, printed per chain): each recomputed only when its branch prefix changes */
        alive = sr_run_stages(k, pose, q, c, s, d->params, prev, amp, &ws, key, stage_ok, stage_flags, &f);
        if ((k & 1) == 0) chord.ok = 0; /* an odd set reuses its even neighbour's LU only */
#if SR_REUSE_MIRROR_CHECK
        if ((k & 1) == 0) base_err = -1.0;
#endif
        if (!alive) continue;
#if SR_REUSE_MIRROR_CHECK
        /* An odd set mirrors the wrist of the even set before it, and its fk_cs is that set's bit for bit: every
           temporary of the kernel is unchanged or exactly negated by the flip (proven on the kernel when it was
           generated, dh_serial.mirror_keeps_fk). So the even set's check is the odd one's, unless it was polished. */
        if ((k & 1) == 1 && base_err >= 0.0) {
            err = base_err;
            have_t = 0;
        } else {
            sr_k_fk_cs(q, c, s, d->params, t);
            for (j = 0; j < 12; ++j) {
                const double e = fabs(t[j] - pose[j]);
                if (!(e <= err)) err = e; /* inline max that lets a NaN through, so it fails the check */
            }
            if ((k & 1) == 0 && err <= SR_IK_VERIFY_TOL) base_err = err;
        }
#else
        sr_k_fk_cs(q, c, s, d->params, t);
        for (j = 0; j < 12; ++j) {
            const double e = fabs(t[j] - pose[j]);
            if (!(e <= err)) err = e; /* inline max that lets a NaN through, so it fails the check */
        }
#endif
        for (j = 0; j < SR_N; ++j) out->values[k][j] = q[j];
        moved_by_checks = !(err <= SR_IK_VERIFY_TOL) || (((f & WK_FLAG_DOUBLE_ROOT) || SR_CALIBRATED) &&
                                                         err > polish_double);
        if (moved_by_checks) {
            /* a tangent root leaves a sqrt(eps) error downstream, and a double root's centre its stage's noise (a
               UR's folded elbow behind a wrist 1e-5 from singular: the pose within 3e-12): polish a copy of the
               set, a double root's to rounding (Python's DOUBLE_ROOT_POLISH_TOL says when); a calibrated robot's
               (the stages solve its ideal geometry) every set to DOUBLE_ROOT_POLISH_TOL. From the stages' (cos, sin)
               and their check (the stages' c, s stay as they are: a later set shares their prefix) */
            double cc[SR_N], sc[SR_N];
            for (j = 0; j < SR_N; ++j) {
                cc[j] = c[j];
                sc[j] = s[j];
            }
            if (!have_t) sr_k_fk_cs(q, c, s, d->params, t); /* the check was the even set's: this set's own t */
            err = sr_polish_cs(out->values[k], cc, sc, t, err, pose, d->params, (f & WK_FLAG_DOUBLE_ROOT) ? rounding :
                               (SR_CALIBRATED ? polish_double : SR_IK_VERIFY_TOL), &chord,
                               SR_HAS_WRIST_MIRROR && (k & 1));
            for (j = 0; j < SR_N; ++j)
                if (sr_revolute[j]) out->values[k][j] = wk_wrap(out->values[k][j]);
        }
#if SR_CALIBRATED
        {
            int searched = 0;
            if (!(err <= SR_IK_VERIFY_TOL)) {
                err = sr_compensated(k, pose, out->values[k], d->params, prev, polish_double, err);
                if (!(err <= SR_IK_VERIFY_TOL)) { /* along the near-null direction, to rounding (Python's reasons) */
                    err = sr_along_null(out->values[k], pose, d->params, rounding, err);
                    searched = 1;
                }
            }
            if (!searched && err > rounding && err <= SR_IK_VERIFY_TOL &&
                (err > polish_double || (f & WK_FLAG_SINGULAR_INVERSE) || sr_wrist_bent(out->values[k]))) {
                /* near a singularity of the ideal geometry a set that passes the check may lie residual /
                   sigma_min from the true chain's solution (its polish stalled short of its target, or it reached it
                   on a nearly singular J; or the compensated re-solve brought it within the check): searched along
                   the near-null direction to the FK's rounding, where the pose places it (`previous` then does not
                   move it; Python's reasons) */
                err = sr_along_null(out->values[k], pose, d->params, rounding, err);
                placed = err <= rounding;
                moved_by_checks = 1;
            }
        }
#endif
        if (err <= SR_IK_VERIFY_TOL && moved_by_checks) { /* only a polished or searched set can be carried */
            for (j = 0; j < SR_N; ++j) {
                const double moved = out->values[k][j] - q[j];
                if (fabs(sr_revolute[j] ? wk_wrap(moved) : moved) > WK_CARRIED_MOVE) carried[k] = 1;
            }
            if (carried[k] && err > rounding) { /* to rounding: wk_drop_carried then knows the solution it reached */
                err = sr_polish(out->values[k], pose, d->params, rounding);
                for (j = 0; j < SR_N; ++j)
                    if (sr_revolute[j]) out->values[k][j] = wk_wrap(out->values[k][j]);
            }
        }
#if SR_HAS_PRISMATIC
        if (!(err <= SR_IK_VERIFY_TOL) || !sr_prismatic_in_range(out->values[k])) {
#else
        if (!(err <= SR_IK_VERIFY_TOL)) {
#endif
            for (j = 0; j < SR_N; ++j) out->values[k][j] = NAN;
            continue;
        }
#if SR_WRIST_STAGE >= 0
        if (previous && !placed && (stage_flags[SR_WRIST_STAGE] & (WK_FLAG_INDETERMINATE | WK_FLAG_READ_MEMBER)) ==
                            WK_FLAG_INDETERMINATE) {
            /* the wrist's own family (|sin theta5| <= the family tolerance), not another stage's: above it the pose
               places the wrist and `previous` must not move it */
            double moved[SR_N], e6[6];
            for (j = 0; j < SR_N; ++j) moved[j] = out->values[k][j];
            sr_nearest_member(moved, previous, d->params);
            {
                const double err_moved = sr_pose_error(moved, pose, d->params, e6);
                if (err_moved <= SR_IK_VERIFY_TOL) { /* exact in theory; confirmed */
                    for (j = 0; j < SR_N; ++j) out->values[k][j] = moved[j];
                    err = err_moved;
                }
            }
        }
#endif
        out->aux[k][0] = err;
        out->valid[k] = 1;
        out->flags[k] = (f & ~WK_FLAG_READ_MEMBER) | projected;
        ++out->count;
    }
    /* a set the polish carried to another branch's solution (a 5-joint arm's candidate that no orientation fits) is
       that solution twice */
    out->count -= wk_drop_carried(SR_MAX_IK, SR_N, sr_revolute, &out->values[0][0], out->valid, out->flags,
                                  &out->aux[0][0], SR_N_IK_AUX, carried);
#if SR_N_FOLD_MASKS > 0
    {
        /* a stage's pair that the pose cannot tell apart is one double root (the runtime says when); a calibrated
           arm's every single-bit pair (Python's reasons) */
        sr_fit fit;
        fit.pose = pose;
        fit.dp = d->params;
        out->count -= wk_merge_indistinct(SR_MAX_IK, SR_N, sr_revolute, sr_fold_masks, SR_N_FOLD_MASKS,
                                          &out->values[0][0],
                                          out->valid, out->flags, &out->aux[0][0], SR_N_IK_AUX,
                                          sr_refit, &fit, size, SR_N >= 6 && !SR_CALIBRATED);
    }
#endif
#if SR_FAMILY_SCAN /* after the merge: a mirror pair searched onto one solution leaves a slot for the scan */
    out->count += sr_scan_families(pose, d->params, rounding, projected, out);
#endif
    for (k = 0; k < SR_MAX_IK; ++k) /* of the sets kept (as Python's flags read after the merge) */
        if (out->valid[k] && (out->flags[k] & WK_FLAG_INDETERMINATE)) indeterminate = 1;
    out->status = out->count == 0 ? WK_STATUS_UNREACHABLE : (indeterminate ? WK_STATUS_INDETERMINATE : WK_STATUS_OK);
    return WK_OK;
}

static int sr_api_ik(const double pose[12], const sr_design *design, sr_ik_solutions *out)
{
    return sr_api_ik_near(pose, design, NULL, out);
}

static int sr_api_ik_batch(size_t n, const double *poses, const sr_design *design,
                           sr_ik_solutions *out)
{
    size_t r;
    int first = WK_OK;
    if (n == 0) return WK_OK;
    if (!poses || !out) return WK_ERR_NULL;
    for (r = 0; r < n; ++r) {
        const int rc = sr_api_ik(poses + 12 * r, design, out + r);
        if (rc != WK_OK && first == WK_OK) first = rc;
    }
    return first;
}

static int sr_api_select_ik(const sr_ik_solutions *s, const double *previous, const double *lower,
                            const double *upper)
{
    /* the contract of every select (the runtime's wk_select): with previous, the nearest valid set within limits
       (a singular flag is information, not a reason to jump); without it the first regular one, else the first.
       A user robot's NULL limits are its description's (Python LOWER / UPPER), as Python's */
    if (!s) return -1;
#if SR_HAS_LIMITS
    if (!lower) lower = sr_lower;
    if (!upper) upper = sr_upper;
#endif
    return wk_select(SR_MAX_IK, SR_N, s->valid, s->flags, &s->values[0][0], sr_revolute, previous, lower,
                     upper, NULL);
}
