"""Measured materials from Python (docs/PYTHON.md, "Measured materials and library sweeps"):
load_measured reads what `abrdf tabulate` writes as `abrdf inspect` reads it, Measured.eval
is the library's `measured` model on the table (checked against the grid's own nodes and
midpoints, computed here in NumPy), measured_from_array refuses what is not a table."""
import gc
import math
import os
import pickle

import numpy as np
import pytest

import abrdf
from abrdf import _abrdf

HALF_PI = math.pi / 2


def tabulate(cli, tmp_path, name, *args):
    path = os.path.join(str(tmp_path), name)
    cli("tabulate", *args, "-o", path)
    return path


def inspect_numbers(m):
    """What `abrdf inspect --json` reports, computed from a Measured's table in NumPy (the
    command's rules: cmd_inspect.c)."""
    t = m.table
    nh, nd, nphi = m.grid
    measured = t >= 0
    max_fr = [float(t[..., c][measured[..., c]].max()) for c in range(3)]
    theta = (np.arange(360) + 0.5) * (HALF_PI / 360)
    half = theta / 2
    ih = np.minimum((np.sqrt(half / HALF_PI) * nh).astype(int), nh - 1)
    idd = np.minimum((half / HALF_PI * nd).astype(int), nd - 1)
    f = t[ih, idd, 0].astype(np.float64)
    albedo = None
    if (f >= 0).all():
        w = 4 * HALF_PI * np.cos(theta) * np.sin(theta) * (HALF_PI / 360)
        albedo = [float(np.sum(f[:, c] * w)) for c in range(3)]
    return max_fr, albedo


def node_directions(grid, ih, idd, ip):
    """wi, wo of grid coordinates (fractional allowed), phi_h = 0: the grid's parametrisation
    (measured_table.h; Rusinkiewicz 1998)."""
    nh, nd, nphi = grid
    u = np.asarray(ih, float) / nh
    th = u * u * HALF_PI
    td = np.asarray(idd, float) / nd * HALF_PI
    pd = np.asarray(ip, float) / nphi * math.pi
    d = np.stack([np.sin(td) * np.cos(pd), np.sin(td) * np.sin(pd), np.cos(td)], axis=-1)
    wi = np.stack([d[..., 0] * np.cos(th) + d[..., 2] * np.sin(th), d[..., 1],
                   -d[..., 0] * np.sin(th) + d[..., 2] * np.cos(th)], axis=-1)
    h = np.stack([np.sin(th), 0 * th, np.cos(th)], axis=-1)
    wo = 2 * np.sum(wi * h, axis=-1, keepdims=True) * h - wi
    return wi, wo


@pytest.mark.parametrize("model,sets,grid", [
    ("lambert", ["kd=0.5"], "16,16,32"),
    ("disney_specular", ["r=0.35", "f0=0.9,0.6,0.3"], "16,16,32"),
    ("blinn_phong", ["n=40"], None),  # MERL's grid, 90 x 90 x 180
])
def test_load_measured_reads_what_tabulate_wrote(cli, tmp_path, model, sets, grid):
    args = [model] + [x for s in sets for x in ("--set", s)]
    if grid:
        args += ["--grid", grid]
    path = tabulate(cli, tmp_path, model + ".binary", *args)
    m = abrdf.load_measured(path)
    ref = cli("inspect", path, "--json")
    assert m.path == path and m.format == ref["format"] == "MERL BRDF database"
    assert list(m.grid) == ref["grid"]
    assert m.table.shape == tuple(ref["grid"]) + (3,) and m.table.dtype == np.float32
    assert m.table.flags.c_contiguous and not m.table.flags.writeable
    assert m.unmeasured == ref["unmeasured"]
    max_fr, albedo = inspect_numbers(m)
    assert max_fr == pytest.approx(ref["max_f_r"], rel=1e-9)
    assert albedo == pytest.approx(ref["albedo_normal"], rel=1e-9)
    # The file's bytes: MERL stores red, green, blue planes of doubles after a 12-byte header.
    raw = np.fromfile(path, dtype="<f8", offset=12).reshape(3, -1).T
    scales = np.array([1 / 1500, 1.15 / 1500, 1.66 / 1500])
    want = np.where(raw < 0, -1.0, raw * scales).astype(np.float32)
    np.testing.assert_array_equal(m.table.reshape(-1, 3), want)


def test_lambert_table_evaluates_to_kd_over_pi(cli, tmp_path):
    m = abrdf.load_measured(tabulate(cli, tmp_path, "l.binary", "lambert", "--set", "kd=0.5",
                                     "--grid", "16,16,32"))
    rng = np.random.default_rng(1)
    wi = rng.normal(size=(1000, 3))
    wo = rng.normal(size=(1000, 3))
    wi[:, 2] = np.abs(wi[:, 2]) + 0.05
    wo[:, 2] = np.abs(wo[:, 2]) + 0.05
    f = m.eval(wi, wo)
    assert f.dtype == np.float32 and f.shape == (1000, 3)
    np.testing.assert_allclose(f, 0.5 / math.pi, rtol=1e-5)
    d = abrdf.eval(m, wi, wo, precision="double")
    assert d.dtype == np.float64
    np.testing.assert_allclose(d, float(np.float32(0.5 / math.pi)), rtol=1e-12)  # the cells
    # below the horizon: 0, as every model
    assert np.all(abrdf.eval(m, [0, 0, -1], [0, 0, 1]) == 0)


def random_table(grid, seed=3):
    return np.random.default_rng(seed).uniform(0.1, 1.0, size=grid + (3,)).astype(np.float32)


def interior_nodes(grid):
    """Nodes inside the grid whose directions, and those half a cell further along theta_d,
    are above the horizon (theta_h + theta_d < 90 degrees)."""
    nh, nd, nphi = grid
    ih, idd, ip = np.meshgrid(np.arange(1, nh - 1), np.arange(1, nd // 2 - 1),
                              np.arange(0, nphi, 3), indexing="ij")
    return ih.ravel(), idd.ravel(), ip.ravel()


def test_eval_at_nodes_and_midpoints_of_a_numpy_table():
    grid = (8, 10, 12)
    t = random_table(grid)
    m = abrdf.measured_from_array(t)
    assert m.grid == grid and m.unmeasured == 0 and m.path is None and m.format is None
    np.testing.assert_array_equal(m.table, t)
    ih, idd, ip = interior_nodes(grid)
    wi, wo = node_directions(grid, ih, idd, ip)
    np.testing.assert_allclose(m.eval(wi, wo, precision="double"), t[ih, idd, ip], rtol=1e-9)
    np.testing.assert_allclose(m.eval(wi, wo), t[ih, idd, ip], rtol=2e-3)
    # half way along theta_d: the mean of the two nodes (trilinear)
    wi, wo = node_directions(grid, ih, idd + 0.5, ip)
    want = (t[ih, idd, ip].astype(np.float64) + t[ih, idd + 1, ip]) / 2
    np.testing.assert_allclose(m.eval(wi, wo, precision="double"), want, rtol=1e-9)
    np.testing.assert_allclose(m.eval(wi, wo), want, rtol=2e-3)
    # reciprocal (the parametrisation is; the angles of swapped directions round apart)
    np.testing.assert_allclose(m.eval(wi, wo, precision="double"),
                               m.eval(wo, wi, precision="double"), rtol=1e-12)


def test_unmeasured_cells_drop_out():
    grid = (8, 10, 12)
    t = random_table(grid)
    t[3, 4, 6] = -1.0  # one cell not measured: between it and its neighbour, the neighbour
    t[3, 2, 6, 1] = -1.0  # one channel of another
    m = abrdf.measured_from_array(t)
    assert m.unmeasured == 2
    wi, wo = node_directions(grid, 3, 3.5, 6)
    np.testing.assert_allclose(m.eval(wi, wo, precision="double"), t[3, 3, 6], rtol=1e-9)
    wi, wo = node_directions(grid, 3, 2.5, 6)
    f = m.eval(wi, wo, precision="double")
    assert f[1] == pytest.approx(t[3, 3, 6, 1], rel=1e-9)
    assert f[0] == pytest.approx((float(t[3, 2, 6, 0]) + float(t[3, 3, 6, 0])) / 2, rel=1e-9)


def test_from_array_copies_and_converts():
    t = random_table((4, 4, 6)).astype(np.float64)
    m = abrdf.measured_from_array(t)
    t[:] = 0  # the caller's array is not the table
    assert m.table.min() > 0
    i = abrdf.measured_from_array(np.ones((2, 3, 4, 3), dtype=np.int16))
    assert i.table.dtype == np.float32 and np.all(i.table == 1)
    f = abrdf.measured_from_array(np.asfortranarray(random_table((4, 5, 6))))
    assert f.table.flags.c_contiguous
    with pytest.raises(ValueError):
        m.table[0, 0, 0, 0] = 1.0  # read-only: the prepared model points at it
    with pytest.raises(ValueError):
        m.table.flags.writeable = True


@pytest.mark.parametrize("array,error,words", [
    (np.ones((4, 4, 3)), ValueError, "shape (n_theta_h, n_theta_d, n_phi_d, 3)"),
    (np.ones((4, 4, 4, 2)), ValueError, "shape (n_theta_h, n_theta_d, n_phi_d, 3)"),
    (np.ones((1, 4, 4, 3)), ValueError, "each axis must be in [2, 1024]"),
    (np.ones((2, 2, 1025, 3)), ValueError, "each axis must be in [2, 1024]"),
    (np.ones((4, 4, 4, 3), dtype=complex), TypeError, "a real number array is needed"),
    (np.ones((4, 4, 4, 3), dtype=bool), TypeError, "a real number array is needed"),
    (np.full((4, 4, 4, 3), None), TypeError, "a real number array is needed"),
    ("table", TypeError, "a real number array is needed"),
])
def test_from_array_refuses_what_is_not_a_table(array, error, words):
    with pytest.raises(error) as e:
        abrdf.measured_from_array(array)
    assert words in str(e.value)


@pytest.mark.parametrize("value,shown", [(np.nan, "nan"), (np.inf, "inf"), (-np.inf, "-inf"),
                                         (1e300, "inf")])
def test_from_array_refuses_non_finite_values(value, shown):
    t = np.ones((4, 4, 4, 3))
    t[1, 2, 3, 1] = value
    with pytest.raises(ValueError) as e:
        abrdf.measured_from_array(t)
    assert str(e.value).startswith("table[1, 2, 3, 1] = %s (as float32)" % shown)
    assert "never NaN or an infinity" in str(e.value)


def test_the_readers_words(cli, tmp_path):
    good = tabulate(cli, tmp_path, "g.binary", "lambert", "--grid", "4,4,8")
    cut = os.path.join(str(tmp_path), "cut.binary")
    with open(good, "rb") as f, open(cut, "wb") as g:
        g.write(f.read(100))
    for path in (cut, os.path.join(str(tmp_path), "missing.binary"),
                 os.path.join(str(tmp_path), "table.txt"), str(tmp_path)):
        r = cli("inspect", path, check=False)
        assert r.returncode != 0
        with pytest.raises(abrdf.Error) as e:
            abrdf.load_measured(path)
        assert e.value.status == -7  # ABRDF_E_TABLE
        assert r.stderr.strip() == "abrdf inspect: " + str(e.value)


def test_rgl_file_reads_onto_merls_grid(cli, tmp_path):
    path = tabulate(cli, tmp_path, "l.bsdf", "lambert", "--set", "kd=0.5")
    m = abrdf.load_measured(path)
    ref = cli("inspect", path, "--json")
    assert m.grid == (90, 90, 180) and list(m.grid) == ref["grid"]
    assert m.unmeasured == ref["unmeasured"] and m.format == ref["format"]
    f = m.eval([0.3, 0.1, 1.0], [-0.2, 0.1, 1.0], precision="double")
    np.testing.assert_allclose(f, 0.5 / math.pi, rtol=1e-3)


def test_the_table_lives_as_long_as_the_prepared_object():
    t = random_table((6, 6, 8))
    m = abrdf.measured_from_array(t)
    block = m.block
    wi, wo = node_directions((6, 6, 8), 2, 2, 3)
    want = m.eval(wi, wo, precision="double")
    del m
    gc.collect()
    junk = [np.full(6 * 6 * 8 * 3, 7.0, np.float32) for _ in range(50)]  # reuse freed memory
    out = np.empty((1, 3))
    _abrdf.eval_double(block, wi.reshape(1, 3), wo.reshape(1, 3), out)
    np.testing.assert_array_equal(out[0], want)
    assert len(junk) == 50
    with pytest.raises(abrdf.Error):
        _abrdf.Table(np.zeros(10, np.float32), 2, 2, 2)
    with pytest.raises(TypeError):
        _abrdf.Table(np.zeros(24, np.float64), 2, 2, 2)
    with pytest.raises(abrdf.Error):
        _abrdf.Table(np.zeros(3, np.float32), 1, 1, 1)
    with pytest.raises(abrdf.Error):
        _abrdf.Table(np.zeros(0, np.float32), 0, 4, 4)
    with pytest.raises(abrdf.Error):  # the product of the axes would overflow
        _abrdf.Table(np.zeros(24, np.float32), 2 ** 31 - 1, 2 ** 31 - 1, 2 ** 31 - 1)


def test_pickle_keeps_the_table():
    m = abrdf.measured_from_array(random_table((4, 5, 6)))
    m2 = pickle.loads(pickle.dumps(m))
    np.testing.assert_array_equal(m2.table, m.table)
    assert (m2.grid, m2.unmeasured, m2.path) == (m.grid, m.unmeasured, m.path)
    wi, wo = node_directions((4, 5, 6), 1.3, 2.2, 3.7)
    np.testing.assert_array_equal(m2.eval(wi, wo), m.eval(wi, wo))


def test_eval_takes_a_measured_where_it_takes_a_brdf():
    m = abrdf.measured_from_array(random_table((4, 5, 6)))
    wi = np.array([[0.3, 0.0, 1.0]] * 70000)  # past one thread's share: split over threads
    wo = np.array([-0.2, 0.1, 1.0])
    one = abrdf.eval(m, wi, wo, threads=1)
    np.testing.assert_array_equal(abrdf.eval(m, wi, wo, threads=2), one)
    with pytest.raises(TypeError):
        abrdf.eval(m, wi, wo, r=0.3)
    with pytest.raises(TypeError):
        abrdf.eval(3, wi, wo)
    with pytest.raises(ValueError):
        m.eval(wi, wo, precision="half")
    with pytest.raises(TypeError):
        abrdf.Measured()
