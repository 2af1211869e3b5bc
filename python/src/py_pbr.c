/* py_pbr.c - glTF metallic-roughness materials (abrdf_pbr.h) from Python: a dict of
 * abrdf.Pbr's fields (the names of abrdf_pbr's fields) read into an abrdf_pbr over glTF's
 * defaults, then
 *   pbr_check     abrdf_pbr_check: None, or abrdf.Error with the library's message
 *   pbr_lobes     abrdf_pbr_lobes: the explicit lobes as Params (diffuse, specular)
 *   pbr_material  abrdf_pbr_material: the flowchart's material as abrdf.Material's fields */
#include "abrdf_py.h" /* first: Python.h sets the feature macros */

#include <stddef.h>
#include <string.h>

#include "abrdf_pbr.h"

/* abrdf_pbr's fields by name: where each lives and whether it is a colour. */
static const struct {
    const char *name;
    size_t offset;
    int rgb;
} fields[] = {
    {"base_color", offsetof(abrdf_pbr, base_color), 1},
    {"metallic", offsetof(abrdf_pbr, metallic), 0},
    {"roughness", offsetof(abrdf_pbr, roughness), 0},
    {"ior", offsetof(abrdf_pbr, ior), 0},
    {"specular", offsetof(abrdf_pbr, specular), 0},
    {"specular_color", offsetof(abrdf_pbr, specular_color), 1},
    {"clearcoat", offsetof(abrdf_pbr, clearcoat), 0},
    {"clearcoat_roughness", offsetof(abrdf_pbr, clearcoat_roughness), 0},
    {"sheen_color", offsetof(abrdf_pbr, sheen_color), 1},
    {"sheen_roughness", offsetof(abrdf_pbr, sheen_roughness), 0},
    {"anisotropy", offsetof(abrdf_pbr, anisotropy), 0},
    {"anisotropy_rotation", offsetof(abrdf_pbr, anisotropy_rotation), 0},
    {"transmission", offsetof(abrdf_pbr, transmission), 0},
};

/* One value of d (a number, or three for a colour) into v. 0 or -1. */
static int read_field(PyObject *value, const char *name, int rgb, double *v)
{
    if (!rgb) return abrdf_py_real_number(value, name, v);
    if (!PySequence_Check(value) || PyUnicode_Check(value) || PyBytes_Check(value)) {
        PyErr_Format(PyExc_TypeError, "%s: a colour is 3 numbers (R, G, B), got %.100s", name,
                     Py_TYPE(value)->tp_name);
        return -1;
    }
    PyObject *seq = PySequence_Fast(value, "a colour is 3 numbers");
    if (!seq) return -1;
    int rc = 0;
    if (PySequence_Fast_GET_SIZE(seq) != 3) {
        abrdf_py_fail(ABRDF_E_RANGE, "%s: a colour needs 3 numbers (R, G, B)", name);
        rc = -1;
    }
    for (int c = 0; !rc && c < 3; ++c)
        rc = abrdf_py_real_number(PySequence_Fast_GET_ITEM(seq, c), name, &v[c]);
    Py_DECREF(seq);
    return rc;
}

/* p from a dict of abrdf.Pbr's fields over glTF's defaults, checked by abrdf_pbr_check
 * (abrdf.Error with its message). 0 or -1. */
static int pbr_from(PyObject *d, abrdf_pbr *p)
{
    abrdf_pbr_init(p);
    PyObject *key, *value;
    Py_ssize_t pos = 0;
    while (PyDict_Next(d, &pos, &key, &value)) {
        const char *k = PyUnicode_Check(key) ? PyUnicode_AsUTF8(key) : NULL;
        size_t i = 0;
        while (k && i < sizeof fields / sizeof fields[0] && strcmp(k, fields[i].name)) ++i;
        if (!k || i == sizeof fields / sizeof fields[0]) {
            if (!PyErr_Occurred()) PyErr_Format(PyExc_TypeError, "pbr: unknown field %R", key);
            return -1;
        }
        double v[3];
        if (read_field(value, fields[i].name, fields[i].rgb, v)) return -1;
        memcpy((char *)p + fields[i].offset, v, (fields[i].rgb ? 3 : 1) * sizeof(double));
    }
    char msg[256];
    int st = abrdf_pbr_check(p, msg, sizeof msg);
    if (st == ABRDF_OK) return 0;
    abrdf_py_fail(st, "%s", msg);
    return -1;
}

static PyObject *py_pbr_check(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *d;
    abrdf_pbr p;
    if (!PyArg_ParseTuple(args, "O!:pbr_check", &PyDict_Type, &d) || pbr_from(d, &p)) return NULL;
    Py_RETURN_NONE;
}

static PyObject *py_pbr_lobes(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *d;
    abrdf_pbr p;
    if (!PyArg_ParseTuple(args, "O!:pbr_lobes", &PyDict_Type, &d) || pbr_from(d, &p)) return NULL;
    abrdf_model lobes[ABRDF_PBR_MAX_LOBES];
    int count = 0;
    abrdf_params params;
    abrdf_params_init(ABRDF_DISNEY_SPECULAR, &params);
    int st = abrdf_pbr_lobes(&p, lobes, &count, &params);
    if (st != ABRDF_OK) return abrdf_py_fail(st, "abrdf_pbr_lobes: %s", abrdf_strerror(st));
    PyObject *list = PyList_New(count);
    for (int l = 0; list && l < count; ++l) {
        PyObject *block = abrdf_py_params_from_block(lobes[l], &params);
        if (!block) {
            Py_CLEAR(list);
            break;
        }
        PyList_SET_ITEM(list, l, block);
    }
    return list;
}

static PyObject *py_pbr_material(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *d;
    abrdf_pbr p;
    if (!PyArg_ParseTuple(args, "O!:pbr_material", &PyDict_Type, &d) || pbr_from(d, &p))
        return NULL;
    abrdf_material m;
    abrdf_material_init(&m);
    int st = abrdf_pbr_material(&p, &m);
    if (st != ABRDF_OK) return abrdf_py_fail(st, "abrdf_pbr_material: %s", abrdf_strerror(st));
    return abrdf_py_material_dict(&m);
}

PyMethodDef abrdf_py_pbr_methods[] = {
    {"pbr_check", py_pbr_check, METH_VARARGS,
     "pbr_check(fields: dict) -> None: abrdf_pbr_check on abrdf.Pbr's fields over glTF's "
     "defaults; abrdf.Error with the library's message"},
    {"pbr_lobes", py_pbr_lobes, METH_VARARGS,
     "pbr_lobes(fields: dict) -> list[Params]: abrdf_pbr_lobes, the diffuse and the specular "
     "lobe with their shared parameters"},
    {"pbr_material", py_pbr_material, METH_VARARGS,
     "pbr_material(fields: dict) -> dict: abrdf_pbr_material, the flowchart's material as "
     "abrdf.Material's fields (name None)"},
    {NULL, NULL, 0, NULL}};
