/* Subproblem 6's stage (an offset wrist: two joints from the parallel group's invariants; wk_sp6.c, inlined before
 * it), on the direction, axes, points and constants its derived kernel gives. The candidates are computed once per
 * prefix of the set index above the stage's bits and kept in the call's scratch (sr_ws); set k takes candidate
 * (k >> shift) & 3, at most four (the quartic's real roots; the core returns none twice: a near pair 3e-11 apart is
 * two roots, which a 1e-9 sameness band merged, losing the generating set). The stage
 * sets amp[k] to how much its q_k amplifies the input's rounding: near the wrist singularity (g = |h_l x R_k^T n|
 * small) q_k from the quartic and Newton on its equations carries eps / g, from the split eps; the next stage, q_l
 * about its axis, adds its own 1 / g, and the bands after it grow by the product. The FK check after the stages
 * verifies each set.
 * (a wristkin runtime source, inlined whole into a serial arm's generated C that has an sp6 stage, after sr_verify.c;
 * Python's serial_sp6.py; derive/serial_core/views.py, tests/test_derived_robot.py) */
#if SR_HAS_SP6
/* the core's bands: a polynomial stage's roots carry ~1e-12 (the degree-4 eliminant's rounding), and subproblem 4's
 * tangent band is the stages' (TANGENT_TOL) */
#define SR_SP6_DOUBLE_ROOT_TOL 1e-12
#define SR_SP6_ON_AXIS_TOL 1e-12
#define SR_SP6_TANGENT_TOL 1e-9
/* the wrist's family: the pose's axis on n within the rounding of unit vectors (Python's SP6_FAMILY_TOL says why) */
#define SR_SP6_FAMILY_TOL 1.4210854715202004e-14

/* the candidates of the stage's outputs (n, h_j, p_j, h_k, p_k, d_j, g, h_l) into ws, at most SR_SP6_KEEP */
static int sr_sp6_candidates(const double *out, sr_ws *ws)
{
    double q0[WK_SP6_MAX], q4[WK_SP6_MAX], scale = 1.0;
    unsigned fl[WK_SP6_MAX];
    int ord[WK_SP6_MAX], i, n = 0, nc;
    wk_sp6_tols t;
    for (i = 6; i < 16; ++i) /* the lengths' size: the points' and the constant's largest coordinate */
        if (i < 9 || i >= 12)
            if (fabs(out[i]) > scale) scale = fabs(out[i]);
    t.scale = scale;
    t.degenerate = SR_DEGENERATE_EPS;
    t.double_root = SR_SP6_DOUBLE_ROOT_TOL;
    t.tangent = SR_SP6_TANGENT_TOL;
    t.on_axis = SR_SP6_ON_AXIS_TOL;
    t.family = SR_SP6_FAMILY_TOL;
    nc = wk_sp6(out, out + 3, out + 6, out + 9, out + 12, out[15], 0.0, out + 16, out + 19, &t, q0, q4, fl, ord);
    for (i = 0; i < nc && n < SR_SP6_KEEP; ++i) {
        double a[3], x[3], g;
        ws->q[n][0] = q0[i];
        ws->q[n][1] = q4[i];
        ws->f[n] = fl[i];
        /* g = |h_l x rot(h_k, q_k)^T n|: q_k carries eps / g from the quartic (order 2), ~eps from the split */
        wk_g3_turn_dir(out + 9, -q4[i], out, a);
        wk_g3_cross(out + 19, a, x);
        g = wk_g3_norm(x);
        ws->amp[n] = ord[i] == 2 ? fmax(1.0, 1.0 / fmax(g, 1e-300)) : 1.0;
        ++n;
    }
    return n;
}

/* Set k's candidate: `kernel` the stage's outputs, `parent` the set index's prefix above the stage's bits (the
 * candidates are recomputed when it changes), `idx` the candidate; 0 when there is no such candidate */
static int sr_sp6(sr_stage_kernel kernel, long parent, int idx, const int *joints, double *q, double *c, double *s,
                  const double *pose, const double *dp, double *amp, sr_ws *ws, unsigned *f)
{
    if (ws->key != parent) {
        double out[22];
        kernel(pose, q, c, s, dp, out);
        ws->key = parent;
        ws->n = sr_sp6_candidates(out, ws);
        sr_ws_mark_near(ws);
    }
    if (!sr_ws_take(ws, idx, joints, q, c, s, f)) return 0;
    amp[joints[0]] = 1.0;
    amp[joints[1]] = ws->amp[idx];
    return 1;
}
#endif
