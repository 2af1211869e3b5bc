/* py_module.c - the module abrdf._abrdf: the method tables of the parts (abrdf_py.h) joined
 * into one, the Params type and the exception. */
#include "abrdf_py.h"

/* Room for the methods of every part (checked when the table is filled). */
#define METHODS_MAX 32
static PyMethodDef methods[METHODS_MAX + 1];

static int join_methods(void)
{
    const PyMethodDef *parts[] = {abrdf_py_models_methods, abrdf_py_eval_methods,
                                  abrdf_py_select_methods, abrdf_py_compare_methods,
                                  abrdf_py_fit_methods,    abrdf_py_measured_methods,
                                  abrdf_py_pbr_methods};
    int n = 0;
    for (size_t p = 0; p < sizeof parts / sizeof parts[0]; ++p)
        for (const PyMethodDef *m = parts[p]; m->ml_name; ++m) {
            if (n == METHODS_MAX) return -1;
            methods[n++] = *m;
        }
    return 0;
}

static struct PyModuleDef module = {
    PyModuleDef_HEAD_INIT,
    .m_name = "abrdf._abrdf",
    .m_doc =
        "libabrdf's C API for the package abrdf (python/abrdf): the registry, parameter "
        "blocks, evaluation over arrays, the selection flowchart, fitting and the budget mode, "
        "image metrics, measured tables and glTF metallic-roughness materials.",
    .m_size = -1,
    .m_methods = methods,
};

PyMODINIT_FUNC PyInit__abrdf(void)
{
    if (join_methods()) {
        PyErr_SetString(PyExc_SystemError, "abrdf._abrdf: METHODS_MAX is too small");
        return NULL;
    }
    if (PyType_Ready(&abrdf_py_params_type) < 0 || PyType_Ready(&abrdf_py_table_type) < 0)
        return NULL;
    PyObject *m = PyModule_Create(&module);
    if (!m) return NULL;
    PyObject *error = abrdf_py_error_type_new();
    if (!error || PyModule_AddObject(m, "Error", error) < 0) {
        Py_XDECREF(error);
        Py_DECREF(m);
        return NULL;
    }
    Py_INCREF(&abrdf_py_params_type);
    if (PyModule_AddObject(m, "Params", (PyObject *)&abrdf_py_params_type) < 0) {
        Py_DECREF(&abrdf_py_params_type);
        Py_DECREF(m);
        return NULL;
    }
    Py_INCREF(&abrdf_py_table_type);
    if (PyModule_AddObject(m, "Table", (PyObject *)&abrdf_py_table_type) < 0) {
        Py_DECREF(&abrdf_py_table_type);
        Py_DECREF(m);
        return NULL;
    }
    if (PyModule_AddIntConstant(m, "MAX_LAYERS", ABRDF_MAX_LAYERS) < 0) {
        Py_DECREF(m);
        return NULL;
    }
    return m;
}
