/* abrdf_py.h - what the files of the Python module abrdf._abrdf share: the exception, the
 * buffer helpers and the parameter-block type. The module is a thin layer over libabrdf's
 * C API written against the CPython API; the package abrdf (python/abrdf) builds the
 * user-facing functions on it, and NumPy stays on the Python side (the C code sees buffers
 * through the buffer protocol, PEP 3118).
 *
 * One file per part of the API, each adding its functions to the module's method table:
 *   py_module.c   the module, its method table, PyInit__abrdf
 *   py_util.c     abrdf.Error (a ValueError carrying the library's message and status) and
 *                 small conversions
 *   py_buffers.c  (N, 3) float buffers in, float buffers out
 *   py_models.c   the registry: models, parameters, their metadata
 *   py_params.c   Params: a validated parameter block for one model
 *   py_eval.c     f_r over arrays: the float batch path and the double scalar reference
 *   py_select.c   the material table, cost files, the paper's flowchart with its trace
 *   py_compare.c  the paper's NMSE, PSNR and Table-8 class of two float images
 *   py_fit.c      one model fitted to another, the selection's budget mode
 *   py_measured.c measured tables: Table (the `measured` model on a held buffer), the readers
 *                 of MERL and RGL files (tools/measured)
 *   py_pbr.c      glTF metallic-roughness materials (abrdf_pbr.h): their lobes and the
 *                 flowchart's material
 * A new C entry point (prepared evaluation, sampling, fitting) is a new py_*.c with its
 * methods, listed in py_module.c, using Params and the buffer helpers below. */
#ifndef ABRDF_PY_H
#define ABRDF_PY_H

#define PY_SSIZE_T_CLEAN
#include <Python.h>

#include "abrdf_select.h"
#include "select_trace.h"

/* ---- errors (py_util.c) ------------------------------------------------------------ */
/* Create abrdf.Error; returns it (a new reference) or NULL. */
PyObject *abrdf_py_error_type_new(void);
/* Raise abrdf.Error with `status` (an abrdf_status) and the message; returns NULL. */
PyObject *abrdf_py_fail(int status, const char *fmt, ...);

/* ---- buffers (py_buffers.c) ------------------------------------------------------------ */
/* A C-contiguous buffer of `rows` x 3 numbers of one kind. */
typedef enum abrdf_py_real { ABRDF_PY_F32 = 'f', ABRDF_PY_F64 = 'd' } abrdf_py_real;

/* Acquire `obj` as a C-contiguous (N, 3) buffer of float32 or float64 (want = 0: either;
 * else that kind). writable: the buffer is written. On success fills *view (release it with
 * PyBuffer_Release), *rows and *kind and returns 0; else raises TypeError/ValueError naming
 * `what` and returns -1. */
int abrdf_py_rows3(PyObject *obj, const char *what, int want, int writable, Py_buffer *view,
                   Py_ssize_t *rows, abrdf_py_real *kind);
/* The same for a C-contiguous float32 buffer of any shape; *count is its number of floats
 * and, for images, shape[0..2] are (height, width, channels) with channels 1 for 2-D. */
int abrdf_py_float_image(PyObject *obj, const char *what, Py_buffer *view, Py_ssize_t shape[3]);
/* The same for a C-contiguous float32 buffer of any shape, read only; view->len is its bytes. */
int abrdf_py_float_buffer(PyObject *obj, const char *what, Py_buffer *view);
/* The same for a C-contiguous float64 buffer, writable if asked. 0 or -1 (TypeError). */
int abrdf_py_double_buffer(PyObject *obj, const char *what, int writable, Py_buffer *view);

/* ---- Params (py_params.c) ------------------------------------------------------------ */
typedef struct abrdf_py_params {
    PyObject ob_base;    /* what PyObject_HEAD declares */
    abrdf_model model;   /* the model this block was validated for */
    abrdf_params params; /* passes abrdf_params_check for `model` */
} abrdf_py_params;

extern PyTypeObject abrdf_py_params_type;
/* A new Params for `model` holding a copy of `params`, checked by abrdf_params_check
 * (abrdf.Error with its message if it fails). */
PyObject *abrdf_py_params_from_block(abrdf_model model, const abrdf_params *params);
/* `obj` as a Params (a borrowed pointer), or NULL with TypeError. */
abrdf_py_params *abrdf_py_params_arg(PyObject *obj, const char *what);
/* The model of a stable name (the registry's): 0, or -1 with abrdf.Error for an unknown
 * name. */
int abrdf_py_model_find(const char *name, abrdf_model *out);
/* Python value of parameter `id` read from `params` (float, int or a 3-tuple). */
PyObject *abrdf_py_param_value(const abrdf_params *params, int id);

/* ---- Table (py_measured.c) ------------------------------------------------------------ */
typedef struct abrdf_py_table {
    PyObject ob_base;        /* what PyObject_HEAD declares */
    Py_buffer data;          /* the table's values, exported to this object while it lives */
    int grid[3];             /* measured: n_theta_h, n_theta_d, n_phi_d; huang: NT, NV, NP */
    int sets;                /* huang: the shift sets per node; measured: 0 */
    abrdf_prepared prepared; /* ABRDF_MEASURED on data.buf (float32), or ABRDF_HUANG on its
                                table (float64, huang_table) */
} abrdf_py_table;

extern PyTypeObject abrdf_py_table_type;
/* The prepared model of `obj`, a Params (abrdf_prepare of its block: abrdf.Error if that
 * fails) or a Table (a copy of its prepared object, valid while the Table lives), into *out;
 * else TypeError naming `what`. 0 or -1. */
int abrdf_py_prepared_arg(PyObject *obj, const char *what, abrdf_prepared *out);

/* ---- method tables of the parts, joined by py_module.c ---------------------------------- */
extern PyMethodDef abrdf_py_models_methods[];
extern PyMethodDef abrdf_py_eval_methods[];
extern PyMethodDef abrdf_py_select_methods[];
extern PyMethodDef abrdf_py_compare_methods[];
extern PyMethodDef abrdf_py_fit_methods[];
extern PyMethodDef abrdf_py_measured_methods[];
extern PyMethodDef abrdf_py_pbr_methods[];

/* ---- the selection's conversions (py_select.c), shared with py_fit.c ------------------ */
/* m from a dict of abrdf.Material's fields (absent ones keep abrdf_material_init's); m->name
 * may point into *name_ref (borrowed: hold a reference while m is used). 0 or -1. */
int abrdf_py_material_from(PyObject *d, abrdf_material *m, PyObject **name_ref);
/* c from {model name: cost} in `unit`. 0 or -1. */
int abrdf_py_costs_from(PyObject *costs, const char *unit, abrdf_costs *c);
/* m from the material dict `mat` and, unless `costs` is None, c from the costs dict in `unit`
 * (TypeError when costs is neither). On success *name_ref is NULL or a new reference that
 * m->name points into: Py_XDECREF it once m is no longer used. 0 or -1 (nothing held). */
int abrdf_py_material_costs_from(PyObject *mat, PyObject *costs, const char *unit,
                                 abrdf_material *m, abrdf_costs *c, PyObject **name_ref);
/* m as a dict of abrdf.Material's fields (name, type, n, r, kd, ks, f0, eta, anisotropy,
 * melanin, redness, layers; unset n, r and eta as None). */
PyObject *abrdf_py_material_dict(const abrdf_material *m);
/* The dict abrdf._abrdf.select returns: the choice, its lobes' Params and the trace. */
PyObject *abrdf_py_selection_dict(const abrdf_selection *s, const abrdf_params *p,
                                  const select_trace *trace);

/* ---- small conversions (py_util.c) --------------------------------------------------- */
/* v < 0 ("not applicable" in abrdf_selection and the trace) -> None, else a float. */
PyObject *abrdf_py_opt(double v);
/* Three doubles as a tuple. */
PyObject *abrdf_py_rgb(const double v[3]);
/* Set d[key] = value and drop the reference to value; returns -1 if value is NULL or the
 * insertion fails. */
int abrdf_py_set(PyObject *d, const char *key, PyObject *value);
/* A number given by the caller into *out: an int or a float, or another numbers.Real
 * (NumPy's integer and floating scalars). bool, complex, None, strings and datetimes are
 * refused with TypeError "WHAT: a real number is needed, got TYPE" rather than cast (a cast
 * would drop an imaginary part). 0 or -1. */
int abrdf_py_real_number(PyObject *v, const char *what, double *out);

#endif
