"""abrdf.huang_table, abrdf.HuangTable and select(budget=..., reference=...): huang tabulated
from Python is the library's table (abrdf.h, "huang tabulated"), built over threads to the same
bits, read back as the library reads it, and the budget's converged reference."""
import pickle

import numpy as np
import pytest

import abrdf

SMALL = (6, 3, 8, 1)  # the checks are the binding's, not the table's accuracy


@pytest.fixture(scope="module")
def brown():
    """hair_brown's photoreal choice (huang) and its small table."""
    brdf = abrdf.select("hair_brown").specular_brdf
    assert brdf.model == "huang"
    return brdf, abrdf.huang_table(brdf, SMALL, threads=2)


def pairs(n=64, seed=3):
    rng = np.random.default_rng(seed)
    d = rng.normal(size=(2, n, 3))
    d[..., 2] = np.abs(d[..., 2]) + 0.05
    return d[0] / np.linalg.norm(d[0], axis=1)[:, None], d[1] / np.linalg.norm(d[1], axis=1)[:, None]


def test_values_and_eval(brown):
    brdf, t = brown
    assert t.sizes == SMALL and t.brdf == brdf
    count, _ = abrdf._abrdf.huang_table_size(brdf.block, SMALL)
    assert t.values.shape == (count,) and not t.values.flags.writeable
    assert t.block.grid == SMALL[:3]
    # the same bits on one thread; the header's sizes where abrdf.h puts them
    one = abrdf.huang_table(brdf, SMALL, threads=1)
    assert np.array_equal(one.values, t.values)
    assert tuple(t.values[2:6]) == SMALL
    wi, wo = pairs()
    f = t.eval(wi, wo)
    fd = t.eval(wi, wo, precision="double")
    assert f.dtype == np.float32 and f.shape == (64, 3) and fd.dtype == np.float64
    assert np.all(np.isfinite(fd)) and np.all(fd >= 0) and fd.max() > 0
    np.testing.assert_allclose(f, fd, rtol=1e-3, atol=1e-6)
    # not the per-call quadrature (the table averages its shift sets and interpolates)
    assert not np.allclose(fd, brdf.eval(wi, wo, precision="double"), rtol=1e-6)
    # a pickled table is the same table
    back = pickle.loads(pickle.dumps(t))
    assert np.array_equal(back.eval(wi, wo, precision="double"), fd)


def test_cost_is_a_fraction_of_the_quadrature(brown):
    _, t = brown
    cost = t.cost()
    huang = abrdf._abrdf.builtin_costs()["costs"]["huang"]
    assert 0 < cost < huang / 10


def test_budget_against_the_table(brown):
    """The budget's reference is the table: its trace says so, every coarser quadrature is
    predicted against it (error > 0), and the table wins at its cost with error 0; an explicit
    cost no candidate can beat is taken as given."""
    _, t = brown
    s = abrdf.select("hair_brown", budget="slight", reference=t)
    assert (s.specular, s.error_nmse) == ("huang", 0)
    assert "(the photoreal choice, as the caller prepared it)" in s.explain()
    fits = [x for x in s.trace if x.kind == "fit"]
    coarser = [x for x in fits[1:] if x.model == "huang"]
    assert len(coarser) == 4 and all(x.value > 0 for x in coarser)
    assert s.cost_total == fits[0].cost < min(x.cost for x in coarser)
    s2 = abrdf.select("hair_brown", budget="slight", reference=t, reference_cost=1.5)
    assert s2.cost_total == 1.5 and s2.specular == "huang"
    # costs without huang: the table cannot be costed; a cost must then be given
    with pytest.raises(abrdf.Error, match="could not be timed"):
        abrdf.select("hair_brown", budget="slight", reference=t, costs={"lambert": 1.0},
                     cost_unit="ns")


def test_refusals(brown):
    brdf, t = brown
    with pytest.raises(abrdf.Error, match="melanin"):
        abrdf.select("hair_blond", budget="slight", reference=t)
    with pytest.raises(abrdf.Error, match="goes with budget"):
        abrdf.select("hair_brown", reference=t)
    with pytest.raises(abrdf.Error, match="goes with reference"):
        abrdf.select("hair_brown", budget="slight", reference_cost=1.0)
    for bad in (-1.0, float("nan"), float("inf")):
        with pytest.raises(abrdf.Error, match="finite cost"):
            abrdf.select("hair_brown", budget="slight", reference=t, reference_cost=bad)
    with pytest.raises(TypeError, match="read-only"):
        abrdf._abrdf.huang_table(brdf.block, SMALL, t.values.copy())
    with pytest.raises(abrdf.Error, match="huang_table Table"):
        abrdf._abrdf.prepared_cost(t.block, abrdf.BRDF("lambert").block)
    with pytest.raises(TypeError):
        abrdf.select("hair_brown", budget="slight", reference=brdf)
    with pytest.raises(abrdf.Error, match="not huang's"):
        abrdf.huang_table(abrdf.BRDF("lambert"), SMALL)
    with pytest.raises(abrdf.Error, match=r"sizes \(6, 3, 8, 0\)"):
        abrdf.huang_table(brdf, (6, 3, 8, 0))
    with pytest.raises(ValueError, match="four ints"):
        abrdf.huang_table(brdf, (6, 3, 8))
    with pytest.raises(ValueError, match="threads"):
        abrdf.huang_table(brdf, SMALL, threads=-1)
    # a table of other parameters, or bytes that are no table, are refused when prepared
    other = abrdf.BRDF("huang", **{**brdf.params, "melanin": 0.2})
    with pytest.raises(abrdf.Error, match="abrdf_prepare_huang_table"):
        abrdf.HuangTable._from_bytes(other, SMALL, t.values.tobytes())
    with pytest.raises(abrdf.Error, match="abrdf_prepare_huang_table"):
        abrdf.HuangTable._from_bytes(brdf, SMALL, bytes(t.values.nbytes))
