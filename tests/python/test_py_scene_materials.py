"""python -m abrdf.scene_materials: one scene-format line per material of a .gltf, .glb or
.mtlx file, in the syntax `abrdf render` parses (docs/GLTF.md, "In a scene"): the lines are
rendered by the command ($ABRDF) in a small scene; a glTF material and its MaterialX twin
render the same image; bad files give one line on stderr and exit 1."""
import math
import subprocess
import sys

import numpy as np
import pytest

import abrdf
from abrdf import scene_materials

SCENE = """camera position=0,0,4 look_at=0,0,0 fov=40 resolution=32,32
light point position=2,2,4 intensity=20
ambient 0.05
"""


def run(*args):
    return subprocess.run([sys.executable, "-m", "abrdf.scene_materials", *map(str, args)],
                          capture_output=True, text=True)


# a unit quad facing the camera, with texture coordinates (textured materials need them)
QUAD = """v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0
vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1
f 1/1/1 2/2/1 3/3/1 4/4/1
"""


def render(cli, tmp_path, lines, name, *materials):
    """The lines and a grid of quads with texture coordinates, one per material, rendered at
    32 x 32."""
    scene = tmp_path / (name + ".scene")
    (tmp_path / "quad.obj").write_text(QUAD)
    cols = math.ceil(math.sqrt(len(materials)))
    cell = 2.0 / cols
    quads = "".join("mesh file=quad.obj material=%s scale=%g translate=%g,%g,0\n"
                    % (m, 0.45 * cell, -1 + cell * (i % cols + 0.5),
                       1 - cell * (i // cols + 0.5)) for i, m in enumerate(materials))
    scene.write_text(SCENE + "".join(line + "\n" for line in lines) + quads)
    out = tmp_path / (name + ".exr")
    cli("render", scene, "-o", out, "--spp", "1", "--threads", "1", "--no-preview")
    return abrdf.read_image(out)


@pytest.mark.parametrize("form", ["scene.gltf", "scene.glb", "scene_datauri.gltf",
                                  "materials.mtlx"])
def test_every_line_renders(material_assets, cli, tmp_path, form):
    out, _ = material_assets
    r = run(out / form, "--images", tmp_path / "images")
    assert r.returncode == 0, r.stderr
    lines = r.stdout.splitlines()
    load = abrdf.load_materialx if form.endswith(".mtlx") else abrdf.load_gltf
    names = list(load(out / form))
    assert len(lines) == len(names)
    assert [line.split()[1] for line in lines] == names  # these names are scene names
    assert all(line.split()[0] == "material" and line.split()[2] == "pbr" for line in lines)
    img = render(cli, tmp_path, lines, "all", *names)
    assert np.all(np.isfinite(img)) and img.max() > 0


def test_textured_lines_carry_the_maps(material_assets, tmp_path):
    out, _ = material_assets
    r = run(out / "scene.glb", "--images", tmp_path / "images")
    line = next(x for x in r.stdout.splitlines() if x.split()[1] == "textured")
    words = dict(w.split("=", 1) for w in line.split()[3:])
    assert words["metallic_channel"] == "2" and words["roughness_channel"] == "1"
    assert words["occlusion_strength"] == "0.75" and words["normal_scale"] == "0.5"
    assert words["roughness_map"] == words["metallic_map"]
    with open(words["roughness_map"], "rb") as f:  # the PNG written out of the GLB
        assert f.read() == (out / "textures" / "metal_rough.png").read_bytes()
    assert "base_color_srgb" not in words  # sRGB is the scene format's default
    # what a line cannot carry is named on stderr
    assert "'textured': the base_color map: its texture transform" in r.stderr
    assert "'material_7': the clearcoat map is not carried" in r.stderr


def test_gltf_and_materialx_twins_render_the_same(material_assets, cli, tmp_path):
    out, gen = material_assets
    gl = run(out / "scene.gltf").stdout.splitlines()
    mx = run(out / "materials.mtlx").stdout.splitlines()
    names = list(gen.CONSTANTS)
    a = [next(x for x in gl if x.split()[1] == n) for n in names]
    b = [next(x for x in mx if x.split()[1] == "opbr_" + n) for n in names]
    for x, y in zip(a, b):
        assert x.split()[3:] == y.split()[3:]  # the same factors, word for word
    ia = render(cli, tmp_path, a, "gl", *names)
    ib = render(cli, tmp_path, b, "mx", *["opbr_" + n for n in names])
    assert ia.max() > 0 and np.array_equal(ia, ib)


def test_scene_names():
    taken = set()
    assert scene_materials.scene_name("Red Paint #2", taken) == "Red_Paint__2"
    assert scene_materials.scene_name("Red_Paint__2", taken) == "Red_Paint__2_2"
    assert scene_materials.scene_name("a=b\u00e9", taken) == "a_b_"
    assert scene_materials.scene_name("", taken) == "material"
    long = scene_materials.scene_name("x" * 100, taken)
    assert long == "x" * 63
    assert scene_materials.scene_name("x" * 100, taken) == "x" * 61 + "_2"


def test_unnamed_and_clashing_names_render(material_assets, cli, tmp_path):
    out, _ = material_assets
    doc = (out / "scene.gltf").read_text()
    p = tmp_path / "names.gltf"
    p.write_text(doc.replace('"name": "gold_mirror"', '"name": "red plastic"')
                 .replace('"name": "red_plastic"', '"name": "red_plastic"'))
    (tmp_path / "scene.bin").write_bytes((out / "scene.bin").read_bytes())
    (tmp_path / "textures").mkdir()
    for t in (out / "textures").iterdir():
        (tmp_path / "textures" / t.name).write_bytes(t.read_bytes())
    r = run(p)
    assert r.returncode == 0, r.stderr
    names = [x.split()[1] for x in r.stdout.splitlines()]
    assert names[:2] == ["red_plastic", "red_plastic_2"] and "material_7" in names
    render(cli, tmp_path, r.stdout.splitlines(), "names", "red_plastic_2")


@pytest.mark.parametrize("setup,message", [
    (lambda d: d / "missing.gltf", "missing.gltf: No such file"),
    (lambda d: (d / "x.obj").write_text("") and d / "x.obj", "not a .gltf, .glb or .mtlx"),
    (lambda d: (d / "b.gltf").write_text("{") and d / "b.gltf", "b.gltf: malformed JSON"),
])
def test_bad_files_one_line_exit_1(tmp_path, setup, message):
    r = run(setup(tmp_path))
    assert r.returncode == 1 and r.stdout == ""
    assert message in r.stderr and r.stderr.count("\n") == 1


def test_embedded_images_need_a_directory(material_assets):
    out, _ = material_assets
    r = run(out / "scene.glb")
    assert r.returncode == 1 and r.stdout == ""
    assert "is held inside the file; give --images DIR" in r.stderr
    assert r.stderr.count("\n") == 1
    assert run().returncode == 2 and "usage" in run().stderr


def test_paths_a_scene_cannot_carry(material_assets, tmp_path):
    out, _ = material_assets
    d = tmp_path / "with space"
    d.mkdir()
    (d / "textures").mkdir()
    for t in (out / "textures").iterdir():
        (d / "textures" / t.name).write_bytes(t.read_bytes())
    (d / "materials.mtlx").write_text((out / "materials.mtlx").read_text())
    r = run(d / "materials.mtlx")
    assert r.returncode == 1 and "holds a space" in r.stderr and r.stdout == ""


def test_abrdf_advise_reads_materialx_through_this_module(material_assets, cli, monkeypatch):
    """`abrdf advise FILE.mtlx` runs `python -m abrdf.scene_materials` ($ABRDF_PYTHON, this
    interpreter with this package): its choice for every constant material is
    abrdf.select's on the same PbrMaterial."""
    out, gen = material_assets
    mx = abrdf.load_materialx(out / "materials.mtlx")
    monkeypatch.setenv("ABRDF_PYTHON", sys.executable)
    for goal in ("photoreal", "performance"):
        d = cli("advise", out / "materials.mtlx", "--goal", goal, "--json")
        got = {m["material"]: m for m in d["materials"]}
        assert list(got) == list(mx)
        for prefix in ("gltf", "std", "opbr"):
            for name in gen.CONSTANTS:
                s = abrdf.select(mx["%s_%s" % (prefix, name)], goal=goal)
                m = got["%s_%s" % (prefix, name)]
                assert (m["type"], m["diffuse"], m["specular"]) == \
                    (s.type, s.diffuse, s.specular), (prefix, name, goal)


def test_abrdf_advise_gives_a_gltf_material_and_its_materialx_twin_the_same(material_assets,
                                                                             cli, monkeypatch):
    """`abrdf advise scene.gltf` (the C++ glTF reader) and `abrdf advise materials.mtlx` (this
    package's MaterialX reader): each constant material and its MaterialX twin, through each
    of the three shader nodes, get the same choice, parameters, predicted error and cost."""
    out, gen = material_assets
    monkeypatch.setenv("ABRDF_PYTHON", sys.executable)
    for goal in ("photoreal", "performance"):
        gl = {m["material"]: m for m in
              cli("advise", out / "scene.gltf", "--goal", goal, "--json")["materials"]}
        mx = {m["material"]: m for m in
              cli("advise", out / "materials.mtlx", "--goal", goal, "--json")["materials"]}
        for name in gen.CONSTANTS:
            for prefix in ("gltf", "std", "opbr"):
                a, b = gl[name], mx["%s_%s" % (prefix, name)]
                for key in ("type", "diffuse", "specular", "error", "cost"):
                    assert a[key] == b[key], (name, prefix, goal, key)
                for key, v in a["params"].items():
                    if key == "layers":  # a list of objects: compared field by field
                        assert len(b["params"][key]) == len(v), (name, prefix, goal)
                        for la, lb in zip(v, b["params"][key]):
                            for f, x in la.items():
                                assert lb[f] == pytest.approx(x, rel=1e-9, abs=1e-12), \
                                    (name, prefix, goal, f)
                    else:
                        assert b["params"][key] == pytest.approx(v, rel=1e-9, abs=1e-12), \
                            (name, prefix, goal, key)
