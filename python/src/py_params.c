/* py_params.c - Params: a parameter block validated for one model, as the evaluation
 * functions (and a later prepared path) take it. Built from a model name and a mapping of
 * the model's parameters (the registry's names: "kd", "r", "layer0_eta", ...); every value is
 * set through abrdf_param_set and the block is checked by abrdf_params_check, whose message
 * the exception carries. */
#include "abrdf_py.h" /* first: Python.h sets the feature macros */

#include <math.h>
#include <stdio.h>
#include <string.h>

int abrdf_py_model_find(const char *name, abrdf_model *out)
{
    if (abrdf_model_find(name, out) == ABRDF_OK) return 0;
    abrdf_py_fail(ABRDF_E_MODEL, "unknown model '%s' (%s; abrdf.models() lists them)", name,
                  abrdf_strerror(ABRDF_E_MODEL));
    return -1;
}

static const abrdf_model_param *model_param(const abrdf_model_info *m, int id)
{
    for (int k = 0; k < m->param_count; ++k)
        if (m->params[k].id == id) return &m->params[k];
    return NULL;
}

/* "kd, ks, f0, r": the names of the parameters `m` reads. */
static void param_names(const abrdf_model_info *m, char *buf, size_t size)
{
    size_t w = 0;
    buf[0] = '\0';
    for (int k = 0; k < m->param_count && w < size; ++k) {
        const abrdf_param_info *p = abrdf_param_get(m->params[k].id);
        int n = snprintf(buf + w, size - w, "%s%s", k ? ", " : "", p ? p->name : "?");
        if (n < 0) break;
        w += (size_t)n;
    }
}

/* One value of `info`'s kind from a Python object into v[0..2]; returns the count or -1. */
static int read_value(const abrdf_param_info *info, PyObject *value, double v[3])
{
    char what[96];
    snprintf(what, sizeof what, "parameter '%s'", info->name);
    /* Strings and bytes are sequences too, but never a colour. */
    if (info->kind == ABRDF_PARAM_RGB && PySequence_Check(value) && !PyUnicode_Check(value) &&
        !PyBytes_Check(value) && !PyByteArray_Check(value)) {
        if (PySequence_Size(value) != 3) {
            if (!PyErr_Occurred())
                abrdf_py_fail(ABRDF_E_RANGE, "%s: a colour needs 3 values (R, G, B)", what);
            return -1;
        }
        for (int c = 0; c < 3; ++c) {
            PyObject *item = PySequence_GetItem(value, c);
            int rc = item ? abrdf_py_real_number(item, what, &v[c]) : -1;
            Py_XDECREF(item);
            if (rc) return -1;
        }
        return 3;
    }
    if (abrdf_py_real_number(value, what, &v[0])) return -1;
    if (info->kind == ABRDF_PARAM_INT && !(floor(v[0]) == v[0])) {
        abrdf_py_fail(ABRDF_E_RANGE, "parameter '%s' is an integer, got %g", info->name, v[0]);
        return -1;
    }
    if (info->kind == ABRDF_PARAM_RGB) {
        v[1] = v[2] = v[0];
        return 3;
    }
    return 1;
}

/* Set values[name] for every item of the mapping into p, for model m. */
static int set_values(const abrdf_model_info *m, abrdf_params *p, PyObject *values)
{
    PyObject *key, *value;
    Py_ssize_t pos = 0;
    while (PyDict_Next(values, &pos, &key, &value)) {
        const char *name = PyUnicode_AsUTF8(key);
        if (!name) return -1;
        int id;
        char names[512];
        param_names(m, names, sizeof names);
        if (abrdf_param_find(name, &id) != ABRDF_OK) {
            abrdf_py_fail(ABRDF_E_PARAM, "%s: unknown parameter '%s' (%s); it reads: %s", m->name,
                          name, abrdf_strerror(ABRDF_E_PARAM), names[0] ? names : "nothing");
            return -1;
        }
        if (!model_param(m, id)) {
            abrdf_py_fail(ABRDF_E_UNUSED, "%s does not read parameter '%s' (%s); it reads: %s",
                          m->name, name, abrdf_strerror(ABRDF_E_UNUSED),
                          names[0] ? names : "nothing");
            return -1;
        }
        const abrdf_param_info *info = abrdf_param_get(id);
        double v[3];
        int count = read_value(info, value, v);
        if (count < 0) return -1;
        int st = abrdf_param_set(p, id, v, count);
        if (st != ABRDF_OK) {
            if (count == 3)
                abrdf_py_fail(st, "%s: %s = %g,%g,%g: %s (its range is [%g, %g])", m->name,
                              info->name, v[0], v[1], v[2], abrdf_strerror(st), info->min,
                              info->max);
            else
                abrdf_py_fail(st, "%s: %s = %g: %s (its range is [%g, %g])", m->name, info->name,
                              v[0], abrdf_strerror(st), info->min, info->max);
            return -1;
        }
    }
    return 0;
}

static int check(abrdf_model model, const abrdf_params *p)
{
    char msg[512];
    int st = abrdf_params_check(model, p, msg, sizeof msg);
    if (st == ABRDF_OK) return 0;
    abrdf_py_fail(st, "%s", msg);
    return -1;
}

static int params_init(PyObject *self, PyObject *args, PyObject *kwargs)
{
    static char *kw[] = {"model", "values", NULL};
    const char *name;
    PyObject *values = NULL;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "s|O!:Params", kw, &name, &PyDict_Type, &values))
        return -1;
    abrdf_py_params *o = (abrdf_py_params *)self;
    if (abrdf_py_model_find(name, &o->model)) return -1;
    abrdf_params_init(o->model, &o->params);
    const abrdf_model_info *m = abrdf_model_get(o->model);
    if (values && set_values(m, &o->params, values)) return -1;
    return check(o->model, &o->params);
}

PyObject *abrdf_py_params_from_block(abrdf_model model, const abrdf_params *params)
{
    if (check(model, params)) return NULL;
    abrdf_py_params *o = PyObject_New(abrdf_py_params, &abrdf_py_params_type);
    if (!o) return NULL;
    o->model = model;
    o->params = *params;
    return (PyObject *)o;
}

abrdf_py_params *abrdf_py_params_arg(PyObject *obj, const char *what)
{
    if (PyObject_TypeCheck(obj, &abrdf_py_params_type)) return (abrdf_py_params *)obj;
    PyErr_Format(PyExc_TypeError, "%s: a Params is needed, not %.100s", what,
                 Py_TYPE(obj)->tp_name);
    return NULL;
}

PyObject *abrdf_py_param_value(const abrdf_params *params, int id)
{
    double v[3];
    int n = abrdf_param_read(params, id, v);
    if (n < 0) return abrdf_py_fail(n, "parameter id %d: %s", id, abrdf_strerror(n));
    const abrdf_param_info *info = abrdf_param_get(id);
    if (n == 3) return abrdf_py_rgb(v);
    if (info && info->kind == ABRDF_PARAM_INT) return PyLong_FromDouble(v[0]);
    return PyFloat_FromDouble(v[0]);
}

static PyObject *params_model(PyObject *self, void *closure)
{
    (void)closure;
    return PyUnicode_FromString(abrdf_model_get(((abrdf_py_params *)self)->model)->name);
}

static PyObject *params_values(PyObject *self, PyObject *unused)
{
    (void)unused;
    abrdf_py_params *o = (abrdf_py_params *)self;
    const abrdf_model_info *m = abrdf_model_get(o->model);
    PyObject *d = PyDict_New();
    if (!d) return NULL;
    for (int k = 0; k < m->param_count; ++k) {
        const abrdf_param_info *info = abrdf_param_get(m->params[k].id);
        if (abrdf_py_set(d, info->name, abrdf_py_param_value(&o->params, m->params[k].id))) {
            Py_DECREF(d);
            return NULL;
        }
    }
    return d;
}

static PyObject *params_repr(PyObject *self)
{
    PyObject *values = params_values(self, NULL);
    if (!values) return NULL;
    PyObject *r = PyUnicode_FromFormat(
        "Params('%s', %R)", abrdf_model_get(((abrdf_py_params *)self)->model)->name, values);
    Py_DECREF(values);
    return r;
}

static PyGetSetDef params_getset[] = {
    {"model", params_model, NULL, "the model's stable name", NULL}, {NULL, NULL, NULL, NULL, NULL}};

static PyMethodDef params_methods[] = {
    {"values", params_values, METH_NOARGS,
     "values() -> dict: every parameter the model reads, by name (a colour as a 3-tuple)"},
    {NULL, NULL, 0, NULL}};

PyTypeObject abrdf_py_params_type = {
    PyVarObject_HEAD_INIT(NULL, 0).tp_name = "abrdf._abrdf.Params",
    .tp_basicsize = sizeof(abrdf_py_params),
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_doc = "Params(model, values={}) - a parameter block validated for one model.\n\n"
              "The model's defaults (abrdf_params_init), then each value of `values` (the\n"
              "registry's parameter names; a colour as one number or three) set through\n"
              "abrdf_param_set; the block is checked by abrdf_params_check. Raises\n"
              "abrdf.Error with the library's message.",
    .tp_new = PyType_GenericNew,
    .tp_init = params_init,
    .tp_repr = params_repr,
    .tp_getset = params_getset,
    .tp_methods = params_methods,
};
