#!/usr/bin/env python3
"""nk_rgb.py - n and k at 650/550/450 nm (the R, G, B wavelengths of data/metal_nk.csv) from a
refractiveindex.info database file (type "tabulated nk", wavelength in micrometres), by linear
interpolation between the tabulated wavelengths, and the normal-incidence reflectance
F0 = ((n-1)^2 + k^2) / ((n+1)^2 + k^2) at each.

usage: scripts/nk_rgb.py FILE.yml [FILE.yml ...]
The database is public domain (CC0): https://github.com/polyanskiy/refractiveindex.info-database
"""
import sys

WAVELENGTHS_UM = (0.650, 0.550, 0.450)


def tabulated_nk(path):
    rows, inside = [], False
    with open(path, encoding="utf-8") as f:
        for line in f:
            if "type: tabulated nk" in line:
                inside = True
                continue
            if inside:
                parts = line.split()
                if len(parts) == 3:
                    try:
                        rows.append(tuple(float(x) for x in parts))
                        continue
                    except ValueError:
                        pass
                if rows:
                    break
    if not rows:
        sys.exit(f"{path}: no 'tabulated nk' data")
    return rows


def at(rows, lam):
    for a, b in zip(rows, rows[1:]):
        if a[0] <= lam <= b[0]:
            t = (lam - a[0]) / (b[0] - a[0])
            return a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])
    sys.exit(f"wavelength {lam} um outside the table")


def f0(n, k):
    return ((n - 1) ** 2 + k * k) / ((n + 1) ** 2 + k * k)


for path in sys.argv[1:]:
    rows = tabulated_nk(path)
    nk = [at(rows, lam) for lam in WAVELENGTHS_UM]
    print(path)
    print("  n,k 650/550/450 nm: " + ",".join(f"{n:.4f},{k:.4f}" for n, k in nk))
    print("  F0  650/550/450 nm: " + ",".join(f"{f0(n, k):.3f}" for n, k in nk))
