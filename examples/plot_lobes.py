#!/usr/bin/env python3
"""Two plots from the abrdf Python package (docs/PYTHON.md), with matplotlib:

  left   polar lobes in the plane of incidence: f_r cos(theta_i) of Blinn-Phong (n = 50),
         three of its Table-1 approximations at the same n, and the Disney GGX lobe of the
         same width (r from n: alpha_g = sqrt(2 / (n + 2)), r = sqrt(alpha_g)), for light
         at 30 degrees, each normalised to its peak (abrdf.eval over 721 view directions);
  right  the Pareto plot behind the performance branch of the paper's flowchart: for each
         exponent n, every Table-1 candidate's cost (the paper's Table 4, cycles) against its
         maximum relative error in the highlight (the trace of abrdf.select), the cheapest
         candidate within the tolerance (the selection's choice) ringed.

usage: python examples/plot_lobes.py [-o docs/python_plots.png]
"""
import argparse
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import abrdf  # noqa: E402

THETA_I = math.radians(30.0)
N = 50


def polar_lobes(ax):
    t = np.radians(np.linspace(-90.0, 90.0, 721))
    wo = np.stack([np.sin(t), np.zeros_like(t), np.cos(t)], axis=-1)
    wi = np.array([-math.sin(THETA_I), 0.0, math.cos(THETA_I)])  # mirror direction at +30
    r = math.sqrt(math.sqrt(2.0 / (N + 2.0)))
    lobes = [("blinn_phong", {"n": N}, "-"), ("f2", {"n": N}, "--"), ("f8", {"n": N}, "-."),
             ("fs", {"n": N}, ":"), ("disney_specular", {"r": r, "f0": 1.0}, "-")]
    for name, params, style in lobes:
        f = abrdf.eval(name, wi, wo, **params)[:, 0] * math.cos(THETA_I)
        ax.plot(t, f / f.max(), style, lw=1.4, label="%s (%s)" % (name, abrdf.model(name).equation))
    ax.set_thetamin(-90)
    ax.set_thetamax(90)
    ax.set_theta_zero_location("N")
    ax.set_theta_direction(-1)
    ax.set_rticks([0.25, 0.5, 0.75, 1.0])
    ax.set_title("Lobes in the plane of incidence, light at 30 deg, n = %d\n"
                 "f_r cos(theta_i), each normalised to its peak" % N, fontsize=9)
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, 0.12), fontsize=7, ncol=2)


def pareto(ax):
    tol = abrdf._abrdf.rules()["default_max_rel_pct"]
    markers = {}
    for n, colour in ((20, "tab:blue"), (100, "tab:orange"), (1000, "tab:green")):
        sel = abrdf.select(abrdf.Material(n=n), goal="performance")
        cands = [s for s in sel.trace if s.kind == "candidate"]
        for s in cands:
            markers.setdefault(s.model, len(markers))
            ax.scatter(s.cost, s.value, color=colour, marker="osD^vP*"[markers[s.model] % 7],
                       s=28, zorder=3)
        # The Pareto front: candidates no other is both cheaper and more accurate than.
        pts = sorted((s.cost, s.value) for s in cands)
        front, best = [], math.inf
        for c, e in pts:
            if e < best:
                front.append((c, e))
                best = e
        ax.plot(*zip(*front), color=colour, lw=1, label="n = %d: chose %s" % (n, sel.specular))
        chosen = next((s for s in cands if s.model == sel.specular), None)
        if chosen:
            ax.scatter(chosen.cost, chosen.value, s=150, facecolors="none", edgecolors=colour,
                       lw=1.5, zorder=4)
    for name, k in markers.items():
        ax.scatter([], [], color="grey", marker="osD^vP*"[k % 7], label=name)
    ax.axhline(tol, color="black", lw=0.8, ls="--")
    ax.text(0.01, tol * 1.08, "tolerance %g %%" % tol, fontsize=7,
            transform=ax.get_yaxis_transform())
    ax.set_yscale("log")
    ax.set_xlabel("cost, cycles (the paper's Table 4)")
    ax.set_ylabel("max relative error vs Blinn-Phong in the highlight, %")
    ax.set_title("Performance branch: Table-1 candidates (abrdf.select's trace)\n"
                 "ringed: the cheapest within the tolerance", fontsize=9)
    ax.legend(fontsize=7, loc="lower left", ncol=2)
    ax.grid(True, which="both", lw=0.3)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("-o", "--out", default="python_plots.png")
    a = ap.parse_args()
    fig = plt.figure(figsize=(11, 4.6))
    polar_lobes(fig.add_subplot(1, 2, 1, projection="polar"))
    pareto(fig.add_subplot(1, 2, 2))
    fig.tight_layout()
    fig.savefig(a.out, dpi=110)
    print("wrote %s" % a.out)


if __name__ == "__main__":
    main()
