"""abrdf.sweep: a material library against candidate models, on dask.distributed and in a plain
loop, with the same result number for number. dask.distributed is a test dependency
(scripts/setup_python.sh): without it this module fails to import, it does not skip."""
import math
import os

import distributed
import pytest

import abrdf

CANDIDATES = ["blinn_phong", "f_ge", "lambert+disney_specular"]


def materials():
    return ["gold", abrdf.BRDF("disney_specular", r=0.4),
            (abrdf.BRDF("lambert", kd=0.3), abrdf.BRDF("f_ge", n=80))]


@pytest.fixture(scope="module")
def serial():
    return abrdf.sweep(materials(), CANDIDATES, "slight", scheduler="serial")


def test_rows_are_the_fits_in_order(serial):
    assert len(serial.rows) == 9 and len(serial.best) == 3
    assert [(r.material, r.candidate) for r in serial.rows] == [
        (i, c) for i in range(3) for c in CANDIDATES]
    assert [r.name for r in serial.rows[::3]] == ["gold", "disney_specular", "tuple #2"]
    assert serial.max_nmse == abrdf.budget_nmse("slight") == 2.5e-4
    for r, m in zip(serial.rows, [m for m in materials() for _ in CANDIDATES]):
        f = abrdf.fit(m, r.candidate)
        assert r.fit == f  # the same fit, parameters and numbers
        assert r.nmse_pred == f.nmse_pred and r.within == (f.nmse_pred < 2.5e-4)


def test_costs_and_the_cheapest_within_the_budget(serial):
    table = abrdf._abrdf.builtin_costs()
    assert serial.cost_unit == table["unit"]
    costs = table["costs"]
    for r in serial.rows:
        want = sum(costs[x] for x in r.candidate.split("+"))
        assert r.cost == pytest.approx(want, rel=1e-15)
    for i, best in enumerate(serial.best):
        rows = [r for r in serial.rows if r.material == i and r.within]
        if not rows:
            assert best is None
            continue
        cheapest = min(r.cost for r in rows)
        tied = [r for r in rows if r.cost <= cheapest * 1.15]
        assert best is min(tied, key=lambda r: r.nmse_pred)
    # gold's own photoreal choice fits it exactly: within any budget
    assert serial.best[0].candidate == "lambert+disney_specular" and serial.best[0].nmse_pred == 0
    assert "*" in serial.text().splitlines()[3]


def test_budget_and_costs_given():
    s = abrdf.sweep(["gold"], ["blinn_phong", "f_ge"], 1.0, costs={"blinn_phong": 2.0},
                    cost_unit="units", scheduler="serial")
    assert s.cost_unit == "units" and s.max_nmse == 1.0
    assert [r.cost for r in s.rows] == [2.0, None]
    assert all(r.within for r in s.rows)
    assert s.best[0].candidate == "blinn_phong"  # f_ge's cost is unknown: never the best


def test_bad_arguments():
    with pytest.raises(abrdf.Error):
        abrdf.sweep(["gold"], ["blinn_phong"], "huge", scheduler="serial")
    with pytest.raises(abrdf.Error):
        abrdf.sweep(["gold"], [], scheduler="serial")
    with pytest.raises(abrdf.Error):
        abrdf.sweep(["gold"], ["no_such_model"], scheduler="serial")
    with pytest.raises(TypeError):
        abrdf.sweep(["gold"], ["blinn_phong"], scheduler="serial", workers=2)
    with pytest.raises(ValueError):
        abrdf.sweep(["gold"], ["blinn_phong"], workers=0)
    with pytest.raises(ValueError):
        abrdf.sweep(["gold"], ["blinn_phong"], scheduler="serail")


def test_local_cluster_of_two_workers_equals_the_loop(serial):
    d = abrdf.sweep(materials(), CANDIDATES, "slight", workers=2)
    assert d == serial  # every number, every fitted parameter, the same order
    assert [r.fit.nmse_pred for r in d.rows] == [r.fit.nmse_pred for r in serial.rows]


def test_a_client_given_is_used_and_left_open(serial):
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        assert abrdf.sweep(materials(), CANDIDATES, "slight", scheduler=client) == serial
        assert abrdf.sweep(materials(), CANDIDATES, "slight",
                           scheduler=cluster.scheduler_address) == serial
        assert client.status == "running"
        # a failed fit on a worker raises its abrdf.Error here
        with pytest.raises(abrdf.Error):
            abrdf.sweep(["gold"], ["no_such_model"], scheduler=client)
    assert not math.isnan(serial.max_nmse)


def test_a_worker_rereads_a_rewritten_file(cli, tmp_path):
    from abrdf import _sweep
    path = str(tmp_path / "t.binary")
    cli("tabulate", "lambert", "--set", "kd=0.5", "--grid", "4,4,8", "-o", path)
    first = _sweep._loaded(path)
    assert _sweep._loaded(path) is first  # read once
    stamp = os.stat(path).st_mtime_ns
    cli("tabulate", "lambert", "--set", "kd=0.25", "--grid", "4,4,8", "-o", path)
    # The same size and, as on a file system with a coarse clock, the same modification time.
    os.utime(path, ns=(stamp, stamp))
    again = _sweep._loaded(path)
    assert again is not first and again.table.max() < first.table.max()
    _sweep._loaded_version.cache_clear()
