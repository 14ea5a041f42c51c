/* A serial arm's base and tool frames at run time (design_set_frames): they replace the chain's own (sr_base0,
 * sr_tool0: the catalogue's identity, a user robot's description's), which its derived kernels fold in. The
 * kernels answer pose0 = left^-1 . pose . right^-1, with left = base . base0^-1 and right = tool0^-1 . tool
 * (Python serial_frames.py). Transforms are the top 3x4 of a rigid 4x4, row-major.
 * (a wristkin runtime source, inlined whole into every serial arm's generated C after its SR_* constants and
 * switches, the sr_design / sr_ik_solutions / sr_fk_solutions types, its derived kernels sr_k_* and stage
 * functions; derive/runtime_files.py, derive/families/serial/views.py, tests/test_serial_runtime.py) */

/* o = a . b */
static void sr_compose(const double *a, const double *b, double *o)
{
    int i, j;
    for (i = 0; i < 3; ++i)
        for (j = 0; j < 4; ++j)
            o[4 * i + j] = a[4 * i] * b[j] + a[4 * i + 1] * b[4 + j] + a[4 * i + 2] * b[8 + j] +
                           (j == 3 ? a[4 * i + 3] : 0.0);
}

/* o = a^-1 (R^T, -R^T t) */
static void sr_invert(const double *a, double *o)
{
    int i, j;
    for (i = 0; i < 3; ++i) {
        for (j = 0; j < 3; ++j) o[4 * i + j] = a[4 * j + i];
        o[4 * i + 3] = -(a[i] * a[3] + a[4 + i] * a[7] + a[8 + i] * a[11]);
    }
}

/* a frame as given (wk_input_frame), its translation within SR_LENGTH_MAX */
static int sr_frame(const double *in, double *out)
{
    const int rc = wk_input_frame(in, out);
    if (rc != WK_OK) return rc;
    return fabs(out[3]) <= SR_LENGTH_MAX && fabs(out[7]) <= SR_LENGTH_MAX && fabs(out[11]) <= SR_LENGTH_MAX
               ? WK_OK
               : WK_ERR_DESIGN;
}

/* base and / or tool (NULL: the chain's own); framed when either differs from it, and then the transforms the calls
 * apply (left, right and their inverses) are composed here once, not per call */
static int sr_api_design_set_frames(sr_design *design, const double *base, const double *tool)
{
    double b[12], t[12], inv[12];
    int i, rc;
    if (!design) return WK_ERR_NULL;
    for (i = 0; i < 12; ++i) {
        b[i] = sr_base0[i];
        t[i] = sr_tool0[i];
    }
    if (base && (rc = sr_frame(base, b)) != WK_OK) return rc;
    if (tool && (rc = sr_frame(tool, t)) != WK_OK) return rc;
    design->framed = 0;
    for (i = 0; i < 12; ++i) {
        design->base[i] = b[i];
        design->tool[i] = t[i];
        if (b[i] != sr_base0[i] || t[i] != sr_tool0[i]) design->framed = 1;
    }
    sr_invert(sr_base0, inv);
    sr_compose(b, inv, design->left);
    sr_invert(sr_tool0, inv);
    sr_compose(inv, t, design->right);
    sr_invert(design->left, design->left_inv);
    sr_invert(design->right, design->right_inv);
    return WK_OK;
}

/* the pose the kernels answer for a pose in the design's frames: left^-1 . pose . right^-1 */
static void sr_unframe(const sr_design *d, const double *pose, double *pose0)
{
    double tmp[12];
    sr_compose(d->left_inv, pose, tmp);
    sr_compose(tmp, d->right_inv, pose0);
}

/* the pose in the design's frames of the kernels' pose0: left . pose0 . right */
static void sr_reframe(const sr_design *d, const double *pose0, double *pose)
{
    double tmp[12];
    sr_compose(d->left, pose0, tmp);
    sr_compose(tmp, d->right, pose);
}

/* the geometric Jacobian in the design's frames, from the kernels' (jac, 6 x SR_N, at the end pose pose0): the end
 * frame's origin moves by R0 r (r: right's translation), so each linear column gains w x R0 r; then both rows turn
 * by left's rotation */
static void sr_reframe_jacobian(const sr_design *d, const double *pose0, double *jac)
{
    const double *left = d->left, *right = d->right;
    double a[3];
    int i, j;
    for (i = 0; i < 3; ++i) a[i] = pose0[4 * i] * right[3] + pose0[4 * i + 1] * right[7] + pose0[4 * i + 2] * right[11];
    for (j = 0; j < SR_N; ++j) {
        const double w[3] = { jac[3 * SR_N + j], jac[4 * SR_N + j], jac[5 * SR_N + j] };
        const double v[3] = { jac[j] + w[1] * a[2] - w[2] * a[1], jac[SR_N + j] + w[2] * a[0] - w[0] * a[2],
                              jac[2 * SR_N + j] + w[0] * a[1] - w[1] * a[0] };
        for (i = 0; i < 3; ++i) {
            jac[i * SR_N + j] = left[4 * i] * v[0] + left[4 * i + 1] * v[1] + left[4 * i + 2] * v[2];
            jac[(3 + i) * SR_N + j] = left[4 * i] * w[0] + left[4 * i + 1] * w[1] + left[4 * i + 2] * w[2];
        }
    }
}
