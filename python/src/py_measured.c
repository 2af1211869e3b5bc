/* py_measured.c - models read from tables, from Python:
 *   Table          the library's `measured` model prepared once (abrdf_prepare_measured) on
 *                  a float32 buffer the object holds for as long as it lives (docs/MEASURED.md),
 *                  or huang prepared on its table (huang_table): the evaluation functions take
 *                  a Table wherever they take a Params
 *   read_measured  a MERL .binary or RGL .bsdf file through the readers `abrdf inspect` uses
 *                  (tools/measured: the format by the extension, then its reader)
 *   huang_table_size, huang_table_build, huang_table   huang tabulated (abrdf.h, "huang
 *                  tabulated"): its size, rows of it built into a float64 buffer (the GIL
 *                  released, so that threads build rows at once), a Table prepared on it
 * The library only points at a table (abrdf.h, "LIFETIME"): a Table keeps its buffer exported
 * (PyObject_GetBuffer) until it is freed, so the memory stays where the prepared object points
 * and NumPy refuses to resize it; the package hands it an immutable bytes object. */
#include "abrdf_py.h" /* first: Python.h sets the feature macros */

#include <string.h>

#include "measured_file.h"

/* Cells per axis this file multiplies without overflow; more than the library takes. */
#define GRID_AXIS_MAX 65536

static void table_dealloc(PyObject *self)
{
    abrdf_py_table *t = (abrdf_py_table *)self;
    if (t->data.obj) PyBuffer_Release(&t->data);
    Py_TYPE(self)->tp_free(self);
}

/* Table(data, n_theta_h, n_theta_d, n_phi_d): data a C-contiguous float32 buffer of
 * 3 * n_theta_h * n_theta_d * n_phi_d values (abrdf_measured's layout). */
static PyObject *table_new(PyTypeObject *type, PyObject *args, PyObject *kwargs)
{
    static char *kw[] = {"data", "n_theta_h", "n_theta_d", "n_phi_d", NULL};
    PyObject *data;
    int n[3];
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "Oiii:Table", kw, &data, &n[0], &n[1], &n[2]))
        return NULL;
    Py_buffer view;
    if (abrdf_py_float_buffer(data, "data", &view)) return NULL;
    abrdf_measured m;
    abrdf_measured_init(&m);
    m.n_theta_h = n[0], m.n_theta_d = n[1], m.n_phi_d = n[2];
    m.data = view.buf;
    /* Each axis bounded before the product (no overflow); the library's own bounds, [2, 1024],
     * are checked by abrdf_prepare_measured below, once the buffer is known to be whole. */
    long long cells = 1;
    for (int k = 0; k < 3; ++k) cells *= n[k] > 0 && n[k] <= GRID_AXIS_MAX ? n[k] : 0;
    if (view.len != (Py_ssize_t)(3 * cells * (long long)sizeof(float))) {
        PyBuffer_Release(&view);
        return abrdf_py_fail(ABRDF_E_TABLE,
                             "Table: a %d x %d x %d grid needs %lld float32 values, got %zd", n[0],
                             n[1], n[2], 3 * cells, view.len / (Py_ssize_t)sizeof(float));
    }
    abrdf_py_table *t = (abrdf_py_table *)type->tp_alloc(type, 0);
    if (!t) {
        PyBuffer_Release(&view);
        return NULL;
    }
    int st = abrdf_prepare_measured(&m, &t->prepared);
    if (st != ABRDF_OK) {
        PyBuffer_Release(&view);
        Py_DECREF(t);
        return abrdf_py_fail(st,
                             "abrdf_prepare_measured: %s (a %d x %d x %d grid; each axis in "
                             "[2, 1024])",
                             abrdf_strerror(st), n[0], n[1], n[2]);
    }
    t->data = view;
    memcpy(t->grid, n, sizeof n);
    return (PyObject *)t;
}

static PyObject *table_grid(PyObject *self, void *closure)
{
    (void)closure;
    const abrdf_py_table *t = (const abrdf_py_table *)self;
    return Py_BuildValue("(iii)", t->grid[0], t->grid[1], t->grid[2]);
}

static PyGetSetDef table_getset[] = {
    {"grid", table_grid, NULL, "(n_theta_h, n_theta_d, n_phi_d); huang_table's: (NT, NV, NP)",
     NULL},
    {NULL, NULL, NULL, NULL, NULL}};

PyTypeObject abrdf_py_table_type = {
    PyVarObject_HEAD_INIT(NULL, 0).tp_name = "abrdf._abrdf.Table",
    .tp_basicsize = sizeof(abrdf_py_table),
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_doc = "Table(data, n_theta_h, n_theta_d, n_phi_d): the `measured` model prepared on a "
              "C-contiguous float32 buffer (abrdf_prepare_measured), held while the Table "
              "lives. Evaluated as a Params is (eval_float, eval_double).",
    .tp_new = table_new,
    .tp_dealloc = table_dealloc,
    .tp_getset = table_getset,
};

int abrdf_py_prepared_arg(PyObject *obj, const char *what, abrdf_prepared *out)
{
    if (PyObject_TypeCheck(obj, &abrdf_py_table_type)) {
        *out = ((const abrdf_py_table *)obj)->prepared; /* plain data: a copy is valid */
        return 0;
    }
    const abrdf_py_params *p = abrdf_py_params_arg(obj, what);
    if (!p) return -1;
    int st = abrdf_prepare(p->model, &p->params, out);
    if (st == ABRDF_OK) return 0;
    abrdf_py_fail(st, "abrdf_prepare: %s", abrdf_strerror(st));
    return -1;
}

/* read_measured(path) -> dict: the table of a measured file (bytes of float32 in the
 * library's layout), its grid, its cells not measured and the format's name. */
static PyObject *py_read_measured(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *bytes;
    if (!PyArg_ParseTuple(args, "O&:read_measured", PyUnicode_FSConverter, &bytes)) return NULL;
    const char *path = PyBytes_AS_STRING(bytes);
    char err[512] = "";
    measured_table t = {0};
    const measured_format *fmt = measured_file_format(path, 0, err, sizeof err);
    int rc = -1;
    if (fmt) {
        Py_BEGIN_ALLOW_THREADS;
        rc = fmt->read(path, &t, err, sizeof err);
        Py_END_ALLOW_THREADS;
    }
    Py_DECREF(bytes);
    if (rc != 0) return abrdf_py_fail(ABRDF_E_TABLE, "%s", err);
    size_t cells = (size_t)t.n_theta_h * (size_t)t.n_theta_d * (size_t)t.n_phi_d;
    PyObject *out = PyDict_New();
    if (!out ||
        abrdf_py_set(out, "data",
                     PyBytes_FromStringAndSize((const char *)t.data,
                                               (Py_ssize_t)(3 * cells * sizeof(float)))) ||
        abrdf_py_set(out, "grid", Py_BuildValue("(iii)", t.n_theta_h, t.n_theta_d, t.n_phi_d)) ||
        abrdf_py_set(out, "unmeasured", PyLong_FromSize_t(t.unmeasured)) ||
        abrdf_py_set(out, "format", PyUnicode_FromString(fmt->name))) {
        Py_XDECREF(out);
        out = NULL;
    }
    measured_table_free(&t);
    return out;
}

/* ---- huang tabulated ------------------------------------------------------------------ */

/* The Params of huang and the four sizes of a call's first two arguments: 0, or -1 with the
 * error set. */
static int huang_args(PyObject *params, const int sizes[4], const char *name,
                      const abrdf_py_params **out, long *values, int *rows)
{
    const abrdf_py_params *p = abrdf_py_params_arg(params, name);
    if (!p) return -1;
    if (p->model != ABRDF_HUANG) {
        abrdf_py_fail(ABRDF_E_MODEL, "%s: the params are %s's, not huang's", name,
                      abrdf_model_get(p->model)->name);
        return -1;
    }
    int st = abrdf_huang_table_size(&p->params, sizes, values, rows);
    if (st != ABRDF_OK) {
        abrdf_py_fail(st,
                      "%s: sizes (%d, %d, %d, %d): %s (theta nodes [4, 256], view azimuths "
                      "[2, 256] or 1 for a round fibre, light azimuths [4, 256], sets [1, 64], "
                      "at most 2^28 values)",
                      name, sizes[0], sizes[1], sizes[2], sizes[3], abrdf_strerror(st));
        return -1;
    }
    *out = p;
    return 0;
}

/* huang_args, then data as the table's buffer in *view: C-contiguous float64 of the table's
 * size, writable for a build (writable 1), read-only for a Table (writable 0: prepare checks
 * the values once, so they must not change after). 0, or -1 with the error set (nothing
 * held). */
static int huang_buffer_args(PyObject *params, const int sizes[4], PyObject *data, int writable,
                             const char *name, const abrdf_py_params **out, int *rows,
                             Py_buffer *view)
{
    long values;
    if (huang_args(params, sizes, name, out, &values, rows)) return -1;
    if (abrdf_py_double_buffer(data, "data", writable, view)) return -1;
    if (!writable && !view->readonly) {
        PyBuffer_Release(view);
        PyErr_Format(PyExc_TypeError,
                     "%s: data must be read-only (bytes, or a read-only array): the Table reads "
                     "it while it lives",
                     name);
        return -1;
    }
    if (view->len != (Py_ssize_t)values * (Py_ssize_t)sizeof(double)) {
        Py_ssize_t got = view->len / (Py_ssize_t)sizeof(double);
        PyBuffer_Release(view);
        abrdf_py_fail(ABRDF_E_TABLE, "%s: the table holds %ld values, got %zd", name, values, got);
        return -1;
    }
    return 0;
}

/* huang_table_size(params, sizes) -> (values, rows) */
static PyObject *py_huang_table_size(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *params;
    int s[4];
    if (!PyArg_ParseTuple(args, "O(iiii):huang_table_size", &params, &s[0], &s[1], &s[2], &s[3]))
        return NULL;
    const abrdf_py_params *p;
    long values;
    int rows;
    if (huang_args(params, s, "huang_table_size", &p, &values, &rows)) return NULL;
    return Py_BuildValue("(li)", values, rows);
}

/* huang_table_build(params, sizes, row0, row1, data): rows [row0, row1) of the table (and its
 * header when row0 is 0) into data, a writable C-contiguous float64 buffer of the table's
 * size; the GIL is released while it builds. */
static PyObject *py_huang_table_build(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *params, *data;
    int s[4], row0, row1;
    if (!PyArg_ParseTuple(args, "O(iiii)iiO:huang_table_build", &params, &s[0], &s[1], &s[2], &s[3],
                          &row0, &row1, &data))
        return NULL;
    const abrdf_py_params *p;
    int rows;
    Py_buffer view;
    if (huang_buffer_args(params, s, data, 1, "huang_table_build", &p, &rows, &view)) return NULL;
    abrdf_params block = p->params; /* the Params may change while the GIL is released */
    int st;
    Py_BEGIN_ALLOW_THREADS;
    st = abrdf_huang_table_build(&block, s, row0, row1, view.buf);
    Py_END_ALLOW_THREADS;
    PyBuffer_Release(&view);
    if (st != ABRDF_OK)
        return abrdf_py_fail(st, "huang_table_build: rows [%d, %d) of %d: %s", row0, row1, rows,
                             abrdf_strerror(st));
    Py_RETURN_NONE;
}

/* huang_table(params, sizes, data) -> Table: huang prepared on the table in data (a
 * C-contiguous float64 buffer, held while the Table lives). */
static PyObject *py_huang_table(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *params, *data;
    int s[4];
    if (!PyArg_ParseTuple(args, "O(iiii)O:huang_table", &params, &s[0], &s[1], &s[2], &s[3], &data))
        return NULL;
    const abrdf_py_params *p;
    int rows;
    Py_buffer view;
    if (huang_buffer_args(params, s, data, 0, "huang_table", &p, &rows, &view)) return NULL;
    abrdf_py_table *t = (abrdf_py_table *)abrdf_py_table_type.tp_alloc(&abrdf_py_table_type, 0);
    if (!t) {
        PyBuffer_Release(&view);
        return NULL;
    }
    int st = abrdf_prepare_huang_table(&p->params, s, view.buf, &t->prepared);
    if (st != ABRDF_OK) {
        PyBuffer_Release(&view);
        Py_DECREF(t);
        return abrdf_py_fail(st,
                             "abrdf_prepare_huang_table: %s (a table of other parameters, other "
                             "sizes, another library, or rows never built)",
                             abrdf_strerror(st));
    }
    t->data = view;
    memcpy(t->grid, s, sizeof t->grid);
    t->sets = s[3];
    return (PyObject *)t;
}

PyMethodDef abrdf_py_measured_methods[] = {
    {"read_measured", py_read_measured, METH_VARARGS,
     "read_measured(path) -> dict: a measured BRDF file (MERL .binary; RGL .bsdf, resampled "
     "onto 90 x 90 x 180) by the readers of `abrdf inspect`: data (bytes: float32 f_r in 1/sr, "
     "abrdf_measured's layout, < 0 = not measured), grid, unmeasured (cells), format; "
     "abrdf.Error with the reader's line. Releases the GIL while reading."},
    {"huang_table_size", py_huang_table_size, METH_VARARGS,
     "huang_table_size(params, sizes) -> (values, rows): abrdf_huang_table_size of huang's "
     "Params at sizes (theta nodes, view azimuths, light azimuths, shift sets)"},
    {"huang_table_build", py_huang_table_build, METH_VARARGS,
     "huang_table_build(params, sizes, row0, row1, data): rows [row0, row1) of the table into "
     "a writable C-contiguous float64 buffer of its size (abrdf_huang_table_build; row0 0 "
     "writes the header too). Releases the GIL: threads build disjoint rows at once."},
    {"huang_table", py_huang_table, METH_VARARGS,
     "huang_table(params, sizes, data) -> Table: huang prepared on the table in a C-contiguous "
     "float64 buffer (abrdf_prepare_huang_table), held while the Table lives"},
    {NULL, NULL, 0, NULL}};
