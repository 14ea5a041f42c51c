/* The CPython binding's results: solution sets in the Python modules' layout and finished Solutions objects.
 * (a wristkin runtime source, inlined whole into the CPython binding generated/native/_native.c after Python.h,
 * numpy's arrayobject.h, wristkin_common.h and WKN_ROW_TOL; derive/runtime_files.py, tests/test_native_helpers.py) */
/* One solution set (max rows of nv values and na aux) into arrays in the Python layout: rows that are not valid
   become NaN. */
static void wkn_fill(int max, int nv, int na, const int *valid, const unsigned *flags, const double *values,
                     const double *aux, double *out_values, unsigned char *out_valid, int64_t *out_flags,
                     double *out_aux)
{
    int k, j;
    for (k = 0; k < max; ++k) {
        int good = valid[k] != 0;
        out_valid[k] = (unsigned char)good;
        out_flags[k] = (int64_t)flags[k];
        for (j = 0; j < nv; ++j)
            out_values[k * nv + j] = good ? values[k * nv + j] : NAN;
        for (j = 0; j < na; ++j)
            out_aux[k * na + j] = good ? aux[k * na + j] : NAN;
    }
}

/* The attribute names of a Solutions object, interned once (module init). */
static PyObject *wkn_names[6];
static PyObject *wkn_no_args;

/* A finished Solutions object: `cls` made as object.__new__(cls) with its six fields set as object.__setattr__
   sets them (the class is a frozen dataclass; this is what its __init__ does, without the Python frames). */
static PyObject *wkn_object(PyObject *cls, PyObject **fields)
{
    PyObject *obj = PyBaseObject_Type.tp_new((PyTypeObject *)cls, wkn_no_args, NULL);
    int i;
    if (obj == NULL)
        return NULL;
    for (i = 0; i < 6; ++i) {
        if (PyObject_GenericSetAttr(obj, wkn_names[i], fields[i]) < 0) {
            Py_DECREF(obj);
            return NULL;
        }
    }
    return obj;
}

/* The reason text `spec` = (Solutions class, reason text by count, {status: text}) gives a result without a
   projected pose: by its count for status ok or indeterminate, else its status's fixed text; NULL (borrowed). */
static PyObject *wkn_reason(PyObject *spec, int summary)
{
    const int status = summary & 255, count = (summary >> 8) & 255;
    PyObject *texts, *fixed, *key, *text;
    if (spec == NULL || !PyTuple_Check(spec) || PyTuple_GET_SIZE(spec) != 3 || !PyType_Check(PyTuple_GET_ITEM(spec, 0))
        || (summary >> 16))
        return NULL;
    texts = PyTuple_GET_ITEM(spec, 1);
    fixed = PyTuple_GET_ITEM(spec, 2);
    if (status == WK_STATUS_OK || status == WK_STATUS_INDETERMINATE)
        return PyTuple_Check(texts) && count < PyTuple_GET_SIZE(texts) ? PyTuple_GET_ITEM(texts, count) : NULL;
    if (!PyDict_Check(fixed) || (key = PyLong_FromLong(status)) == NULL) {
        PyErr_Clear();
        return NULL;
    }
    text = PyDict_GetItem(fixed, key);
    Py_DECREF(key);
    return text;
}

/* One solution set as new arrays in the Python layout. With `spec` (see wkn_reason) and a result whose reason it
   gives: a finished Solutions object. Otherwise (summary, values, valid, flags, aux): the caller words the reason or
   takes the Python path. */
static PyObject *wkn_result(PyObject *spec, int summary, int max, int nv, int na, const int *valid,
                            const unsigned *flags, const double *values, const double *aux)
{
    npy_intp dv[2] = {max, nv}, da[2] = {max, na}, dm[1] = {max};
    PyObject *reason = wkn_reason(spec, summary);
    PyObject *v = PyArray_SimpleNew(2, dv, NPY_DOUBLE), *ok = PyArray_SimpleNew(1, dm, NPY_BOOL),
             *f = PyArray_SimpleNew(1, dm, NPY_INT64), *x = PyArray_SimpleNew(2, da, NPY_DOUBLE);
    if (!v || !ok || !f || !x) {
        Py_XDECREF(v);
        Py_XDECREF(ok);
        Py_XDECREF(f);
        Py_XDECREF(x);
        return NULL;
    }
    wkn_fill(max, nv, na, valid, flags, values, aux, (double *)PyArray_DATA((PyArrayObject *)v),
             (unsigned char *)PyArray_DATA((PyArrayObject *)ok), (int64_t *)PyArray_DATA((PyArrayObject *)f),
             (double *)PyArray_DATA((PyArrayObject *)x));
    if (reason != NULL) {
        PyObject *st = PyLong_FromLong(summary & 255), *obj = NULL;
        if (st != NULL) {
            PyObject *fields[6];
            fields[0] = v;
            fields[1] = ok;
            fields[2] = f;
            fields[3] = x;
            fields[4] = st;
            fields[5] = reason;
            obj = wkn_object(PyTuple_GET_ITEM(spec, 0), fields);
            Py_DECREF(st);
        }
        Py_DECREF(v);
        Py_DECREF(ok);
        Py_DECREF(f);
        Py_DECREF(x);
        return obj;
    }
    return Py_BuildValue("(iNNNN)", summary, v, ok, f, x);
}

/* status | count << 8 | (any set projected) << 16: what the caller needs without a numpy reduction */
static int wkn_summary(int status, const int *valid, const unsigned *flags, int max)
{
    int k, count = 0, projected = 0;
    for (k = 0; k < max; ++k) {
        if (valid[k]) {
            ++count;
            projected |= (flags[k] & WK_FLAG_PROJECTED) != 0;
        }
    }
    return status | count << 8 | projected << 16;
}

/* The last row (0, 0, 0, 1) of a 4x4 pose whose top 3x4 block the solver wrote. */
static void wkn_last_row(double *t)
{
    t[12] = 0.0;
    t[13] = 0.0;
    t[14] = 0.0;
    t[15] = 1.0;
}
