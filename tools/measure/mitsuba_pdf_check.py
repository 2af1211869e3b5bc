#!/usr/bin/env python3
"""mitsuba_pdf_check.py - the GGX (visible normals) and Beckmann (D cos) densities of
`abrdf sample` against Mitsuba 3's MicrofacetDistribution, an independent implementation
(docs/RENDERER.md, "Importance sampling",
quotes the result; a one-off check, not a test: Mitsuba is not a
dependency of the project).

    python3 -m venv /tmp/mi && /tmp/mi/bin/pip install mitsuba
    /tmp/mi/bin/python tools/measure/mitsuba_pdf_check.py build/bin/abrdf

For each sampled wi: h = normalize(wi + wo), Mitsuba's density of h for the view direction
wo divided by the Jacobian 4 wo.h is the density of wi. Mitsuba's scalar_rgb variant is
single precision: agreement to ~1e-6 is agreement."""
import json
import math
import subprocess
import sys

import mitsuba as mi

mi.set_variant("scalar_rgb")


def samples(abrdf, model, wo, sets):
    args = [abrdf, "sample", model, "--wo", ",".join(map(repr, wo)), "-n", "200", "--json",
            "--seed", "3"]
    for s in sets:
        args += ["--set", s]
    return [json.loads(l) for l in subprocess.check_output(args, text=True).splitlines()]


def main():
    abrdf = sys.argv[1]
    aspect = math.sqrt(1.0 - 0.9 * 0.8)
    cases = [  # model, parameters, Mitsuba distribution, visible normals, (alpha_u, alpha_v)
        ("disney_specular", ["r=0.5"], mi.MicrofacetType.GGX, True, (0.25, 0.25)),
        ("disney_specular", ["r=0.2"], mi.MicrofacetType.GGX, True, (0.04, 0.04)),
        ("disney_specular_aniso", ["r=0.6", "anisotropic=0.8"], mi.MicrofacetType.GGX, True,
         (0.36 / aspect, 0.36 * aspect)),
        ("cook_torrance", ["r=0.5"], mi.MicrofacetType.Beckmann, False, (0.25, 0.25)),
        ("cook_torrance", ["r=0.9"], mi.MicrofacetType.Beckmann, False, (0.81, 0.81)),
    ]
    for model, sets, typ, visible, (au, av) in cases:
        md = mi.MicrofacetDistribution(typ, au, av, visible)
        worst = 0.0
        for wo in ([0.3, 0.2, 0.9], [0.9, -0.3, 0.3]):
            l = math.sqrt(sum(x * x for x in wo))
            wo = [x / l for x in wo]
            for s in samples(abrdf, model, wo, sets):
                h = [a + b for a, b in zip(s["wi"], wo)]
                hl = math.sqrt(sum(x * x for x in h))
                h = [x / hl for x in h]
                if h[2] <= 0.0:
                    continue
                ref = md.pdf(mi.Vector3f(wo), mi.Vector3f(h)) / (4.0 * sum(a * b for a, b in zip(wo, h)))
                worst = max(worst, abs(s["pdf"] - ref) / ref)
        print("%-22s %-28s max relative difference of the pdf: %.2e" % (model, " ".join(sets), worst))
    print("Mitsuba", mi.__version__)


if __name__ == "__main__":
    main()
