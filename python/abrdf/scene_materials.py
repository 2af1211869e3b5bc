"""python -m abrdf.scene_materials FILE [--images DIR]: the materials of a glTF 2.0 file
(.gltf, .glb) or a MaterialX document (.mtlx) as scene-format lines, one per material:

    material NAME pbr base_color=R,G,B metallic=M roughness=R ... [roughness_map=PATH ...]

(docs/GLTF.md, "In a scene"; `abrdf render` reads them). Every factor is written; each map
the scene format carries (base colour, metallic, roughness, occlusion, normal) is an absolute
path with its channel. Names are made scene names: printable ASCII without spaces, '#' or
'=' (others become '_'), at most 63 characters, unique ("_2", "_3" appended). Images held
inside a file (GLB buffers, data URIs) are written to DIR (--images; without it such a
material is an error). What a scene line cannot say (the extensions' maps, texture
transforms, texture coordinate sets other than 0) is named on stderr, one line each, and
left out. A bad file: one line "FILE: problem" on stderr, exit 1, nothing on stdout.
"""
from __future__ import annotations

import hashlib
import os
import sys

from . import _abrdf
from ._gltf import load_gltf
from ._materialx import load_materialx
from ._pbr import IDENTITY, Pbr, PbrMaterial, TextureRef

NAME_MAX = 63  # SCENE_NAME_MAX - 1 (tools/render/scene.h)
WORD_MAX = 256  # SCENE_WORD_MAX (tools/render/scene.c)
# The maps a scene line carries, with the channel key of the one-channel ones.
SCENE_MAPS = {"base_color": None, "metallic": "metallic_channel",
              "roughness": "roughness_channel", "occlusion": "occlusion_channel",
              "normal": None}
_COLOURS = ("base_color", "specular_color", "sheen_color")
_EXT = {"image/png": ".png", "image/jpeg": ".jpg"}


class _Bad(Exception):
    pass


def scene_name(name: str, taken: set[str]) -> str:
    """`name` as a scene material name, unique among `taken` (which it joins)."""
    s = "".join(c if 0x21 <= ord(c) <= 0x7E and c not in "#=" else "_" for c in name)
    s = s[:NAME_MAX] or "material"
    k, out = 2, s
    while out in taken:
        suffix = "_%d" % k
        out = s[:NAME_MAX - len(suffix)] + suffix
        k += 1
    taken.add(out)
    return out


def _number(v: float) -> str:
    return repr(float(v))


def _image_path(t: TextureRef, images: str | None, what: str) -> str:
    if t.file is not None:
        return t.file
    if images is None:
        raise _Bad("%s is held inside the file; give --images DIR to write it out" % what)
    data = t.embedded or b""
    ext = _EXT.get(t.mime_type or "", ".png")
    path = os.path.join(os.path.abspath(images), hashlib.sha256(data).hexdigest()[:16] + ext)
    if not os.path.exists(path):
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "wb") as f:
            f.write(data)
    return path


def scene_line(m: PbrMaterial, name: str, images: str | None = None,
               notes: list[str] | None = None) -> str:
    """The scene line of one material (docs/GLTF.md, "In a scene")."""
    p: Pbr = m.pbr
    words = ["material", name, "pbr"]
    for f in ("base_color", "metallic", "roughness", "ior", "specular", "specular_color",
              "clearcoat", "clearcoat_roughness", "sheen_color", "sheen_roughness",
              "anisotropy", "anisotropy_rotation", "transmission"):
        v = getattr(p, f)
        words.append("%s=%s" % (f, ",".join(map(_number, v)) if f in _COLOURS else _number(v)))
    for slot, t in m.textures.items():
        what = "material '%s': the %s map" % (m.name, slot)
        if slot not in SCENE_MAPS:
            if notes is not None:
                notes.append("%s is not carried by a scene line (its factor is)" % what)
            continue
        if notes is not None and t.transform != IDENTITY:
            notes.append("%s: its texture transform is not carried by a scene line" % what)
        if notes is not None and t.uv_set != 0:
            notes.append("%s: its texture coordinate set %d is not carried by a scene line "
                         "(set 0 is read)" % (what, t.uv_set))
        path = _image_path(t, images, what)
        if any(c in path for c in " \t#") or any(ord(c) < 0x20 or ord(c) == 0x7F for c in path):
            raise _Bad("%s: its path %r holds a space, tab, '#' or control character, which "
                       "a scene line cannot carry" % (what, path))
        word = "%s_map=%s" % (slot, path)
        if len(word) > WORD_MAX:
            raise _Bad("%s: its path is longer than a scene word (%d characters)"
                       % (what, WORD_MAX))
        words.append(word)
        channel_key = SCENE_MAPS[slot]
        if channel_key and t.channel is not None:
            words.append("%s=%d" % (channel_key, t.channel))
        if slot == "base_color" and not t.srgb:
            words.append("base_color_srgb=off")
    if "occlusion" in m.textures and m.occlusion_strength != 1.0:
        if not 0.0 <= m.occlusion_strength <= 1.0:
            raise _Bad("material '%s': occlusion strength %g is outside [0, 1]"
                       % (m.name, m.occlusion_strength))
        words.append("occlusion_strength=%s" % _number(m.occlusion_strength))
    if "normal" in m.textures and m.normal_scale != 1.0:
        if not -100.0 <= m.normal_scale <= 100.0:
            raise _Bad("material '%s': normal scale %g is outside [-100, 100]"
                       % (m.name, m.normal_scale))
        words.append("normal_scale=%s" % _number(m.normal_scale))
    return " ".join(words)


def load(path: str) -> dict[str, PbrMaterial]:
    """The materials of a .gltf, .glb or .mtlx file (by its extension)."""
    ext = os.path.splitext(path)[1].lower()
    if ext in (".gltf", ".glb"):
        return load_gltf(path)
    if ext == ".mtlx":
        return load_materialx(path)
    err = _abrdf.Error("%s: not a .gltf, .glb or .mtlx file" % path)
    err.status = None
    raise err


def scene_lines(path: str, images: str | None = None,
                notes: list[str] | None = None) -> list[str]:
    """The scene lines of every material of a file (abrdf.Error "FILE: problem")."""
    taken: set[str] = set()
    try:
        return [scene_line(m, scene_name(m.name, taken), images, notes)
                for m in load(path).values()]
    except (_Bad, OSError) as e:
        err = _abrdf.Error("%s: %s" % (path, e))
        err.status = None
        raise err from None


USAGE = "usage: python -m abrdf.scene_materials FILE.(gltf|glb|mtlx) [--images DIR]\n"


def main(argv: list[str]) -> int:
    args, images = list(argv[1:]), None
    if "--images" in args:
        i = args.index("--images")
        if i + 1 >= len(args):
            sys.stderr.write(USAGE)
            return 2
        images = args[i + 1]
        del args[i:i + 2]
    if len(args) != 1 or args[0].startswith("-"):
        sys.stderr.write(USAGE)
        return 2
    notes: list[str] = []
    try:
        lines = scene_lines(args[0], images, notes)
    except _abrdf.Error as e:
        sys.stderr.write("%s\n" % " ".join(str(e).split()))
        return 1
    for n in notes:
        sys.stderr.write("%s: note: %s\n" % (args[0], n))
    sys.stdout.write("".join(line + "\n" for line in lines))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
