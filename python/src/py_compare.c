/* py_compare.c - the image metrics of `abrdf compare` (tools/image/metrics.c) on two float32
 * images in memory: the paper's NMSE (Sec. 4: sum (TEST - REF)^2 / sum REF^2 over every pixel
 * and channel), MSE, PSNR against the brightest value, the largest error and where it is,
 * and the Table-8 class. The package reads image files (OpenImageIO) and calls this. */
#include "abrdf_py.h" /* first: Python.h sets the feature macros */

#include <limits.h>
#include <math.h>

#include "metrics.h"

static PyObject *py_compare(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *ref_obj, *test_obj;
    if (!PyArg_ParseTuple(args, "OO:compare", &ref_obj, &test_obj)) return NULL;
    Py_buffer ref, test;
    Py_ssize_t rs[3], ts[3];
    if (abrdf_py_float_image(ref_obj, "reference", &ref, rs)) return NULL;
    if (abrdf_py_float_image(test_obj, "test", &test, ts)) {
        PyBuffer_Release(&ref);
        return NULL;
    }
    PyObject *out = NULL;
    if (rs[0] != ts[0] || rs[1] != ts[1] || rs[2] != ts[2]) {
        abrdf_py_fail(ABRDF_E_RANGE,
                      "images differ in size or channels: the reference is %zdx%zd with %zd "
                      "channels, the test %zdx%zd with %zd",
                      rs[1], rs[0], rs[2], ts[1], ts[0], ts[2]);
        goto done;
    }
    if (rs[0] < 1 || rs[1] < 1 || rs[2] < 1 || rs[0] > INT_MAX / rs[1] || rs[2] > INT_MAX) {
        abrdf_py_fail(ABRDF_E_RANGE, "images of %zdx%zd pixels and %zd channels cannot be compared",
                      rs[1], rs[0], rs[2]);
        goto done;
    }
    abrdf_metrics m;
    int rc;
    Py_BEGIN_ALLOW_THREADS;
    rc = abrdf_metrics_compute(test.buf, ref.buf, (int)rs[1], (int)rs[0], (int)rs[2], &m);
    Py_END_ALLOW_THREADS;
    if (rc == ABRDF_METRICS_NONFINITE) {
        const float *bad = (const float *)ref.buf + (m.max_y * rs[1] + m.max_x) * rs[2] + m.max_c;
        abrdf_py_fail(ABRDF_E_RANGE,
                      "the %s image has a NaN or infinite value at pixel (%d, %d) channel %d",
                      isfinite(*bad) ? "test" : "reference", m.max_x, m.max_y, m.max_c);
        goto done;
    }
    if (rc != ABRDF_METRICS_OK) {
        abrdf_py_fail(ABRDF_E_RANGE, "these images cannot be compared");
        goto done;
    }
    double nmse = m.nmse_defined ? m.nmse : -1.0;
    PyObject *d = PyDict_New();
    if (!d) goto done;
    if (abrdf_py_set(d, "nmse", abrdf_py_opt(nmse)) ||
        abrdf_py_set(d, "sse", PyFloat_FromDouble(m.sse)) ||
        abrdf_py_set(d, "reference_energy", PyFloat_FromDouble(m.ref_energy)) ||
        abrdf_py_set(d, "mse", PyFloat_FromDouble(m.mse)) ||
        abrdf_py_set(d, "peak", PyFloat_FromDouble(m.peak)) ||
        abrdf_py_set(d, "psnr", PyFloat_FromDouble(m.psnr)) ||
        abrdf_py_set(d, "max_abs_error", PyFloat_FromDouble(m.max_abs)) ||
        abrdf_py_set(d, "max_pixel", Py_BuildValue("(ii)", m.max_x, m.max_y)) ||
        abrdf_py_set(d, "max_channel", PyLong_FromLong(m.max_c)) ||
        abrdf_py_set(d, "nmse_class", PyUnicode_FromString(abrdf_nmse_class(nmse))) ||
        abrdf_py_set(d, "nmse_class_description",
                     PyUnicode_FromString(abrdf_nmse_class_description(nmse)))) {
        Py_DECREF(d);
        goto done;
    }
    out = d;
done:
    PyBuffer_Release(&ref);
    PyBuffer_Release(&test);
    return out;
}

PyMethodDef abrdf_py_compare_methods[] = {
    {"compare", py_compare, METH_VARARGS,
     "compare(reference, test) -> dict: NMSE (None for an all-black reference), SSE, reference "
     "energy, MSE, peak, PSNR, max |test - reference| with its pixel (x, y) and channel, and the "
     "paper's Table-8 class of the NMSE; float32 images (H, W) or (H, W, C) of the same shape. "
     "Releases the GIL."},
    {NULL, NULL, 0, NULL}};
