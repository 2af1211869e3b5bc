"""A material library against candidate models (sweep): every material fitted by every candidate
(abrdf.fit), its predicted image NMSE, its cost and whether it is within a budget, and per
material the cheapest candidate within it; on dask.distributed (a local cluster of processes,
or a real one) or in a plain loop, with the same result."""
from __future__ import annotations

import functools
import os
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Callable, Mapping, Sequence, Union

from . import _abrdf
from ._brdf import BRDF
from ._fit import Fit, Metric, Reference, _lobes, _reference, fit
from ._measured import Measured, is_measured_path, load_measured
from ._select import Budget, Material, _error, budget_nmse

if TYPE_CHECKING:
    from distributed import Client

Candidate = Union[str, tuple]
Scheduler = Union[None, str, "Client"]

# The budget mode's rule (libabrdf/src/selection/budget.c, COST_TIE; docs/SELECTION.md): costs
# within 15 % of the cheapest within the budget are not told apart, and of those the smallest
# predicted NMSE wins.
COST_TIE = 0.15
# Measured files a worker keeps loaded (a MERL table is 17 MB): tasks of one file that
# follow each other read it once.
_LOADED_MAX = 8


@dataclass(frozen=True)
class SweepRow:
    """One material fitted by one candidate: the material's index in the list given and its
    name, the candidate ("blinn_phong", "lambert+f_ge"), the fit (abrdf.Fit: the fitted lobes,
    the errors, nmse_pred), its cost (the sum of its lobes' in the cost table; None when the
    table lacks one) and whether its predicted NMSE is below the budget's."""

    material: int
    name: str
    candidate: str
    fit: Fit
    cost: float | None
    within: bool

    @property
    def nmse_pred(self) -> float:
        """The predicted image NMSE against the material (abrdf.Fit.nmse_pred)."""
        return self.fit.nmse_pred  # type: ignore[return-value]


@dataclass(frozen=True)
class Sweep:
    """The rows, material by material in the order given and, within one, the candidates in
    the order given; per material the cheapest row within the budget (None if none is), as
    the budget mode chooses (costs within 15 % count as equal, then the smallest predicted
    NMSE); the budget as an NMSE; the costs' unit."""

    rows: tuple[SweepRow, ...]
    best: tuple[SweepRow | None, ...]
    max_nmse: float
    cost_unit: str

    def text(self) -> str:
        """The rows as a fixed-width table, the best of each material marked with '*'."""
        lines = ["%-24s %-28s %12s %10s  %s" % ("material", "candidate", "nmse_pred", "cost",
                                              "within")]
        for r in self.rows:
            mark = "*" if self.best[r.material] is r else ""
            cost = "-" if r.cost is None else "%.4g" % r.cost
            lines.append("%-24s %-28s %12.4g %10s  %s%s" % (r.name[-24:], r.candidate,
                                                           r.nmse_pred, cost,
                                                           "yes" if r.within else "no", mark))
        return "\n".join(lines)


def _name(m: object, i: int) -> str:
    if is_measured_path(m):
        return os.fspath(m)  # type: ignore[arg-type]
    if isinstance(m, Measured):
        return m.path if m.path is not None else "table #%d" % i
    if isinstance(m, str):
        return m
    if isinstance(m, BRDF):
        return m.model
    if isinstance(m, Material) and m.name:
        return m.name
    if isinstance(m, Mapping) and isinstance(m.get("name"), str):
        return m["name"]  # type: ignore[return-value]
    return "%s #%d" % (type(m).__name__, i)


def _candidate_name(c: Candidate) -> str:
    d, s = _lobes(c)
    return "+".join(x for x in (d, s) if x)


@functools.lru_cache(maxsize=_LOADED_MAX)
def _loaded_version(path: str, version: tuple[int, ...]) -> Measured:
    return load_measured(path)


def _loaded(path: str) -> Measured:
    """The file read, or the copy read before if it has not changed since (a worker that
    outlives one sweep sees a rewritten file anew). A file's version is its inode with its
    change and modification times and size: abrdf writes a file whole by renaming a new one
    over it, so a rewrite within one tick of the file system's clock is still seen."""
    try:
        st = os.stat(path)
    except OSError:
        return load_measured(path)  # raises abrdf.Error with the reader's words
    return _loaded_version(path, (st.st_dev, st.st_ino, st.st_ctime_ns, st.st_mtime_ns,
                                  st.st_size))


def _shippable(m: object) -> tuple[Any, ...]:
    """What a task needs of material m, small where it can be: a measured file's path (the
    worker reads it), a Measured as is (scattered once), anything else resolved here into its
    reference lobes (abrdf.fit's, two small BRDFs)."""
    if is_measured_path(m):
        return ("path", os.fspath(m))  # type: ignore[arg-type]
    if isinstance(m, Measured):
        return ("table", m)
    return ("lobes", _reference(m))  # type: ignore[arg-type]


def _fit_one(ref: tuple[Any, ...], candidate: Candidate, metric: Metric,
             resolution: int) -> Fit:
    """One task: material `ref` (from _shippable) fitted by one candidate."""
    kind, what = ref
    reference: Reference = _loaded(what) if kind == "path" else what
    return fit(reference, candidate, metric=metric, resolution=resolution)


def _costs(costs: str | os.PathLike[str] | Mapping[str, float] | None,
           cost_unit: str | None) -> tuple[dict[str, float], str]:
    if costs is None:
        d = _abrdf.builtin_costs()
        return d["costs"], d["unit"]
    if isinstance(costs, (str, os.PathLike)):
        d = _abrdf.load_costs(os.fspath(costs))
        return d["costs"], d["unit"]
    return dict(costs), cost_unit or "user costs"


def _cost(table: Mapping[str, float], c: Candidate) -> float | None:
    total = 0.0
    for lobe in _lobes(c):
        if lobe:
            if lobe not in table:
                return None
            total += table[lobe]
    return total


def _best(rows: Sequence[SweepRow]) -> SweepRow | None:
    ok = [r for r in rows if r.within and r.cost is not None]
    if not ok:
        return None
    cheapest = min(r.cost for r in ok)  # type: ignore[type-var]
    tied = [r for r in ok if r.cost <= cheapest * (1.0 + COST_TIE)]  # type: ignore[operator]
    return min(tied, key=lambda r: r.nmse_pred)  # the first of equal NMSEs: the order given


def _run_serial(jobs: list[tuple[tuple[Any, ...], Candidate]], metric: Metric,
                resolution: int) -> list[Fit]:
    try:
        return [_fit_one(ref, c, metric, resolution) for ref, c in jobs]
    finally:
        _loaded_version.cache_clear()  # the caller's process keeps no table


def _run_dask(client: Client, jobs: list[tuple[tuple[Any, ...], Candidate]], metric: Metric,
              resolution: int) -> list[Fit]:
    # A Measured goes to the cluster once, whatever the number of its tasks.
    scattered: dict[int, Any] = {}
    shipped = []
    for ref, c in jobs:
        if ref[0] == "table":
            key = id(ref[1])
            if key not in scattered:
                scattered[key] = client.scatter(ref[1], hash=False)
            ref = ("table", scattered[key])
        shipped.append((ref, c))
    futures = [client.submit(_fit_task, ref[0], ref[1], c, metric, resolution, pure=False)
               for ref, c in shipped]
    return client.gather(futures)


def _fit_task(kind: str, what: Any, candidate: Candidate, metric: Metric,
              resolution: int) -> Fit:
    # dask resolves a scattered future given as an argument, not one inside a tuple.
    return _fit_one((kind, what), candidate, metric, resolution)


def _usable_cores() -> int:
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # not Linux
        return os.cpu_count() or 1


def _with_client(scheduler: Scheduler, workers: int | None,
                 run: Callable[[Client], list[Fit]]) -> list[Fit]:
    try:
        from distributed import Client, LocalCluster
    except ImportError as e:
        raise ImportError("abrdf.sweep on a cluster needs dask.distributed (pip install "
                          "distributed), or scheduler='serial'") from e
    if isinstance(scheduler, Client):
        return run(scheduler)
    if scheduler is not None and not (isinstance(scheduler, str) and "://" in scheduler):
        raise ValueError("sweep: scheduler is None, 'serial', a scheduler's address "
                         "('tcp://host:8786') or a distributed.Client, got %r" % (scheduler,))
    if scheduler is None:
        n = _usable_cores() if workers is None else workers
        with LocalCluster(n_workers=n, threads_per_worker=1, processes=True,
                          dashboard_address=None) as cluster, Client(cluster) as client:
            return run(client)
    with Client(scheduler) as client:
        return run(client)


def sweep(materials: Sequence[object], models: Sequence[Candidate], budget: Budget = "slight",
          *, costs: str | os.PathLike[str] | Mapping[str, float] | None = None,
          cost_unit: str | None = None, metric: Metric = "l2", resolution: int = 0,
          scheduler: Scheduler = None, workers: int | None = None) -> Sweep:
    """Every material fitted by every candidate model, with the predicted image NMSE, the
    cost and the verdict against `budget`, and per material the cheapest candidate within it.

    materials: each a Measured, the path of a measured file (an os.PathLike, or a str ending
    in .binary or .bsdf), or anything abrdf.fit takes as a reference (a BRDF, a (diffuse,
    specular) pair of BRDFs, a Selection, a material name, a Material or a mapping).
    models: each a model name, "diffuse+specular" or a (diffuse, specular) pair of names.
    budget: a Table-8 class ("none", "slight", "noticeable") or an NMSE in (0, 1]; a row is
    within it when its predicted NMSE is below. costs: None for the built-in table of
    measured costs (the budget mode's, abrdf_costs_builtin), a cost file of `abrdf
    calibrate`, or {model: cost} in `cost_unit`; a pair costs the sum of its lobes'. metric,
    resolution: abrdf.fit's.

    scheduler: None (default) starts a dask.distributed LocalCluster of `workers` processes
    (default: one per usable core), one thread each, for this call; "serial" runs the plain
    loop in this process; an address ("tcp://host:8786") connects to a running scheduler; a
    distributed.Client is used as it is. One task per (material, candidate). A material given
    as a path travels as its path and each worker reads the file (keeping the last few it
    read); a Measured travels once (Client.scatter) and its tasks share it; other materials
    travel as their two small reference lobes. Every fit is deterministic, so the result is
    the serial loop's, number for number and in the same order, on workers that run the same
    build on the same kind of processor. A failed fit raises its abrdf.Error here."""
    max_nmse = budget_nmse(budget)
    table, unit = _costs(costs, cost_unit)
    materials = list(materials)
    models = list(models)
    if not models:
        raise _error("sweep: no candidate model")
    names = [_candidate_name(c) for c in models]
    jobs = [(_shippable(m), c) for m in materials for c in models]
    if scheduler == "serial":
        if workers is not None:
            raise TypeError("sweep: workers is for the local cluster, not scheduler='serial'")
        fits = _run_serial(jobs, metric, resolution)
    else:
        if workers is not None and scheduler is not None:
            raise TypeError("sweep: workers is for the local cluster (scheduler=None)")
        if workers is not None and not (isinstance(workers, int) and workers >= 1):
            raise ValueError("sweep: workers must be an int >= 1, got %r" % (workers,))
        fits = _with_client(scheduler, workers,
                            lambda client: _run_dask(client, jobs, metric, resolution))
    rows = []
    k = 0
    for i, m in enumerate(materials):
        name = _name(m, i)
        for c, cname in zip(models, names):
            f = fits[k]
            k += 1
            rows.append(SweepRow(material=i, name=name, candidate=cname, fit=f,
                                 cost=_cost(table, c),
                                 within=f.nmse_pred is not None and f.nmse_pred < max_nmse))
    n = len(models)
    best = tuple(_best(rows[i * n:(i + 1) * n]) for i in range(len(materials)))
    return Sweep(rows=tuple(rows), best=best, max_nmse=max_nmse, cost_unit=unit)
