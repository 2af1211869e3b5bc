"""The material readers under seeded mutations of the generated files (a few hundred cases,
the same on every run): bytes of the GLB and the MaterialX document changed, cut or
inserted, and values of the glTF JSON replaced by values of other types and ranges. Each
case either loads (every material a PbrMaterial with a valid Pbr) or raises abrdf.Error
with one line naming the file; no other exception escapes."""
import copy
import json
import random

import pytest

import abrdf

ODD_VALUES = [None, True, -1, 0, 1, 7, 2 ** 70, -1e308, 1e308, 0.5, 3.5, float("nan"),
              "", "x", "data:", "../../etc/passwd", "a\0b", "%00", [], [1], [0.1] * 4,
              {}, {"index": 0}, {"index": -1}]


def check(load, path):
    try:
        mats = load(path)
    except abrdf.Error as e:
        text = str(e)
        assert text.startswith(str(path) + ": ") and "\n" not in text, text
        return "error"
    assert isinstance(mats, dict)
    for name, m in mats.items():
        assert isinstance(m, abrdf.PbrMaterial) and m.name == name
        abrdf.pbr_lobes(m.pbr)  # a Pbr that loaded is in its ranges
    return "loaded"


def mutate_bytes(data, rng):
    b = bytearray(data)
    for _ in range(rng.randint(1, 4)):
        kind = rng.randrange(4)
        at = rng.randrange(len(b))
        if kind == 0:
            b[at] = rng.randrange(256)
        elif kind == 1:
            b[at] ^= 1 << rng.randrange(8)
        elif kind == 2:
            del b[at:at + rng.randint(1, 16)]
        else:
            b[at:at] = bytes(rng.randrange(256) for _ in range(rng.randint(1, 8)))
    if rng.random() < 0.1:
        b = b[:rng.randrange(len(b))]
    return bytes(b)


def paths(node, prefix=()):
    """Every place of a JSON document: (path to it, its value)."""
    yield prefix
    if isinstance(node, dict):
        for k, v in node.items():
            yield from paths(v, prefix + (k,))
    elif isinstance(node, list):
        for i, v in enumerate(node):
            yield from paths(v, prefix + (i,))


def mutate_json(doc, rng):
    doc = copy.deepcopy(doc)
    places = [p for p in paths(doc) if p]
    for _ in range(rng.randint(1, 3)):
        p = rng.choice(places)
        parent = doc
        try:
            for k in p[:-1]:
                parent = parent[k]
            if rng.random() < 0.2 and isinstance(parent, dict):
                del parent[p[-1]]
            else:
                parent[p[-1]] = copy.deepcopy(rng.choice(ODD_VALUES))
        except (KeyError, IndexError, TypeError):
            pass  # an earlier mutation removed this place
    return doc


def test_glb_bytes(material_assets, tmp_path):
    out, _ = material_assets
    data = (out / "scene.glb").read_bytes()
    rng = random.Random(1)
    seen = set()
    for i in range(150):
        p = tmp_path / ("glb_%d.glb" % i)
        p.write_bytes(mutate_bytes(data, rng))
        seen.add(check(abrdf.load_gltf, p))
    assert seen == {"error", "loaded"}


def test_gltf_json_values(material_assets, tmp_path):
    out, _ = material_assets
    for d in ("textures",):
        (tmp_path / d).mkdir()
        for t in (out / d).iterdir():
            (tmp_path / d / t.name).write_bytes(t.read_bytes())
    (tmp_path / "scene.bin").write_bytes((out / "scene.bin").read_bytes())
    doc = json.loads((out / "scene.gltf").read_text())
    datauri = json.loads((out / "scene_datauri.gltf").read_text())
    rng = random.Random(2)
    seen = set()
    for i in range(200):
        p = tmp_path / ("json_%d.gltf" % i)
        p.write_text(json.dumps(mutate_json(doc if i % 2 else datauri, rng)))
        seen.add(check(abrdf.load_gltf, p))
    assert seen == {"error", "loaded"}


def test_gltf_text_bytes(material_assets, tmp_path):
    out, _ = material_assets
    data = (out / "scene_datauri.gltf").read_bytes()
    rng = random.Random(3)
    for i in range(60):
        p = tmp_path / ("text_%d.gltf" % i)
        p.write_bytes(mutate_bytes(data, rng))
        check(abrdf.load_gltf, p)


def test_materialx_bytes(material_assets, tmp_path):
    out, _ = material_assets
    (tmp_path / "textures").mkdir()
    for t in (out / "textures").iterdir():
        (tmp_path / "textures" / t.name).write_bytes(t.read_bytes())
    data = (out / "materials.mtlx").read_bytes()
    rng = random.Random(4)
    seen = set()
    for i in range(50):
        p = tmp_path / ("m_%d.mtlx" % i)
        p.write_bytes(mutate_bytes(data, rng))
        seen.add(check(abrdf.load_materialx, p))
    assert seen == {"error", "loaded"}


@pytest.mark.parametrize("value", ['value="nan"', 'value="1e400"', 'value="-3"',
                                   'value="0.5, 0.5"', 'nodename="nowhere"',
                                   'nodegraph="NG_std_textured" output="nothing"'])
def test_materialx_values(material_assets, tmp_path, value):
    out, _ = material_assets
    (tmp_path / "textures").mkdir()
    for t in (out / "textures").iterdir():
        (tmp_path / "textures" / t.name).write_bytes(t.read_bytes())
    text = (out / "materials.mtlx").read_text()
    p = tmp_path / "m.mtlx"
    p.write_text(text.replace('name="metalness" type="float" value="0.0"',
                              'name="metalness" type="float" ' + value, 1))
    assert check(abrdf.load_materialx, p) == "error"
