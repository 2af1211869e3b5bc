"""make_gltf_corpus.py - writes the seeds of fuzz_gltf (tests/fuzz/fuzz_gltf.c) beside itself:
small glTF files, as .gltf text (buffers as data: URIs, or one .bin file beside them) and as
.glb, covering what the reader reads (indices of every width, strips and fans, node
hierarchies, materials with extensions and textures, cameras, lights) and a few broken ones.
The seeds are committed; run this again only to change them."""
import base64
import math
import os
import struct
import sys
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "..", "cli"))
from gltf_build import Gltf, cube, UBYTE, USHORT  # noqa: E402


def png_1x1(rgb):
    """A 1x1 8-bit RGB PNG."""
    def chunk(tag, data):
        return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data))
    raw = b"\0" + bytes(rgb)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", 1, 1, 8, 2, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def scene_cube():
    g = Gltf()
    pos, nrm, idx = cube()
    mat = g.material(pbrMetallicRoughness={"baseColorFactor": [0.8, 0.3, 0.2, 1],
                                           "metallicFactor": 0.0, "roughnessFactor": 0.5},
                     extensions={"KHR_materials_ior": {"ior": 1.4},
                                 "KHR_materials_specular": {"specularFactor": 0.7},
                                 "KHR_materials_clearcoat": {"clearcoatFactor": 0.5}})
    m = g.mesh(pos, idx, nrm, material=mat, index_type=USHORT)
    g.node(mesh=m, translation=[0.1, 0.2, -0.3], rotation=[0, 0.2588, 0, 0.9659])
    g.doc["cameras"] = [{"type": "perspective",
                         "perspective": {"yfov": 0.7, "aspectRatio": 1.5, "znear": 0.1}}]
    g.node(camera=0, translation=[0, 0.5, 4])
    g.doc["extensionsUsed"] = ["KHR_lights_punctual", "KHR_materials_ior",
                               "KHR_materials_specular", "KHR_materials_clearcoat"]
    g.doc["extensions"] = {"KHR_lights_punctual": {"lights": [
        {"type": "point", "intensity": 20}, {"type": "directional", "color": [1, 0.5, 0.5]}]}}
    g.node(translation=[2, 3, 3], extensions={"KHR_lights_punctual": {"light": 0}})
    g.node(rotation=[-0.3827, 0, 0, 0.9239], extensions={"KHR_lights_punctual": {"light": 1}})
    return g


def scene_strip():
    """A quad as a strip and as a fan (u8 indices), in a parent-child hierarchy, no camera
    and no light (the defaults), TEXCOORD_0 and a textured material with a transform."""
    g = Gltf()
    pos = [0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0]
    uv = [0, 0, 1, 0, 0, 1, 1, 1]
    img = png_1x1((200, 100, 50))
    g.doc["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(img).decode()}]
    g.doc["textures"] = [{"source": 0}]
    mat = g.material(pbrMetallicRoughness={
        "baseColorTexture": {"index": 0, "extensions": {"KHR_texture_transform": {
            "offset": [0.5, 0], "scale": [2, 2], "rotation": 0.3}}},
        "metallicRoughnessTexture": {"index": 0}}, normalTexture={"index": 0, "scale": 0.5})
    strip = g.mesh(pos, [0, 1, 2, 3], uvs=uv, material=mat, mode=5, index_type=UBYTE)
    fan = g.mesh(pos, [0, 1, 3, 2], mode=6, index_type=UBYTE)
    child = g.node(root=False, mesh=fan, translation=[2, 0, 0], scale=[1, -1, 1])
    g.node(mesh=strip, children=[child],
           matrix=[1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0.5, 0, 0, 1])
    return g


def main():
    cube_g = scene_cube()
    cube_g.write_gltf(os.path.join(HERE, "cube.gltf"))
    cube_g.write_glb(os.path.join(HERE, "cube.glb"))
    strip = scene_strip()
    strip.write_gltf(os.path.join(HERE, "strip.gltf"), "strip.bin")
    strip.write_glb(os.path.join(HERE, "strip.glb"))
    with open(os.path.join(HERE, "bad_index.gltf"), "w") as f:
        g = Gltf()
        g.node(mesh=g.mesh([0, 0, 0, 1, 0, 0, 0, 1, 0], [0, 1, 7]))
        g.write_gltf(f.name)
    with open(os.path.join(HERE, "ortho.gltf"), "w") as f:
        g = Gltf()
        g.node(mesh=g.mesh([0, 0, 0, 1, 0, 0, 0, 1, 0]))
        g.doc["cameras"] = [{"type": "orthographic",
                             "orthographic": {"xmag": 1, "ymag": 1, "znear": 0.1, "zfar": 9}}]
        g.node(camera=0)
        g.write_gltf(f.name)
    glb = cube_g.glb_bytes()
    with open(os.path.join(HERE, "cut.glb"), "wb") as f:
        f.write(glb[:len(glb) // 2])


if __name__ == "__main__":
    main()
