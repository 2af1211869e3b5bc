"""abrdf.Lobes (a material of several lobes evaluated in one pass over the rows) and the out=
argument of the evaluations: the sum equals the lobes' own evals, threads do not change a bit,
bad arguments get one clear error."""
import pickle

import numpy as np
import pytest

import abrdf
from abrdf import _abrdf

LOBES = [
    abrdf.BRDF("disney_diffuse", r=0.3, kd=(0.5, 0.4, 0.3)),
    abrdf.BRDF("disney_specular", r=0.3),
    abrdf.BRDF("blinn_phong", n=80),
    abrdf.BRDF("lambert"),
    abrdf.BRDF("disney_specular_aniso", r=0.4, anisotropic=0.8, f0=(0.9, 0.6, 0.3)),
]


def directions(n, seed, odd=True):
    rng = np.random.default_rng(seed)
    v = rng.normal(size=(n, 3))
    v[:, 2] = np.abs(v[:, 2]) + 0.05  # above the surface
    v /= np.linalg.norm(v, axis=1, keepdims=True)
    if odd and n > 40:
        v[3::37] *= 2.5  # not unit: the library's general path makes the chunk unit
        v[7::41] = 0.0   # zero: f_r = 0
        v[11::43] *= 1e25  # float64: converted as it is (1e50 squared is within its range)
        v[13::47] *= 1e35  # float64: normalised in double before the conversion to float
    return v


def separate(lobes, wi, wo, **kw):
    """The lobes' own evals, added in order in the result's dtype."""
    out = lobes[0].eval(wi, wo, **kw)
    for b in lobes[1:]:
        out = out + b.eval(wi, wo, **kw)
    return out


@pytest.mark.parametrize("count", [1, 2, 3, 5])
@pytest.mark.parametrize("n", [1, 7, 255, 257, 1001])
@pytest.mark.parametrize("dtype", [np.float32, np.float64])
def test_the_sum_is_the_lobes_own_evals(count, n, dtype):
    """Float path: bit for bit the float32 sum of the separate evals, odd row counts (around
    the 256-row chunks), float32 (the rows path) and float64 (the layout) input, rows that are
    not unit, zero or huge."""
    wi, wo = directions(n, 1).astype(dtype), directions(n, 2).astype(dtype)
    m = abrdf.Lobes(LOBES[:count])
    f = m.eval(wi, wo)
    assert f.dtype == np.float32 and f.shape == (n, 3)
    np.testing.assert_array_equal(f, separate(LOBES[:count], wi, wo))
    d = m.eval(wi, wo, precision="double")
    assert d.dtype == np.float64
    np.testing.assert_allclose(d, separate(LOBES[:count], wi, wo, precision="double"),
                               rtol=1e-12, atol=0)
    np.testing.assert_allclose(f, d, rtol=2e-4, atol=1e-5 * max(float(d.max()), 1e-30))


def test_threads_give_the_result_of_one_thread():
    """A large material split over threads (automatic, or a count that does not divide the
    rows) is the one-thread result bit for bit, with the odd rows in some chunks."""
    n = 3 * 32768 + 17
    m = abrdf.Lobes(LOBES[:3])
    for dtype in (np.float32, np.float64):
        wi, wo = directions(n, 3).astype(dtype), directions(n, 4).astype(dtype)
        one = m.eval(wi, wo, threads=1)
        for t in (0, 2, 3, 7):
            np.testing.assert_array_equal(m.eval(wi, wo, threads=t), one)
        np.testing.assert_array_equal(one, separate(LOBES[:3], wi, wo, threads=1))


def test_broadcast_and_eval_dispatch():
    wi = np.array([0.3, 0.0, 1.0])
    wo = directions(12, 5, odd=False).reshape(3, 4, 3)
    m = abrdf.Lobes(LOBES[:2])
    f = abrdf.eval(m, wi, wo)
    assert f.shape == (3, 4, 3)
    np.testing.assert_array_equal(f, separate(LOBES[:2], wi, wo))
    assert m.eval(wi, wi).shape == (3,)
    assert m.eval(np.empty((0, 3)), np.empty((0, 3))).shape == (0, 3)
    with pytest.raises(TypeError, match="parameters are given to BRDF"):
        abrdf.eval(m, wi, wo, r=0.3)


def test_a_measured_lobe():
    """A Measured table is a lobe like a BRDF (the prepared table is held while evaluating)."""
    rng = np.random.default_rng(9)
    t = abrdf.measured_from_array(rng.uniform(0.1, 1.0, size=(4, 5, 6, 3)))
    m = abrdf.Lobes([t, LOBES[1]])
    wi, wo = directions(300, 6), directions(300, 7)
    np.testing.assert_array_equal(m.eval(wi, wo), separate([t, LOBES[1]], wi, wo))


def test_the_object():
    m = abrdf.Lobes(iter(LOBES[:2]))
    assert len(m) == 2 and list(m) == LOBES[:2] and m.lobes == tuple(LOBES[:2])
    assert m == abrdf.Lobes(LOBES[:2]) and hash(m) == hash(abrdf.Lobes(LOBES[:2]))
    assert m != abrdf.Lobes(LOBES[1:3])
    assert pickle.loads(pickle.dumps(m)) == m
    assert repr(m).startswith("Lobes([BRDF('disney_diffuse'")
    pbr = abrdf.Lobes(abrdf.pbr_lobes(abrdf.Pbr(base_color=(0.8, 0.1, 0.1), metallic=0)))
    assert [b.model for b in pbr] == ["lambert_fresnel", "disney_specular"]


def test_bad_lobes_get_one_clear_error():
    with pytest.raises(ValueError, match="at least one lobe"):
        abrdf.Lobes([])
    with pytest.raises(TypeError, match="lobe 1 is a str"):
        abrdf.Lobes([LOBES[0], "lambert"])
    with pytest.raises(TypeError, match="a sequence of BRDFs"):
        abrdf.Lobes(LOBES[0])
    with pytest.raises(TypeError):
        abrdf.Lobes(3)
    # the module function: an empty material, a wrong lobe, too many lobes
    wi = directions(4, 1).astype(np.float32)
    out = np.empty_like(wi)
    with pytest.raises(ValueError, match="at least one lobe"):
        _abrdf.eval_float((), wi, wi, out)
    with pytest.raises(TypeError):
        _abrdf.eval_float([LOBES[0].block, "x"], wi, wi, out)
    with pytest.raises(ValueError, match="at most 4096 lobes"):
        _abrdf.eval_float([LOBES[0].block] * 4097, wi, wi, out)
    m = abrdf.Lobes(LOBES[:2])
    with pytest.raises(ValueError, match="threads"):
        m.eval(wi, wi, threads=65)
    with pytest.raises(ValueError, match="precision"):
        m.eval(wi, wi, precision="half")
    with pytest.raises(TypeError, match="wi: a real number array"):
        m.eval(np.array([0, 1j, 1]), wi[0])


@pytest.mark.parametrize("precision,dtype", [("float", np.float32), ("double", np.float64)])
def test_out_is_written_and_returned(precision, dtype):
    wi, wo = directions(513, 1), directions(513, 2)
    for what in (LOBES[1], abrdf.Lobes(LOBES[:3])):
        want = what.eval(wi, wo, precision=precision)
        out = np.full((513, 3), -1.0, dtype)
        assert what.eval(wi, wo, precision=precision, out=out) is out
        np.testing.assert_array_equal(out, want)
        got = abrdf.eval(what, wi, wo, precision=precision, out=np.empty((513, 3), dtype))
        np.testing.assert_array_equal(got, want)
    out = np.empty((2, 3, 3), dtype)  # the broadcast shape, not only (N, 3)
    r = abrdf.eval("lambert", wi[:3], wo[:6].reshape(2, 3, 3), precision=precision, out=out)
    assert r is out
    one = np.empty(3, dtype)
    assert abrdf.eval("lambert", wi[0], wo[0], precision=precision, out=one) is one


def test_a_bad_out_gets_one_clear_error():
    wi, wo = directions(10, 1).astype(np.float32), directions(10, 2).astype(np.float32)
    b = LOBES[1]
    ro = np.empty((10, 3), np.float32)
    ro.flags.writeable = False
    cases = [
        (np.empty((10, 3)), TypeError, "out: float32 is needed for precision='float', got float64"),
        (np.empty((10, 3), np.float32).tolist(), TypeError, "out: a NumPy array is needed"),
        (np.empty((9, 3), np.float32), ValueError, r"out: shape \(10, 3\) is needed, got \(9, 3\)"),
        (np.empty((30,), np.float32), ValueError, "out: shape"),
        (np.empty((10, 6), np.float32)[:, ::2], ValueError, "out: a C-contiguous array"),
        (np.empty((3, 10), np.float32).T, ValueError, "out: a C-contiguous array"),
        (np.empty((3, 10), np.float32).T.copy(order="F"), ValueError, "C-contiguous"),
        (ro, ValueError, "out: the array is read-only"),
        (wi, ValueError, "out: shares memory with wi or wo"),
        (wo, ValueError, "out: shares memory with wi or wo"),
    ]
    for out, err, msg in cases:
        for what in (b, abrdf.Lobes([b, b])):
            with pytest.raises(err, match=msg):
                what.eval(wi, wo, out=out)
    with pytest.raises(TypeError, match="float64 is needed for precision='double'"):
        b.eval(wi, wo, precision="double", out=np.empty((10, 3), np.float32))
