"""The selection: the material table, materials(), material(), select() and its trace."""
from __future__ import annotations

import dataclasses
import difflib
import functools
import os
from dataclasses import dataclass
from importlib import resources
from typing import Any, Literal, Mapping, Sequence, Union

from . import _abrdf
from ._arrays import real_number
from ._brdf import BRDF
from ._hair import HuangTable

RGB = tuple[float, float, float]
PathLike = Union[str, "os.PathLike[str]"]
Goal = Literal["photoreal", "performance"]
Budget = Union[Literal["none", "slight", "noticeable"], float]


@dataclass(frozen=True)
class Layer:
    """One interface of a layer stack and the medium below it (abrdf_layer): relative index
    of refraction, extinction (a conductor if > 0), roughness, absorption per unit depth and
    thickness of the medium."""

    eta: float = 1.5
    kappa: float = 0.0
    r: float = 0.0
    sigma_a: RGB = (0.0, 0.0, 0.0)
    depth: float = 0.0


@dataclass(frozen=True)
class Material:
    """A material as the flowchart reads it (abrdf_material; a row of data/materials.csv,
    docs/SELECTION.md, "The material table"). None leaves a field at the library's default
    (abrdf_material_init: n and r unset, one derived from the other; kd 0.8, ks 1, f0 0.04, eta
    unset, melanin 0.3). source, file and line say where a table entry comes from."""

    name: str | None = None
    type: str = "general"
    n: float | None = None
    r: float | None = None
    kd: RGB | None = None
    ks: RGB | None = None
    f0: RGB | None = None
    eta: float | None = None
    anisotropy: float | None = None
    melanin: float | None = None
    redness: float | None = None
    layers: tuple[Layer, ...] = ()
    source: str = ""
    file: str = ""
    line: int = 0

    def _fields(self) -> dict[str, object]:
        d: dict[str, object] = {}
        for f in dataclasses.fields(self):
            v = getattr(self, f.name)
            if f.name == "layers":
                d["layers"] = [dataclasses.asdict(layer) for layer in v]
            elif v is not None:
                d[f.name] = v
        return d


@dataclass(frozen=True)
class Step:
    """One decision of the flowchart (abrdf_select_step): its kind ("input", "goal",
    "candidate", ...), the model it is about, the number that decided it and what that was
    compared with (inf: no limit; None: not applicable), a second criterion, the model's
    cost, whether the comparison held, and the library's line of text. In the budget mode a
    "fit" step is one candidate: `diffuse` + `model`, value = its predicted image NMSE,
    threshold = the budget, and `params` its fitted parameters (None elsewhere)."""

    kind: str
    model: str | None
    value: float | None
    threshold: float | None
    value2: float | None
    threshold2: float | None
    cost: float | None
    passed: bool
    text: str
    diffuse: str | None = None
    params: dict[str, float | int | tuple[float, float, float]] | None = None


@dataclass(frozen=True)
class Selection:
    """The flowchart's choice (abrdf_selection): the diffuse model (None when the special
    model has its own) and the specular model with their parameter blocks, the exponent and
    roughness used, the predicted error (None where it does not apply), the cost in
    `cost_unit`, and the trace of every decision."""

    material: Material
    goal: str
    type: str
    diffuse: str | None
    specular: str
    n: float
    r: float
    error_rel_pct: float | None
    error_abs: float | None
    error_nmse: float | None
    cost_diffuse: float | None
    cost_specular: float | None
    cost_total: float | None
    cost_unit: str
    diffuse_brdf: BRDF | None
    specular_brdf: BRDF
    trace: tuple[Step, ...]

    def explain(self) -> str:
        """The trace as numbered lines, as `abrdf advise` prints it under "why:"."""
        return "\n".join("%2d. %s" % (i + 1, s.text) for i, s in enumerate(self.trace))


def surfaces() -> list[str]:
    """The surface classes a Material's type names ("general", "cloth_rough", ...)."""
    return _abrdf.surfaces()


def goals() -> list[str]:
    """The goals of the flowchart ("performance", "photoreal")."""
    return _abrdf.goals()


def _material_of(d: Mapping[str, object]) -> Material:
    d = dict(d)
    d["layers"] = tuple(layer if isinstance(layer, Layer) else Layer(**layer)
                        for layer in d.get("layers", ()))  # type: ignore[union-attr]
    return Material(**d)  # type: ignore[arg-type]


def _table_path() -> str:
    """data/materials.csv: $ABRDF_DATA_DIR's (as the command reads it), else the package's."""
    env = os.environ.get("ABRDF_DATA_DIR")
    if env:
        return os.path.join(env, "materials.csv")
    return str(resources.files("abrdf").joinpath("data", "materials.csv"))


@functools.lru_cache(maxsize=8)
def _table(paths: tuple[str, ...]) -> dict[str, Material]:
    return {d["name"]: _material_of(d) for d in _abrdf.load_materials(list(paths))}


def materials(extra: PathLike | Sequence[PathLike] | None = None) -> dict[str, Material]:
    """The material table by name: data/materials.csv (shipped in the package;
    $ABRDF_DATA_DIR/materials.csv when that is set, as for the command), then the files in
    `extra` (same format), each replacing entries of the same name, as
    `abrdf advise --materials FILE`. A malformed file raises abrdf.Error "file:line: ...".
    """
    files = [] if extra is None else [extra] if isinstance(extra, (str, os.PathLike)) else extra
    return dict(_table(tuple([_table_path()] + [os.fspath(f) for f in files])))


def material(name: str, extra: PathLike | Sequence[PathLike] | None = None) -> Material:
    """The table's material `name` (abrdf.Error, with the nearest names, if unknown)."""
    return _lookup(name, extra)


def _lookup(name: str, extra: PathLike | Sequence[PathLike] | None) -> Material:
    table = materials(extra)
    if name in table:
        return table[name]
    near = difflib.get_close_matches(name, list(table), n=5)
    hint = "did you mean: %s? " % ", ".join(near) if near else ""
    err = _abrdf.Error("unknown material '%s'; %s(abrdf.materials() lists the %d known ones)"
                       % (name, hint, len(table)))
    err.status = None
    raise err


def _costs(costs: PathLike | Mapping[str, float] | None,
           cost_unit: str | None) -> tuple[dict[str, float] | None, str | None]:
    if costs is None:
        return None, None
    if isinstance(costs, (str, os.PathLike)):
        d = _abrdf.load_costs(os.fspath(costs))
        return d["costs"], d["unit"]
    return dict(costs), cost_unit or "user costs"


def budget_nmse(budget: Budget) -> float:
    """The largest image NMSE of a budget: a class of the paper's Table 8 ("none" 1e-4,
    "slight" 2.5e-4, "noticeable" 1e-3) or a number in (0, 1]; abrdf.Error otherwise."""
    if isinstance(budget, str):
        return _abrdf.budget_class(budget)
    v = real_number(budget, "budget")
    if not 0.0 < v <= 1.0:
        raise _error("budget %r is not in (0, 1]" % v)
    return v


def _error(message: str) -> _abrdf.Error:
    err = _abrdf.Error(message)
    err.status = None
    return err


def select(material: str | Material | Mapping[str, object] | Any, goal: Goal | None = None,
           max_rel_error: float | None = None, max_abs_error: float | None = None,
           costs: PathLike | Mapping[str, float] | None = None, cost_unit: str | None = None,
           extra: PathLike | Sequence[PathLike] | None = None,
           budget: Budget | None = None, reference: HuangTable | None = None,
           reference_cost: float | None = None) -> Selection:
    """The paper's flowchart (Fig. 2; abrdf_select) for a material and a goal, or the
    selection's budget mode (abrdf_select_budget, docs/SELECTION.md, "The budget mode").

    material: a table name (abrdf.materials(extra)), a Material, a mapping of Material's
    fields, or a glTF / MaterialX material (a PbrMaterial of abrdf.load_gltf or
    abrdf.load_materialx, or a Pbr: abrdf.pbr_material's Material). goal: "photoreal" (the default) or "performance". max_rel_error (percent) and
    max_abs_error: the performance branch's tolerances (None: the library's defaults, 2 %
    and 0.05; math.inf: no limit). costs: None for the paper's Table 4 (in the budget mode:
    the built-in table of measured costs), a cost file of `abrdf calibrate`, or
    {model: cost} in `cost_unit`. budget: a Table-8 class ("none", "slight", "noticeable")
    or an NMSE in (0, 1]: every model or pair that can represent the material's class is
    fitted to the photoreal choice and the cheapest whose predicted image NMSE is below the
    budget wins (costs within 15 % of it count as equal: of those, the smallest predicted
    NMSE); the trace has one "fit" step per candidate. budget excludes goal and the
    tolerances. reference (with budget): the photoreal choice as a HuangTable of its block
    (abrdf.huang_table(select(material).specular_brdf)), nearer the converged model than the
    quadrature: every candidate is then predicted against it, candidate 0 at reference_cost
    (None: reference.cost(costs, cost_unit)); a table of another block raises abrdf.Error
    (docs/SELECTION.md, "A converged reference for hair"). Invalid values raise abrdf.Error
    with the library's message. The same choice as `abrdf advise` (`--budget`,
    `--hair-table`) with the same inputs."""
    if isinstance(material, str):
        mat = _lookup(material, extra)
    elif isinstance(material, Material):
        mat = material
    elif hasattr(material, "_flowchart_material"):  # a Pbr or PbrMaterial (_pbr.py)
        mat = material._flowchart_material()  # type: ignore[union-attr]
    else:
        mat = _material_of(material)
    table, unit = _costs(costs, cost_unit)
    if reference is not None and budget is None:
        raise _error("reference goes with budget: it is the budget's reference")
    if reference_cost is not None and reference is None:
        raise _error("reference_cost goes with reference: it is the reference's cost")
    if budget is not None:
        if goal is not None or max_rel_error is not None or max_abs_error is not None:
            raise _error("budget excludes goal and the tolerances: the budget's reference is "
                         "the photoreal choice")
        if reference is None:
            d = _abrdf.select_budget(mat._fields(), budget_nmse(budget), table, unit)
        else:
            if not isinstance(reference, HuangTable):
                raise TypeError("reference: a HuangTable (abrdf.huang_table) or None, not %r"
                                % (reference,))
            cost = (reference.cost(table, unit) if reference_cost is None
                    else real_number(reference_cost, "reference_cost"))
            if not (0 <= cost < float("inf")):
                raise _error("reference_cost %r: a finite cost >= 0 is needed%s"
                             % (cost, " (the table could not be timed against the costs: give "
                                      "reference_cost)" if reference_cost is None else ""))
            d = _abrdf.select_budget(mat._fields(), budget_nmse(budget), table, unit,
                                     reference.block, cost)
    else:
        rules = _abrdf.rules()
        rel = (rules["default_max_rel_pct"] if max_rel_error is None
               else real_number(max_rel_error, "max_rel_error"))
        abs_ = (rules["default_max_abs"] if max_abs_error is None
                else real_number(max_abs_error, "max_abs_error"))
        d = _abrdf.select(mat._fields(), goal or "photoreal", rel, abs_, table, unit)
    trace = tuple(Step(**s) for s in d.pop("trace"))
    dp = d.pop("diffuse_params")
    sp = d.pop("specular_params")
    return Selection(material=mat, trace=trace,
                     diffuse_brdf=None if dp is None else BRDF._from_params(dp),
                     specular_brdf=BRDF._from_params(sp), **d)
