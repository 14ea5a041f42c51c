/* The points and directions an op reads off the ideal chain (where axes meet, a point on an axis).
 * (a wristkin runtime source, inlined whole into every user robot's generated C, after the robot's CK_*
 * constants; derive/runtime_files.py, tests/test_chain_runtime.py) */
static void ck_meet(const ck_chain *ch, const int *js, int count, double *o)
{
    double m[9] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0}, v[3] = {0.0, 0.0, 0.0};
    int i, r, c;
    for (i = 0; i < count; ++i) {
        const double *a = ch->axis[js[i]], *p = ch->point[js[i]];
        for (r = 0; r < 3; ++r)
            for (c = 0; c < 3; ++c) {
                const double pr = (r == c ? 1.0 : 0.0) - a[r] * a[c];
                m[3 * r + c] += pr;
                v[r] += pr * p[c];
            }
    }
    if (!ck_solve3(m, v, o)) ck_lstsq(m, 3, 3, v, o); /* (near) parallel axes: least norm, as lstsq */
}

static void ck_point(const ck_chain *ch, const ck_op *op, double *o)
{
    if (op->spec == CK_MEET) {
        ck_meet(ch, op->spec_js, op->n_spec, o);
    } else if (op->spec == CK_ON) {
        o[0] = ch->point[op->spec_js[0]][0];
        o[1] = ch->point[op->spec_js[0]][1];
        o[2] = ch->point[op->spec_js[0]][2];
    } else if (op->spec == CK_HOME) {
        o[0] = ch->home.t[0];
        o[1] = ch->home.t[1];
        o[2] = ch->home.t[2];
    } else if (op->spec == CK_DIR) {
        o[0] = ch->axis[op->spec_js[0]][0];
        o[1] = ch->axis[op->spec_js[0]][1];
        o[2] = ch->axis[op->spec_js[0]][2];
    } else if (op->spec == CK_CROSS) {
        ck_cross(ch->axis[op->spec_js[0]], ch->axis[op->spec_js[1]], o);
        ck_scale(o, 1.0 / ck_norm(o), o);
    } else {
        o[0] = o[1] = o[2] = 0.0;
    }
}

