/* py_fit.c - one model fitted to another and the selection's budget mode (abrdf_fit.h) from
 * Python, through the code `abrdf fit` and `abrdf advise --budget` use:
 *   fit            abrdf_fit of a candidate (one model or a diffuse + specular pair) to a
 *                  reference given as Params, with its errors and predicted image NMSE
 *   fit_to         abrdf_fit_to: the same against a prepared reference, a measured Table
 *                  (or a Params, prepared here)
 *   select_budget  abrdf_select_budget (budget_run, tools/common) on a material dict, with
 *                  the trace (every fitted candidate)
 *   budget_class   a Table-8 class name -> its largest NMSE (abrdf_budget_class_find) */
#include "abrdf_py.h" /* first: Python.h sets the feature macros */

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "abrdf_fit.h"
#include "budget_run.h"

/* NULL or "" -> ABRDF_MODEL_NONE, else the model of that name (abrdf.Error if unknown). */
static int model_or_none(const char *name, abrdf_model *out)
{
    if (!name || !name[0]) {
        *out = ABRDF_MODEL_NONE;
        return 0;
    }
    return abrdf_py_model_find(name, out);
}

/* The reference block: the specular lobe's Params, with every parameter the diffuse lobe
 * reads taken from the diffuse lobe's Params (a Selection's two blocks are one). */
static int reference_block(const abrdf_py_params *d, const abrdf_py_params *s, abrdf_params *out)
{
    *out = s ? s->params : d->params;
    if (!d || !s) return 0;
    const abrdf_model_info *mi = abrdf_model_get(d->model);
    for (int k = 0; mi && k < mi->param_count; ++k) {
        double v[3];
        int n = abrdf_param_read(&d->params, mi->params[k].id, v);
        if (n > 0 && abrdf_param_set(out, mi->params[k].id, v, n) != ABRDF_OK) {
            abrdf_py_fail(ABRDF_E_RANGE, "reference: parameter id %d cannot be merged",
                          mi->params[k].id);
            return -1;
        }
    }
    return 0;
}

static PyObject *lobe_params(abrdf_model m, const abrdf_params *p)
{
    return m == ABRDF_MODEL_NONE ? Py_NewRef(Py_None) : abrdf_py_params_from_block(m, p);
}

/* The options of a fit from fit()'s arguments and the candidate's lobes: 0, or -1 with
 * abrdf.Error (an unknown model or metric). */
static int fit_setup(const char *cd_name, const char *cs_name, const char *metric_name,
                     int resolution, int keep_shared, int predict, abrdf_model *cd, abrdf_model *cs,
                     abrdf_fit_options *opt)
{
    if (model_or_none(cd_name, cd) || model_or_none(cs_name, cs)) return -1;
    abrdf_fit_options_init(opt);
    if (abrdf_fit_metric_find(metric_name, &opt->metric) != ABRDF_OK) {
        abrdf_py_fail(ABRDF_E_RANGE, "fit: unknown metric '%s' (l2, log, cbrt, auto)", metric_name);
        return -1;
    }
    opt->resolution = resolution;
    opt->keep_shared = keep_shared;
    opt->predict = predict;
    return 0;
}

/* A workspace for opt (PyMem_RawFree it), or NULL with the exception set. */
static void *fit_workspace(const abrdf_fit_options *opt, size_t *size)
{
    *size = abrdf_fit_workspace_size(opt, NULL);
    if (!*size) {
        abrdf_py_fail(ABRDF_E_RANGE, "fit: resolution %d is outside [0, 5]", opt->resolution);
        return NULL;
    }
    void *work = PyMem_RawMalloc(*size);
    if (!work) PyErr_NoMemory();
    return work;
}

/* The dict fit() returns: the fitted Params per lobe and the errors. */
static PyObject *fit_dict(abrdf_model cd, abrdf_model cs, const abrdf_params *cand,
                          const abrdf_fit_result *res)
{
    PyObject *out = PyDict_New();
    if (!out) return NULL;
    if (abrdf_py_set(out, "diffuse_params", lobe_params(cd, cand)) ||
        abrdf_py_set(out, "specular_params", lobe_params(cs, cand)) ||
        abrdf_py_set(out, "rel_l2", PyFloat_FromDouble(res->rel_l2)) ||
        abrdf_py_set(out, "max_rel_pct", PyFloat_FromDouble(res->max_rel_pct)) ||
        abrdf_py_set(out, "max_abs", PyFloat_FromDouble(res->max_abs)) ||
        abrdf_py_set(out, "nmse_pred", abrdf_py_opt(res->nmse_pred)) ||
        abrdf_py_set(out, "objective", PyFloat_FromDouble(res->objective)) ||
        abrdf_py_set(out, "metric", PyUnicode_FromString(abrdf_fit_metric_name(res->metric))) ||
        abrdf_py_set(out, "fitted", PyLong_FromLong(res->fitted)) ||
        abrdf_py_set(out, "evals", PyLong_FromLong(res->evals)) ||
        abrdf_py_set(out, "directions", PyLong_FromLong(res->directions))) {
        Py_DECREF(out);
        return NULL;
    }
    return out;
}

static PyObject *py_fit(PyObject *self, PyObject *args, PyObject *kwargs)
{
    (void)self;
    static char *kw[] = {"ref_diffuse",   "ref_specular", "cand_diffuse",
                         "cand_specular", "metric",       "resolution",
                         "keep_shared",   "predict",      NULL};
    PyObject *rd = Py_None, *rs = Py_None;
    const char *cd_name = NULL, *cs_name = NULL, *metric_name = "l2";
    int resolution = 0, keep_shared = 1, predict = 1;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "OOzz|sipp:fit", kw, &rd, &rs, &cd_name,
                                     &cs_name, &metric_name, &resolution, &keep_shared, &predict))
        return NULL;
    const abrdf_py_params *d = NULL, *s = NULL;
    if (rd != Py_None && !(d = abrdf_py_params_arg(rd, "ref_diffuse"))) return NULL;
    if (rs != Py_None && !(s = abrdf_py_params_arg(rs, "ref_specular"))) return NULL;
    if (!d && !s) return abrdf_py_fail(ABRDF_E_MODEL, "fit: the reference has no lobe");
    abrdf_model cd, cs;
    abrdf_fit_options opt;
    if (fit_setup(cd_name, cs_name, metric_name, resolution, keep_shared, predict, &cd, &cs, &opt))
        return NULL;
    abrdf_params ref, cand;
    if (reference_block(d, s, &ref)) return NULL;
    abrdf_params_init(cs != ABRDF_MODEL_NONE ? cs : cd, &cand);
    abrdf_fit_result res;
    abrdf_fit_result_init(&res);
    size_t ws;
    void *work = fit_workspace(&opt, &ws);
    if (!work) return NULL;
    int st;
    Py_BEGIN_ALLOW_THREADS;
    st = abrdf_fit(d ? d->model : ABRDF_MODEL_NONE, s ? s->model : ABRDF_MODEL_NONE, &ref, cd, cs,
                   &cand, &opt, &res, work, ws);
    Py_END_ALLOW_THREADS;
    PyMem_RawFree(work);
    if (st != ABRDF_OK) return abrdf_py_fail(st, "%s", res.message);
    return fit_dict(cd, cs, &cand, &res);
}

static PyObject *py_fit_to(PyObject *self, PyObject *args, PyObject *kwargs)
{
    (void)self;
    static char *kw[] = {"reference",  "cand_diffuse", "cand_specular", "metric",
                         "resolution", "keep_shared",  "predict",       NULL};
    PyObject *reference;
    const char *cd_name = NULL, *cs_name = NULL, *metric_name = "l2";
    int resolution = 0, keep_shared = 1, predict = 1;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "Ozz|sipp:fit_to", kw, &reference, &cd_name,
                                     &cs_name, &metric_name, &resolution, &keep_shared, &predict))
        return NULL;
    /* A Table's prepared object points at the Table's buffer; `reference` is held by the
     * arguments for the whole call. */
    abrdf_prepared ref;
    if (abrdf_py_prepared_arg(reference, "reference", &ref)) return NULL;
    abrdf_model cd, cs;
    abrdf_fit_options opt;
    if (fit_setup(cd_name, cs_name, metric_name, resolution, keep_shared, predict, &cd, &cs, &opt))
        return NULL;
    abrdf_params cand;
    abrdf_params_init(cs != ABRDF_MODEL_NONE ? cs : cd, &cand);
    abrdf_fit_result res;
    abrdf_fit_result_init(&res);
    size_t ws;
    void *work = fit_workspace(&opt, &ws);
    if (!work) return NULL;
    int st;
    Py_BEGIN_ALLOW_THREADS;
    st = abrdf_fit_to(&ref, cd, cs, &cand, &opt, &res, work, ws);
    Py_END_ALLOW_THREADS;
    PyMem_RawFree(work);
    if (st != ABRDF_OK) return abrdf_py_fail(st, "%s", res.message);
    return fit_dict(cd, cs, &cand, &res);
}

static PyObject *py_budget_class(PyObject *self, PyObject *args)
{
    (void)self;
    const char *name;
    if (!PyArg_ParseTuple(args, "s:budget_class", &name)) return NULL;
    double v;
    if (abrdf_budget_class_find(name, &v) != ABRDF_OK)
        return abrdf_py_fail(ABRDF_E_RANGE,
                             "unknown budget class '%s' (none, slight, noticeable or a number "
                             "in (0, 1])",
                             name);
    return PyFloat_FromDouble(v);
}

static PyObject *py_select_budget(PyObject *self, PyObject *args, PyObject *kwargs)
{
    (void)self;
    static char *kw[] = {"material",  "max_nmse",       "costs", "cost_unit",
                         "reference", "reference_cost", NULL};
    PyObject *mat, *costs = Py_None, *reference = Py_None;
    const char *unit = NULL;
    double max_nmse, reference_cost = -1.0;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "O!d|OzOd:select_budget", kw, &PyDict_Type, &mat,
                                     &max_nmse, &costs, &unit, &reference, &reference_cost))
        return NULL;
    abrdf_prepared ref;
    if (reference != Py_None) {
        if (!PyObject_TypeCheck(reference, &abrdf_py_table_type)) {
            PyErr_Format(PyExc_TypeError,
                         "select_budget: reference must be a Table (huang_table) or None, not "
                         "%.100s",
                         Py_TYPE(reference)->tp_name);
            return NULL;
        }
        ref = ((const abrdf_py_table *)reference)->prepared; /* plain data: a copy is valid */
    }
    abrdf_material m;
    abrdf_costs c;
    PyObject *name_ref;
    if (abrdf_py_material_costs_from(mat, costs, unit, &m, &c, &name_ref)) return NULL;
    budget_result r;
    char err[512];
    int rc;
    Py_BEGIN_ALLOW_THREADS;
    rc = budget_run_to(&m, max_nmse, 0, costs == Py_None ? NULL : &c, NULL,
                       reference == Py_None ? NULL : &ref, reference_cost, &r, err, sizeof err);
    Py_END_ALLOW_THREADS;
    Py_XDECREF(name_ref);
    if (rc) return abrdf_py_fail(ABRDF_E_RANGE, "%s", err);
    PyObject *out =
        r.trace.lost ? PyErr_NoMemory() : abrdf_py_selection_dict(&r.sel, &r.params, &r.trace);
    budget_result_free(&r);
    return out;
}

/* prepared_cost(prepared, params, costs=None, cost_unit=None) -> float: budget_prepared_cost of
 * a Table (huang_table) whose model's block is params. */
static PyObject *py_prepared_cost(PyObject *self, PyObject *args, PyObject *kwargs)
{
    (void)self;
    static char *kw[] = {"prepared", "params", "costs", "cost_unit", NULL};
    PyObject *prepared, *params, *costs = Py_None;
    const char *unit = NULL;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "O!O|Oz:prepared_cost", kw, &abrdf_py_table_type,
                                     &prepared, &params, &costs, &unit))
        return NULL;
    const abrdf_py_params *p = abrdf_py_params_arg(params, "prepared_cost");
    if (!p) return NULL;
    if (((const abrdf_py_table *)prepared)->sets == 0 || p->model != ABRDF_HUANG)
        return abrdf_py_fail(ABRDF_E_MODEL, "prepared_cost: a huang_table Table and its huang "
                                            "Params are needed");
    abrdf_costs c;
    if (costs != Py_None && abrdf_py_costs_from(costs, unit, &c)) return NULL;
    abrdf_prepared obj = ((const abrdf_py_table *)prepared)->prepared;
    abrdf_params block = p->params;
    double v;
    Py_BEGIN_ALLOW_THREADS;
    v = budget_prepared_cost(&obj, p->model, &block, costs == Py_None ? NULL : &c);
    Py_END_ALLOW_THREADS;
    return PyFloat_FromDouble(v);
}

PyMethodDef abrdf_py_fit_methods[] = {
    {"fit", (PyCFunction)(void (*)(void))py_fit, METH_VARARGS | METH_KEYWORDS,
     "fit(ref_diffuse, ref_specular, cand_diffuse, cand_specular, metric='l2', resolution=0, "
     "keep_shared=True, predict=True) -> dict: abrdf_fit of the candidate models (names or "
     "None) to the reference (Params or None; one block, the diffuse lobe's parameters from "
     "its Params): the fitted Params per lobe and the errors. Releases the GIL."},
    {"fit_to", (PyCFunction)(void (*)(void))py_fit_to, METH_VARARGS | METH_KEYWORDS,
     "fit_to(reference, cand_diffuse, cand_specular, metric='l2', resolution=0, "
     "keep_shared=True, predict=True) -> dict: abrdf_fit_to of the candidate models (names or "
     "None) to a prepared reference: a Table (a measured table) or a Params; fit()'s dict. "
     "Releases the GIL."},
    {"select_budget", (PyCFunction)(void (*)(void))py_select_budget, METH_VARARGS | METH_KEYWORDS,
     "select_budget(material, max_nmse, costs=None, cost_unit=None, reference=None, "
     "reference_cost=-1) -> dict: abrdf_select_budget on a material dict (abrdf.Material's "
     "fields), with the trace; costs None: the built-in table; reference: a Table of the "
     "photoreal choice (huang_table; abrdf_budget.reference) at reference_cost (< 0: unknown). "
     "Releases the GIL."},
    {"prepared_cost", (PyCFunction)(void (*)(void))py_prepared_cost, METH_VARARGS | METH_KEYWORDS,
     "prepared_cost(prepared, params, costs=None, cost_unit=None) -> float: the cost of one "
     "evaluation of a huang_table Table made from params (huang's), in the unit of costs "
     "(None: the built-in table): huang's entry times the Table's time over the per-call "
     "quadrature's, both timed now; < 0 if it cannot be timed. Releases the GIL."},
    {"budget_class", py_budget_class, METH_VARARGS,
     "budget_class(name) -> float: the largest NMSE of a Table-8 class (none, slight, "
     "noticeable)"},
    {NULL, NULL, 0, NULL}};
