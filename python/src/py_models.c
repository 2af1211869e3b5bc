/* py_models.c - the registry as Python data: every model with its metadata (name, title,
 * the paper's formula, citation, needs, properties, the paper's Table-4 cost), as
 * `abrdf models --json` gives it, and the
 * parameters it reads with this model's default and range; every parameter with its own. */
#include "abrdf_py.h"

/* The words of `abrdf models --json` (tools/cli/cmd_models.c). */
static const struct {
    unsigned bit;
    const char *name;
} needs_names[] = {{ABRDF_NEEDS_TANGENT, "tangent"},
                   {ABRDF_NEEDS_FRESNEL, "fresnel"},
                   {ABRDF_NEEDS_LAYERS, "layers"},
                   {ABRDF_NEEDS_INTEGRATION, "integration"},
                   {ABRDF_NEEDS_TABLE, "table"}};

static const char *kind_name(abrdf_param_kind k)
{
    return k == ABRDF_PARAM_RGB ? "rgb" : k == ABRDF_PARAM_INT ? "int" : "scalar";
}

/* The names of the set ABRDF_NEEDS_* bits as a tuple. */
static PyObject *needs_tuple(unsigned flags)
{
    PyObject *t = PyList_New(0);
    for (size_t k = 0; t && k < sizeof needs_names / sizeof needs_names[0]; ++k) {
        unsigned bit = needs_names[k].bit;
        const char *name = needs_names[k].name;
        if (flags & bit) {
            PyObject *s = PyUnicode_FromString(name);
            if (!s || PyList_Append(t, s)) {
                Py_XDECREF(s);
                Py_DECREF(t);
                return NULL;
            }
            Py_DECREF(s);
        }
    }
    if (!t) return NULL;
    PyObject *tuple = PyList_AsTuple(t);
    Py_DECREF(t);
    return tuple;
}

/* name, help, kind, and default/min/max (the model's when mp is given, else the parameter's). */
static PyObject *param_dict(const abrdf_param_info *p, const abrdf_model_param *mp)
{
    PyObject *d = PyDict_New();
    if (!d) return NULL;
    double def = mp ? mp->def : p->def, lo = mp ? mp->min : p->min, hi = mp ? mp->max : p->max;
    if (abrdf_py_set(d, "name", PyUnicode_FromString(p->name)) ||
        abrdf_py_set(d, "help", PyUnicode_FromString(p->help)) ||
        abrdf_py_set(d, "kind", PyUnicode_FromString(kind_name(p->kind))) ||
        abrdf_py_set(d, "default", PyFloat_FromDouble(def)) ||
        abrdf_py_set(d, "min", PyFloat_FromDouble(lo)) ||
        abrdf_py_set(d, "max", PyFloat_FromDouble(hi))) {
        Py_DECREF(d);
        return NULL;
    }
    return d;
}

static PyObject *model_dict(const abrdf_model_info *m)
{
    PyObject *d = PyDict_New(), *params = PyTuple_New(m->param_count);
    if (!d || !params) goto fail;
    for (int k = 0; k < m->param_count; ++k) {
        PyObject *p = param_dict(abrdf_param_get(m->params[k].id), &m->params[k]);
        if (!p) goto fail;
        PyTuple_SET_ITEM(params, k, p);
    }
    if (abrdf_py_set(d, "id", PyLong_FromLong(m->id)) ||
        abrdf_py_set(d, "name", PyUnicode_FromString(m->name)) ||
        abrdf_py_set(d, "title", PyUnicode_FromString(m->title)) ||
        abrdf_py_set(d, "equation", PyUnicode_FromString(m->equation)) ||
        abrdf_py_set(d, "citation", PyUnicode_FromString(m->citation)) ||
        abrdf_py_set(d, "needs", needs_tuple(m->needs)) ||
        abrdf_py_set(d, "reciprocal", PyBool_FromLong(m->props & ABRDF_PROP_RECIPROCAL)) ||
        abrdf_py_set(d, "energy_conserving",
                     PyBool_FromLong(m->props & ABRDF_PROP_ENERGY_CONSERVING)) ||
        abrdf_py_set(d, "kind",
                     PyUnicode_FromString((m->props & ABRDF_PROP_DIFFUSE)    ? "diffuse"
                                          : (m->props & ABRDF_PROP_SPECULAR) ? "specular"
                                                                             : "special")) ||
        abrdf_py_set(d, "paper_cycles",
                     m->paper_cycles >= 0 ? PyLong_FromLong(m->paper_cycles) : Py_NewRef(Py_None)))
        goto fail;
    if (PyDict_SetItemString(d, "params", params)) goto fail;
    Py_DECREF(params);
    return d;
fail:
    Py_XDECREF(d);
    Py_XDECREF(params);
    return NULL;
}

static PyObject *py_models(PyObject *self, PyObject *unused)
{
    (void)self, (void)unused;
    int count = abrdf_model_count();
    PyObject *list = PyList_New(0);
    for (int i = 0; list && i < count; ++i) {
        const abrdf_model_info *m = abrdf_model_get((abrdf_model)i);
        if (!m) continue;
        PyObject *d = model_dict(m);
        if (!d || PyList_Append(list, d)) {
            Py_XDECREF(d);
            Py_DECREF(list);
            return NULL;
        }
        Py_DECREF(d);
    }
    return list;
}

static PyObject *py_params(PyObject *self, PyObject *unused)
{
    (void)self, (void)unused;
    int count = abrdf_param_count();
    PyObject *list = PyList_New(0);
    for (int i = 0; list && i < count; ++i) {
        const abrdf_param_info *p = abrdf_param_get(i);
        if (!p) continue;
        PyObject *d = param_dict(p, NULL);
        if (!d || PyList_Append(list, d)) {
            Py_XDECREF(d);
            Py_DECREF(list);
            return NULL;
        }
        Py_DECREF(d);
    }
    return list;
}

static PyObject *py_version(PyObject *self, PyObject *unused)
{
    (void)self, (void)unused;
    return PyUnicode_FromString(abrdf_version());
}

PyMethodDef abrdf_py_models_methods[] = {
    {"models", py_models, METH_NOARGS,
     "models() -> list[dict]: every registered model (abrdf_model_get) with the parameters it "
     "reads, each with this model's default and range"},
    {"params", py_params, METH_NOARGS,
     "params() -> list[dict]: every parameter of the library (abrdf_param_get) with its own "
     "default and range"},
    {"version", py_version, METH_NOARGS, "version() -> str: the library's abrdf_version()"},
    {NULL, NULL, 0, NULL}};
