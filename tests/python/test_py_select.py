"""abrdf.select, abrdf.materials: the flowchart from Python is `abrdf advise` with the same
inputs (models, exponent, parameters, predicted error, cost, every trace line)."""
import math
import os

import numpy as np
import pytest

import abrdf


def same_as_advise(sel, ref):
    assert sel.goal == ref["goal"] and sel.type == ref["type"]
    assert (sel.diffuse, sel.specular) == (ref["diffuse"], ref["specular"])
    p = ref["params"]
    assert math.isclose(sel.n, p["n"], rel_tol=1e-9) and math.isclose(sel.r, p["r"], rel_tol=1e-9)
    params = sel.specular_brdf.params
    for k in ("kd", "ks", "f0", "n", "r", "anisotropic", "eta", "melanin", "redness"):
        if k in params:
            np.testing.assert_allclose(params[k], p[k], rtol=1e-9, err_msg=k)
    for k, v in (("error_rel_pct", ref["error"]["rel_pct"]), ("error_abs", ref["error"]["abs"]),
                 ("error_nmse", ref["error"]["nmse"]), ("cost_total", ref["cost"]["total"]),
                 ("cost_specular", ref["cost"]["specular"])):
        got = getattr(sel, k)
        assert (got is None) == (v is None), k
        if v is not None:
            assert math.isclose(got, v, rel_tol=1e-9), k
    assert sel.cost_unit == ref["cost"]["unit"]
    assert [s.text for s in sel.trace] == [s["text"] for s in ref["trace"]]
    assert [s.kind for s in sel.trace] == [s["step"] for s in ref["trace"]]
    assert [s.model for s in sel.trace] == [s["model"] for s in ref["trace"]]
    assert [s.passed for s in sel.trace] == [s["passed"] for s in ref["trace"]]


@pytest.mark.parametrize("name", ["gold", "brushed_aluminium", "mirror_silver", "glass",
                                  "velvet", "hair_brown", "car_paint", "coated_steel"])
@pytest.mark.parametrize("goal", ["photoreal", "performance"])
def test_table_materials_choose_as_advise(cli, name, goal):
    sel = abrdf.select(name, goal=goal)
    same_as_advise(sel, cli("advise", name, "--goal", goal, "--json"))
    assert sel.material.name == name and sel.material.source
    assert sel.explain().splitlines()[0].startswith(" 1. material %s" % name)


def test_tolerances_and_explicit_values(cli):
    sel = abrdf.select(abrdf.Material(n=300), goal="performance", max_rel_error=5,
                       max_abs_error=math.inf)
    same_as_advise(sel, cli("advise", "--n", "300", "--goal", "performance",
                            "--max-rel-error", "5", "--max-abs-error", "none", "--json"))
    sel = abrdf.select({"r": 0.4, "anisotropy": 0.7, "f0": (0.9, 0.8, 0.6)})
    same_as_advise(sel, cli("advise", "--r", "0.4", "--anisotropy", "0.7", "--f0", "0.9,0.8,0.6",
                            "--json"))
    assert sel.specular == "disney_specular_aniso"
    # The chosen lobes evaluate with the selection's parameters.
    f = sel.specular_brdf.eval([0.3, 0, 1], [-0.2, 0.1, 1])
    assert f.shape == (3,) and np.all(f > 0)


def test_table_is_the_commands(cli):
    ref = {m["name"]: m for m in cli("advise", "--list", "--json")["materials"]}
    table = abrdf.materials()
    assert list(table) == list(ref)
    for name, m in table.items():
        r = ref[name]
        assert m.type == r["type"] and m.source == r["source"] and len(m.layers) == r["layers"]
        assert m.r == r["r"] and m.n == r["n"] and m.eta == r["eta"]
        np.testing.assert_allclose(m.f0, r["f0"], rtol=1e-9)
    assert abrdf.material("coated_steel").layers[1].kappa > 0


def test_user_file_overrides_by_name(cli, tmp_path):
    with open(abrdf._select._table_path()) as f:
        header = next(line for line in f if line.startswith("name,"))
    mine = tmp_path / "mine.csv"
    mine.write_text(header + "gold,general,,0.02,0,0,0,1,1,1,0.9,0.8,0.4,,,,,,,,,,,,,mine\n"
                    "my_paint,general,40,,0.5,0.1,0.1,1,1,1,,,,1.5,,,,,,,,,,,,mine\n")
    table = abrdf.materials(mine)
    assert table["gold"].r == 0.02 and table["gold"].file == str(mine)
    assert "my_paint" in table and len(table) == len(abrdf.materials()) + 1
    sel = abrdf.select("my_paint", goal="performance", extra=mine)
    same_as_advise(sel, cli("advise", "my_paint", "--goal", "performance", "--materials",
                            str(mine), "--json"))
    bad = tmp_path / "bad.csv"
    bad.write_text(header + "broken,general,,2,0,0,0,1,1,1,0.9,0.8,0.4,,,,,,,,,,,,,mine\n")
    with pytest.raises(abrdf.Error) as e:
        abrdf.materials(bad)
    r = cli("advise", "gold", "--materials", str(bad), check=False, parse=False)
    assert r.returncode != 0 and str(e.value) in r.stderr
    assert str(e.value).startswith("%s:%d: column 'r'" % (bad, 2))


def test_cost_files_and_tables(cli, tmp_path):
    costs = tmp_path / "costs.txt"
    costs.write_text("# hand-made\npowf_blinn_phong 4\nlambert 1\nf2 9\nf4 2\nf8 3\nf16 4\n"
                     "fs 5\nfkv 6\nfkub 7\nblinn_phong 4\n")
    sel = abrdf.select("gold", goal="performance", costs=costs)
    same_as_advise(sel, cli("advise", "gold", "--goal", "performance", "--costs", str(costs),
                            "--json"))
    assert sel.specular == "f8" and sel.cost_unit.startswith("ns/eval")
    sel = abrdf.select("gold", goal="performance", costs={"f8": 30, "f16": 3}, cost_unit="units")
    assert sel.specular == "f16" and sel.cost_specular == 3 and sel.cost_unit == "units"
    with pytest.raises(abrdf.Error):
        abrdf.select("gold", costs={"nope": 1})
    costs.write_text("f2 fast\n")
    with pytest.raises(abrdf.Error) as e:
        abrdf.select("gold", costs=costs)
    assert str(costs) in str(e.value)


def test_invalid_inputs_raise_the_librarys_message(cli):
    with pytest.raises(abrdf.Error) as e:
        abrdf.select(abrdf.Material(r=1.5))
    r = cli("advise", "--r", "1.5", check=False, parse=False)
    assert r.returncode == 2
    with pytest.raises(abrdf.Error) as e:
        abrdf.select(abrdf.Material(type="hair", r=0.01), goal="photoreal")
    assert e.value.status == -4 and "huang" in str(e.value)
    with pytest.raises(abrdf.Error) as e:
        abrdf.select("gld")
    assert "did you mean: gold" in str(e.value) and e.value.status is None
    with pytest.raises(abrdf.Error):
        abrdf.select("gold", goal="fast")
    with pytest.raises(abrdf.Error):
        abrdf.select(abrdf.Material(r=0.2, type="metal"))
    with pytest.raises(TypeError):
        abrdf.select({"r": 0.2, "roughness": 0.3})
    with pytest.raises(abrdf.Error):
        abrdf.select(abrdf.Material(r=0.2), max_rel_error=-1)


def test_data_dir_override(tmp_path, monkeypatch):
    # $ABRDF_DATA_DIR names the table, as for the command.
    with open(abrdf._select._table_path()) as f:
        lines = [l for l in f if l.startswith(("name,", "gold,"))]
    (tmp_path / "materials.csv").write_text("".join(lines))
    monkeypatch.setenv("ABRDF_DATA_DIR", str(tmp_path))
    assert list(abrdf.materials()) == ["gold"]
    monkeypatch.delenv("ABRDF_DATA_DIR")
    assert len(abrdf.materials()) > 50
    assert os.path.isfile(abrdf._select._table_path())
