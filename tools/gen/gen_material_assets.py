#!/usr/bin/env python3
"""gen_material_assets.py - small glTF 2.0 and MaterialX files covering every material input
abrdf reads (docs/GLTF.md), for the tests of the readers (abrdf.load_gltf,
abrdf.load_materialx, python -m abrdf.scene_materials) and of the renderer.

    tools/gen/gen_material_assets.py OUTDIR

writes, byte for byte the same on every run of one OpenImageIO version (the PNGs are written
by OpenImageIO: Debian's python3-openimageio or the pip wheel; everything else is the
standard library):
    OUTDIR/textures/*.png   base colour (sRGB), metallic-roughness (G roughness across the
                            flowchart's smooth limit, B metallic), normal, and an RGBA map
                            for the extensions
    OUTDIR/scene.gltf       + scene.bin: every constant material, two textured ones (core maps
                            with KHR_texture_transform, and the extensions' maps), a quad per
                            material with UVs, a camera and a KHR_lights_punctual light
    OUTDIR/scene.glb        the same with its images inside the binary chunk
    OUTDIR/scene_datauri.gltf  the same with its buffer and images as data URIs
    OUTDIR/materials.mtlx   every constant material three times (gltf_pbr, standard_surface,
                            open_pbr_surface: the glTF file's factors through each node's
                            inputs) and textured materials of each node type

CONSTANTS below is the table of the constant materials; the tests read it to know what each
file must give.
"""
from __future__ import annotations

import base64
import json
import math
import os
import struct
import sys

# name -> the glTF factors (Pbr's fields; absent fields keep glTF's defaults). Roughness 0.02
# is below the flowchart's smooth limit (r <= 0.03, docs/SELECTION.md).
CONSTANTS: dict[str, dict[str, object]] = {
    "red_plastic": {"base_color": (0.8, 0.1, 0.1), "metallic": 0.0, "roughness": 0.4},
    "gold_mirror": {"base_color": (1.0, 0.75, 0.25), "metallic": 1.0, "roughness": 0.02},
    "coated_blue": {"base_color": (0.1, 0.2, 0.6), "metallic": 0.0, "roughness": 0.5,
                    "clearcoat": 1.0, "clearcoat_roughness": 0.05},
    "velvet": {"base_color": (0.3, 0.05, 0.1), "metallic": 0.0, "roughness": 0.8,
               "sheen_color": (0.8, 0.2, 0.4), "sheen_roughness": 0.75},
    "brushed_steel": {"base_color": (0.75, 0.75, 0.75), "metallic": 1.0, "roughness": 0.35,
                      "anisotropy": 0.75},
    "tinted_glass": {"base_color": (0.9, 0.95, 1.0), "metallic": 0.0, "roughness": 0.05,
                     "ior": 1.25, "specular": 0.75, "specular_color": (1.0, 0.875, 0.75),
                     "transmission": 0.875},
}
DEFAULTS: dict[str, object] = {
    "base_color": (1.0, 1.0, 1.0), "metallic": 1.0, "roughness": 1.0, "ior": 1.5,
    "specular": 1.0, "specular_color": (1.0, 1.0, 1.0), "clearcoat": 0.0,
    "clearcoat_roughness": 0.0, "sheen_color": (0.0, 0.0, 0.0), "sheen_roughness": 0.0,
    "anisotropy": 0.0, "anisotropy_rotation": 0.0, "transmission": 0.0}
# The roughness texels of metal_rough.png (green, 8-bit): 0.0118 and 0.0235 are smooth for
# the flowchart (r <= 0.03), 0.102 and 0.302 rough; 0.102 and 0.153 straddle r^2 = 0.03.
ROUGHNESS_BYTES = (3, 6, 26, 39, 77, 128, 153, 255)


# ---- PNG (8-bit RGB or RGBA, no filter) -----------------------------------------------

def png(width: int, height: int, rows: list[list[tuple[int, ...]]]) -> bytes:
    """The bytes of an 8-bit PNG of these pixels, written by OpenImageIO (Debian's
    python3-openimageio, or the pip wheel)."""
    import tempfile

    import OpenImageIO as oiio
    channels = len(rows[0][0])
    pixels = [c / 255.0 for row in rows for px in row for c in px]
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "t.png")
        out = oiio.ImageOutput.create(path)
        spec = oiio.ImageSpec(width, height, channels, "uint8")
        if not out or not out.open(path, spec):
            raise RuntimeError("cannot write a PNG: " + oiio.geterror())
        buf = oiio.ImageBuf(spec)
        for y in range(height):
            for x in range(width):
                base = (y * width + x) * channels
                buf.setpixel(x, y, pixels[base:base + channels])
        ok = out.write_image(buf.get_pixels(oiio.UINT8))
        out.close()
        if not ok:
            raise RuntimeError("cannot write a PNG: " + oiio.geterror())
        with open(path, "rb") as f:
            return f.read()


def textures() -> dict[str, bytes]:
    n = 8
    base = [[(200, 40 + 20 * x, 40 + 20 * y) for x in range(n)] for y in range(n)]
    # occlusion in red (glTF's ORM packing), roughness in green, metallic in blue
    mr = [[(255 - 8 * y, ROUGHNESS_BYTES[x], 255 if y >= n // 2 else 0) for x in range(n)]
          for y in range(n)]
    normal = [[(128, 128, 255)] * n for _ in range(n)]
    ext = [[(32 * x, 32 * y, 128, 255 - 16 * x) for x in range(n)] for y in range(n)]
    return {"base_color.png": png(n, n, base), "metal_rough.png": png(n, n, mr),
            "normal.png": png(n, n, normal), "ext.png": png(n, n, ext)}


# ---- glTF ------------------------------------------------------------------------------

def quad_buffer() -> tuple[bytes, list[dict[str, object]], list[dict[str, object]]]:
    """A unit quad in the xy plane facing +z: positions, normals, UVs, indices."""
    pos = [(-0.5, -0.5, 0.0), (0.5, -0.5, 0.0), (0.5, 0.5, 0.0), (-0.5, 0.5, 0.0)]
    uv = [(0.0, 1.0), (1.0, 1.0), (1.0, 0.0), (0.0, 0.0)]
    data = b"".join(struct.pack("<3f", *p) for p in pos)
    data += b"".join(struct.pack("<3f", 0.0, 0.0, 1.0) for _ in pos)
    data += b"".join(struct.pack("<2f", *t) for t in uv)
    data += struct.pack("<6H", 0, 1, 2, 0, 2, 3) + b"\0\0"
    views = [{"buffer": 0, "byteOffset": 0, "byteLength": 96, "target": 34962},
             {"buffer": 0, "byteOffset": 96, "byteLength": 32, "target": 34962},
             {"buffer": 0, "byteOffset": 128, "byteLength": 12, "target": 34963}]
    accessors = [
        {"bufferView": 0, "byteOffset": 0, "componentType": 5126, "count": 4, "type": "VEC3",
         "min": [-0.5, -0.5, 0.0], "max": [0.5, 0.5, 0.0]},
        {"bufferView": 0, "byteOffset": 48, "componentType": 5126, "count": 4, "type": "VEC3"},
        {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"},
        {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}]
    return data, views, accessors


def gltf_constant(f: dict[str, object]) -> dict[str, object]:
    m: dict[str, object] = {"pbrMetallicRoughness": {
        "baseColorFactor": list(f.get("base_color", (1, 1, 1))) + [1.0],
        "metallicFactor": f.get("metallic", 1.0), "roughnessFactor": f.get("roughness", 1.0)}}
    ext: dict[str, dict[str, object]] = {}
    if "ior" in f:
        ext["KHR_materials_ior"] = {"ior": f["ior"]}
    if "specular" in f or "specular_color" in f:
        ext["KHR_materials_specular"] = {"specularFactor": f.get("specular", 1.0),
                                         "specularColorFactor": list(
                                             f.get("specular_color", (1, 1, 1)))}
    if "clearcoat" in f:
        ext["KHR_materials_clearcoat"] = {"clearcoatFactor": f["clearcoat"],
                                          "clearcoatRoughnessFactor":
                                          f.get("clearcoat_roughness", 0.0)}
    if "sheen_color" in f:
        ext["KHR_materials_sheen"] = {"sheenColorFactor": list(f["sheen_color"]),  # type: ignore
                                      "sheenRoughnessFactor": f.get("sheen_roughness", 0.0)}
    if "anisotropy" in f:
        ext["KHR_materials_anisotropy"] = {"anisotropyStrength": f["anisotropy"],
                                           "anisotropyRotation": 0.0}
    if "transmission" in f:
        ext["KHR_materials_transmission"] = {"transmissionFactor": f["transmission"]}
    if ext:
        m["extensions"] = ext
    return m


def gltf_document(image_refs: list[dict[str, object]]) -> dict[str, object]:
    """The glTF JSON (buffer 0 and the images filled in by the caller)."""
    _, views, accessors = quad_buffer()
    materials = []
    for name, f in CONSTANTS.items():
        m = gltf_constant(f)
        m["name"] = name
        materials.append(m)
    # textures: 0 base colour, 1 metallic-roughness, 2 normal, 3 extensions (RGBA)
    materials.append({
        "name": "textured",
        "pbrMetallicRoughness": {
            "baseColorFactor": [1.0, 0.9, 0.8, 1.0], "metallicFactor": 1.0,
            "roughnessFactor": 1.0,
            "baseColorTexture": {"index": 0, "extensions": {"KHR_texture_transform": {
                "offset": [0.25, 0.0], "scale": [2.0, 2.0], "rotation": 0.5}}},
            "metallicRoughnessTexture": {"index": 1}},
        "normalTexture": {"index": 2, "scale": 0.5},
        "occlusionTexture": {"index": 1, "strength": 0.75}})
    materials.append({
        "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1.0],
                                 "metallicFactor": 0.0, "roughnessFactor": 0.5},
        "extensions": {
            "KHR_materials_specular": {"specularTexture": {"index": 3},
                                       "specularColorTexture": {"index": 0}},
            "KHR_materials_clearcoat": {"clearcoatFactor": 0.5,
                                        "clearcoatTexture": {"index": 3},
                                        "clearcoatRoughnessTexture": {"index": 3}},
            "KHR_materials_sheen": {"sheenColorFactor": [0.5, 0.5, 0.5],
                                    "sheenColorTexture": {"index": 0},
                                    "sheenRoughnessTexture": {"index": 3}},
            "KHR_materials_anisotropy": {"anisotropyStrength": 0.5,
                                         "anisotropyTexture": {"index": 3, "texCoord": 0}},
            "KHR_materials_transmission": {"transmissionFactor": 0.5,
                                           "transmissionTexture": {"index": 3}}}})
    meshes = [{"name": "quad_%s" % m.get("name", "material_%d" % i),
               "primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2},
                               "indices": 3, "material": i}]}
              for i, m in enumerate(materials)]
    nodes: list[dict[str, object]] = [
        {"name": m["name"], "mesh": i,
         "translation": [1.25 * (i % 4) - 1.875, 1.25 * (i // 4) - 0.625, 0.0]}
        for i, m in enumerate(meshes)]
    nodes.append({"name": "camera", "camera": 0, "translation": [0.0, 0.0, 6.0]})
    nodes.append({"name": "light", "translation": [1.0, 2.0, 4.0],
                  "extensions": {"KHR_lights_punctual": {"light": 0}}})
    exts = ["KHR_lights_punctual", "KHR_materials_anisotropy", "KHR_materials_clearcoat",
            "KHR_materials_ior", "KHR_materials_sheen", "KHR_materials_specular",
            "KHR_materials_transmission", "KHR_texture_transform"]
    return {
        "asset": {"version": "2.0", "generator": "abrdf tools/gen/gen_material_assets.py"},
        "extensionsUsed": exts,
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"type": "point", "color": [1.0, 1.0, 1.0], "intensity": 40.0}]}},
        "scene": 0, "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes, "meshes": meshes, "materials": materials,
        "cameras": [{"type": "perspective", "perspective": {
            "yfov": 0.7, "aspectRatio": 1.0, "znear": 0.1, "zfar": 100.0}}],
        "textures": [{"source": i, "sampler": 0} for i in range(4)],
        "samplers": [{"magFilter": 9729, "minFilter": 9987, "wrapS": 10497, "wrapT": 10497}],
        "images": image_refs,
        "buffers": [], "bufferViews": views, "accessors": accessors}


TEXTURE_ORDER = ("base_color.png", "metal_rough.png", "normal.png", "ext.png")


def write_gltf_files(out: str, tex: dict[str, bytes]) -> None:
    data, _, _ = quad_buffer()
    # external: scene.gltf + scene.bin + textures/
    doc = gltf_document([{"uri": "textures/" + t} for t in TEXTURE_ORDER])
    doc["buffers"] = [{"uri": "scene.bin", "byteLength": len(data)}]
    write(os.path.join(out, "scene.bin"), data)
    write(os.path.join(out, "scene.gltf"), json_bytes(doc))
    # data URIs
    doc = gltf_document([{"uri": "data:image/png;base64,"
                          + base64.b64encode(tex[t]).decode("ascii")} for t in TEXTURE_ORDER])
    doc["buffers"] = [{"uri": "data:application/octet-stream;base64,"
                       + base64.b64encode(data).decode("ascii"), "byteLength": len(data)}]
    write(os.path.join(out, "scene_datauri.gltf"), json_bytes(doc))
    # GLB: the images after the mesh data in the one binary chunk, each 4-byte aligned
    binary = bytearray(data)
    images = []
    doc = gltf_document([])
    views: list[dict[str, object]] = doc["bufferViews"]  # type: ignore[assignment]
    for t in TEXTURE_ORDER:
        binary += b"\0" * (-len(binary) % 4)  # each image 4-byte aligned, and the chunk's end
        views.append({"buffer": 0, "byteOffset": len(binary), "byteLength": len(tex[t])})
        images.append({"bufferView": len(views) - 1, "mimeType": "image/png"})
        binary += tex[t]
    binary += b"\0" * (-len(binary) % 4)
    doc["images"] = images
    doc["buffers"] = [{"byteLength": len(binary)}]
    js = json_bytes(doc)
    js += b" " * (-len(js) % 4)
    glb = (struct.pack("<III", 0x46546C67, 2, 12 + 8 + len(js) + 8 + len(binary))
           + struct.pack("<II", len(js), 0x4E4F534A) + js
           + struct.pack("<II", len(binary), 0x004E4942) + bytes(binary))
    write(os.path.join(out, "scene.glb"), glb)


# ---- MaterialX -------------------------------------------------------------------------

def fmt(v: object) -> str:
    if isinstance(v, tuple):
        return ", ".join(fmt(x) for x in v)
    return repr(float(v))  # type: ignore[arg-type]


def mx_input(name: str, kind: str, value: object) -> str:
    return '    <input name="%s" type="%s" value="%s" />\n' % (name, kind, fmt(value))


def mx_constant(name: str, f: dict[str, object], node: str) -> str:
    """One constant material as a `node` shader (gltf_pbr, standard_surface or
    open_pbr_surface) whose inputs give the glTF factors f (with glTF's defaults)."""
    g = dict(DEFAULTS)
    g.update(f)
    col, num = "color3", "float"
    if node == "gltf_pbr":
        inputs = [(k, col if isinstance(v, tuple) else num, v) for k, v in g.items()
                  if k not in ("anisotropy", "anisotropy_rotation")]
        inputs += [("anisotropy_strength", num, g["anisotropy"]),
                   ("anisotropy_rotation", num, g["anisotropy_rotation"])]
    elif node == "standard_surface":
        inputs = [("base", num, 1.0), ("base_color", col, g["base_color"]),
                  ("metalness", num, g["metallic"]),
                  ("specular_roughness", num, g["roughness"]),
                  ("specular_IOR", num, g["ior"]), ("specular", num, g["specular"]),
                  ("specular_color", col, g["specular_color"]), ("coat", num, g["clearcoat"]),
                  ("coat_roughness", num, g["clearcoat_roughness"]), ("sheen", num, 1.0),
                  ("sheen_color", col, g["sheen_color"]),
                  ("sheen_roughness", num, g["sheen_roughness"]),
                  ("specular_anisotropy", num, g["anisotropy"]),
                  ("specular_rotation", num, g["anisotropy_rotation"] / (2 * math.pi)),
                  ("transmission", num, g["transmission"])]
    else:
        inputs = [("base_weight", num, 1.0), ("base_color", col, g["base_color"]),
                  ("base_metalness", num, g["metallic"]),
                  ("specular_roughness", num, g["roughness"]),
                  ("specular_ior", num, g["ior"]), ("specular_weight", num, g["specular"]),
                  ("specular_color", col, g["specular_color"]),
                  ("coat_weight", num, g["clearcoat"]),
                  ("coat_roughness", num, g["clearcoat_roughness"]),
                  ("fuzz_weight", num, 1.0), ("fuzz_color", col, g["sheen_color"]),
                  ("fuzz_roughness", num, g["sheen_roughness"]),
                  ("specular_roughness_anisotropy", num, g["anisotropy"]),
                  ("transmission_weight", num, g["transmission"])]
    shader = "SR_" + name
    return ('  <%s name="%s" type="surfaceshader">\n' % (node, shader)
            + "".join(mx_input(*i) for i in inputs) + "  </%s>\n" % node
            + material(name, shader))


def material(name: str, shader: str) -> str:
    return ('  <surfacematerial name="%s" type="material">\n'
            '    <input name="surfaceshader" type="surfaceshader" nodename="%s" />\n'
            '  </surfacematerial>\n' % (name, shader))


PREFIX = {"gltf_pbr": "gltf", "standard_surface": "std", "open_pbr_surface": "opbr"}

MX_TEXTURED = '''\
  <nodegraph name="NG_std_textured">
    <image name="base_image" type="color3">
      <input name="file" type="filename" value="base_color.png" colorspace="srgb_texture" />
    </image>
    <image name="mr_image" type="vector3">
      <input name="file" type="filename" value="metal_rough.png" />
    </image>
    <extract name="roughness" type="float">
      <input name="in" type="vector3" nodename="mr_image" />
      <input name="index" type="integer" value="1" />
    </extract>
    <separate3 name="mr_split" type="multioutput">
      <input name="in" type="vector3" nodename="mr_image" />
    </separate3>
    <image name="normal_image" type="vector3">
      <input name="file" type="filename" value="normal.png" />
    </image>
    <normalmap name="normal_map" type="vector3">
      <input name="in" type="vector3" nodename="normal_image" />
      <input name="scale" type="float" value="0.5" />
    </normalmap>
    <output name="base_out" type="color3" nodename="base_image" />
    <output name="roughness_out" type="float" nodename="roughness" />
    <output name="metallic_out" type="float" nodename="mr_split" output="outz" />
    <output name="normal_out" type="vector3" nodename="normal_map" />
  </nodegraph>
  <standard_surface name="SR_std_textured" type="surfaceshader">
    <input name="base_color" type="color3" nodegraph="NG_std_textured" output="base_out" />
    <input name="metalness" type="float" nodegraph="NG_std_textured" output="metallic_out" />
    <input name="specular_roughness" type="float" nodegraph="NG_std_textured"
           output="roughness_out" />
    <input name="normal" type="vector3" nodegraph="NG_std_textured" output="normal_out" />
  </standard_surface>
  <surfacematerial name="std_textured" type="material">
    <input name="surfaceshader" type="surfaceshader" nodename="SR_std_textured" />
  </surfacematerial>
  <tiledimage name="opbr_rough_image" type="float">
    <input name="file" type="filename" value="metal_rough.png" />
  </tiledimage>
  <texcoord name="uv1" type="vector2">
    <input name="index" type="integer" value="1" />
  </texcoord>
  <image name="opbr_base_image" type="color3">
    <input name="file" type="filename" value="base_color.png" colorspace="srgb_texture" />
    <input name="texcoord" type="vector2" nodename="uv1" />
  </image>
  <open_pbr_surface name="SR_opbr_textured" type="surfaceshader">
    <input name="base_color" type="color3" nodename="opbr_base_image" />
    <input name="base_metalness" type="float" value="0.0" />
    <input name="specular_roughness" type="float" nodename="opbr_rough_image" />
  </open_pbr_surface>
  <surfacematerial name="opbr_textured" type="material">
    <input name="surfaceshader" type="surfaceshader" nodename="SR_opbr_textured" />
  </surfacematerial>
  <gltf_colorimage name="gltf_base_image" type="multioutput">
    <input name="file" type="filename" value="base_color.png" colorspace="srgb_texture" />
    <input name="color" type="color4" value="1.0, 0.9, 0.8, 1.0" />
  </gltf_colorimage>
  <gltf_image name="gltf_mr_image" type="vector3">
    <input name="file" type="filename" value="metal_rough.png" />
  </gltf_image>
  <extract name="gltf_roughness" type="float">
    <input name="in" type="vector3" nodename="gltf_mr_image" />
    <input name="index" type="integer" value="1" />
  </extract>
  <extract name="gltf_metallic" type="float">
    <input name="in" type="vector3" nodename="gltf_mr_image" />
    <input name="index" type="integer" value="2" />
  </extract>
  <gltf_image name="gltf_clearcoat_image" type="float">
    <input name="file" type="filename" value="ext.png" />
    <input name="factor" type="float" value="0.5" />
  </gltf_image>
  <gltf_pbr name="SR_gltf_textured" type="surfaceshader">
    <input name="base_color" type="color3" nodename="gltf_base_image" output="outcolor" />
    <input name="metallic" type="float" nodename="gltf_metallic" />
    <input name="roughness" type="float" nodename="gltf_roughness" />
    <input name="clearcoat" type="float" nodename="gltf_clearcoat_image" />
  </gltf_pbr>
  <surfacematerial name="gltf_textured" type="material">
    <input name="surfaceshader" type="surfaceshader" nodename="SR_gltf_textured" />
  </surfacematerial>
'''


def write_materialx(out: str) -> None:
    body = "".join(mx_constant("%s_%s" % (PREFIX[node], name), f, node)
                   for node in PREFIX for name, f in CONSTANTS.items())
    text = ('<?xml version="1.0"?>\n'
            '<materialx version="1.39" fileprefix="textures/">\n' + body + MX_TEXTURED
            + "</materialx>\n")
    write(os.path.join(out, "materials.mtlx"), text.encode("ascii"))


# ---- files -----------------------------------------------------------------------------

def json_bytes(doc: object) -> bytes:
    return (json.dumps(doc, indent=1) + "\n").encode("ascii")


def write(path: str, data: bytes) -> None:
    with open(path, "wb") as f:
        f.write(data)


def generate(out: str) -> None:
    os.makedirs(os.path.join(out, "textures"), exist_ok=True)
    tex = textures()
    for name, data in tex.items():
        write(os.path.join(out, "textures", name), data)
    write_gltf_files(out, tex)
    write_materialx(out)


def main(argv: list[str]) -> int:
    if len(argv) != 2 or argv[1].startswith("-"):
        sys.stderr.write("usage: gen_material_assets.py OUTDIR\n")
        return 2
    try:
        generate(argv[1])
    except OSError as e:
        sys.stderr.write("%s: %s\n" % (e.filename or argv[1], e.strerror or e))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
