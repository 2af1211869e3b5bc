"""One model fitted to another (abrdf_fit, docs/SELECTION.md, "The budget mode") or to a measured
table (abrdf_fit_to, docs/MEASURED.md): fit() and its result, Fit."""
from __future__ import annotations

import os
from dataclasses import dataclass
from typing import Literal, Mapping, Union

from . import _abrdf
from ._brdf import BRDF
from ._measured import Measured, is_measured_path, load_measured
from ._select import Material, Selection, _error, select

Metric = Literal["l2", "log", "cbrt", "auto"]
Reference = Union[str, "os.PathLike[str]", BRDF, Measured, Selection, Material,
                  Mapping[str, object], tuple]


@dataclass(frozen=True)
class Fit:
    """The candidate's fitted parameters and how close it came (abrdf_fit_result): the
    diffuse and specular lobes as BRDFs (one block: a parameter both read has one value;
    None for an absent lobe), the relative L2 error of f cos over the direction set, the
    largest relative error in the reference's highlight zone (percent, Table 2's measure),
    the largest absolute error of f cos relative to the reference's peak (Table 3's), the
    predicted image NMSE against the reference (None if not asked), the metric of the kept
    fit, and the work done (fitted parameters, objective evaluations, direction pairs)."""

    diffuse: BRDF | None
    specular: BRDF | None
    rel_l2: float
    max_rel_pct: float
    max_abs: float
    nmse_pred: float | None
    objective: float
    metric: str
    fitted: int
    evals: int
    directions: int


def _lobes(x: object) -> tuple[str | None, str | None]:
    """"lambert+f_ge" or ("lambert", "f_ge") or "f_ge" -> (diffuse, specular) names."""
    if isinstance(x, str):
        parts = x.split("+")
        if len(parts) == 1:
            return None, parts[0]
        if len(parts) == 2:
            return parts[0] or None, parts[1] or None
        raise _error("candidate %r: one model or diffuse+specular" % x)
    d, s = x  # type: ignore[misc]
    return d, s


def _reference(ref: Reference) -> tuple[BRDF | None, BRDF | None]:
    if isinstance(ref, BRDF):
        return None, ref
    if isinstance(ref, tuple):
        d, s = ref
        return d, s
    sel = ref if isinstance(ref, Selection) else select(ref, goal="photoreal")  # type: ignore[arg-type]
    return sel.diffuse_brdf, sel.specular_brdf


def fit(reference: Reference, candidate: str | tuple[str | None, str | None] | None = None, *,
        to: Reference | None = None, metric: Metric = "l2", resolution: int = 0,
        keep_shared: bool = True, predict: bool = True) -> Fit:
    """Fit a candidate model (or diffuse + specular pair) to a reference (abrdf_fit).

    fit(reference, candidate) or, the same, fit(candidate, to=reference): "fit this model to
    that", as fit("disney_specular", to=abrdf.load_measured("gold.binary")) reads.

    reference: a BRDF; a (diffuse BRDF or None, specular BRDF) pair, whose parameters the
    library reads as one block (the diffuse lobe's from its BRDF); a Selection (its two
    lobes); a material (a table name, a Material or a mapping), whose photoreal choice
    of the flowchart is the reference, as `abrdf fit --material NAME`; or a measured table,
    a Measured or the path of a measured file (an os.PathLike, or a str ending in .binary or
    .bsdf: load_measured reads it), fitted by abrdf_fit_to on the prepared table, as
    `abrdf fit --to FILE` (no parameter is shared with a table). candidate: a model
    name, "diffuse+specular" or a (diffuse, specular) pair of names (either may be None).
    metric: "l2" (cosine-weighted L2), "log", "cbrt" or "auto" (each, the smallest
    predicted image NMSE wins). resolution: direction-set density 1-5 (0: the default, 3).
    keep_shared: a candidate lobe of the same model as a reference lobe keeps the
    reference's parameters. predict: also predict the image NMSE (the default sphere view).
    The minimised objective is the cosine-weighted squared error of f cos over a direction
    set covering the hemisphere; the parameters the model is linear in are solved in closed
    form (variable projection), the rest searched inside the model's range. Invalid input
    (no candidate lobe, unknown model or metric) raises abrdf.Error. Releases the GIL.
    For example fit(BRDF("disney_specular", r=0.5), "blinn_phong").specular.params["n"] is
    the Blinn-Phong exponent closest to that GGX lobe over the hemisphere."""
    if to is not None:
        if candidate is not None:
            raise _error("fit: give the reference first or as to=, not both")
        reference, candidate = to, reference  # type: ignore[assignment]
    if candidate is None:
        raise _error("fit: no candidate (fit(reference, candidate) or fit(candidate, to=...))")
    cd, cs = _lobes(candidate)
    if is_measured_path(reference):
        reference = load_measured(reference)  # type: ignore[arg-type]
    if isinstance(reference, Measured):
        d = _abrdf.fit_to(reference.block, cd, cs, metric, resolution, keep_shared, predict)
    else:
        rd, rs = _reference(reference)
        d = _abrdf.fit(None if rd is None else rd.block, None if rs is None else rs.block, cd,
                       cs, metric, resolution, keep_shared, predict)
    dp, sp = d.pop("diffuse_params"), d.pop("specular_params")
    return Fit(diffuse=None if dp is None else BRDF._from_params(dp),
               specular=None if sp is None else BRDF._from_params(sp), **d)
