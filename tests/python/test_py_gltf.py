"""abrdf.load_gltf on the generated assets (tools/gen/gen_material_assets.py): the three forms
of one file (.gltf with a .bin and PNG files, .glb, data URIs) give the same materials, every
factor and map as written, the maps' texels across the flowchart's smooth limit, and one-line
errors "FILE: where: problem" for broken files."""
import filecmp
import json
import os
import struct
import subprocess
import sys

import pytest

import abrdf

FORMS = ("scene.gltf", "scene.glb", "scene_datauri.gltf")


def _bytes(t):
    if t.file is not None:
        with open(t.file, "rb") as f:
            return f.read()
    return t.embedded


def test_generator_is_deterministic(material_assets, source_dir, tmp_path):
    out, _ = material_assets
    script = os.path.join(source_dir, "tools", "gen", "gen_material_assets.py")
    subprocess.run([sys.executable, script, str(tmp_path)], check=True)
    cmp = filecmp.dircmp(out, tmp_path)
    assert not cmp.diff_files and not cmp.left_only and not cmp.right_only
    assert not filecmp.dircmp(out / "textures", tmp_path / "textures").diff_files


def test_constants_are_the_generator_factors(material_assets):
    out, gen = material_assets
    mats = abrdf.load_gltf(out / "scene.gltf")
    for name, f in gen.CONSTANTS.items():
        want = abrdf.Pbr(**f)
        assert mats[name].pbr == want, name
        assert mats[name].textures == {} and mats[name].name == name
        assert mats[name].source == str(out / "scene.gltf")


def test_three_forms_give_the_same_materials(material_assets):
    out, _ = material_assets
    forms = [abrdf.load_gltf(out / f) for f in FORMS]
    assert [list(m) for m in forms] == [list(forms[0])] * 3
    assert list(forms[0])[-2:] == ["textured", "material_7"]  # unnamed: its index
    for name in forms[0]:
        a = forms[0][name]
        for b in forms[1:]:
            assert b[name].pbr == a.pbr
            assert set(b[name].textures) == set(a.textures)
            for slot, t in a.textures.items():
                u = b[name].textures[slot]
                assert (u.channel, u.srgb, u.uv_set, u.transform) == \
                    (t.channel, t.srgb, t.uv_set, t.transform)
                assert u.file is None and u.mime_type == "image/png"
                assert _bytes(u) == _bytes(t)  # the same PNG, held inside the file


def test_core_maps(material_assets):
    out, _ = material_assets
    m = abrdf.load_gltf(out / "scene.gltf")["textured"]
    t = m.textures
    assert m.pbr.base_color == (1.0, 0.9, 0.8) and m.pbr.metallic == 1.0
    assert t["base_color"].file == str(out / "textures" / "base_color.png")
    assert t["base_color"].srgb and t["base_color"].channel is None
    assert t["base_color"].transform == ((0.25, 0.0), (2.0, 2.0), 0.5)
    assert (t["metallic"].channel, t["roughness"].channel, t["occlusion"].channel) == (2, 1, 0)
    assert t["metallic"].file == t["roughness"].file == t["occlusion"].file
    assert not t["metallic"].srgb and not t["normal"].srgb
    assert (m.occlusion_strength, m.normal_scale) == (0.75, 0.5)


def test_extension_maps(material_assets):
    out, _ = material_assets
    m = abrdf.load_gltf(out / "scene.gltf")["material_7"]
    channels = {k: (v.channel, v.srgb) for k, v in m.textures.items()}
    assert channels == {  # the channels and encodings each KHR extension specifies
        "specular": (3, False), "specular_color": (None, True), "clearcoat": (0, False),
        "clearcoat_roughness": (1, False), "sheen_color": (None, True),
        "sheen_roughness": (3, False), "anisotropy": (None, False),
        "transmission": (0, False)}
    p = m.pbr
    assert (p.clearcoat, p.sheen_color, p.anisotropy, p.transmission) == \
        (0.5, (0.5, 0.5, 0.5), 0.5, 0.5)
    assert m.material.type == "layered_plastic"  # a clearcoat: the flowchart's layered class


def test_roughness_map_crosses_the_smooth_limit(material_assets):
    """The roughness texels (green of metal_rough.png, read by OpenImageIO as stored: the
    map is data, not colour) lie on both sides of the flowchart's smooth limit, so a
    per-texel selection changes its class across the map."""
    import OpenImageIO as oiio

    out, gen = material_assets
    buf = oiio.ImageBuf(str(out / "textures" / "metal_rough.png"))
    assert not buf.has_error and buf.spec().nchannels == 3
    g = buf.get_pixels(oiio.UINT8)[0, :, 1]
    assert tuple(g) == gen.ROUGHNESS_BYTES
    g = g / 255.0
    limit = abrdf._abrdf.rules()["smooth_r_max"]
    assert g.min() <= limit < g.max() and (g * g).min() <= 0.03 < (g * g).max()
    classes = set()
    for r in g:
        s = abrdf.select(abrdf.Pbr(metallic=0, roughness=float(r)))
        classes.add(next(x.text.rsplit(": ", 1)[1] for x in s.trace
                         if x.text.startswith("alpha")))
    assert classes == {"smooth", "rough"}


def test_select_takes_the_read_material(material_assets):
    out, _ = material_assets
    m = abrdf.load_gltf(out / "scene.glb")["gold_mirror"]
    a, b = abrdf.select(m, goal="performance"), abrdf.select(m.material, goal="performance")
    assert (a.diffuse, a.specular, a.r, a.error_rel_pct) == \
        (b.diffuse, b.specular, b.r, b.error_rel_pct)
    assert a.material.name == "gold_mirror"
    assert [x.model for x in m.brdfs] == ["lambert_fresnel", "disney_specular"]


def _doc(out):
    with open(out / "scene.gltf") as f:
        return json.load(f)


def _write(tmp_path, out, doc, name="t.gltf"):
    (tmp_path / "textures").mkdir(exist_ok=True)
    for t in os.listdir(out / "textures"):
        (tmp_path / "textures" / t).write_bytes((out / "textures" / t).read_bytes())
    (tmp_path / "scene.bin").write_bytes((out / "scene.bin").read_bytes())
    p = tmp_path / name
    p.write_text(json.dumps(doc))
    return p


def _edit(path, value):
    def apply(doc):
        d = doc
        for k in path[:-1]:
            d = d[k]
        if value is KeyError:
            del d[path[-1]]
        else:
            d[path[-1]] = value
    return apply


@pytest.mark.parametrize("edit,message", [
    (_edit(["asset", "version"], "1.0"), "asset.version: glTF 2.x is needed"),
    (_edit(["asset"], KeyError), "asset: an object is needed"),
    (_edit(["extensionsRequired"], ["KHR_materials_pbrSpecularGlossiness"]),
     "KHR_materials_pbrSpecularGlossiness is required, and abrdf does not read it"),
    (_edit(["materials", 0, "pbrMetallicRoughness", "roughnessFactor"], 2),
     "materials[0]: roughness = 2 is outside [0, 1]"),
    (_edit(["materials", 0, "pbrMetallicRoughness", "roughnessFactor"], "rough"),
     "materials[0].pbrMetallicRoughness.roughnessFactor: a finite number is needed"),
    (_edit(["materials", 0, "pbrMetallicRoughness", "baseColorFactor"], [1, 1]),
     "baseColorFactor: 4 finite numbers are needed"),
    (_edit(["materials", 6, "pbrMetallicRoughness", "baseColorTexture", "index"], 9),
     "baseColorTexture.index: texture 9 does not exist (the file has 4)"),
    (_edit(["images", 0, "uri"], "textures/missing.png"), "images[0]: uri \"textures/missing"),
    (_edit(["images", 0, "uri"], "http://example.com/a.png"), "not URLs"),
    (_edit(["materials", 4, "extensions", "KHR_materials_anisotropy", "anisotropyStrength"],
           -1), "materials[4]: anisotropy = -1 is outside [0, 1]"),
    (_edit(["materials", 6, "occlusionTexture", "strength"], 3), "strength: 3 is outside"),
    (_edit(["materials", 0, "name"], 5), "materials[0].name: a string is needed"),
    (_edit(["textures", 0, "source"], KeyError), "textures[0]: no source"),
])
def test_broken_files_raise_one_line(material_assets, tmp_path, edit, message):
    out, _ = material_assets
    doc = _doc(out)
    edit(doc)
    p = _write(tmp_path, out, doc)
    with pytest.raises(abrdf.Error) as e:
        abrdf.load_gltf(p)
    text = str(e.value)
    assert text.startswith(str(p) + ": ") and message in text and "\n" not in text


def test_names_given_twice_stay_apart(material_assets, tmp_path):
    out, _ = material_assets
    doc = _doc(out)
    doc["materials"][1]["name"] = "red_plastic"
    mats = abrdf.load_gltf(_write(tmp_path, out, doc))
    assert "red_plastic" in mats and "red_plastic_1" in mats
    assert mats["red_plastic_1"].pbr.metallic == 1.0


@pytest.mark.parametrize("cut,message", [
    (lambda b: b[:8], "12-byte header"),
    (lambda b: b[:-4], "the GLB header says"),
    (lambda b: b[:12 + 4] + struct.pack("<I", 0x4E4942) + b[20:], "first GLB chunk must be JSON"),
    (lambda b: b[:4] + struct.pack("<I", 1) + b[8:], "GLB version 1"),
    (lambda b: b[:12] + struct.pack("<I", len(b)) + b[16:], "run past the end"),
])
def test_broken_glb(material_assets, tmp_path, cut, message):
    out, _ = material_assets
    p = tmp_path / "t.glb"
    p.write_bytes(cut((out / "scene.glb").read_bytes()))
    with pytest.raises(abrdf.Error, match=message) as e:
        abrdf.load_gltf(p)
    assert "\n" not in str(e.value)


def test_missing_and_not_json(tmp_path):
    with pytest.raises(abrdf.Error, match="missing.gltf: No such file"):
        abrdf.load_gltf(tmp_path / "missing.gltf")
    p = tmp_path / "bad.gltf"
    p.write_text("{ not json")
    with pytest.raises(abrdf.Error, match="bad.gltf: malformed JSON"):
        abrdf.load_gltf(p)
    p.write_bytes(b'{"asset": {"version": "2.0"}, "materials": [{"name": "\xff"}]}')
    with pytest.raises(abrdf.Error, match="not UTF-8"):
        abrdf.load_gltf(p)
    p.write_text('{"asset": {"version": "2.0"}}')
    assert abrdf.load_gltf(p) == {}


def _glb_with(out, tmp_path, edit):
    """scene.glb with its JSON chunk edited."""
    b = (out / "scene.glb").read_bytes()
    size = struct.unpack_from("<I", b, 12)[0]
    doc = json.loads(b[20:20 + size])
    edit(doc)
    js = json.dumps(doc).encode()
    js += b" " * (-len(js) % 4)
    rest = b[20 + size:]
    p = tmp_path / "t.glb"
    p.write_bytes(struct.pack("<III", 0x46546C67, 2, 20 + len(js) + len(rest))
                  + struct.pack("<II", len(js), 0x4E4F534A) + js + rest)
    return p


@pytest.mark.parametrize("edit,message", [
    (_edit(["buffers", 0, "byteLength"], 10 ** 6), "byteLength 1000000, but the data holds"),
    (_edit(["bufferViews", 3, "byteOffset"], 10 ** 5), "bufferViews[3]: bytes 100000.."),
    (_edit(["images", 0, "mimeType"], KeyError), "images[0]: an image in a bufferView needs"),
    (_edit(["images", 0, "mimeType"], "image/webp"), "image/png or image/jpeg"),
    (_edit(["images", 0, "bufferView"], 99), "images[0].bufferView: bufferView 99 does not"),
    (_edit(["buffers", 0, "uri"], "data:xyz"), "a data URI must be base64"),
])
def test_broken_glb_json(material_assets, tmp_path, edit, message):
    out, _ = material_assets
    assert abrdf.load_gltf(_glb_with(out, tmp_path, lambda d: None))  # the repacking is sound
    p = _glb_with(out, tmp_path, edit)
    with pytest.raises(abrdf.Error) as e:
        abrdf.load_gltf(p)
    assert str(e.value).startswith(str(p) + ": ") and message in str(e.value)
    assert "\n" not in str(e.value)
