"""abrdf.load_gltf: the materials of a glTF 2.0 file (.gltf JSON or .glb binary), read with
the standard library. Only what materials need is parsed and validated: the materials, their
KHR material extensions, and the textures, images, samplers, buffer views and buffers their
maps name (glTF 2.0 specification, sections 3.9 Materials, 3.8 Textures, 4.4 GLB). Every
problem is one line, "FILE: where: problem", raised as abrdf.Error."""
from __future__ import annotations

import binascii
import json
import math
import os
import struct
import urllib.parse
from typing import Any

from . import _abrdf
from ._pbr import IDENTITY, Pbr, PbrMaterial, TextureRef, Transform

_GLB_MAGIC = 0x46546C67  # "glTF"
_CHUNK_JSON = 0x4E4F534A  # "JSON"
_CHUNK_BIN = 0x004E4942  # "BIN\0"

# Extensions a file may require that leave its materials as this reader reads them
# (geometry compression and lights do not touch a material; the rest are read here).
_READ = {"KHR_materials_ior", "KHR_materials_specular", "KHR_materials_clearcoat",
         "KHR_materials_sheen", "KHR_materials_anisotropy", "KHR_materials_transmission",
         "KHR_texture_transform"}
_HARMLESS = {"KHR_lights_punctual", "KHR_mesh_quantization", "KHR_draco_mesh_compression",
             "EXT_meshopt_compression", "KHR_materials_emissive_strength",
             "KHR_materials_unlit"}

Json = Any


class _Bad(Exception):
    """A problem at a place in the file: where (a JSON path) and what."""

    def __init__(self, where: str, what: str) -> None:
        super().__init__("%s: %s" % (where, what) if where else what)


def _error(message: str) -> _abrdf.Error:
    err = _abrdf.Error(" ".join(message.split()))  # one line, whatever the parts held
    err.status = None
    return err


def _is_number(v: Json) -> bool:
    if not isinstance(v, (int, float)) or isinstance(v, bool):
        return False
    try:
        return math.isfinite(float(v))
    except OverflowError:  # an integer beyond a double's range
        return False


def _number(d: dict[str, Json], key: str, where: str, default: float) -> float:
    v = d.get(key, default)
    if not _is_number(v):
        raise _Bad("%s.%s" % (where, key), "a finite number is needed, got %s" % _shown(v))
    return float(v)


def _numbers(d: dict[str, Json], key: str, where: str, default: tuple[float, ...]
             ) -> tuple[float, ...]:
    v = d.get(key, list(default))
    if not (isinstance(v, list) and len(v) == len(default) and all(map(_is_number, v))):
        raise _Bad("%s.%s" % (where, key), "%d finite numbers are needed, got %s"
                   % (len(default), _shown(v)))
    return tuple(float(x) for x in v)


def _index(d: dict[str, Json], key: str, where: str, items: list[Json] | None,
           what: str) -> int:
    v = d.get(key)
    if not (isinstance(v, int) and not isinstance(v, bool)):
        raise _Bad("%s.%s" % (where, key), "an index is needed, got %s" % _shown(v))
    if items is None or not 0 <= v < len(items):
        raise _Bad("%s.%s" % (where, key), "%s %d does not exist (the file has %d)"
                   % (what, v, 0 if items is None else len(items)))
    return v


def _object(v: Json, where: str) -> dict[str, Json]:
    if not isinstance(v, dict):
        raise _Bad(where, "an object is needed, got %s" % _shown(v))
    return v


def _array(root: dict[str, Json], key: str) -> list[Json] | None:
    v = root.get(key)
    if v is None:
        return None
    if not isinstance(v, list):
        raise _Bad(key, "an array is needed, got %s" % _shown(v))
    return v


def _shown(v: Json) -> str:
    s = json.dumps(v) if not isinstance(v, bytes) else repr(v)
    return s if len(s) <= 40 else s[:37] + "..."


def _split_glb(data: bytes) -> tuple[bytes, bytes | None]:
    """The JSON chunk and the BIN chunk (None if absent) of a GLB file (section 4.4)."""
    if len(data) < 12:
        raise _Bad("", "a GLB file has a 12-byte header; this one has %d bytes" % len(data))
    magic, version, length = struct.unpack_from("<III", data, 0)
    if version != 2:
        raise _Bad("", "GLB version %d (abrdf reads version 2)" % version)
    if length != len(data):
        raise _Bad("", "the GLB header says %d bytes, the file has %d" % (length, len(data)))
    chunks: list[tuple[int, bytes]] = []
    at = 12
    while at < len(data):
        if at + 8 > len(data):
            raise _Bad("", "chunk %d: its header is cut at byte %d" % (len(chunks), at))
        size, kind = struct.unpack_from("<II", data, at)
        if at + 8 + size > len(data):
            raise _Bad("", "chunk %d: %d bytes from byte %d run past the end (%d bytes)"
                       % (len(chunks), size, at + 8, len(data)))
        chunks.append((kind, data[at + 8:at + 8 + size]))
        at += 8 + size
    if not chunks or chunks[0][0] != _CHUNK_JSON:
        raise _Bad("", "the first GLB chunk must be JSON")
    binary = chunks[1][1] if len(chunks) > 1 and chunks[1][0] == _CHUNK_BIN else None
    return chunks[0][1], binary


def _decode_data_uri(uri: str, where: str) -> tuple[bytes, str | None]:
    head, comma, body = uri.partition(",")
    if not comma or not head.endswith(";base64"):
        raise _Bad(where, "a data URI must be base64 ('data:MIME;base64,...')")
    try:
        return binascii.a2b_base64(body.encode("ascii"), strict_mode=True), head[5:-7] or None
    except (binascii.Error, UnicodeEncodeError, ValueError) as e:
        raise _Bad(where, "the data URI's base64 is malformed (%s)" % e) from None


def _file_of_uri(uri: str, base: str, where: str) -> str:
    if "://" in uri or uri.startswith("/") or uri.startswith("\\"):
        raise _Bad(where, "uri %s: abrdf reads files relative to the glTF file, not %s"
                   % (_shown(uri), "URLs" if "://" in uri else "absolute paths"))
    path = os.path.normpath(os.path.join(base, urllib.parse.unquote(uri)))
    if "\0" in path:
        raise _Bad(where, "uri %s holds a NUL character" % _shown(uri))
    if not os.path.isfile(path):
        raise _Bad(where, "uri %s: no such file %s" % (_shown(uri), path))
    return path


class _Reader:
    """One glTF file's JSON and binary chunk, and what its materials' maps resolve to."""

    def __init__(self, path: str, root: dict[str, Json], binary: bytes | None) -> None:
        self.path = path
        self.base = os.path.dirname(path)
        self.root = root
        self.binary = binary
        self.textures = _array(root, "textures")
        self.images = _array(root, "images")
        self.samplers = _array(root, "samplers")
        self.views = _array(root, "bufferViews")
        self.buffers = _array(root, "buffers")
        self._buffer_cache: dict[int, bytes] = {}

    def buffer(self, i: int) -> bytes:
        if i in self._buffer_cache:
            return self._buffer_cache[i]
        where = "buffers[%d]" % i
        b = _object(self.buffers[i], where)  # type: ignore[index]
        length = b.get("byteLength")
        if not (isinstance(length, int) and not isinstance(length, bool) and length >= 1):
            raise _Bad(where + ".byteLength", "a positive integer is needed, got %s"
                       % _shown(length))
        uri = b.get("uri")
        if uri is None:
            if i != 0 or self.binary is None:
                raise _Bad(where, "no uri, and it is not a GLB file's binary chunk")
            data = self.binary
        elif not isinstance(uri, str):
            raise _Bad(where + ".uri", "a string is needed, got %s" % _shown(uri))
        elif uri.startswith("data:"):
            data = _decode_data_uri(uri, where + ".uri")[0]
        else:
            with open(_file_of_uri(uri, self.base, where), "rb") as f:
                data = f.read()
        if len(data) < length:
            raise _Bad(where, "byteLength %d, but the data holds %d bytes" % (length, len(data)))
        self._buffer_cache[i] = data[:length]
        return self._buffer_cache[i]

    def view(self, i: int) -> bytes:
        where = "bufferViews[%d]" % i
        v = _object(self.views[i], where)  # type: ignore[index]
        buf = self.buffer(_index(v, "buffer", where, self.buffers, "buffer"))
        offset = v.get("byteOffset", 0)
        length = v.get("byteLength")
        for key, x, lo in (("byteOffset", offset, 0), ("byteLength", length, 1)):
            if not (isinstance(x, int) and not isinstance(x, bool) and x >= lo):
                raise _Bad("%s.%s" % (where, key), "an integer >= %d is needed, got %s"
                           % (lo, _shown(x)))
        if offset + length > len(buf):
            raise _Bad(where, "bytes %d..%d run past its buffer's %d"
                       % (offset, offset + length, len(buf)))
        return buf[offset:offset + length]

    def image(self, i: int) -> tuple[str | None, bytes | None, str | None]:
        """(file, embedded bytes, MIME type) of images[i]."""
        where = "images[%d]" % i
        im = _object(self.images[i], where)  # type: ignore[index]
        uri, view, mime = im.get("uri"), im.get("bufferView"), im.get("mimeType")
        if mime is not None and mime not in ("image/png", "image/jpeg"):
            raise _Bad(where + ".mimeType", "image/png or image/jpeg, got %s" % _shown(mime))
        if (uri is None) == (view is None):
            raise _Bad(where, "an image has a uri or a bufferView, exactly one")
        if view is not None:
            if mime is None:
                raise _Bad(where, "an image in a bufferView needs its mimeType")
            return None, self.view(_index(im, "bufferView", where, self.views, "bufferView")), mime
        if not isinstance(uri, str):
            raise _Bad(where + ".uri", "a string is needed, got %s" % _shown(uri))
        if uri.startswith("data:"):
            data, uri_mime = _decode_data_uri(uri, where + ".uri")
            return None, data, mime or uri_mime
        return _file_of_uri(uri, self.base, where), None, mime

    def texture_ref(self, info: Json, where: str, channel: int | None, srgb: bool) -> TextureRef:
        """A textureInfo (with KHR_texture_transform) as a TextureRef."""
        info = _object(info, where)
        t = _index(info, "index", where, self.textures, "texture")
        tw = "textures[%d]" % t
        tex = _object(self.textures[t], tw)  # type: ignore[index]
        if "sampler" in tex:
            _index(tex, "sampler", tw, self.samplers, "sampler")
        if "source" not in tex:
            names = ", ".join(sorted(_object(tex.get("extensions", {}), tw + ".extensions")))
            raise _Bad(tw, "no source%s: abrdf reads PNG and JPEG images"
                       % (" (only %s)" % names if names else ""))
        file, embedded, mime = self.image(_index(tex, "source", tw, self.images, "image"))
        uv_set = info.get("texCoord", 0)
        if not (isinstance(uv_set, int) and not isinstance(uv_set, bool) and uv_set >= 0):
            raise _Bad(where + ".texCoord", "an integer >= 0 is needed, got %s"
                       % _shown(uv_set))
        transform: Transform = IDENTITY
        ext = _object(info.get("extensions", {}), where + ".extensions")
        if "KHR_texture_transform" in ext:
            tw2 = where + ".extensions.KHR_texture_transform"
            tt = _object(ext["KHR_texture_transform"], tw2)
            off = _numbers(tt, "offset", tw2, (0.0, 0.0))
            scale = _numbers(tt, "scale", tw2, (1.0, 1.0))
            transform = ((off[0], off[1]), (scale[0], scale[1]),
                         _number(tt, "rotation", tw2, 0.0))
            if "texCoord" in tt:
                uv_set = tt["texCoord"]
                if not (isinstance(uv_set, int) and not isinstance(uv_set, bool) and uv_set >= 0):
                    raise _Bad(tw2 + ".texCoord", "an integer >= 0 is needed, got %s"
                               % _shown(uv_set))
        return TextureRef(file=file, embedded=embedded, mime_type=mime, channel=channel,
                          srgb=srgb, uv_set=uv_set, transform=transform)


def _material(r: _Reader, i: int, m: dict[str, Json]) -> tuple[Pbr, dict[str, TextureRef],
                                                                  float, float]:
    where = "materials[%d]" % i
    f: dict[str, object] = {}
    maps: dict[str, TextureRef] = {}

    def tex(d: dict[str, Json], key: str, w: str, slot: str, channel: int | None,
            srgb: bool) -> dict[str, Json] | None:
        if key in d:
            maps[slot] = r.texture_ref(d[key], "%s.%s" % (w, key), channel, srgb)
            return _object(d[key], "%s.%s" % (w, key))
        return None

    pw = where + ".pbrMetallicRoughness"
    pmr = _object(m.get("pbrMetallicRoughness", {}), pw)
    f["base_color"] = _numbers(pmr, "baseColorFactor", pw, (1.0, 1.0, 1.0, 1.0))[:3]
    f["metallic"] = _number(pmr, "metallicFactor", pw, 1.0)
    f["roughness"] = _number(pmr, "roughnessFactor", pw, 1.0)
    tex(pmr, "baseColorTexture", pw, "base_color", None, True)
    if "metallicRoughnessTexture" in pmr:
        # One file: roughness in green, metallic in blue (section 3.9.2).
        key = "metallicRoughnessTexture"
        ref = r.texture_ref(pmr[key], "%s.%s" % (pw, key), 2, False)
        maps["metallic"] = ref
        maps["roughness"] = TextureRef(file=ref.file, embedded=ref.embedded,
                                       mime_type=ref.mime_type, channel=1, srgb=False,
                                       uv_set=ref.uv_set, transform=ref.transform)
    normal = tex(m, "normalTexture", where, "normal", None, False)
    normal_scale = _number(normal, "scale", where + ".normalTexture", 1.0) if normal else 1.0
    occ = tex(m, "occlusionTexture", where, "occlusion", 0, False)
    occlusion = _number(occ, "strength", where + ".occlusionTexture", 1.0) if occ else 1.0
    if not 0.0 <= occlusion <= 1.0:
        raise _Bad(where + ".occlusionTexture.strength", "%g is outside [0, 1]" % occlusion)
    ext = _object(m.get("extensions", {}), where + ".extensions")

    def extension(name: str) -> tuple[dict[str, Json], str]:
        w = "%s.extensions.%s" % (where, name)
        return _object(ext.get(name, {}), w), w

    e, w = extension("KHR_materials_ior")
    f["ior"] = _number(e, "ior", w, 1.5)
    e, w = extension("KHR_materials_specular")
    f["specular"] = _number(e, "specularFactor", w, 1.0)
    f["specular_color"] = _numbers(e, "specularColorFactor", w, (1.0, 1.0, 1.0))
    tex(e, "specularTexture", w, "specular", 3, False)
    tex(e, "specularColorTexture", w, "specular_color", None, True)
    e, w = extension("KHR_materials_clearcoat")
    f["clearcoat"] = _number(e, "clearcoatFactor", w, 0.0)
    f["clearcoat_roughness"] = _number(e, "clearcoatRoughnessFactor", w, 0.0)
    tex(e, "clearcoatTexture", w, "clearcoat", 0, False)
    tex(e, "clearcoatRoughnessTexture", w, "clearcoat_roughness", 1, False)
    tex(e, "clearcoatNormalTexture", w, "clearcoat_normal", None, False)
    e, w = extension("KHR_materials_sheen")
    f["sheen_color"] = _numbers(e, "sheenColorFactor", w, (0.0, 0.0, 0.0))
    f["sheen_roughness"] = _number(e, "sheenRoughnessFactor", w, 0.0)
    tex(e, "sheenColorTexture", w, "sheen_color", None, True)
    tex(e, "sheenRoughnessTexture", w, "sheen_roughness", 3, False)
    e, w = extension("KHR_materials_anisotropy")
    f["anisotropy"] = _number(e, "anisotropyStrength", w, 0.0)
    f["anisotropy_rotation"] = _number(e, "anisotropyRotation", w, 0.0)
    tex(e, "anisotropyTexture", w, "anisotropy", None, False)
    e, w = extension("KHR_materials_transmission")
    f["transmission"] = _number(e, "transmissionFactor", w, 0.0)
    tex(e, "transmissionTexture", w, "transmission", 0, False)
    try:
        pbr = Pbr(**f)  # type: ignore[arg-type]
    except _abrdf.Error as err:
        raise _Bad(where, str(err)) from None
    return pbr, maps, occlusion, normal_scale


def _required(root: dict[str, Json]) -> list[str]:
    req = root.get("extensionsRequired", [])
    if not (isinstance(req, list) and all(isinstance(x, str) for x in req)):
        raise _Bad("extensionsRequired", "an array of strings is needed, got %s" % _shown(req))
    return req


def _unique(name: str, i: int, taken: set[str]) -> str:
    if name not in taken:
        return name
    k = i
    while "%s_%d" % (name, k) in taken:
        k += 1
    return "%s_%d" % (name, k)


def load_gltf(path: str | os.PathLike[str]) -> dict[str, PbrMaterial]:
    """The materials of a glTF 2.0 file (.gltf, or .glb with its binary chunk) by name, in
    the file's order: each a PbrMaterial with its factors (Pbr: glTF's defaults where the
    file says nothing) and its maps (TextureRef: an absolute file path, or the bytes of an
    image held in a buffer or a data URI). A material without a name is "material_I" (I its
    index); a name given twice gets "_I" appended. Only what the materials need is read:
    materials, KHR_materials_ior / specular / clearcoat / sheen / anisotropy / transmission,
    textures, images, samplers, buffer views, buffers and KHR_texture_transform. A file that
    requires another extension touching materials is refused. Problems raise abrdf.Error
    with one line "FILE: where: problem"."""
    p = os.fspath(path)
    shown = p
    p = os.path.abspath(p)
    try:
        with open(p, "rb") as fh:
            data = fh.read()
    except OSError as e:
        raise _error("%s: %s" % (shown, e.strerror or e)) from None
    try:
        binary = None
        if data[:4] == struct.pack("<I", _GLB_MAGIC):
            data, binary = _split_glb(data)
        try:
            root = json.loads(data.decode("utf-8"))
        except UnicodeDecodeError as e:
            raise _Bad("", "the JSON is not UTF-8 (byte %d)" % e.start) from None
        except (json.JSONDecodeError, RecursionError) as e:
            raise _Bad("", "malformed JSON (%s)" % (e.msg if hasattr(e, "msg") else e)) from None
        root = _object(root, "the top level")
        asset = _object(root.get("asset"), "asset")
        version = asset.get("version")
        if not (isinstance(version, str) and version.split(".")[0] == "2"):
            raise _Bad("asset.version", "glTF 2.x is needed, got %s" % _shown(version))
        for name in _required(root):
            if name not in _READ and name not in _HARMLESS:
                raise _Bad("extensionsRequired",
                           "%s is required, and abrdf does not read it" % name)
        r = _Reader(p, root, binary)
        out: dict[str, PbrMaterial] = {}
        for i, m in enumerate(_array(root, "materials") or []):
            m = _object(m, "materials[%d]" % i)
            name = m.get("name", "material_%d" % i)
            if not isinstance(name, str):
                raise _Bad("materials[%d].name" % i, "a string is needed, got %s"
                           % _shown(name))
            name = _unique(name, i, set(out))
            pbr, maps, occ, ns = _material(r, i, m)
            out[name] = PbrMaterial(name=name, pbr=pbr, textures=maps, occlusion_strength=occ,
                                    normal_scale=ns, source=p)
        return out
    except _Bad as e:
        raise _error("%s: %s" % (shown, e)) from None
    except OSError as e:
        raise _error("%s: %s" % (shown, e)) from None
