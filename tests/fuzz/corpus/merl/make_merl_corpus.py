"""make_merl_corpus.py - writes the seeds of fuzz_merl (tests/fuzz/fuzz_merl.c) beside itself:
tiny MERL BRDF files (tools/measured/merl.h), valid ones on 2x2x2 and 2x3x4 grids and broken
ones (a short header, absurd sizes, a cut body, trailing bytes, NaN, infinity, an implausible
value). The seeds are committed; run this again only to change them."""
import math
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))


def merl(dims, value=lambda c, i: 100.0 * (c + 1) + i, extra=b"", cut=0):
    n = dims[0] * dims[1] * dims[2] if min(dims) > 0 else 0
    body = b"".join(struct.pack("<d", value(c, i)) for c in range(3) for i in range(n))
    data = struct.pack("<iii", *dims) + body + extra
    return data[:len(data) - cut] if cut else data


SEEDS = {
    "merl_valid_2x2x2.binary": merl((2, 2, 2)),
    "merl_valid_2x3x4.binary": merl((2, 3, 4), lambda c, i: 0.5 * i + c),
    "merl_holes_2x2x2.binary": merl((2, 2, 2), lambda c, i: -1.0 if i % 3 == c else 7.5),
    "merl_zeros_2x2x2.binary": merl((2, 2, 2), lambda c, i: 0.0),
    "merl_short.binary": struct.pack("<ii", 2, 2),
    "merl_absurd.binary": struct.pack("<iii", 90, 0, 180),
    "merl_huge_grid.binary": struct.pack("<iii", 1024, 1024, 1024),
    "merl_cut.binary": merl((2, 2, 2), cut=5),
    "merl_trailing.binary": merl((2, 2, 2), extra=b"\x00\x01\x02"),
    "merl_nan.binary": merl((2, 2, 2), lambda c, i: math.nan if (c, i) == (1, 3) else 1.0),
    "merl_inf.binary": merl((2, 2, 2), lambda c, i: math.inf if (c, i) == (2, 7) else 1.0),
    "merl_implausible.binary": merl((2, 2, 2), lambda c, i: 1e12 if (c, i) == (0, 0) else 1.0),
}

for name, data in SEEDS.items():
    with open(os.path.join(HERE, name), "wb") as f:
        f.write(data)
