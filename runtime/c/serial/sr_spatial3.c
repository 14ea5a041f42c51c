/* A spatial 3R's stage: three revolute axes in general position placing a point (wk_spatial3.c, inlined before it),
 * on the lines, the point and its target its derived kernel gives. The candidates are computed once per prefix of the
 * set index above the stage's bits and kept in the call's scratch (sr_ws); set k takes candidate (k >> shift) & 3.
 * A candidate found twice (a double root's two isolations) is kept once; at most four are (Pieper's bound: more
 * only where the pose is on a family, whose first four stand for it). A point on the first axis leaves that joint
 * undetermined: previous's value, else 0 (flagged indeterminate). The FK check after the stages verifies each set.
 * (a wristkin runtime source, inlined whole into a serial arm's generated C that has a spatial3 stage, after
 * sr_verify.c; Python's serial_spatial3.py; derive/serial_core/views.py, tests/test_derived_robot.py) */
#if SR_HAS_SPATIAL3
/* the candidates of the stage's outputs (3 axes, 3 points, x, y) into ws: distinct, at most SR_S3_KEEP */
static int sr_s3_candidates(const double *out, sr_ws *ws)
{
    double h[3][3], r[3][3], cand[WK_S3_MAX][3], scale = 1.0;
    unsigned fl[WK_S3_MAX];
    int i, j, m, n = 0, nc;
    for (i = 0; i < 3; ++i)
        for (m = 0; m < 3; ++m) {
            h[i][m] = out[3 * i + m];
            r[i][m] = out[9 + 3 * i + m];
        }
    for (i = 9; i < 24; ++i) /* the lengths' size: the points', the point's and its target's largest coordinate */
        if (fabs(out[i]) > scale) scale = fabs(out[i]);
    nc = wk_spatial3((const double (*)[3])h, (const double (*)[3])r, out + 18, out + 21, scale, SR_DEGENERATE_EPS,
                     SR_ON_AXIS_TOL, cand, fl);
    for (i = 0; i < nc && n < SR_S3_KEEP; ++i) {
        int dup = 0;
        for (j = 0; j < n && !dup; ++j) dup = wk_same_set(3, NULL, cand[i], ws->q[j]); /* a solution's identity */
        if (dup) continue;
        for (m = 0; m < 3; ++m) ws->q[n][m] = cand[i][m];
        ws->f[n] = fl[i];
        ++n;
    }
    return n;
}

/* Set k's candidate: `kernel` the stage's (axes, points, x, y), `parent` the set index's prefix above the stage's bits
 * (the candidates are recomputed when it changes), `idx` the candidate; 0 when there is no such candidate */
static int sr_spatial3(sr_stage_kernel kernel, long parent, int idx, const int *joints, double *q, double *c,
                       double *s, const double *pose, const double *dp, const double *prev, sr_ws *ws, unsigned *f)
{
    if (ws->key != parent) {
        double out[24];
        kernel(pose, q, c, s, dp, out);
        ws->key = parent;
        ws->n = sr_s3_candidates(out, ws);
        sr_ws_mark_near(ws);
    }
    if (!sr_ws_take(ws, idx, joints, q, c, s, f)) return 0;
    if ((*f & WK_FLAG_INDETERMINATE) && prev) { /* the first joint's family: previous's member */
        const double v = prev[joints[0]];
        q[joints[0]] = v;
        c[joints[0]] = cos(v);
        s[joints[0]] = sin(v);
    }
    return 1;
}
#endif
