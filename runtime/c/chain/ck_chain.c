/* A chain's variants (a joint held, read from the tool), its product of exponentials and Jacobian.
 * (a wristkin runtime source, inlined whole into every user robot's generated C, after the robot's CK_*
 * constants; derive/runtime_files.py, tests/test_chain_runtime.py) */
/* ------------------------------------------------------------------ the chain of a call */
#if CK_FREE >= 0
/* The chain with joint f held at v: the joints after it and the end frame move rigidly with it. */
static void ck_held(const ck_chain *ch, int f, double v, ck_chain *o)
{
    ck_rt m;
    int i, k = 0;
    ck_screw(ch->prismatic[f], ch->axis[f], ch->point[f], v, &m);
    for (i = 0; i < ch->n; ++i) {
        if (i == f) continue;
        o->prismatic[k] = ch->prismatic[i];
        if (i > f) {
            ck_mv(m.r, ch->axis[i], o->axis[k]);
            ck_apply(&m, ch->point[i], o->point[k]);
        } else {
            o->axis[k][0] = ch->axis[i][0];
            o->axis[k][1] = ch->axis[i][1];
            o->axis[k][2] = ch->axis[i][2];
            o->point[k][0] = ch->point[i][0];
            o->point[k][1] = ch->point[i][1];
            o->point[k][2] = ch->point[i][2];
        }
        o->index[k] = ch->index[i];
        ++k;
    }
    o->n = k;
    ck_compose(&m, &ch->home, &o->home);
}
#endif
#if CK_REVERSED

/* The chain read from the tool: T^-1 = M^-1 exp(-S_n q_n) ... exp(-S_1 q_1), axes flipped so the values stay. */
static void ck_reversed(const ck_chain *ch, ck_chain *o)
{
    ck_rt minv;
    int i, n = ch->n;
    ck_inverse(&ch->home, &minv);
    for (i = 0; i < n; ++i) {
        const int s = n - 1 - i;
        o->prismatic[i] = ch->prismatic[s];
        ck_mv(minv.r, ch->axis[s], o->axis[i]);
        ck_scale(o->axis[i], -1.0, o->axis[i]);
        ck_apply(&minv, ch->point[s], o->point[i]);
        o->index[i] = ch->index[s];
    }
    o->n = n;
    o->home = minv;
}
#endif

/* The product exp(S_lo q_lo) ... exp(S_{hi-1} q_{hi-1}) */
static void ck_product(const ck_chain *ch, const double *q, int lo, int hi, ck_rt *o)
{
    ck_rt e;
    int j;
    ck_identity(o);
    for (j = lo; j < hi; ++j) {
        ck_screw(ch->prismatic[j], ch->axis[j], ch->point[j], q[j], &e);
        ck_compose(o, &e, o);
    }
}

/* The chain's end frame (no base / tool) */
static void ck_fk_chain(const ck_chain *ch, const double *q, ck_rt *o)
{
    ck_product(ch, q, 0, ch->n, o);
    ck_compose(o, &ch->home, o);
}

/* Geometric Jacobian of the chain's end frame (no base / tool), 6 x n row-major, linear rows first; the end frame
 * itself (ck_fk_chain's, bit for bit) in *frame when frame is not NULL. */
static void ck_jacobian_chain(const ck_chain *ch, const double *q, double *jac, ck_rt *frame)
{
    ck_rt t, e;
    double w[CK_N][3], o[CK_N][3], end[3];
    int j, i, n = ch->n;
    ck_identity(&t);
    for (j = 0; j < n; ++j) {
        ck_mv(t.r, ch->axis[j], w[j]);
        ck_apply(&t, ch->point[j], o[j]);
        ck_screw(ch->prismatic[j], ch->axis[j], ch->point[j], q[j], &e);
        ck_compose(&t, &e, &t);
    }
    ck_compose(&t, &ch->home, &t);
    if (frame) *frame = t;
    end[0] = t.t[0];
    end[1] = t.t[1];
    end[2] = t.t[2];
    for (j = 0; j < n; ++j) {
        double lin[3];
        if (ch->prismatic[j]) {
            lin[0] = w[j][0];
            lin[1] = w[j][1];
            lin[2] = w[j][2];
            for (i = 0; i < 3; ++i) jac[(3 + i) * n + j] = 0.0;
        } else {
            double d[3];
            ck_sub(end, o[j], d);
            ck_cross(w[j], d, lin);
            for (i = 0; i < 3; ++i) jac[(3 + i) * n + j] = w[j][i];
        }
        for (i = 0; i < 3; ++i) jac[i * n + j] = lin[i];
    }
}
