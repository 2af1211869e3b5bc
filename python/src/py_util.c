/* py_util.c - what every part of the module uses: abrdf.Error, the library's failures as a
 * Python exception, and small conversions of C values to Python objects. abrdf.Error derives
 * from ValueError (every failure of the library is a bad value: an unknown name, a parameter
 * out of its range, a malformed table) and carries the library's message and its status code
 * (`status`, an abrdf_status: ABRDF_E_RANGE = -4, ...). */
#include "abrdf_py.h" /* first: Python.h sets the feature macros */

#include <stdarg.h>
#include <stdio.h>

/* The module's exception type, created once by PyInit__abrdf (py_module.c). */
static PyObject *error_type;

PyObject *abrdf_py_error_type_new(void)
{
    error_type = PyErr_NewExceptionWithDoc(
        "abrdf.Error",
        "A failure of libabrdf: the library's message, and its status code in `status`.",
        PyExc_ValueError, NULL);
    Py_XINCREF(error_type);
    return error_type;
}

PyObject *abrdf_py_fail(int status, const char *fmt, ...)
{
    char msg[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    PyObject *exc = PyObject_CallFunction(error_type, "s", msg);
    if (!exc) return NULL;
    PyObject *code = PyLong_FromLong(status);
    if (code && PyObject_SetAttrString(exc, "status", code) == 0) PyErr_SetObject(error_type, exc);
    Py_XDECREF(code);
    Py_DECREF(exc);
    return NULL;
}

PyObject *abrdf_py_opt(double v) { return v < 0.0 ? Py_NewRef(Py_None) : PyFloat_FromDouble(v); }

PyObject *abrdf_py_rgb(const double v[3]) { return Py_BuildValue("(ddd)", v[0], v[1], v[2]); }

int abrdf_py_set(PyObject *d, const char *key, PyObject *value)
{
    if (!value) return -1;
    int rc = PyDict_SetItemString(d, key, value);
    Py_DECREF(value);
    return rc;
}

int abrdf_py_real_number(PyObject *v, const char *what, double *out)
{
    int real = !PyBool_Check(v) && (PyFloat_Check(v) || PyLong_Check(v));
    if (!real && !PyBool_Check(v)) {
        PyObject *numbers = PyImport_ImportModule("numbers");
        PyObject *type = numbers ? PyObject_GetAttrString(numbers, "Real") : NULL;
        Py_XDECREF(numbers);
        real = type ? PyObject_IsInstance(v, type) : -1;
        Py_XDECREF(type);
        if (real < 0) return -1;
    }
    if (real) {
        *out = PyFloat_AsDouble(v);
        if (!(*out == -1.0 && PyErr_Occurred())) return 0;
        /* numpy.timedelta64 is registered as a Real but has no float value. */
        if (!PyErr_ExceptionMatches(PyExc_TypeError)) return -1;
        PyErr_Clear();
    }
    PyErr_Format(PyExc_TypeError, "%s: a real number is needed, got %.100s", what,
                 Py_TYPE(v)->tp_name);
    return -1;
}
