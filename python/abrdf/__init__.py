"""abrdf - surface reflectance models and their adaptive selection, from Python.

NumPy bindings over libabrdf, the C library of the reflectance models of Zavalniuk &
Romanyuk, "Adaptive selection of the surface reflectance model for rendering tasks" (2024),
and of its selection flowchart (Fig. 2). The C code is the library's own: the package's
extension module links libabrdf and calls it.

    >>> import numpy as np, abrdf
    >>> wi, wo = np.array([0.3, 0.0, 1.0]), np.array([-0.2, 0.1, 1.0])
    >>> abrdf.eval("disney_specular", wi, wo, r=0.3, precision="double")  # f_r per RGB, 1/sr
    array([0.16682263, 0.16682263, 0.16682263])
    >>> s = abrdf.select("gold", goal="performance")
    >>> s.diffuse, s.specular, s.trace[-1].text
    ('lambert', 'f8', 'f8: rel 1.61% <= 2%, abs 0.0351 <= 0.05, 14 cycles: cheapest that passes')

Functions:
    models(), model(name)        the registry: every model, its formula, parameters, ranges
    BRDF(model, **params)        a validated parameter block; .eval(wi, wo, precision=)
    eval(model, wi, wo, **p)     f_r over arrays of directions (the C batch path, or the
                                 double scalar reference with precision="double"); out=
    Lobes([brdf, ...])           a material of several lobes: .eval(wi, wo) their sum, in one
                                 pass over the rows
    materials(), material(name)  the material table (data/materials.csv, shipped here)
    select(material, goal=...)   the paper's flowchart, with its trace
    select(material, budget=...) the budget mode: the cheapest candidate fitted to the
                                 photoreal choice within a Table-8 image-error class
    fit(reference, candidate)    one model's parameters fitted to another's (or to a measured
                                 table), with the errors and the predicted image NMSE
    load_measured(path)          a measured BRDF file (MERL .binary, RGL .bsdf) as a Measured
    measured_from_array(a)       a Measured from a NumPy table on MERL's grid
    Measured                     a measured table: .table, .grid, .unmeasured, .eval(wi, wo)
    huang_table(brdf, sizes)     huang's residual lobes tabulated once (a HuangTable): nearer
                                 the converged model and ~150x cheaper per call; select's
                                 budget reference=
    sweep(materials, models)     every material fitted by every candidate, with the NMSE, cost
                                 and budget verdict, on dask.distributed or in a loop
    surfaces(), goals()          the flowchart's surface classes and goals
    compare(reference, test)     NMSE (the paper's), PSNR, Table-8 class, of arrays or files
    read_image(path)             a linear float RGB image (OpenImageIO)
    Pbr                          a glTF metallic-roughness material's factors (abrdf_pbr)
    pbr_lobes(p), pbr_material(p)  its explicit lobes (BRDFs) and the flowchart's Material
    load_gltf(path)              the materials of a .gltf / .glb file, as PbrMaterials
    load_materialx(path)         the materials of a MaterialX document (PyPI materialx)
    PbrMaterial, TextureRef      a material read from a file: name, Pbr, texture maps
    Error                        a failure of the library (a ValueError), with its message

Conventions are libabrdf's (abrdf.h): directions in the local frame (N = +z, T = +x), `wi`
toward the light, `wo` toward the viewer, both away from the surface; f_r is returned
without the cosine factor, per RGB channel.
"""
from __future__ import annotations

from ._abrdf import MAX_LAYERS, Error, Params
from ._brdf import BRDF, Model, Parameter, model, models
from ._eval import Lobes, eval
from ._compare import Comparison, compare, read_image
from ._fit import Fit, fit
from ._hair import HuangTable, huang_table
from ._measured import Measured, load_measured, measured_from_array
from ._pbr import Pbr, PbrMaterial, TextureRef, pbr_lobes, pbr_material
from ._gltf import load_gltf
from ._materialx import load_materialx
from ._select import (Layer, Material, Selection, Step, budget_nmse, goals, material, materials,
                      select, surfaces)
from ._sweep import Sweep, SweepRow, sweep

__version__: str = "0.2.0"

# `eval` is abrdf.eval; it stays out of __all__ so that `from abrdf import *` keeps the
# builtin.
__all__ = [
    "BRDF",
    "Comparison",
    "Error",
    "Fit",
    "HuangTable",
    "Layer",
    "Lobes",
    "MAX_LAYERS",
    "Material",
    "Measured",
    "Model",
    "Parameter",
    "Params",
    "Pbr",
    "PbrMaterial",
    "Selection",
    "Step",
    "Sweep",
    "SweepRow",
    "TextureRef",
    "budget_nmse",
    "compare",
    "fit",
    "goals",
    "huang_table",
    "load_gltf",
    "load_materialx",
    "load_measured",
    "material",
    "materials",
    "measured_from_array",
    "model",
    "models",
    "pbr_lobes",
    "pbr_material",
    "read_image",
    "select",
    "surfaces",
    "sweep",
]
