"""abrdf.load_materialx on the generated document (tools/gen/gen_material_assets.py), read
through the MaterialX library: the document is valid MaterialX, each constant material gives
the same Pbr, the same select() choice and the same numbers as the glTF file's, through each
of gltf_pbr, standard_surface and open_pbr_surface; image inputs become TextureRefs; what is
not read is refused in one line naming the node and the file."""
import os
import subprocess
import sys

import pytest

import abrdf

SHADERS = {"gltf": "gltf_pbr", "std": "standard_surface", "opbr": "open_pbr_surface"}


def test_the_document_is_valid_materialx(material_assets):
    import MaterialX as mx

    out, gen = material_assets
    doc = mx.createDocument()
    mx.readFromXmlFile(doc, str(out / "materials.mtlx"))
    lib = mx.createDocument()
    mx.loadLibraries(mx.getDefaultDataLibraryFolders(), mx.getDefaultDataSearchPath(), lib)
    doc.importLibrary(lib)
    ok, message = doc.validate()
    assert ok, message
    shaders = {mx.getShaderNodes(m)[0].getCategory() for m in doc.getMaterialNodes()}
    assert shaders == set(SHADERS.values())
    assert len(doc.getMaterialNodes()) == 3 * len(gen.CONSTANTS) + 3


@pytest.mark.parametrize("prefix", sorted(SHADERS))
def test_constants_match_gltf(material_assets, prefix):
    out, gen = material_assets
    mx = abrdf.load_materialx(out / "materials.mtlx")
    gl = abrdf.load_gltf(out / "scene.gltf")
    for name in gen.CONSTANTS:
        a, b = mx["%s_%s" % (prefix, name)], gl[name]
        assert a.pbr == b.pbr, name
        assert a.textures == {}
        assert a.brdfs == b.brdfs
        for kw in ({"goal": "photoreal"}, {"goal": "performance"}):
            sa, sb = abrdf.select(a, **kw), abrdf.select(b, **kw)
            assert (sa.type, sa.diffuse, sa.specular, sa.r, sa.n, sa.error_rel_pct,
                    sa.error_abs, sa.cost_total) == \
                (sb.type, sb.diffuse, sb.specular, sb.r, sb.n, sb.error_rel_pct,
                 sb.error_abs, sb.cost_total), name
            assert sa.specular_brdf == sb.specular_brdf
            assert [s.text for s in sa.trace][1:] == [s.text for s in sb.trace][1:]


def test_the_classes_of_the_constants(material_assets):
    out, _ = material_assets
    mx = abrdf.load_materialx(out / "materials.mtlx")
    types = {n: mx["std_" + n].material.type for n in
             ("red_plastic", "coated_blue", "velvet", "gold_mirror")}
    assert types == {"red_plastic": "general", "coated_blue": "layered_plastic",
                     "velvet": "cloth_rough", "gold_mirror": "general"}
    s = abrdf.select(mx["opbr_brushed_steel"])
    assert s.specular == "disney_specular_aniso"


def test_textured(material_assets):
    out, _ = material_assets
    mx = abrdf.load_materialx(out / "materials.mtlx")
    tex = str(out / "textures")
    std = mx["std_textured"]
    t = std.textures
    assert set(t) == {"base_color", "metallic", "roughness", "normal"}
    assert t["base_color"].file == os.path.join(tex, "base_color.png")  # the fileprefix
    assert t["base_color"].srgb and t["base_color"].channel is None
    assert (t["roughness"].channel, t["metallic"].channel) == (1, 2)  # extract, separate3
    assert not t["roughness"].srgb and std.normal_scale == 0.5
    # nodedef defaults where the document says nothing: standard_surface's, not glTF's
    assert std.pbr.clearcoat_roughness == 0.1 and std.pbr.sheen_roughness == 0.3
    o = mx["opbr_textured"].textures
    assert o["base_color"].uv_set == 1 and o["roughness"].channel == 0  # texcoord, float
    g = mx["gltf_textured"]
    assert g.pbr.base_color == (1.0, 0.9, 0.8)  # gltf_colorimage's color
    assert g.pbr.clearcoat == 0.5 and g.textures["clearcoat"].file.endswith("ext.png")
    assert (g.textures["metallic"].channel, g.textures["roughness"].channel) == (2, 1)


DOC = """<?xml version="1.0"?>
<materialx version="1.39">
%s
  <surfacematerial name="M" type="material">
    <input name="surfaceshader" type="surfaceshader" nodename="S" />
  </surfacematerial>
</materialx>
"""


@pytest.mark.parametrize("body,message", [
    ('<UsdPreviewSurface name="S" type="surfaceshader" />',
     "material 'M': surface shader 'S' is a 'UsdPreviewSurface'; abrdf reads "
     "standard_surface, open_pbr_surface, gltf_pbr"),
    ('<noise2d name="N" type="float" />\n<standard_surface name="S" type="surfaceshader">'
     '<input name="specular_roughness" type="float" nodename="N" /></standard_surface>',
     "input 'specular_roughness': node 'N' is a 'noise2d', which abrdf does not read"),
    ('<image name="I" type="float"><input name="file" type="filename" value="nope.png" />'
     '</image>\n<gltf_pbr name="S" type="surfaceshader">'
     '<input name="roughness" type="float" nodename="I" /></gltf_pbr>',
     "image node 'I': no such file"),
    ('<image name="I" type="float"><input name="file" type="filename" value="t.png" />'
     '</image>\n<standard_surface name="S" type="surfaceshader">'
     '<input name="base" type="float" nodename="I" /></standard_surface>',
     "input 'base': a map on a weight is not read"),
    ('<tiledimage name="I" type="float"><input name="file" type="filename" value="t.png" />'
     '<input name="uvtiling" type="vector2" value="2, 2" /></tiledimage>\n'
     '<open_pbr_surface name="S" type="surfaceshader">'
     '<input name="specular_roughness" type="float" nodename="I" /></open_pbr_surface>',
     "image node 'I': uvtiling = 2,2"),
    ('<standard_surface name="S" type="surfaceshader">'
     '<input name="specular_roughness" type="float" value="1.5" /></standard_surface>',
     "standard_surface 'S': roughness = 1.5 is outside [0, 1]"),
    ('<standard_surface name="S" type="surfaceshader">'
     '<input name="base_color" type="color3" value="1, 1" /></standard_surface>',
     "not a valid MaterialX document"),
])
def test_refused_in_one_line(tmp_path, body, message):
    (tmp_path / "t.png").write_bytes(b"")  # named only, never opened by the reader
    p = tmp_path / "m.mtlx"
    p.write_text(DOC % body)
    with pytest.raises(abrdf.Error) as e:
        abrdf.load_materialx(p)
    text = str(e.value)
    assert text.startswith(str(p) + ": ") and message in text and "\n" not in text


def test_not_xml_and_missing(tmp_path):
    p = tmp_path / "bad.mtlx"
    p.write_text("<materialx")
    with pytest.raises(abrdf.Error, match="bad.mtlx: ") as e:
        abrdf.load_materialx(p)
    assert "\n" not in str(e.value)
    with pytest.raises(abrdf.Error, match="missing.mtlx: no such file"):
        abrdf.load_materialx(tmp_path / "missing.mtlx")


def test_without_the_materialx_package(material_assets):
    """The package imports without MaterialX; load_materialx then names the package."""
    out, _ = material_assets
    code = ("import sys; sys.modules['MaterialX'] = None\n"
            "import abrdf\n"
            "print(len(abrdf.load_gltf(sys.argv[1])))\n"
            "try:\n"
            "    abrdf.load_materialx(sys.argv[2])\n"
            "except abrdf.Error as e:\n"
            "    print(e)\n")
    r = subprocess.run([sys.executable, "-c", code, str(out / "scene.gltf"),
                        str(out / "materials.mtlx")], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    lines = r.stdout.splitlines()
    assert lines[0] == "8"
    assert lines[1] == ("%s: reading MaterialX needs the Python package 'materialx' "
                        "(pip install materialx)" % (out / "materials.mtlx"))
