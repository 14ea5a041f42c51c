/* Three revolute axes in general position: the interpreted plan's spatial3 op, on wk_spatial3.c (inlined before it).
 * (a wristkin runtime source, inlined whole into every user robot's generated C, after the robot's CK_*
 * constants; derive/runtime_files.py, tests/test_chain_runtime.py) */
/* (q_a, q_b, q_c, flags) with e_a e_b e_c x = y for three revolute axes in general position (the Python module's
 * _spatial3). At most WK_S3_MAX candidates. */
static int ck_spatial3(const ck_chain *ch, int ja, int jb, int jc, const double *x, const double *y, double *qa,
                       double *qb, double *qc, unsigned *fl)
{
    const int js[3] = {ja, jb, jc};
    double h[3][3], r[3][3], q[WK_S3_MAX][3];
    int i, m, n;
    for (i = 0; i < 3; ++i)
        for (m = 0; m < 3; ++m) {
            h[i][m] = ch->axis[js[i]][m];
            r[i][m] = ch->point[js[i]][m];
        }
    n = wk_spatial3((const double (*)[3])h, (const double (*)[3])r, x, y, CK_SCALE, CK_DEGENERATE_EPS, CK_ON_AXIS_TOL, q,
                    fl);
    for (i = 0; i < n; ++i) {
        qa[i] = q[i][0];
        qb[i] = q[i][1];
        qc[i] = q[i][2];
    }
    return n;
}
