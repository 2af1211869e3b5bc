"""abrdf.load_materialx: the materials of a MaterialX document (.mtlx), read through the
official MaterialX library (PyPI `materialx`). Each surfacematerial's surface shader, a
standard_surface, open_pbr_surface or gltf_pbr node, is mapped input by input onto Pbr
(docs/GLTF.md, "MaterialX"); an input connected to an image node becomes a TextureRef."""
from __future__ import annotations

import functools
import math
import os
from typing import Any

from . import _abrdf
from ._pbr import IDENTITY, Pbr, PbrMaterial, TextureRef

_TWO_PI = 2.0 * math.pi

# Each shader's inputs onto Pbr's fields: field -> (input with the map, weight inputs
# multiplied in, scale of the value). A map is read on the first input only.
_INPUTS: dict[str, dict[str, tuple[str, tuple[str, ...], float]]] = {
    "standard_surface": {
        "base_color": ("base_color", ("base",), 1.0),
        "metallic": ("metalness", (), 1.0),
        "roughness": ("specular_roughness", (), 1.0),
        "ior": ("specular_IOR", (), 1.0),
        "specular": ("specular", (), 1.0),
        "specular_color": ("specular_color", (), 1.0),
        "clearcoat": ("coat", (), 1.0),
        "clearcoat_roughness": ("coat_roughness", (), 1.0),
        "sheen_color": ("sheen_color", ("sheen",), 1.0),
        "sheen_roughness": ("sheen_roughness", (), 1.0),
        "anisotropy": ("specular_anisotropy", (), 1.0),
        # specular_rotation 0..1 is 0..360 degrees (MaterialX's standard_surface graph).
        "anisotropy_rotation": ("specular_rotation", (), _TWO_PI),
        "transmission": ("transmission", (), 1.0),
    },
    "open_pbr_surface": {
        "base_color": ("base_color", ("base_weight",), 1.0),
        "metallic": ("base_metalness", (), 1.0),
        "roughness": ("specular_roughness", (), 1.0),
        "ior": ("specular_ior", (), 1.0),
        "specular": ("specular_weight", (), 1.0),
        "specular_color": ("specular_color", (), 1.0),
        "clearcoat": ("coat_weight", (), 1.0),
        "clearcoat_roughness": ("coat_roughness", (), 1.0),
        "sheen_color": ("fuzz_color", ("fuzz_weight",), 1.0),
        "sheen_roughness": ("fuzz_roughness", (), 1.0),
        "anisotropy": ("specular_roughness_anisotropy", (), 1.0),
        "transmission": ("transmission_weight", (), 1.0),
    },
    "gltf_pbr": {
        "base_color": ("base_color", (), 1.0),
        "metallic": ("metallic", (), 1.0),
        "roughness": ("roughness", (), 1.0),
        "ior": ("ior", (), 1.0),
        "specular": ("specular", (), 1.0),
        "specular_color": ("specular_color", (), 1.0),
        "clearcoat": ("clearcoat", (), 1.0),
        "clearcoat_roughness": ("clearcoat_roughness", (), 1.0),
        "sheen_color": ("sheen_color", (), 1.0),
        "sheen_roughness": ("sheen_roughness", (), 1.0),
        "anisotropy": ("anisotropy_strength", (), 1.0),
        "anisotropy_rotation": ("anisotropy_rotation", (), 1.0),
        "transmission": ("transmission", (), 1.0),
    },
}
# Maps without a Pbr field: slot -> (shader -> input).
_EXTRA_MAPS = {"normal": {"standard_surface": "normal", "open_pbr_surface": "geometry_normal",
                          "gltf_pbr": "normal"},
               "occlusion": {"gltf_pbr": "occlusion"}}
SHADERS = tuple(_INPUTS)
_IMAGES = ("image", "tiledimage", "gltf_image", "gltf_colorimage")
_READS = ("constants and image nodes (image, tiledimage, gltf_image, gltf_colorimage), "
          "directly or through extract, separate3, separate4, dot, normalmap and nodegraph "
          "outputs")
_CHANNEL_OF_OUTPUT = {"outr": 0, "outg": 1, "outb": 2, "outa": 3,
                      "outx": 0, "outy": 1, "outz": 2, "outw": 3}


class _Bad(Exception):
    pass


def _error(message: str) -> _abrdf.Error:
    err = _abrdf.Error(" ".join(message.split()))
    err.status = None
    return err


def _mx() -> Any:
    try:
        import MaterialX
    except ImportError:
        return None
    return MaterialX


@functools.lru_cache(maxsize=1)
def _library() -> Any:
    mx = _mx()
    lib = mx.createDocument()
    mx.loadLibraries(mx.getDefaultDataLibraryFolders(), mx.getDefaultDataSearchPath(), lib)
    return lib


def _numbers(text: str, what: str) -> tuple[float, ...]:
    try:
        v = tuple(float(x) for x in text.split(","))
    except ValueError:
        raise _Bad("%s: %r is not a number or a list of numbers" % (what, text)) from None
    if not all(map(math.isfinite, v)):
        raise _Bad("%s: %r is not finite" % (what, text))
    return v


class _Ref:
    """What an input resolves to: a constant (a tuple of numbers), or a texture times a
    factor."""

    def __init__(self, value: tuple[float, ...], texture: TextureRef | None = None,
                 scale: float = 1.0) -> None:
        self.value, self.texture, self.scale = value, texture, scale


def _input_value(inp: Any, what: str) -> _Ref:
    """An unconnected input's own value, or its node definition's default."""
    text = inp.getValueString()
    return _Ref(_numbers(text, what) if text else ())


class _Reader:
    def __init__(self, doc: Any, path: str) -> None:
        self.doc, self.path = doc, path
        self.base = os.path.dirname(path)

    def node_input(self, node: Any, name: str, what: str) -> _Ref:
        """Input `name` of `node`: its value, its connection followed, or the default."""
        inp = node.getInput(name)
        if inp is None:
            nd = node.getNodeDef()
            di = nd.getActiveInput(name) if nd is not None else None
            if di is None:
                raise _Bad("%s: node '%s' (%s) has no input '%s'"
                           % (what, node.getName(), node.getCategory(), name))
            return _input_value(di, what)
        return self.follow(inp, what)

    def follow(self, inp: Any, what: str, depth: int = 0) -> _Ref:
        if depth > 32:
            raise _Bad("%s: the connections run more than 32 nodes deep" % what)
        if inp.getInterfaceName():
            graph_input = inp.getInterfaceInput()
            if graph_input is None:
                raise _Bad("%s: interface input '%s' does not exist"
                           % (what, inp.getInterfaceName()))
            return self.follow(graph_input, what, depth + 1)
        output_name = inp.getOutputString()
        node = None
        if inp.getNodeGraphString():
            graph = self.doc.getNodeGraph(inp.getNodeGraphString())
            if graph is None:
                raise _Bad("%s: nodegraph '%s' does not exist"
                           % (what, inp.getNodeGraphString()))
            outs = graph.getOutputs()
            out = graph.getOutput(output_name) if output_name else (
                outs[0] if len(outs) == 1 else None)
            if out is None:
                raise _Bad("%s: nodegraph '%s' has no output '%s'"
                           % (what, graph.getName(), output_name))
            return self.follow(out, what, depth + 1)
        if inp.getNodeName():
            node = inp.getConnectedNode()
            if node is None:
                raise _Bad("%s: node '%s' does not exist" % (what, inp.getNodeName()))
            return self.node(node, output_name, what, depth + 1)
        return _input_value(inp, what)

    def node(self, node: Any, output: str, what: str, depth: int) -> _Ref:
        cat = node.getCategory()
        if cat == "constant":
            return self.node_input(node, "value", what)
        if cat in ("dot", "normalmap"):
            ref = self.node_input(node, "in", what)
            if cat == "normalmap" and ref.texture is not None:
                s = self.node_input(node, "scale", what).value
                ref.scale = s[0] if s else 1.0
            return ref
        if cat in ("extract", "separate3", "separate4"):
            if cat == "extract":
                index = self.node_input(node, "index", what).value
                channel = int(index[0]) if index else 0
                if not 0 <= channel <= 3:
                    raise _Bad("%s: node '%s' (extract): index %d is outside [0, 3]"
                               % (what, node.getName(), channel))
            else:
                channel = _CHANNEL_OF_OUTPUT.get(output, -1)
                if channel < 0:
                    raise _Bad("%s: node '%s' (%s) has no output '%s'"
                               % (what, node.getName(), cat, output))
            ref = self.node_input(node, "in", what)
            if ref.texture is None:
                return _Ref((ref.value[channel],) if channel < len(ref.value) else ())
            t = ref.texture
            ref.texture = TextureRef(file=t.file, channel=channel, srgb=t.srgb,
                                     uv_set=t.uv_set, transform=t.transform)
            ref.value = (ref.value[channel],) if channel < len(ref.value) else (1.0,)
            return ref
        if cat in _IMAGES:
            return self.image(node, output, what)
        raise _Bad("%s: node '%s' is a '%s', which abrdf does not read (it reads %s)"
                   % (what, node.getName(), cat, _READS))

    def image(self, node: Any, output: str, what: str) -> _Ref:
        cat, name = node.getCategory(), node.getName()
        f = node.getInput("file")
        if f is None or not f.getValueString():
            raise _Bad("%s: image node '%s' names no file" % (what, name))
        rel = f.getResolvedValueString()  # with the document's fileprefix
        path = os.path.normpath(os.path.join(self.base, rel))
        if not os.path.isfile(path):
            raise _Bad("%s: image node '%s': no such file %s" % (what, name, path))
        cs = f.getActiveColorSpace()
        srgb = cs in ("srgb_texture", "srgb_displayp3")
        for key, default in (("uvtiling", (1.0, 1.0)), ("uvoffset", (0.0, 0.0)),
                             ("scale", (1.0, 1.0)), ("offset", (0.0, 0.0)),
                             ("rotate", (0.0,))):
            if node.getInput(key) is None:
                continue
            v = self.node_input(node, key, what).value
            if v != default:
                raise _Bad("%s: image node '%s': %s = %s; abrdf reads untransformed texture "
                           "coordinates from MaterialX" % (what, name, key,
                                                           ",".join("%g" % x for x in v)))
        uv_set = 0
        tc = node.getInput("texcoord")
        if tc is not None and (tc.getNodeName() or tc.getNodeGraphString()):
            up = tc.getConnectedNode()
            if up is None or up.getCategory() != "texcoord":
                raise _Bad("%s: image node '%s': its texcoord is not a texcoord node"
                           % (what, name))
            idx = self.node_input(up, "index", what).value
            uv_set = int(idx[0]) if idx else 0
            if uv_set < 0:
                raise _Bad("%s: texcoord node '%s': index %d is negative"
                           % (what, up.getName(), uv_set))
        factor: tuple[float, ...] = (1.0,)
        channel = 0 if node.getType() == "float" else None
        nd = node.getNodeDef()
        if cat == "gltf_image" and nd is not None and nd.getActiveInput("factor") is not None:
            factor = self.node_input(node, "factor", what).value
        elif cat == "gltf_colorimage":
            c = self.node_input(node, "color", what).value
            if output == "outa":
                factor, channel = c[3:4], 3
            else:
                factor = c[:3]
        ref = TextureRef(file=path, channel=channel, srgb=srgb and channel is None,
                         uv_set=uv_set, transform=IDENTITY)
        return _Ref(factor, ref)


def _material(r: _Reader, mat: Any, shader: Any) -> tuple[Pbr, dict[str, TextureRef], float]:
    cat = shader.getCategory()
    f: dict[str, object] = {}
    maps: dict[str, TextureRef] = {}
    where = "material '%s': %s '%s'" % (mat.getName(), cat, shader.getName())
    for field, (main, weights, scale) in _INPUTS[cat].items():
        what = "%s input '%s'" % (where, main)
        ref = r.node_input(shader, main, what)
        if ref.texture is not None:
            maps[field] = ref.texture
        v = list(ref.value)
        for w in weights:
            wref = r.node_input(shader, w, "%s input '%s'" % (where, w))
            if wref.texture is not None:
                raise _Bad("%s input '%s': a map on a weight is not read (give the map to "
                           "'%s')" % (where, w, main))
            v = [x * wref.value[0] for x in v]
        v = [x * scale for x in v]
        if field in ("base_color", "specular_color", "sheen_color"):
            if len(v) == 1:
                v = v * 3
            if len(v) != 3:
                raise _Bad("%s: a colour of %d values" % (what, len(v)))
            f[field] = tuple(v)
        else:
            if len(v) != 1:
                raise _Bad("%s: one number is needed, got %d" % (what, len(v)))
            f[field] = v[0]
    normal_scale = 1.0
    for slot, by_shader in _EXTRA_MAPS.items():
        name = by_shader.get(cat)
        inp = shader.getInput(name) if name else None
        if inp is None or not (inp.getNodeName() or inp.getNodeGraphString()):
            continue
        ref = r.follow(inp, "%s input '%s'" % (where, name))
        if ref.texture is not None:
            maps[slot] = ref.texture
            if slot == "normal":
                normal_scale = ref.scale
    try:
        pbr = Pbr(**f)  # type: ignore[arg-type]
    except _abrdf.Error as err:
        raise _Bad("%s: %s" % (where, err)) from None
    return pbr, maps, normal_scale


def load_materialx(path: str | os.PathLike[str]) -> dict[str, PbrMaterial]:
    """The materials of a MaterialX document by name, in the document's order: each
    surfacematerial whose surface shader is a standard_surface, open_pbr_surface or
    gltf_pbr node, its inputs mapped onto a Pbr (docs/GLTF.md, "MaterialX", has the table;
    unconnected inputs take the node definition's defaults) and its image-node inputs as
    TextureRefs (the file resolved with the document's fileprefix against the document's
    directory, the channel an extract or separate node picks, sRGB for the colorspace
    srgb_texture, the texcoord node's index). Read through the MaterialX library (PyPI
    `materialx`): without it, abrdf.Error names the package. Any other shader node,
    connection or transform raises abrdf.Error "FILE: material 'M': ...: problem"."""
    shown = os.fspath(path)
    p = os.path.abspath(shown)
    mx = _mx()
    if mx is None:
        raise _error("%s: reading MaterialX needs the Python package 'materialx' "
                     "(pip install materialx)" % shown)
    if not os.path.isfile(p):
        raise _error("%s: no such file" % shown)
    try:  # the library hands its strings to Python as UTF-8
        with open(p, "rb") as fh:
            fh.read().decode("utf-8")
    except UnicodeDecodeError as e:
        raise _error("%s: not UTF-8 text (byte %d)" % (shown, e.start)) from None
    except OSError as e:
        raise _error("%s: %s" % (shown, e.strerror or e)) from None
    doc = mx.createDocument()
    try:
        mx.readFromXmlFile(doc, p)
    except Exception as e:  # the library's parse and file errors have no common base
        raise _error("%s: %s" % (shown, e)) from None
    doc.importLibrary(_library())
    ok, message = doc.validate()
    if not ok:
        raise _error("%s: not a valid MaterialX document: %s"
                     % (shown, message.strip().splitlines()[0]))
    r = _Reader(doc, p)
    out: dict[str, PbrMaterial] = {}
    try:
        for mat in doc.getMaterialNodes():
            shaders = mx.getShaderNodes(mat)
            if len(shaders) != 1:
                raise _Bad("material '%s': %d surface shaders (abrdf reads one)"
                           % (mat.getName(), len(shaders)))
            shader = shaders[0]
            if shader.getCategory() not in _INPUTS:
                raise _Bad("material '%s': surface shader '%s' is a '%s'; abrdf reads %s"
                           % (mat.getName(), shader.getName(), shader.getCategory(),
                              ", ".join(SHADERS)))
            pbr, maps, ns = _material(r, mat, shader)
            out[mat.getName()] = PbrMaterial(name=mat.getName(), pbr=pbr, textures=maps,
                                             normal_scale=ns, source=p)
    except _Bad as e:
        raise _error("%s: %s" % (shown, e)) from None
    except IndexError as e:
        raise _error("%s: a value has too few components (%s)" % (shown, e)) from None
    return out
