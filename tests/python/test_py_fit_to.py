"""Fits to measured tables from Python (abrdf_fit_to): abrdf.fit with a Measured or a measured
file as the reference agrees with `abrdf fit --to FILE`, whatever made the Measured, and
abrdf.sweep over measured files and tables equals its serial loop on a cluster."""
import os

import numpy as np
import pytest

import abrdf


@pytest.fixture(scope="module")
def files(cli, tmp_path_factory):
    where = tmp_path_factory.mktemp("fit_to")
    out = {}
    for name, model, sets in (("bp", "blinn_phong", ["n=40"]),
                              ("ds", "disney_specular", ["r=0.35", "f0=0.9,0.6,0.3"]),
                              ("lam", "lambert", ["kd=0.6,0.3,0.2"])):
        path = str(where / (name + ".binary"))
        args = [model, "-o", path, "--grid", "32,32,64"]
        for s in sets:
            args += ["--set", s]
        cli("tabulate", *args)
        out[name] = path
    return out


def close(a, b):
    # the command prints 10 significant digits
    return a == pytest.approx(b, rel=2e-9, abs=1e-15)


@pytest.mark.parametrize("name,model,diffuse", [("bp", "blinn_phong", None),
                                                ("ds", "f_ge", "lambert"),
                                                ("ds", "disney_specular", "lambert")])
def test_fit_to_a_file_is_the_commands(cli, files, name, model, diffuse):
    ref = cli("fit", "--to", files[name], model, "--diffuse", diffuse or "none", "--json")
    cand = model if diffuse is None else "%s+%s" % (diffuse, model)
    f = abrdf.fit(files[name], cand)
    assert (f.diffuse and f.diffuse.model) == ref["diffuse"] and f.specular.model == model
    for k in ("rel_l2", "max_rel_pct", "max_abs", "nmse_pred"):
        assert close(getattr(f, k), ref[k]), k
    assert f.directions == ref["directions"] and f.evals == ref["evals"]
    params = dict(f.specular.params, **(f.diffuse.params if f.diffuse else {}))
    for k, v in ref["params"].items():
        got = params[k]
        if isinstance(v, list):
            assert all(close(g, x) for g, x in zip(got, v)), k
        else:
            assert close(got, v), k


def test_a_measured_fits_as_its_file(files):
    path = files["ds"]
    by_path = abrdf.fit(path, "lambert+f_ge", metric="auto")
    loaded = abrdf.load_measured(path)
    assert abrdf.fit(loaded, "lambert+f_ge", metric="auto") == by_path
    assert abrdf.fit(os.fsencode(path).decode(), "lambert+f_ge", metric="auto") == by_path
    copied = abrdf.measured_from_array(np.array(loaded.table))
    assert abrdf.fit(copied, "lambert+f_ge", metric="auto") == by_path
    # "fit this model to that": the same call with the reference as to=
    assert abrdf.fit("lambert+f_ge", to=loaded, metric="auto") == by_path
    with pytest.raises(abrdf.Error):
        abrdf.fit(loaded, "lambert", to=loaded)
    with pytest.raises(abrdf.Error):
        abrdf.fit(loaded)


def test_a_lambert_table_fits_lambert_exactly(files):
    f = abrdf.fit(files["lam"], "lambert")  # one model: the candidate's only lobe
    np.testing.assert_allclose(f.specular.params["kd"], (0.6, 0.3, 0.2), rtol=1e-6)
    assert f.nmse_pred < 1e-10


def test_fit_to_refuses_what_it_cannot_fit(files):
    m = abrdf.load_measured(files["bp"])
    with pytest.raises(abrdf.Error):
        abrdf.fit(m, "no_such_model")
    with pytest.raises(abrdf.Error):
        abrdf.fit(m, "blinn_phong", metric="l3")
    with pytest.raises(abrdf.Error):
        abrdf.fit(m, "blinn_phong", resolution=9)
    with pytest.raises(abrdf.Error) as e:
        abrdf.fit(files["bp"] + ".missing.binary", "blinn_phong")
    assert "cannot open" in str(e.value)


def test_sweep_of_measured_materials_on_a_cluster_equals_the_loop(files):
    table = abrdf.load_measured(files["ds"]).table * np.float32(0.5)
    library = [files["bp"], files["ds"], abrdf.measured_from_array(table), "gold"]
    models = ["blinn_phong", "lambert+f_ge", "lambert+disney_specular"]
    serial = abrdf.sweep(library, models, "noticeable", scheduler="serial")
    assert [r.name for r in serial.rows[::3]] == [files["bp"], files["ds"], "table #2", "gold"]
    for r in serial.rows[:6]:
        assert r.fit == abrdf.fit(library[r.material], r.candidate)
    assert abrdf.sweep(library, models, "noticeable", workers=2) == serial
