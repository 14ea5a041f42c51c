/* Test harness for the CPython binding's hand-written helpers (runtime/c/native/wkn_*.c), compiled as they are
 * where generated/native/_native.c inlines them (after Python.h, numpy's arrayobject.h, wristkin_common.h and
 * WKN_ROW_TOL). tests/test_native_helpers.py compiles it strictly and calls the wkt_* wrappers of the helpers that
 * need no interpreter state through ctypes (the others are run by every call of the generated binding,
 * tests/test_native.py). */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#define NPY_NO_DEPRECATED_API NPY_1_7_API_VERSION
#include <numpy/arrayobject.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "wristkin_common.h"
#define WKN_ROW_TOL WK_ROTATION_PROJECT_TOL

#include "../../runtime/c/native/wkn_inputs.c"
#include "../../runtime/c/native/wkn_results.c"

/* every helper referenced: the strict flags see no unused static function */
struct wkn_helpers {
    void (*release)(wkn_buf *, int);
    int (*get)(PyObject *, wkn_buf *, Py_ssize_t, char, int);
    const double *(*in)(PyObject *, npy_intp);
    const double *(*in_pose12)(PyObject *, int *);
    PyObject *(*result)(PyObject *, int, int, int, int, const int *, const unsigned *, const double *,
                        const double *);
    PyObject *(*new_array)(npy_intp, npy_intp);
    int (*pose12)(const wkn_buf *, const double **);
};
const struct wkn_helpers wkt_helpers = {wkn_release, wkn_get, wkn_in, wkn_in_pose12, wkn_result, wkn_new,
                                        wkn_pose12};

int wkt_summary(int status, const int *valid, const unsigned *flags, int max);
void wkt_fill(int max, int nv, int na, const int *valid, const unsigned *flags, const double *values,
              const double *aux, double *out_values, unsigned char *out_valid, int64_t *out_flags, double *out_aux);
int wkt_last_row_ok(const double *p);
void wkt_last_row(double *t);

int wkt_summary(int status, const int *valid, const unsigned *flags, int max)
{
    return wkn_summary(status, valid, flags, max);
}

void wkt_fill(int max, int nv, int na, const int *valid, const unsigned *flags, const double *values,
              const double *aux, double *out_values, unsigned char *out_valid, int64_t *out_flags, double *out_aux)
{
    wkn_fill(max, nv, na, valid, flags, values, aux, out_values, out_valid, out_flags, out_aux);
}

int wkt_last_row_ok(const double *p)
{
    return wkn_last_row_ok(p);
}

void wkt_last_row(double *t)
{
    wkn_last_row(t);
}
