"""abrdf.models(), abrdf.model(): the registry as `abrdf models --json` gives it."""
import math
import os
import re

import pytest

import abrdf
from abrdf import _abrdf


def test_models_are_the_commands(cli):
    ref = cli("models", "--json")
    assert abrdf._abrdf.version() == ref["version"] == abrdf.__version__
    got = abrdf.models()
    assert [m.name for m in got] == [m["name"] for m in ref["models"]]
    for m, r in zip(got, ref["models"]):
        assert (m.title, m.equation, m.citation) == (r["title"], r["equation"], r["citation"])
        assert list(m.needs) == r["needs"]
        assert (m.reciprocal, m.energy_conserving, m.kind) == (
            r["reciprocal"], r["energy_conserving"], r["kind"])
        assert m.paper_cycles == r["paper_cycles"]
        assert [p.name for p in m.params] == [p["name"] for p in r["params"]]
        for p, q in zip(m.params, r["params"]):
            assert (p.kind, p.help) == (q["kind"], q["help"])
            assert (p.min, p.max, p.default) == (q["min"], q["max"], q["default"]), (m.name, p.name)


def test_model_lookup():
    m = abrdf.model("disney_specular")
    assert m.name == "disney_specular" and m.equation == "Eqs. 5, 6, 8, 9"
    assert m.param("r").max == 1.0
    with pytest.raises(KeyError):
        m.param("sigma")
    with pytest.raises(abrdf.Error) as e:
        abrdf.model("disney_specularr")
    assert "unknown model 'disney_specularr'" in str(e.value)
    assert e.value.status == -2  # ABRDF_E_MODEL


def test_library_parameters_cover_every_model():
    params = {p["name"]: p for p in _abrdf.params()}
    for m in abrdf.models():
        for p in m.params:
            lib = params[p.name]
            assert lib["min"] <= p.min <= p.max <= lib["max"], (m.name, p.name)


def test_surfaces_and_goals(cli):
    assert abrdf.goals() == ["performance", "photoreal"]
    text = cli("advise", "--help").stdout
    listed = re.search(r"--type T\s+(.*?)\n\s+--materials", text, re.S).group(1)
    assert abrdf.surfaces() == [s.strip() for s in listed.replace("\n", " ").split(",")]


def test_stub_lists_every_function():
    # _abrdf.pyi types what the C module defines: the same public names.
    pyi = os.path.join(os.path.dirname(abrdf.__file__), "_abrdf.pyi")
    with open(pyi) as f:
        text = f.read()
    declared = set(re.findall(r"^(?:def|class) (\w+)", text, re.M)) | set(
        re.findall(r"^(\w+): ", text, re.M))
    declared = {n for n in declared if not (n.startswith("_") and n[1:2].isupper())}
    defined = {n for n in dir(_abrdf) if not n.startswith("__")}
    assert declared == defined


def test_paper_costs_are_table_4():
    costs = _abrdf.paper_costs()
    assert costs["unit"].startswith("cycles")
    for m in abrdf.models():
        if m.paper_cycles is not None:
            assert math.isclose(costs["costs"][m.name], m.paper_cycles)
