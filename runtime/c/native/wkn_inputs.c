/* The CPython binding's inputs: buffers of the caller's arrays, checked for type, size and layout, and poses.
 * (a wristkin runtime source, inlined whole into the CPython binding generated/native/_native.c after Python.h,
 * numpy's arrayobject.h, wristkin_common.h and WKN_ROW_TOL; derive/runtime_files.py, tests/test_native_helpers.py) */
typedef struct {
    Py_buffer view;
    int held;
} wkn_buf;

static void wkn_release(wkn_buf *b, int n)
{
    int i;
    for (i = 0; i < n; ++i) {
        if (b[i].held) {
            PyBuffer_Release(&b[i].view);
            b[i].held = 0;
        }
    }
}

/* The bytes of a C-contiguous array of `n` items of `size` bytes (`n` < 0: any count). The Python modules pass
   only arrays they made with the right dtype (float64, bool, int64): a plain buffer request is the cheapest. */
static int wkn_get(PyObject *obj, wkn_buf *b, Py_ssize_t n, char kind, int writable)
{
    Py_ssize_t size = kind == 'd' || kind == 'q' ? 8 : 1;
    if (PyObject_GetBuffer(obj, &b->view, writable ? PyBUF_WRITABLE : PyBUF_SIMPLE) < 0)
        return -1;
    b->held = 1;
    if ((n >= 0 && b->view.len != n * size) || b->view.len % size != 0) {
        PyErr_Format(PyExc_TypeError, "wristkin._native: expected %zd items of type '%c'", n, kind);
        return -1;
    }
    return 0;
}

#define WKN_CONVERT (-100)

/* The last row of a 4x4 pose (p[12..15]) is (0, 0, 0, 1) within WKN_ROW_TOL. */
static int wkn_last_row_ok(const double *p)
{
    return fabs(p[12]) <= WKN_ROW_TOL && fabs(p[13]) <= WKN_ROW_TOL && fabs(p[14]) <= WKN_ROW_TOL &&
           fabs(p[15] - 1.0) <= WKN_ROW_TOL;
}

/* The data of `obj` when it is a C-contiguous float64 numpy array of exactly `n` items and `ndim` dimensions
   (ndim 0: any), else NULL. */
static const double *wkn_in(PyObject *obj, npy_intp n)
{
    PyArrayObject *a = (PyArrayObject *)obj;
    if (!PyArray_Check(obj) || PyArray_TYPE(a) != NPY_DOUBLE || !PyArray_IS_C_CONTIGUOUS(a) || PyArray_SIZE(a) != n)
        return NULL;
    return (const double *)PyArray_DATA(a);
}

/* A pose as the Python modules accept it: (4, 4), (3, 4), (16,) or (12,); the first 12 numbers, or NULL. */
static const double *wkn_in_pose12(PyObject *obj, int *rc)
{
    PyArrayObject *a = (PyArrayObject *)obj;
    npy_intp *d;
    int nd;
    const double *p;
    *rc = WK_OK;
    if (!PyArray_Check(obj) || PyArray_TYPE(a) != NPY_DOUBLE || !PyArray_IS_C_CONTIGUOUS(a))
        return NULL;
    nd = PyArray_NDIM(a);
    d = PyArray_DIMS(a);
    if (!((nd == 2 && (d[0] == 4 || d[0] == 3) && d[1] == 4) || (nd == 1 && (d[0] == 16 || d[0] == 12))))
        return NULL;
    p = (const double *)PyArray_DATA(a);
    if (PyArray_SIZE(a) == 16 && !wkn_last_row_ok(p))
        *rc = WK_ERR_RANGE;
    return p;
}

/* A new (rows, cols) float64 array, or NULL with the error set. */
static PyObject *wkn_new(npy_intp rows, npy_intp cols)
{
    npy_intp d[2] = {rows, cols};
    return PyArray_SimpleNew(2, d, NPY_DOUBLE);
}

/* A 3x4 pose (12 numbers) as given, or a 4x4 one (16) whose last row is (0, 0, 0, 1): its first 12 numbers. */
static int wkn_pose12(const wkn_buf *b, const double **pose)
{
    const double *p = (const double *)b->view.buf;
    Py_ssize_t n = b->view.len / 8;
    if (n == 16) {
        if (!wkn_last_row_ok(p))
            return WK_ERR_RANGE;
    } else if (n != 12) {
        return WK_ERR_RANGE;
    }
    *pose = p;
    return WK_OK;
}
