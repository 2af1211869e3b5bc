/* py_eval.c - f_r over arrays of direction pairs, the GIL released while the library works:
 *   eval_float   the float batch path (abrdf_eval_batch): rows of (N, 3) directions are
 *                normalised and laid out as the batch's structure of arrays, CHUNK at a time
 *                on the stack, and the results written back as rows;
 *   eval_double  the double-precision scalar reference (abrdf_eval with the local frame), one
 *                pair at a time.
 *   _time_eval_batch  the C batch path alone on the same directions, timed here, so that the
 *                binding's cost is measured against it in one process (docs/BENCHMARKS.md).
 * Directions are in the local frame (N = +z, T = +x); wi toward the light, wo toward the
 * viewer; f_r is without the cosine (abrdf.h). Zero or non-finite vectors give f_r = 0. */
#include "abrdf_py.h" /* first: Python.h sets the feature macros */

#include <math.h>
#include <stdlib.h>
#include <time.h>

/* Pairs per call of abrdf_eval_batch: 9 arrays of CHUNK floats on the stack (9 KiB), long
 * enough for the batch loop to run at its vector speed. */
#define CHUNK 256

/* Row k of a (N, 3) buffer of `kind` as doubles. */
static void row(const void *buf, abrdf_py_real kind, Py_ssize_t k, double v[3])
{
    if (kind == ABRDF_PY_F32) {
        const float *p = (const float *)buf + 3 * k;
        v[0] = p[0], v[1] = p[1], v[2] = p[2];
    } else {
        const double *p = (const double *)buf + 3 * k;
        v[0] = p[0], v[1] = p[1], v[2] = p[2];
    }
}

/* Squared lengths that square and invert in double without overflow or loss: outside them a
 * row is first scaled by its largest component. */
#define LEN2_MIN 1e-290
#define LEN2_MAX 1e290

/* Rows [start, start + n) normalised into x, y, z (the batch wants unit length). A row within
 * UNIT_TOL of unit length squared is unit to float precision (a float's rounding is 6e-8) and
 * is only converted: directions that are already unit skip the square root and division. */
#define UNIT_TOL 1e-7
static void load(const void *buf, abrdf_py_real kind, Py_ssize_t start, int n, float *x, float *y,
                 float *z)
{
    for (int k = 0; k < n; ++k) {
        double v[3];
        row(buf, kind, start + k, v);
        double len2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
        if (fabs(len2 - 1.0) <= UNIT_TOL) {
            x[k] = (float)v[0], y[k] = (float)v[1], z[k] = (float)v[2];
            continue;
        }
        if (!(len2 >= LEN2_MIN && len2 <= LEN2_MAX)) { /* rare: tiny, huge, zero or NaN */
            double m = fmax(fabs(v[0]), fmax(fabs(v[1]), fabs(v[2])));
            x[k] = y[k] = z[k] = 0.0f;
            if (!(m > 0.0) || !isfinite(v[0]) || !isfinite(v[1]) || !isfinite(v[2])) continue;
            v[0] /= m, v[1] /= m, v[2] /= m;
            len2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
        }
        double inv = 1.0 / sqrt(len2);
        x[k] = (float)(v[0] * inv), y[k] = (float)(v[1] * inv), z[k] = (float)(v[2] * inv);
    }
}

/* The arguments every evaluation takes: a Params and two (N, 3) direction arrays. */
typedef struct eval_args {
    abrdf_py_params *params;
    Py_buffer wi, wo, out;
    Py_ssize_t rows;
    abrdf_py_real wi_kind, wo_kind;
} eval_args;

static int get_args(PyObject *args, const char *name, int out_kind, eval_args *a)
{
    PyObject *p, *wi, *wo, *out;
    if (!PyArg_ParseTuple(args, "OOOO", &p, &wi, &wo, &out)) return -1;
    if (!(a->params = abrdf_py_params_arg(p, name))) return -1;
    Py_ssize_t n_wo, n_out;
    abrdf_py_real k_out;
    if (abrdf_py_rows3(wi, "wi", 0, 0, &a->wi, &a->rows, &a->wi_kind)) return -1;
    if (abrdf_py_rows3(wo, "wo", 0, 0, &a->wo, &n_wo, &a->wo_kind)) {
        PyBuffer_Release(&a->wi);
        return -1;
    }
    if (abrdf_py_rows3(out, "out", out_kind, 1, &a->out, &n_out, &k_out)) {
        PyBuffer_Release(&a->wi);
        PyBuffer_Release(&a->wo);
        return -1;
    }
    if (n_wo != a->rows || n_out != a->rows) {
        PyErr_Format(PyExc_ValueError,
                     "%s: wi, wo and out need the same number of rows (%zd, %zd, %zd)", name,
                     a->rows, n_wo, n_out);
        PyBuffer_Release(&a->wi);
        PyBuffer_Release(&a->wo);
        PyBuffer_Release(&a->out);
        return -1;
    }
    return 0;
}

static void release(eval_args *a)
{
    PyBuffer_Release(&a->wi);
    PyBuffer_Release(&a->wo);
    PyBuffer_Release(&a->out);
}

static PyObject *py_eval_float(PyObject *self, PyObject *args)
{
    (void)self;
    eval_args a;
    if (get_args(args, "eval_float", ABRDF_PY_F32, &a)) return NULL;
    int st = ABRDF_OK;
    float *out = a.out.buf;
    Py_BEGIN_ALLOW_THREADS;
    float ix[CHUNK], iy[CHUNK], iz[CHUNK], ox[CHUNK], oy[CHUNK], oz[CHUNK];
    float fr[CHUNK], fg[CHUNK], fb[CHUNK];
    for (Py_ssize_t start = 0; start < a.rows && st == ABRDF_OK; start += CHUNK) {
        int n = a.rows - start < CHUNK ? (int)(a.rows - start) : CHUNK;
        load(a.wi.buf, a.wi_kind, start, n, ix, iy, iz);
        load(a.wo.buf, a.wo_kind, start, n, ox, oy, oz);
        abrdf_batch b = {(size_t)n, ix, iy, iz, ox, oy, oz, fr, fg, fb};
        st = abrdf_eval_batch(a.params->model, &a.params->params, &b);
        for (int k = 0; k < n; ++k) {
            float *o = out + 3 * (start + k);
            o[0] = fr[k], o[1] = fg[k], o[2] = fb[k];
        }
    }
    Py_END_ALLOW_THREADS;
    release(&a);
    if (st != ABRDF_OK) return abrdf_py_fail(st, "abrdf_eval_batch: %s", abrdf_strerror(st));
    Py_RETURN_NONE;
}

static PyObject *py_eval_double(PyObject *self, PyObject *args)
{
    (void)self;
    eval_args a;
    if (get_args(args, "eval_double", ABRDF_PY_F64, &a)) return NULL;
    int st = ABRDF_OK;
    double *out = a.out.buf;
    Py_BEGIN_ALLOW_THREADS;
    for (Py_ssize_t k = 0; k < a.rows && st == ABRDF_OK; ++k) {
        double wi[3], wo[3];
        row(a.wi.buf, a.wi_kind, k, wi);
        row(a.wo.buf, a.wo_kind, k, wo);
        st = abrdf_eval(a.params->model, &a.params->params, NULL, wi, wo, out + 3 * k);
    }
    Py_END_ALLOW_THREADS;
    release(&a);
    if (st != ABRDF_OK) return abrdf_py_fail(st, "abrdf_eval: %s", abrdf_strerror(st));
    Py_RETURN_NONE;
}

/* The thread's CPU time, as `abrdf calibrate` times models: time spent descheduled on a busy
 * machine is not counted. */
static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* _time_eval_batch(params, wi, wo, out, calls) -> seconds per call of abrdf_eval_batch over all
 * rows, `calls` calls between two reads of the clock (a read costs about as much as a call on
 * a few pairs), on structure-of-arrays copies made before the clock starts. */
static PyObject *py_time_eval_batch(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *p, *wi, *wo, *out;
    int calls;
    if (!PyArg_ParseTuple(args, "OOOOi", &p, &wi, &wo, &out, &calls)) return NULL;
    if (calls < 1) return PyErr_Format(PyExc_ValueError, "calls must be >= 1");
    PyObject *tuple = Py_BuildValue("(OOOO)", p, wi, wo, out);
    if (!tuple) return NULL;
    eval_args a;
    int bad = get_args(tuple, "_time_eval_batch", ABRDF_PY_F32, &a);
    Py_DECREF(tuple);
    if (bad) return NULL;
    size_t n = (size_t)a.rows;
    float *mem = malloc(9 * (n ? n : 1) * sizeof *mem);
    if (!mem) {
        release(&a);
        return PyErr_NoMemory();
    }
    int st = ABRDF_OK;
    double seconds;
    Py_BEGIN_ALLOW_THREADS;
    for (size_t start = 0; start < n; start += CHUNK) {
        int m = n - start < CHUNK ? (int)(n - start) : CHUNK;
        load(a.wi.buf, a.wi_kind, (Py_ssize_t)start, m, mem + start, mem + n + start,
             mem + 2 * n + start);
        load(a.wo.buf, a.wo_kind, (Py_ssize_t)start, m, mem + 3 * n + start, mem + 4 * n + start,
             mem + 5 * n + start);
    }
    abrdf_batch b = {n,           mem,         mem + n,     mem + 2 * n, mem + 3 * n,
                     mem + 4 * n, mem + 5 * n, mem + 6 * n, mem + 7 * n, mem + 8 * n};
    double t0 = now();
    for (int r = 0; r < calls && st == ABRDF_OK; ++r)
        st = abrdf_eval_batch(a.params->model, &a.params->params, &b);
    seconds = (now() - t0) / calls;
    float *o = a.out.buf;
    for (size_t k = 0; k < n; ++k)
        o[3 * k] = b.f_r[k], o[3 * k + 1] = b.f_g[k], o[3 * k + 2] = b.f_b[k];
    Py_END_ALLOW_THREADS;
    release(&a);
    free(mem);
    if (st != ABRDF_OK) return abrdf_py_fail(st, "abrdf_eval_batch: %s", abrdf_strerror(st));
    return PyFloat_FromDouble(seconds);
}

PyMethodDef abrdf_py_eval_methods[] = {
    {"eval_float", py_eval_float, METH_VARARGS,
     "eval_float(params, wi, wo, out) -> None: f_r of every row pair by the float batch path "
     "(abrdf_eval_batch) into out; wi, wo: C-contiguous (N, 3) float32 or float64 local-frame "
     "directions (normalised here); out: writable (N, 3) float32. Releases the GIL."},
    {"eval_double", py_eval_double, METH_VARARGS,
     "eval_double(params, wi, wo, out) -> None: the same by the double-precision scalar "
     "reference (abrdf_eval, local frame); out: writable (N, 3) float64. Releases the GIL."},
    {"_time_eval_batch", py_time_eval_batch, METH_VARARGS,
     "_time_eval_batch(params, wi, wo, out, calls) -> float: seconds of thread CPU time per "
     "call of abrdf_eval_batch over all rows, `calls` calls timed together, on "
     "structure-of-arrays copies made before timing (the C batch path alone, for the "
     "binding's benchmark); out receives the result."},
    {NULL, NULL, 0, NULL}};
