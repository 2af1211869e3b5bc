"""glTF metallic-roughness materials (abrdf_pbr.h): Pbr, pbr_lobes(), pbr_material(), and
the material a reader returns (PbrMaterial, with its TextureRef maps)."""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from typing import Mapping, Union

from . import _abrdf
from ._arrays import real_number
from ._brdf import BRDF
from ._select import Material, _material_of

RGB = tuple[float, float, float]

_COLOURS = ("base_color", "specular_color", "sheen_color")


@dataclass(frozen=True)
class Pbr:
    """A glTF 2.0 metallic-roughness material with the KHR extensions abrdf maps (abrdf_pbr):
    each field has glTF's default and abrdf_pbr's range (docs/GLTF.md). Colours are linear
    RGB 3-tuples (one number is taken as grey). Built and checked by abrdf_pbr_check: a value
    out of its range raises abrdf.Error with the library's message ("roughness = 2 is
    outside [0, 1]")."""

    base_color: RGB = (1.0, 1.0, 1.0)     # baseColorFactor, [0, 1]
    metallic: float = 1.0                 # metallicFactor, [0, 1]
    roughness: float = 1.0                # roughnessFactor, perceptual (alpha = r^2), [0, 1]
    ior: float = 1.5                      # KHR_materials_ior, [1, 4]
    specular: float = 1.0                 # KHR_materials_specular specularFactor, [0, 1]
    specular_color: RGB = (1.0, 1.0, 1.0)  # specularColorFactor, [0, 100]
    clearcoat: float = 0.0                # KHR_materials_clearcoat clearcoatFactor, [0, 1]
    clearcoat_roughness: float = 0.0      # clearcoatRoughnessFactor, [0, 1]
    sheen_color: RGB = (0.0, 0.0, 0.0)    # KHR_materials_sheen sheenColorFactor, [0, 1]
    sheen_roughness: float = 0.0          # sheenRoughnessFactor, [0, 1]
    anisotropy: float = 0.0               # KHR_materials_anisotropy anisotropyStrength, [0, 1]
    anisotropy_rotation: float = 0.0      # anisotropyRotation, radians, |x| <= 1e3
    transmission: float = 0.0             # KHR_materials_transmission transmissionFactor, [0, 1]

    def __post_init__(self) -> None:
        for f in dataclasses.fields(self):
            v = getattr(self, f.name)
            if f.name in _COLOURS:
                if isinstance(v, (str, bytes)) or not hasattr(v, "__len__"):
                    v = (v, v, v)
                if len(v) != 3:
                    raise _error("%s: a colour needs 3 numbers (R, G, B), got %d"
                                 % (f.name, len(v)))
                v = tuple(real_number(c, f.name) for c in v)
            else:
                v = real_number(v, f.name)
            object.__setattr__(self, f.name, v)
        _abrdf.pbr_check(self._fields())

    def _fields(self) -> dict[str, object]:
        return {f.name: getattr(self, f.name) for f in dataclasses.fields(self)}

    def replace(self, **changes: object) -> Pbr:
        """A copy with some fields changed (checked again)."""
        return dataclasses.replace(self, **changes)  # type: ignore[arg-type]

    def _flowchart_material(self) -> Material:
        """What abrdf.select reads of it (abrdf.pbr_material)."""
        return pbr_material(self)


def _error(message: str) -> _abrdf.Error:
    err = _abrdf.Error(message)
    err.status = None
    return err


def _pbr_of(p: Pbr | PbrMaterial | Mapping[str, object]) -> Pbr:
    if isinstance(p, Pbr):
        return p
    if isinstance(p, PbrMaterial):
        return p.pbr
    if isinstance(p, Mapping):
        return Pbr(**p)  # type: ignore[arg-type]
    raise TypeError("a Pbr, a PbrMaterial or a mapping of Pbr's fields is needed, got %s"
                    % type(p).__name__)


def pbr_lobes(p: Pbr | PbrMaterial | Mapping[str, object]) -> list[BRDF]:
    """The material as abrdf's explicit lobes (abrdf_pbr_lobes): [lambert_fresnel,
    disney_specular] (disney_specular_aniso with anisotropy), sharing one parameter block;
    f_r is their sum. Clearcoat and sheen have no lobe here (docs/GLTF.md)."""
    return [BRDF._from_params(b) for b in _abrdf.pbr_lobes(_pbr_of(p)._fields())]


def pbr_material(p: Pbr | PbrMaterial | Mapping[str, object],
                 name: str | None = None) -> Material:
    """The material as the flowchart reads it (abrdf_pbr_material): a Material for
    abrdf.select (goal or budget). Its type is general, layered_plastic / layered_metal with
    a clearcoat, cloth_rough / cloth_shiny with a sheen; r, kd, ks, f0 and anisotropy as
    pbr_lobes maps them. name: the Material's name (for the trace)."""
    d = _abrdf.pbr_material(_pbr_of(p)._fields())
    d["name"] = name
    return _material_of(d)


Transform = tuple[tuple[float, float], tuple[float, float], float]
IDENTITY: Transform = ((0.0, 0.0), (1.0, 1.0), 0.0)


@dataclass(frozen=True)
class TextureRef:
    """A texture map of a material: the image (`file`, an absolute path, or `embedded`, the
    encoded bytes of an image inside the file: a GLB buffer or a data URI, with its
    `mime_type`), the channel a one-channel input reads (0 R, 1 G, 2 B, 3 A; None for a
    colour), whether the values are sRGB-encoded, the texture coordinate set (glTF
    TEXCOORD_n) and KHR_texture_transform's (offset, scale, rotation in radians):
    uv' = offset + R(rotation) (scale * uv)."""

    file: str | None = None
    embedded: bytes | None = field(default=None, repr=False)
    mime_type: str | None = None
    channel: int | None = None
    srgb: bool = False
    uv_set: int = 0
    transform: Transform = IDENTITY


@dataclass(frozen=True)
class PbrMaterial:
    """A material read from a file (abrdf.load_gltf, abrdf.load_materialx): its name, its
    factors as a Pbr, and its texture maps by slot ("base_color", "metallic", "roughness",
    "occlusion", "normal", and for the extensions "specular", "specular_color",
    "clearcoat", "clearcoat_roughness", "sheen_color", "sheen_roughness", "anisotropy",
    "transmission"); a map multiplies its factor. `occlusion_strength` and `normal_scale`
    are glTF's (1 when absent). `source` is the file it came from."""

    name: str
    pbr: Pbr
    textures: Mapping[str, TextureRef] = field(default_factory=dict)
    occlusion_strength: float = 1.0
    normal_scale: float = 1.0
    source: str = ""

    @property
    def material(self) -> Material:
        """The flowchart's material (abrdf.pbr_material), named after this one."""
        return pbr_material(self.pbr, self.name)

    def _flowchart_material(self) -> Material:
        """What abrdf.select reads of it: the material above."""
        return self.material

    @property
    def brdfs(self) -> list[BRDF]:
        """The explicit lobes (abrdf.pbr_lobes)."""
        return pbr_lobes(self.pbr)


PbrLike = Union[Pbr, PbrMaterial, Mapping[str, object]]
