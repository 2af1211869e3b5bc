"""The advisor of the open file's Principled materials: every material whose Material Output
takes its Surface from a Principled BSDF is read as a glTF metallic-roughness material
(abrdf.Pbr, the mapping below, docs/OSL.md "Advising Principled materials") and given the
selection's choice for a goal or a budget, as `abrdf advise FILE.scene` chooses for a
`material NAME pbr` line of the same values.

Socket values only: an input driven by a link is advised on the socket's own (unlinked)
value, and the result says so. Cycles' meaning of the inputs (Blender 5's Principled BSDF,
intern/cycles/kernel/svm/closure.h): the dielectric F0 is F0(IOR) * 2 * Specular IOR Level,
tinted by Specular Tint and clamped to 1, with F90 = 1 and no specular lobe at all when that
F0 is 0 (level 0 or IOR 1); a metal's F0 is its Base Color and Specular Tint its edge tint (F82).
"""
import math

import abrdf

TEXT = "abrdf advice"  # the text datablock that holds the full trace

# Principled BSDF inputs the mapping reads (the name of the socket, in Blender 5).
READ = ("Base Color", "Metallic", "Roughness", "IOR", "Specular IOR Level", "Specular Tint",
        "Coat Weight", "Coat Roughness", "Sheen Weight", "Sheen Roughness", "Sheen Tint",
        "Anisotropic", "Anisotropic Rotation", "Transmission Weight")

# Inputs abrdf's reflection models do not carry: (socket, its neutral value). A value
# other than the neutral one is named in the result as ignored.
IGNORED = (("Alpha", 1.0), ("Diffuse Roughness", 0.0), ("Subsurface Weight", 0.0),
           ("Coat IOR", 1.5), ("Coat Tint", (1.0, 1.0, 1.0)), ("Emission Strength", 0.0),
           ("Thin Film Thickness", 0.0))

IOR_MAX = 4.0  # abrdf_pbr's ior range is [1, 4]


def _f0(eta):
    return ((eta - 1.0) / (eta + 1.0)) ** 2


def _value(sock):
    v = sock.default_value
    return tuple(v)[:3] if hasattr(v, "__len__") else float(v)


def _source(sock):
    """The node behind a linked input (through reroutes), or None when it is not linked."""
    links = [lk for lk in sock.links if not lk.is_muted]
    if not links:
        return None
    node = links[0].from_node
    while node.bl_idname == "NodeReroute" and node.inputs[0].is_linked:
        node = node.inputs[0].links[0].from_node
    return node


def principled_of(mat):
    """(the Principled BSDF node feeding the material's Cycles output, None) or (None, why)."""
    nt = mat.node_tree
    if nt is None:
        return None, "no shader nodes"
    out = nt.get_output_node("CYCLES")
    if out is None:
        return None, "no Material Output"
    node = _source(out.inputs["Surface"])
    if node is None:
        return None, "nothing feeds its Material Output's Surface"
    if node.bl_idname != "ShaderNodeBsdfPrincipled":
        return None, "its Surface comes from %s \"%s\", not a Principled BSDF" % (
            node.bl_label, node.name)
    return node, None


def socket_inputs(node):
    """{socket name: value} of the inputs the mapping reads, and the notes on them: an
    input driven by a node is taken at its own value."""
    values, notes = {}, []
    for name in READ:
        sock = node.inputs[name]
        values[name] = _value(sock)
        src = _source(sock)
        if src is not None:
            v = values[name]
            shown = ("(%.4g, %.4g, %.4g)" % v) if isinstance(v, tuple) else "%.4g" % v
            notes.append("%s is driven by a node (%s \"%s\"): advised on its default value %s"
                         % (name, src.bl_label, src.name, shown))
    for name, neutral in IGNORED:
        sock = node.inputs[name]
        v = _value(sock)
        if sock.is_linked or (v != neutral if not isinstance(v, tuple)
                              else any(abs(a - b) > 1e-6 for a, b in zip(v, neutral))):
            notes.append("%s is ignored (abrdf's models do not carry it)" % name)
    return values, notes


def pbr_fields(v):
    """The abrdf_pbr fields of Principled BSDF input values {socket name: value}, and notes
    on what the mapping changed. The table of docs/OSL.md, "Advising Principled materials"."""
    notes = []
    eta = v["IOR"]
    if eta < 1.0:  # F0 of 1/eta is F0 of eta: the reflection is the same
        eta = 1.0 / eta if eta > 0 else math.inf
    level, tint = v["Specular IOR Level"], v["Specular Tint"]
    scale = 2.0 * level
    if eta > IOR_MAX:  # the same F0 from ior 4 and a specular colour that makes it up
        scale *= _f0(eta) / _f0(IOR_MAX) if math.isfinite(eta) else 1.0 / _f0(IOR_MAX)
        notes.append("IOR %.4g is beyond abrdf_pbr's [1, 4]: ior 4 with specular_color "
                     "scaled to the same F0" % v["IOR"])
        eta = IOR_MAX
    # Cycles has no specular lobe when the adjusted F0 is 0 (level 0, or IOR 1); else
    # F0 * 2 level and F90 = 1, which glTF's specular 1 and specular_color give.
    lobe = scale > 0 and eta > 1.0
    if v["Metallic"] > 0 and any(abs(t - 1.0) > 1e-6 for t in tint):
        notes.append("Specular Tint on the metallic part (Cycles' edge tint, F82) is ignored")
    fields = {
        "base_color": v["Base Color"],
        "metallic": v["Metallic"],
        "roughness": v["Roughness"],
        "ior": eta,
        "specular": 1.0 if lobe else 0.0,
        "specular_color": tuple(scale * t for t in tint) if lobe else (1.0, 1.0, 1.0),
        "clearcoat": v["Coat Weight"],
        "clearcoat_roughness": v["Coat Roughness"],
        "sheen_color": tuple(v["Sheen Weight"] * t for t in v["Sheen Tint"]),
        "sheen_roughness": v["Sheen Roughness"],
        "anisotropy": v["Anisotropic"],
        # Blender's rotation is a fraction of a turn; glTF's is in radians.
        "anisotropy_rotation": 2.0 * math.pi * v["Anisotropic Rotation"],
        "transmission": v["Transmission Weight"],
    }
    return fields, notes


class Advice:
    """One material's result: its name, the Pbr it was read as, the notes, and the
    selection (None with `skipped` saying why)."""

    def __init__(self, name, pbr=None, notes=(), selection=None, skipped=None):
        self.name, self.pbr, self.notes = name, pbr, list(notes)
        self.selection, self.skipped = selection, skipped

    @property
    def choice(self):
        s = self.selection
        return "%s%s" % (s.diffuse + " + " if s.diffuse else "", s.specular) if s else ""

    @property
    def error(self):
        s = self.selection
        if s is None:
            return ""
        if s.error_nmse is not None:
            return "predicted NMSE %.3g" % s.error_nmse
        if s.error_rel_pct is not None:
            return "predicted error %.3g %% relative, %.3g absolute" % (s.error_rel_pct,
                                                                         s.error_abs)
        return "no predicted error (the reference branch)"

    @property
    def cost(self):
        s = self.selection
        if s is None:
            return ""
        if s.cost_total is not None:
            return "cost %.4g %s" % (s.cost_total, s.cost_unit)
        if s.cost_specular is not None:  # the table has no cost for the diffuse model
            return "cost of the specular lobe %.4g %s" % (s.cost_specular, s.cost_unit)
        return ""


def read(mat):
    """(Advice without a selection) for a material: its Pbr and notes, or why it is skipped.
    abrdf.Error names the material when its values are outside abrdf_pbr's ranges."""
    node, why = principled_of(mat)
    if node is None:
        return Advice(mat.name, skipped=why)
    values, notes = socket_inputs(node)
    fields, more = pbr_fields(values)
    try:
        pbr = abrdf.Pbr(**fields)
    except abrdf.Error as e:
        raise abrdf.Error("material \"%s\": %s" % (mat.name, e)) from None
    return Advice(mat.name, pbr, notes + more)


def select_options(settings):
    """abrdf.select's keyword arguments from the scene's advisor settings."""
    if settings.by == "BUDGET":
        return {"budget": settings.budget}
    return {"goal": settings.goal, "max_rel_error": settings.max_rel_error,
            "max_abs_error": settings.max_abs_error}


def advise(materials, options):
    """Advice for every material (skipped ones say why), in name order. Reads every
    material first: abrdf.Error for the first whose values abrdf_pbr refuses, before any
    selection is run."""
    out = [read(m) for m in sorted(materials, key=lambda m: m.name)]
    for a in out:
        if a.pbr is not None:
            a.selection = abrdf.select(abrdf.pbr_material(a.pbr, name=a.name), **options)
    return out


def _fmt(v):
    return ",".join("%.6g" % c for c in v) if isinstance(v, tuple) else "%.6g" % v


def report(advice, options, source):
    """The full trace of every material, as the text datablock holds it."""
    how = ("budget %s" % options["budget"] if "budget" in options else
           "goal %s (performance tolerances: %.4g %% relative, %.4g absolute)"
           % (options["goal"], options["max_rel_error"], options["max_abs_error"]))
    lines = ["abrdf advice for %s: %s" % (source or "the unsaved file", how),
             "Principled BSDF inputs read as glTF metallic-roughness values (abrdf_pbr); "
             "texture-driven inputs at their socket values.", ""]
    for a in advice:
        if a.skipped:
            lines += ["%s: not advised: %s" % (a.name, a.skipped), ""]
            continue
        s = a.selection
        fields = " ".join("%s=%s" % (k, _fmt(getattr(a.pbr, k)))
                          for k in a.pbr._fields())
        lines += ["%s: %s" % (a.name, a.choice),
                  "  abrdf_pbr: %s" % fields,
                  "  surface class %s; %s; %s" % (s.type, a.error, a.cost or "no cost")]
        lines += ["  note: " + n for n in a.notes]
        lines += ["  why:"] + ["  " + line for line in s.explain().splitlines()] + [""]
    return "\n".join(lines)
