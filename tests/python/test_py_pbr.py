"""abrdf.Pbr, abrdf.pbr_lobes, abrdf.pbr_material (abrdf_pbr.h from Python): glTF's defaults,
the mapping's closed-form values, the flowchart's surface classes, select() on a Pbr, and the
library's range errors."""
import dataclasses
import math

import numpy as np
import pytest

import abrdf


def test_defaults_are_gltf_defaults():
    p = abrdf.Pbr()
    assert p.base_color == (1.0, 1.0, 1.0) and p.metallic == 1.0 and p.roughness == 1.0
    assert p.ior == 1.5 and p.specular == 1.0 and p.specular_color == (1.0, 1.0, 1.0)
    assert p.clearcoat == 0.0 and p.sheen_color == (0.0, 0.0, 0.0) and p.transmission == 0.0
    with pytest.raises(dataclasses.FrozenInstanceError):
        p.metallic = 0.5  # type: ignore[misc]
    assert abrdf.Pbr(base_color=0.5).base_color == (0.5, 0.5, 0.5)
    assert hash(abrdf.Pbr(metallic=0)) == hash(abrdf.Pbr(metallic=0.0))


def test_lobes_in_closed_form():
    base = (0.8, 0.4, 0.2)
    d, s = abrdf.pbr_lobes(abrdf.Pbr(base_color=base, metallic=0, roughness=0.3))
    assert (d.model, s.model) == ("lambert_fresnel", "disney_specular")
    assert d.params["kd"] == pytest.approx(base, abs=1e-15)
    assert s.params["f0"] == pytest.approx((0.04,) * 3, abs=1e-15)  # ((1.5-1)/(1.5+1))^2
    assert s.params["ks"] == pytest.approx((1,) * 3) and s.params["r"] == 0.3
    d, s = abrdf.pbr_lobes(abrdf.Pbr(base_color=base, metallic=1, roughness=0.3))
    assert d.params["kd"] == (0.0, 0.0, 0.0)
    assert s.params["f0"] == pytest.approx(base, abs=1e-15)
    # ior 2: f0 = 1/9; transmission 0.5 halves the diffuse lobe
    d, s = abrdf.pbr_lobes(abrdf.Pbr(base_color=base, metallic=0, ior=2, transmission=0.5))
    assert s.params["f0"][1] == pytest.approx(1 / 9, abs=1e-15)
    assert d.params["kd"][0] == pytest.approx(0.4, abs=1e-15)
    assert abrdf.pbr_lobes(abrdf.Pbr(roughness=0.4, anisotropy=0.6))[1].model == "disney_specular_aniso"


def test_lobes_sum_is_the_gltf_specular_at_normal_incidence():
    """A dielectric at normal incidence: f = kd/pi (1 - F(0)) + F(0) D(0) V, with F(0) =
    f0 for the Schlick term; the sum of the lobes' f_r is checked against the library's own
    models, evaluated on the same block (the two lobes share it)."""
    p = abrdf.Pbr(base_color=(0.5, 0.5, 0.5), metallic=0, roughness=0.5)
    lobes = abrdf.pbr_lobes(p)
    n = np.array([0.0, 0.0, 1.0])
    f = sum(b.eval(n, n, precision="double") for b in lobes)
    assert np.all(np.isfinite(f)) and np.all(f > 0.5 / math.pi * 0.9)
    for b in lobes:
        assert np.allclose(b.eval(n, n, precision="double"),
                           abrdf.eval(b.model, n, n, precision="double", **b.params))


def test_material_classes():
    assert abrdf.pbr_material(abrdf.Pbr(metallic=0)).type == "general"
    m = abrdf.pbr_material(abrdf.Pbr(metallic=0, clearcoat=1, clearcoat_roughness=0.1), "car")
    assert (m.name, m.type, len(m.layers)) == ("car", "layered_plastic", 1)
    assert m.layers[0].eta == 1.5 and m.layers[0].r == 0.1
    m = abrdf.pbr_material(abrdf.Pbr(metallic=1, clearcoat=1))
    assert (m.type, len(m.layers)) == ("layered_metal", 2)
    assert abrdf.pbr_material(abrdf.Pbr(sheen_color=0.5, sheen_roughness=0.8)).type == \
        "cloth_rough"
    assert abrdf.pbr_material(abrdf.Pbr(sheen_color=0.5, sheen_roughness=0.2)).type == \
        "cloth_shiny"
    m = abrdf.pbr_material(abrdf.Pbr(base_color=(0.8, 0.4, 0.2), metallic=0, roughness=0.3))
    assert m.r == 0.3 and m.kd == pytest.approx((0.8, 0.4, 0.2))


def test_select_takes_a_pbr_and_agrees_with_its_material():
    # The flowchart's smooth class: the paper's alpha (abrdf's perceptual r) at most this.
    smooth_r = abrdf._abrdf.rules()["smooth_r_max"]
    for r in (smooth_r * 0.5, smooth_r * 2, 0.5):
        p = abrdf.Pbr(base_color=(0.8, 0.4, 0.2), metallic=0, roughness=r)
        for goal in ("photoreal", "performance"):
            a = abrdf.select(p, goal=goal)
            b = abrdf.select(abrdf.pbr_material(p), goal=goal)
            assert (a.diffuse, a.specular, a.r) == (b.diffuse, b.specular, b.r)
            assert a.specular_brdf == b.specular_brdf
    smooth = abrdf.select(abrdf.Pbr(metallic=0, roughness=smooth_r * 0.5))
    rough = abrdf.select(abrdf.Pbr(metallic=0, roughness=smooth_r * 2))
    assert any(s.text.endswith(": smooth") for s in smooth.trace)
    assert any(s.text.endswith(": rough") for s in rough.trace)
    assert smooth.specular != rough.specular
    s = abrdf.select(abrdf.Pbr(metallic=0, roughness=0.4), budget="slight")
    assert s.error_nmse is not None and s.error_nmse <= 2.5e-4


@pytest.mark.parametrize("field,value,message", [
    ("roughness", 2.0, "roughness = 2 is outside [0, 1]"),
    ("ior", 0.5, "ior = 0.5 is outside [1, 4]"),
    ("metallic", math.nan, "metallic"),
    ("base_color", (0.5, 1.5, 0.5), "base_color"),
    ("anisotropy_rotation", 1e4, "anisotropy_rotation"),
])
def test_range_errors_carry_the_library_message(field, value, message):
    with pytest.raises(abrdf.Error) as e:
        abrdf.Pbr(**{field: value})
    assert message in str(e.value) and "\n" not in str(e.value)
    assert e.value.status == -4  # ABRDF_E_RANGE
    with pytest.raises(abrdf.Error, match=field):
        abrdf.pbr_lobes({field: value})
    with pytest.raises(abrdf.Error, match=field):
        abrdf.pbr_material({field: value})


def test_type_errors():
    with pytest.raises(TypeError, match="real number"):
        abrdf.Pbr(metallic="0.5")  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="real number"):
        abrdf.Pbr(metallic=True)  # type: ignore[arg-type]
    with pytest.raises(abrdf.Error, match="3 numbers"):
        abrdf.Pbr(base_color=(1, 1))  # type: ignore[arg-type]
    with pytest.raises(TypeError):
        abrdf.pbr_lobes({"shininess": 1})
    with pytest.raises(TypeError, match="unknown field"):
        abrdf._abrdf.pbr_check({"shininess": 1})
    with pytest.raises(TypeError):
        abrdf.pbr_lobes(42)  # type: ignore[arg-type]
