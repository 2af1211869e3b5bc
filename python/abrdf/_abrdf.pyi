"""Types of the extension module abrdf._abrdf (python/src): libabrdf's C API for the package.

Arrays go in and out through the buffer protocol: C-contiguous float32/float64 blocks, as
numpy.ascontiguousarray makes them; the package (abrdf/_brdf.py, ...) shapes them, after
abrdf/_arrays.py has refused what is not numbers.
"""
from typing import Any, Mapping, Sequence, TypedDict, Union

# An object with the buffer protocol (PEP 688's collections.abc.Buffer, Python 3.12+).
Buffer = Any

MAX_LAYERS: int

class Error(ValueError):
    """A failure of libabrdf: its message; `status` is its abrdf_status code (negative), or
    None when the package itself found the problem."""

    status: int | None

# A parameter's value: a real number (int, float, or another numbers.Real such as NumPy's
# integer and floating scalars) or, for a colour, three. bool, complex, None, strings and
# datetimes raise TypeError ("parameter 'r': a real number is needed, got complex"), as
# material fields and costs do.
ParamValue = Union[float, int, Sequence[float]]

class Params:
    """A parameter block validated for one model (abrdf_params_init, abrdf_param_set,
    abrdf_params_check)."""

    def __init__(self, model: str, values: Mapping[str, ParamValue] = ...) -> None: ...
    @property
    def model(self) -> str: ...
    def values(self) -> dict[str, float | int | tuple[float, float, float]]: ...

class Table:
    """The `measured` model prepared on a C-contiguous float32 buffer of
    3 * n_theta_h * n_theta_d * n_phi_d values (abrdf_prepare_measured), or huang on its table
    (huang_table), held while the Table lives; taken wherever a Params is by eval_float and
    eval_double."""

    def __init__(self, data: Buffer, n_theta_h: int, n_theta_d: int, n_phi_d: int) -> None: ...
    @property
    def grid(self) -> tuple[int, int, int]: ...

class _MeasuredDict(TypedDict):
    data: bytes
    grid: tuple[int, int, int]
    unmeasured: int
    format: str

class _ParamDict(TypedDict):
    name: str
    help: str
    kind: str
    default: float
    min: float
    max: float

class _ModelDict(TypedDict):
    id: int
    name: str
    title: str
    equation: str
    citation: str
    needs: tuple[str, ...]
    reciprocal: bool
    energy_conserving: bool
    kind: str
    paper_cycles: int | None
    params: tuple[_ParamDict, ...]

def version() -> str: ...
def models() -> list[_ModelDict]: ...
def params() -> list[_ParamDict]: ...
# params: one block, or a material's lobes (a tuple or list of 1 to 4096 blocks), summed in
# their order in one pass over the rows.
def eval_float(params: Params | Table | Sequence[Params | Table], wi: Buffer, wo: Buffer,
               out: Buffer, threads: int = 0) -> None: ...
def eval_double(params: Params | Table, wi: Buffer, wo: Buffer, out: Buffer) -> None: ...
# layout 0: abrdf_eval_batch on structure-of-arrays copies; 1: abrdf_eval_prepared_rows
def _time_eval_batch(params: Params, wi: Buffer, wo: Buffer, out: Buffer,
                     calls: int, layout: int = 0) -> float: ...
def load_materials(paths: list[str]) -> list[dict[str, Any]]: ...
def load_costs(path: str) -> dict[str, Any]: ...
def paper_costs() -> dict[str, Any]: ...
def builtin_costs() -> dict[str, Any]: ...
def select(material: dict[str, Any], goal: str, max_rel_pct: float = ..., max_abs: float = ...,
           costs: dict[str, float] | None = ..., cost_unit: str | None = ...) -> dict[str, Any]: ...
def select_budget(material: dict[str, Any], max_nmse: float,
                  costs: dict[str, float] | None = ...,
                  cost_unit: str | None = ..., reference: Table | None = ...,
                  reference_cost: float = ...) -> dict[str, Any]: ...
def prepared_cost(prepared: Table, params: Params, costs: dict[str, float] | None = ...,
                  cost_unit: str | None = ...) -> float: ...
def budget_class(name: str) -> float: ...
def fit(ref_diffuse: Params | None, ref_specular: Params | None, cand_diffuse: str | None,
        cand_specular: str | None, metric: str = ..., resolution: int = ...,
        keep_shared: bool = ..., predict: bool = ...) -> dict[str, Any]: ...
def fit_to(reference: Table | Params, cand_diffuse: str | None, cand_specular: str | None,
           metric: str = ..., resolution: int = ..., keep_shared: bool = ...,
           predict: bool = ...) -> dict[str, Any]: ...
def surfaces() -> list[str]: ...
def goals() -> list[str]: ...
def rules() -> dict[str, Any]: ...
def compare(reference: Buffer, test: Buffer) -> dict[str, Any]: ...
def read_measured(path: str) -> _MeasuredDict: ...
# huang tabulated (abrdf.h): sizes = (theta nodes, view azimuths, light azimuths, shift sets)
def huang_table_size(params: Params, sizes: tuple[int, int, int, int]) -> tuple[int, int]: ...
def huang_table_build(params: Params, sizes: tuple[int, int, int, int], row0: int, row1: int,
                      data: Buffer) -> None: ...
def huang_table(params: Params, sizes: tuple[int, int, int, int], data: Buffer) -> Table: ...
# glTF metallic-roughness materials (abrdf_pbr.h): abrdf.Pbr's fields over glTF's defaults.
def pbr_check(fields: dict[str, Any]) -> None: ...
def pbr_lobes(fields: dict[str, Any]) -> list[Params]: ...
def pbr_material(fields: dict[str, Any]) -> dict[str, Any]: ...
