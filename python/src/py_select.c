/* py_select.c - the paper's flowchart (abrdf_select, Fig. 2) from Python, with what the
 * command's `abrdf advise` reads around it, through the same code (tools/common):
 *   load_materials  the material table (data/materials.csv and user files, merged by name;
 *                   mat_table_load, with its "file:line: problem" errors)
 *   load_costs      a cost file of `abrdf calibrate` (costs_load)
 *   paper_costs     the paper's Table 4 (abrdf_costs_paper)
 *   builtin_costs   the budget mode's built-in table (abrdf_costs_builtin)
 *   select          abrdf_select on a material given as a dict, with the trace
 *   rules           the flowchart's thresholds and model choices (abrdf_select_rules_get)
 *   surfaces, goals the stable names of the surface classes and goals */
#include "abrdf_py.h" /* first: Python.h sets the feature macros */

#include <math.h>
#include <string.h>

#include "abrdf_fit.h"
#include "cost_file.h"
#include "materials.h"
#include "select_trace.h"

static PyObject *model_name_or_none(abrdf_model m)
{
    const abrdf_model_info *info = abrdf_model_get(m);
    return info ? PyUnicode_FromString(info->name) : Py_NewRef(Py_None);
}

static PyObject *layer_dict(const abrdf_layer *l)
{
    PyObject *d = PyDict_New();
    if (!d) return NULL;
    if (abrdf_py_set(d, "eta", PyFloat_FromDouble(l->eta)) ||
        abrdf_py_set(d, "kappa", PyFloat_FromDouble(l->kappa)) ||
        abrdf_py_set(d, "r", PyFloat_FromDouble(l->r)) ||
        abrdf_py_set(d, "sigma_a", abrdf_py_rgb(l->sigma_a)) ||
        abrdf_py_set(d, "depth", PyFloat_FromDouble(l->depth))) {
        Py_DECREF(d);
        return NULL;
    }
    return d;
}

static PyObject *layers_tuple(const abrdf_layer *layers, int count)
{
    PyObject *t = PyTuple_New(count);
    for (int k = 0; t && k < count; ++k) {
        PyObject *d = layer_dict(&layers[k]);
        if (!d) {
            Py_DECREF(t);
            return NULL;
        }
        PyTuple_SET_ITEM(t, k, d);
    }
    return t;
}

PyObject *abrdf_py_material_dict(const abrdf_material *m)
{
    PyObject *d = PyDict_New();
    if (!d) return NULL;
    if (abrdf_py_set(d, "name", m->name ? PyUnicode_FromString(m->name) : Py_NewRef(Py_None)) ||
        abrdf_py_set(d, "type", PyUnicode_FromString(abrdf_surface_name(m->type))) ||
        abrdf_py_set(d, "n", abrdf_py_opt(m->n)) || abrdf_py_set(d, "r", abrdf_py_opt(m->r)) ||
        abrdf_py_set(d, "kd", abrdf_py_rgb(m->kd)) || abrdf_py_set(d, "ks", abrdf_py_rgb(m->ks)) ||
        abrdf_py_set(d, "f0", abrdf_py_rgb(m->f0)) ||
        abrdf_py_set(d, "eta", abrdf_py_opt(m->eta > 0.0 ? m->eta : -1.0)) ||
        abrdf_py_set(d, "anisotropy", PyFloat_FromDouble(m->anisotropy)) ||
        abrdf_py_set(d, "melanin", PyFloat_FromDouble(m->melanin)) ||
        abrdf_py_set(d, "redness", PyFloat_FromDouble(m->redness)) ||
        abrdf_py_set(d, "layers", layers_tuple(m->layers, m->layer_count))) {
        Py_DECREF(d);
        return NULL;
    }
    return d;
}

/* A table entry as the fields of abrdf.Material. */
static PyObject *entry_dict(const mat_entry *e)
{
    PyObject *d = abrdf_py_material_dict(&e->m);
    if (!d) return NULL;
    if (abrdf_py_set(d, "name", PyUnicode_FromString(e->name)) ||
        abrdf_py_set(d, "source", PyUnicode_FromString(e->source)) ||
        abrdf_py_set(d, "file", PyUnicode_FromString(e->file)) ||
        abrdf_py_set(d, "line", PyLong_FromLong(e->line))) {
        Py_DECREF(d);
        return NULL;
    }
    return d;
}

static PyObject *py_load_materials(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *paths;
    if (!PyArg_ParseTuple(args, "O!:load_materials", &PyList_Type, &paths)) return NULL;
    mat_table t = {NULL, 0, 0};
    char err[MAT_ERR_MAX];
    for (Py_ssize_t i = 0; i < PyList_GET_SIZE(paths); ++i) {
        PyObject *bytes;
        if (!PyUnicode_FSConverter(PyList_GET_ITEM(paths, i), &bytes)) {
            mat_table_free(&t);
            return NULL;
        }
        int rc = mat_table_load(&t, PyBytes_AS_STRING(bytes), err, sizeof err);
        Py_DECREF(bytes);
        if (rc) {
            mat_table_free(&t);
            return abrdf_py_fail(ABRDF_E_TABLE, "%s", err);
        }
    }
    PyObject *list = PyList_New(t.count);
    for (int i = 0; list && i < t.count; ++i) {
        PyObject *d = entry_dict(&t.items[i]);
        if (!d) {
            Py_CLEAR(list);
            break;
        }
        PyList_SET_ITEM(list, i, d);
    }
    mat_table_free(&t);
    return list;
}

/* {"unit": ..., "unit_ns": float | None, "costs": {model: cost}} of a cost table. */
static PyObject *costs_dict(const abrdf_costs *c, double unit_ns)
{
    PyObject *d = PyDict_New(), *costs = PyDict_New();
    if (!d || !costs) goto fail;
    for (int i = 0; i < abrdf_model_count(); ++i) {
        double v = abrdf_costs_get(c, (abrdf_model)i);
        const abrdf_model_info *m = abrdf_model_get((abrdf_model)i);
        if (m && v >= 0.0 && abrdf_py_set(costs, m->name, PyFloat_FromDouble(v))) goto fail;
    }
    if (abrdf_py_set(d, "unit", PyUnicode_FromString(c->unit ? c->unit : "")) ||
        abrdf_py_set(d, "unit_ns", abrdf_py_opt(unit_ns)))
        goto fail;
    if (PyDict_SetItemString(d, "costs", costs)) goto fail;
    Py_DECREF(costs);
    return d;
fail:
    Py_XDECREF(d);
    Py_XDECREF(costs);
    return NULL;
}

static PyObject *py_load_costs(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *bytes;
    if (!PyArg_ParseTuple(args, "O&:load_costs", PyUnicode_FSConverter, &bytes)) return NULL;
    abrdf_costs c;
    double unit_ns;
    char err[512];
    int rc = costs_load(PyBytes_AS_STRING(bytes), &c, &unit_ns, err, sizeof err);
    Py_DECREF(bytes);
    if (rc) return abrdf_py_fail(ABRDF_E_TABLE, "%s", err);
    return costs_dict(&c, unit_ns);
}

static PyObject *py_paper_costs(PyObject *self, PyObject *unused)
{
    (void)self, (void)unused;
    abrdf_costs c;
    abrdf_costs_paper(&c);
    return costs_dict(&c, -1.0);
}

static PyObject *py_builtin_costs(PyObject *self, PyObject *unused)
{
    (void)self, (void)unused;
    abrdf_costs c;
    int st = abrdf_costs_builtin(&c);
    if (st != ABRDF_OK) return abrdf_py_fail(st, "abrdf_costs_builtin: %s", abrdf_strerror(st));
    return costs_dict(&c, -1.0);
}

/* ---- the material and the costs from Python ------------------------------------------ */

/* A number from d[key] into *out; absent keeps *out, None gives `none`. */
static int get_number(PyObject *d, const char *key, double none, double *out)
{
    PyObject *v = PyDict_GetItemString(d, key);
    if (!v) return 0;
    if (v == Py_None) {
        *out = none;
        return 0;
    }
    return abrdf_py_real_number(v, key, out);
}

static int get_rgb(PyObject *d, const char *key, double out[3])
{
    PyObject *v = PyDict_GetItemString(d, key);
    if (!v) return 0;
    if (!PySequence_Check(v) || PyUnicode_Check(v) || PyBytes_Check(v) || PyByteArray_Check(v)) {
        if (abrdf_py_real_number(v, key, &out[0])) return -1;
        out[1] = out[2] = out[0];
        return 0;
    }
    PyObject *seq = PySequence_Fast(v, "a colour is a number or 3 numbers");
    if (!seq) return -1;
    int rc = 0;
    if (PySequence_Fast_GET_SIZE(seq) != 3) {
        PyErr_Format(PyExc_ValueError, "%s: a colour needs 3 numbers (R, G, B)", key);
        rc = -1;
    }
    for (int c = 0; !rc && c < 3; ++c)
        rc = abrdf_py_real_number(PySequence_Fast_GET_ITEM(seq, c), key, &out[c]);
    Py_DECREF(seq);
    return rc;
}

static const char *const material_keys[] = {
    "name",       "type",    "n",       "r",      "kd",     "ks",   "f0",   "eta",
    "anisotropy", "melanin", "redness", "layers", "source", "file", "line", NULL};
static const char *const layer_keys[] = {"eta", "kappa", "r", "sigma_a", "depth", NULL};

static int known_keys(PyObject *d, const char *const *keys, const char *what)
{
    PyObject *key, *value;
    Py_ssize_t pos = 0;
    while (PyDict_Next(d, &pos, &key, &value)) {
        const char *k = PyUnicode_Check(key) ? PyUnicode_AsUTF8(key) : NULL;
        int found = 0;
        for (int i = 0; k && keys[i]; ++i) found |= !strcmp(k, keys[i]);
        if (!found) {
            PyErr_Format(PyExc_TypeError, "%s: unknown field %R", what, key);
            return -1;
        }
    }
    return 0;
}

static int get_layers(PyObject *d, abrdf_material *m)
{
    PyObject *v = PyDict_GetItemString(d, "layers");
    if (!v) return 0;
    PyObject *seq = PySequence_Fast(v, "layers: a sequence of dicts");
    if (!seq) return -1;
    Py_ssize_t n = PySequence_Fast_GET_SIZE(seq);
    int rc = 0;
    if (n > ABRDF_MAX_LAYERS) {
        abrdf_py_fail(ABRDF_E_RANGE, "layers: %zd given, at most %d", n, ABRDF_MAX_LAYERS);
        rc = -1;
    }
    for (Py_ssize_t k = 0; !rc && k < n; ++k) {
        PyObject *l = PySequence_Fast_GET_ITEM(seq, k);
        abrdf_layer *out = &m->layers[k];
        if (!PyDict_Check(l)) {
            PyErr_Format(PyExc_TypeError, "layers[%zd]: a dict is needed", k);
            rc = -1;
        } else if (known_keys(l, layer_keys, "layer") || get_number(l, "eta", 1.0, &out->eta) ||
                   get_number(l, "kappa", 0.0, &out->kappa) || get_number(l, "r", 0.0, &out->r) ||
                   get_rgb(l, "sigma_a", out->sigma_a) ||
                   get_number(l, "depth", 0.0, &out->depth)) {
            rc = -1;
        }
    }
    if (!rc) m->layer_count = (int)n;
    Py_DECREF(seq);
    return rc;
}

/* m from a dict of abrdf.Material's fields; absent fields keep abrdf_material_init's. */
int abrdf_py_material_from(PyObject *d, abrdf_material *m, PyObject **name_ref)
{
    abrdf_material_init(m);
    if (known_keys(d, material_keys, "material")) return -1;
    PyObject *name = PyDict_GetItemString(d, "name");
    if (name && name != Py_None) {
        if (!(m->name = PyUnicode_AsUTF8(name))) return -1;
        *name_ref = name;
    }
    PyObject *type = PyDict_GetItemString(d, "type");
    if (type && type != Py_None) {
        const char *t = PyUnicode_AsUTF8(type);
        if (!t) return -1;
        if (abrdf_surface_find(t, &m->type) != ABRDF_OK) {
            abrdf_py_fail(ABRDF_E_RANGE,
                          "unknown surface type '%s' (general, cloth_rough, cloth_shiny, hair, "
                          "layered_plastic, layered_plate, layered_metal)",
                          t);
            return -1;
        }
    }
    if (get_number(d, "n", -1.0, &m->n) || get_number(d, "r", -1.0, &m->r) ||
        get_rgb(d, "kd", m->kd) || get_rgb(d, "ks", m->ks) || get_rgb(d, "f0", m->f0) ||
        get_number(d, "eta", -1.0, &m->eta) || get_number(d, "anisotropy", 0.0, &m->anisotropy) ||
        get_number(d, "melanin", 0.3, &m->melanin) || get_number(d, "redness", 0.0, &m->redness) ||
        get_layers(d, m))
        return -1;
    return 0;
}

/* costs: None (the paper's Table 4) or {model name: cost}, in `unit`. */
int abrdf_py_costs_from(PyObject *costs, const char *unit, abrdf_costs *c)
{
    abrdf_costs_init(c, unit ? unit : "");
    PyObject *key, *value;
    Py_ssize_t pos = 0;
    while (PyDict_Next(costs, &pos, &key, &value)) {
        const char *name = PyUnicode_AsUTF8(key);
        abrdf_model model;
        if (!name || abrdf_py_model_find(name, &model)) return -1;
        double v;
        if (abrdf_py_real_number(value, name, &v)) return -1;
        int st = abrdf_costs_set(c, model, v);
        if (st != ABRDF_OK) {
            abrdf_py_fail(st, "costs: %s = %g: %s", name, v, abrdf_strerror(st));
            return -1;
        }
    }
    return 0;
}

/* The material dict and the optional costs dict of select and select_budget. */
int abrdf_py_material_costs_from(PyObject *mat, PyObject *costs, const char *unit,
                                 abrdf_material *m, abrdf_costs *c, PyObject **name_ref)
{
    *name_ref = NULL;
    if (abrdf_py_material_from(mat, m, name_ref)) return -1;
    Py_XINCREF(*name_ref); /* m->name points into it */
    if (costs != Py_None && (!PyDict_Check(costs) || abrdf_py_costs_from(costs, unit, c))) {
        if (!PyErr_Occurred())
            PyErr_SetString(PyExc_TypeError, "costs: None or a dict {model: cost}");
        Py_XDECREF(*name_ref);
        *name_ref = NULL;
        return -1;
    }
    return 0;
}

/* ---- select ---------------------------------------------------------------------------- */

/* The values of every parameter the lobes of a budget candidate read, from its fitted block
 * (None for the flowchart's steps). */
static PyObject *fitted_values(const abrdf_select_step *s)
{
    if (!s->params) return Py_NewRef(Py_None);
    PyObject *d = PyDict_New();
    abrdf_model lobes[2] = {s->diffuse, s->model};
    for (int l = 0; d && l < 2; ++l) {
        const abrdf_model_info *mi = abrdf_model_get(lobes[l]);
        for (int k = 0; mi && k < mi->param_count; ++k) {
            int id = mi->params[k].id;
            const abrdf_param_info *pi = abrdf_param_get(id);
            if (pi && abrdf_py_set(d, pi->name, abrdf_py_param_value(s->params, id))) {
                Py_CLEAR(d);
                break;
            }
        }
    }
    return d;
}

static PyObject *step_dict(const abrdf_select_step *s)
{
    PyObject *d = PyDict_New();
    if (!d) return NULL;
    if (abrdf_py_set(d, "kind", PyUnicode_FromString(abrdf_step_name(s->kind))) ||
        abrdf_py_set(d, "model", model_name_or_none(s->model)) ||
        abrdf_py_set(d, "diffuse", model_name_or_none(s->diffuse)) ||
        abrdf_py_set(d, "params", fitted_values(s)) ||
        abrdf_py_set(d, "value", abrdf_py_opt(s->value)) ||
        abrdf_py_set(d, "threshold", abrdf_py_opt(s->threshold)) ||
        abrdf_py_set(d, "value2", abrdf_py_opt(s->value2)) ||
        abrdf_py_set(d, "threshold2", abrdf_py_opt(s->threshold2)) ||
        abrdf_py_set(d, "cost", abrdf_py_opt(s->cost)) ||
        abrdf_py_set(d, "passed", PyBool_FromLong(s->passed)) ||
        abrdf_py_set(d, "text", PyUnicode_FromString(s->text ? s->text : ""))) {
        Py_DECREF(d);
        return NULL;
    }
    return d;
}

PyObject *abrdf_py_selection_dict(const abrdf_selection *s, const abrdf_params *p,
                                  const select_trace *trace)
{
    PyObject *d = PyDict_New(), *steps = PyList_New(trace->count);
    if (!d || !steps) goto fail;
    for (int i = 0; i < trace->count; ++i) {
        PyObject *step = step_dict(&trace->steps[i]);
        if (!step) goto fail;
        PyList_SET_ITEM(steps, i, step);
    }
    PyObject *diffuse = s->diffuse == ABRDF_MODEL_NONE ? Py_NewRef(Py_None)
                                                       : abrdf_py_params_from_block(s->diffuse, p);
    if (!diffuse || abrdf_py_set(d, "diffuse_params", diffuse) ||
        abrdf_py_set(d, "specular_params", abrdf_py_params_from_block(s->specular, p)) ||
        abrdf_py_set(d, "goal", PyUnicode_FromString(abrdf_goal_name(s->goal))) ||
        abrdf_py_set(d, "type", PyUnicode_FromString(abrdf_surface_name(s->type))) ||
        abrdf_py_set(d, "diffuse", model_name_or_none(s->diffuse)) ||
        abrdf_py_set(d, "specular", model_name_or_none(s->specular)) ||
        abrdf_py_set(d, "n", PyFloat_FromDouble(s->n)) ||
        abrdf_py_set(d, "r", PyFloat_FromDouble(s->r)) ||
        abrdf_py_set(d, "error_rel_pct", abrdf_py_opt(s->err_rel_pct)) ||
        abrdf_py_set(d, "error_abs", abrdf_py_opt(s->err_abs)) ||
        abrdf_py_set(d, "error_nmse", abrdf_py_opt(s->err_nmse)) ||
        abrdf_py_set(d, "cost_diffuse", abrdf_py_opt(s->cost_diffuse)) ||
        abrdf_py_set(d, "cost_specular", abrdf_py_opt(s->cost_specular)) ||
        abrdf_py_set(d, "cost_total", abrdf_py_opt(s->cost_total)) ||
        abrdf_py_set(d, "cost_unit", PyUnicode_FromString(s->cost_unit ? s->cost_unit : "")))
        goto fail;
    if (PyDict_SetItemString(d, "trace", steps)) goto fail;
    Py_DECREF(steps);
    return d;
fail:
    Py_XDECREF(d);
    Py_XDECREF(steps);
    return NULL;
}

static PyObject *py_select(PyObject *self, PyObject *args, PyObject *kwargs)
{
    (void)self;
    static char *kw[] = {"material", "goal", "max_rel_pct", "max_abs", "costs", "cost_unit", NULL};
    PyObject *mat, *costs = Py_None;
    const char *goal_name, *unit = NULL;
    abrdf_tolerance tol;
    abrdf_tolerance_init(&tol);
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "O!s|ddOz:select", kw, &PyDict_Type, &mat,
                                     &goal_name, &tol.max_rel_pct, &tol.max_abs, &costs, &unit))
        return NULL;
    abrdf_goal goal;
    if (abrdf_goal_find(goal_name, &goal) != ABRDF_OK)
        return abrdf_py_fail(ABRDF_E_RANGE, "unknown goal '%s' (performance or photoreal)",
                             goal_name);
    abrdf_material m;
    abrdf_costs c;
    PyObject *name_ref;
    if (abrdf_py_material_costs_from(mat, costs, unit, &m, &c, &name_ref)) return NULL;
    abrdf_selection s;
    abrdf_params p;
    select_trace trace = SELECT_TRACE_INIT;
    abrdf_selection_init(&s);
    abrdf_params_init(ABRDF_MODEL_NONE, &p);
    int st;
    Py_BEGIN_ALLOW_THREADS;
    st = abrdf_select(&m, goal, &tol, costs == Py_None ? NULL : &c, &s, &p, select_trace_keep,
                      &trace);
    Py_END_ALLOW_THREADS;
    PyObject *out = NULL;
    if (st != ABRDF_OK)
        abrdf_py_fail(st, "%s", s.message);
    else if (trace.lost)
        PyErr_NoMemory();
    else
        out = abrdf_py_selection_dict(&s, &p, &trace);
    select_trace_free(&trace);
    Py_XDECREF(name_ref);
    return out;
}

static PyObject *py_rules(PyObject *self, PyObject *unused)
{
    (void)self, (void)unused;
    const abrdf_select_rules *R = abrdf_select_rules_get();
    PyObject *d = PyDict_New(), *cands = PyTuple_New(R->candidate_count);
    if (!d || !cands) goto fail;
    for (int i = 0; i < R->candidate_count; ++i) {
        PyObject *name = model_name_or_none(R->candidates[i]);
        if (!name) goto fail;
        PyTuple_SET_ITEM(cands, i, name);
    }
    if (abrdf_py_set(d, "smooth_r_max", PyFloat_FromDouble(R->smooth_r_max)) ||
        abrdf_py_set(d, "aniso_min", PyFloat_FromDouble(R->aniso_min)) ||
        abrdf_py_set(d, "default_max_rel_pct", PyFloat_FromDouble(R->default_max_rel_pct)) ||
        abrdf_py_set(d, "default_max_abs", PyFloat_FromDouble(R->default_max_abs)) ||
        abrdf_py_set(d, "perf_diffuse", model_name_or_none(R->perf_diffuse)) ||
        abrdf_py_set(d, "perf_fallback", model_name_or_none(R->perf_fallback)) ||
        abrdf_py_set(d, "nmse_class_max",
                     Py_BuildValue("(ddd)", R->nmse_class_max[0], R->nmse_class_max[1],
                                   R->nmse_class_max[2])))
        goto fail;
    if (PyDict_SetItemString(d, "candidates", cands)) goto fail;
    Py_DECREF(cands);
    return d;
fail:
    Py_XDECREF(d);
    Py_XDECREF(cands);
    return NULL;
}

/* The stable names of an enum's values, in order, from its name function (NULL ends it). */
static PyObject *names(const char *(*name)(int))
{
    PyObject *list = PyList_New(0);
    for (int i = 0; list && name(i); ++i) {
        PyObject *s = PyUnicode_FromString(name(i));
        if (!s || PyList_Append(list, s)) Py_CLEAR(list);
        Py_XDECREF(s);
    }
    return list;
}

static const char *surface_name(int i) { return abrdf_surface_name((abrdf_surface)i); }
static const char *goal_name(int i) { return abrdf_goal_name((abrdf_goal)i); }

static PyObject *py_surfaces(PyObject *self, PyObject *unused)
{
    (void)self, (void)unused;
    return names(surface_name);
}

static PyObject *py_goals(PyObject *self, PyObject *unused)
{
    (void)self, (void)unused;
    return names(goal_name);
}

PyMethodDef abrdf_py_select_methods[] = {
    {"load_materials", py_load_materials, METH_VARARGS,
     "load_materials(paths: list[str]) -> list[dict]: the material files in order, later "
     "names replacing earlier ones (mat_table_load); abrdf.Error 'file:line: problem'"},
    {"load_costs", py_load_costs, METH_VARARGS,
     "load_costs(path) -> dict: a cost file of `abrdf calibrate` (unit, unit_ns, costs)"},
    {"paper_costs", py_paper_costs, METH_NOARGS,
     "paper_costs() -> dict: the paper's Table 4 cycle counts (unit, unit_ns None, costs)"},
    {"builtin_costs", py_builtin_costs, METH_NOARGS,
     "builtin_costs() -> dict: the built-in table of measured costs the budget mode uses "
     "(abrdf_costs_builtin: unit, unit_ns None, costs)"},
    {"select", (PyCFunction)(void (*)(void))py_select, METH_VARARGS | METH_KEYWORDS,
     "select(material, goal, max_rel_pct=2, max_abs=0.05, costs=None, cost_unit=None) -> dict: "
     "abrdf_select on a material dict (abrdf.Material's fields), with the trace. Releases the "
     "GIL."},
    {"surfaces", py_surfaces, METH_NOARGS,
     "surfaces() -> list[str]: the surface classes of the flowchart (abrdf_surface_name)"},
    {"goals", py_goals, METH_NOARGS, "goals() -> list[str]: the goals (abrdf_goal_name)"},
    {"rules", py_rules, METH_NOARGS,
     "rules() -> dict: the flowchart's thresholds and model choices (abrdf_select_rules_get)"},
    {NULL, NULL, 0, NULL}};
