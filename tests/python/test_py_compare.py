"""abrdf.compare, abrdf.read_image: the paper's NMSE and its companions on arrays and on
image files, as `abrdf compare` computes them."""
import math

import numpy as np
import pytest

import abrdf


def test_nmse_is_the_papers_definition():
    rng = np.random.default_rng(7)
    ref = rng.random((6, 5, 3), dtype=np.float32)
    test = ref + 0.01 * rng.standard_normal((6, 5, 3)).astype(np.float32)
    c = abrdf.compare(ref, test)
    r, t = ref.astype(np.float64), test.astype(np.float64)
    assert math.isclose(c.nmse, np.sum((t - r) ** 2) / np.sum(r ** 2), rel_tol=1e-9)
    assert math.isclose(c.mse, np.mean((t - r) ** 2), rel_tol=1e-9)
    peak = max(r.max(), t.max())
    assert math.isclose(c.psnr, 10 * math.log10(peak ** 2 / c.mse), rel_tol=1e-9)
    y, x, ch = np.unravel_index(np.argmax(np.abs(t - r)), r.shape)
    assert c.max_pixel == (x, y) and c.max_channel == ch
    assert math.isclose(c.max_abs_error, np.max(np.abs(t - r)), rel_tol=1e-6)
    # Not symmetric: the reference's energy normalises.
    assert abrdf.compare(test, ref).nmse != c.nmse


@pytest.mark.parametrize("nmse,cls", [(0.0, "none"), (0.5e-4, "none"), (1.5e-4, "slight"),
                                      (5e-4, "noticeable"), (2e-3, "significant")])
def test_table_8_classes(nmse, cls):
    ref = np.ones((1, 1), np.float32)
    c = abrdf.compare(ref, ref + np.float32(math.sqrt(nmse)))
    assert c.nmse_class == cls and c.passed() == (cls == "none")
    # The same boundaries as the flowchart's rules (abrdf_select_rules: Table 8).
    bounds = abrdf._abrdf.rules()["nmse_class_max"]
    assert sum(c.nmse >= b for b in bounds) == ["none", "slight", "noticeable",
                                                 "significant"].index(cls)


def test_undefined_and_bad_inputs():
    black = np.zeros((2, 2, 3), np.float32)
    c = abrdf.compare(black, black + 1)
    assert c.nmse is None and c.nmse_class == "undefined" and not c.passed()
    with pytest.raises(abrdf.Error) as e:
        abrdf.compare(black, np.zeros((2, 3, 3)))
    assert "differ in size" in str(e.value)
    bad = black.copy()
    bad[1, 0, 2] = np.nan
    with pytest.raises(abrdf.Error) as e:
        abrdf.compare(black + 1, bad)
    assert "test image has a NaN or infinite value at pixel (0, 1) channel 2" in str(e.value)
    with pytest.raises(ValueError):
        abrdf.compare(np.zeros(4), np.zeros(4))


def test_files_compare_as_the_command(cli, source_dir, tmp_path):
    scene = "%s/scenes/sphere.scene" % source_dir
    a, b = tmp_path / "a.exr", tmp_path / "b.exr"
    cli("render", scene, "-o", a, "--width", 24, "--height", 16, "--spp", 1)
    cli("render", scene, "-o", b, "--width", 24, "--height", 16, "--spp", 1,
        "--model", "blinn_phong")
    # Linear files agree to float rounding; 8-bit previews to the sRGB decoding, which
    # OpenImageIO's OpenColorIO does within 2.5e-4 relative per sample (docs/PYTHON.md).
    for ref, test, tol in ((a, b, 1e-6), (a.with_suffix(".png"), b.with_suffix(".png"), 1e-3)):
        want = cli("compare", ref, test, "--json", check=False)
        got = abrdf.compare(ref, test)
        assert got.nmse_class == want["class"]
        for k in ("nmse", "mse", "peak", "psnr", "max_abs_error", "sse", "reference_energy"):
            assert math.isclose(getattr(got, k), want[k], rel_tol=tol, abs_tol=1e-12), k
        assert list(got.max_pixel) == want["max_pixel"]
        assert "RGB"[got.max_channel] == want["max_channel"]
    img = abrdf.read_image(a)
    assert img.shape == (16, 24, 3) and img.dtype == np.float32
    # A file against an array of itself, and the decoded preview against its linear source:
    assert abrdf.compare(a, img).nmse == 0
    png = abrdf.read_image(a.with_suffix(".png"))
    assert abrdf.compare(np.clip(img, 0, 1), png).nmse < 1e-4
    with pytest.raises(abrdf.Error):
        abrdf.compare(a, tmp_path / "missing.exr")
