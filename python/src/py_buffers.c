/* py_buffers.c - arrays in and out through the buffer protocol (PEP 3118): C-contiguous
 * blocks of float32 or float64 in the machine's byte order, as numpy.ascontiguousarray
 * makes them. The package (python/abrdf) shapes and converts; these checks only refuse
 * what the C loops cannot read. */
#include "abrdf_py.h" /* first: Python.h sets the feature macros */

#include <string.h>

/* 'f' or 'd' for a native float32/float64 format string, else 0. */
static int real_kind(const Py_buffer *v)
{
    const char *f = v->format ? v->format : "B";
    if (*f == '@' || *f == '=') ++f;
#if PY_LITTLE_ENDIAN
    else if (*f == '<')
        ++f;
#else
    else if (*f == '>' || *f == '!')
        ++f;
#endif
    if (!strcmp(f, "f") && v->itemsize == 4) return ABRDF_PY_F32;
    if (!strcmp(f, "d") && v->itemsize == 8) return ABRDF_PY_F64;
    return 0;
}

static int acquire(PyObject *obj, const char *what, int writable, Py_buffer *view)
{
    int flags = PyBUF_C_CONTIGUOUS | PyBUF_FORMAT | (writable ? PyBUF_WRITABLE : 0);
    if (PyObject_GetBuffer(obj, view, flags) == 0) return 0;
    PyErr_Clear();
    PyErr_Format(PyExc_TypeError, "%s: a C-contiguous%s float array is needed, not %.100s", what,
                 writable ? " writable" : "", Py_TYPE(obj)->tp_name);
    return -1;
}

int abrdf_py_rows3(PyObject *obj, const char *what, int want, int writable, Py_buffer *view,
                   Py_ssize_t *rows, abrdf_py_real *kind)
{
    if (acquire(obj, what, writable, view)) return -1;
    int k = real_kind(view);
    if (!k || (want && k != want)) {
        PyErr_Format(PyExc_TypeError, "%s: %s needed, got format '%s'", what,
                     want == ABRDF_PY_F32   ? "float32"
                     : want == ABRDF_PY_F64 ? "float64"
                                            : "float32 or float64",
                     view->format ? view->format : "B");
        PyBuffer_Release(view);
        return -1;
    }
    if (view->ndim != 2 || view->shape[1] != 3) {
        PyErr_Format(PyExc_ValueError, "%s: an array of shape (N, 3) is needed", what);
        PyBuffer_Release(view);
        return -1;
    }
    *rows = view->shape[0];
    *kind = (abrdf_py_real)k;
    return 0;
}

int abrdf_py_float_image(PyObject *obj, const char *what, Py_buffer *view, Py_ssize_t shape[3])
{
    if (acquire(obj, what, 0, view)) return -1;
    if (real_kind(view) != ABRDF_PY_F32) {
        PyErr_Format(PyExc_TypeError, "%s: float32 needed, got format '%s'", what,
                     view->format ? view->format : "B");
        PyBuffer_Release(view);
        return -1;
    }
    if (view->ndim != 2 && view->ndim != 3) {
        PyErr_Format(PyExc_ValueError,
                     "%s: an image of shape (height, width) or (height, width, channels) is "
                     "needed, got %d dimensions",
                     what, view->ndim);
        PyBuffer_Release(view);
        return -1;
    }
    shape[0] = view->shape[0];
    shape[1] = view->shape[1];
    shape[2] = view->ndim == 3 ? view->shape[2] : 1;
    return 0;
}

int abrdf_py_float_buffer(PyObject *obj, const char *what, Py_buffer *view)
{
    if (acquire(obj, what, 0, view)) return -1;
    if (real_kind(view) == ABRDF_PY_F32) return 0;
    PyErr_Format(PyExc_TypeError, "%s: float32 needed, got format '%s'", what,
                 view->format ? view->format : "B");
    PyBuffer_Release(view);
    return -1;
}

int abrdf_py_double_buffer(PyObject *obj, const char *what, int writable, Py_buffer *view)
{
    if (acquire(obj, what, writable, view)) return -1;
    if (real_kind(view) == ABRDF_PY_F64) return 0;
    PyErr_Format(PyExc_TypeError, "%s: float64 needed, got format '%s'", what,
                 view->format ? view->format : "B");
    PyBuffer_Release(view);
    return -1;
}
