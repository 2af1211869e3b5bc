"""abrdf.eval and abrdf.BRDF: f_r over arrays, the float batch path and the double scalar
reference, against each other and against `abrdf eval`."""
import math
import os
import signal
import threading
import time

import numpy as np
import pytest

import abrdf
from abrdf import _abrdf

# The float batch path against the double reference: the library's own test holds them to
# this relative tolerance (tests/unit/test_invariants.c); hair and layered models are
# integrated in float, their looser bound is the library's too.
RTOL = {"marschner": 2e-3, "huang": 2e-3, "belcour": 1e-3, "weidlich_wilkie": 1e-3}


def directions(n, seed):
    rng = np.random.default_rng(seed)
    v = rng.normal(size=(n, 3))
    v[:, 2] = np.abs(v[:, 2]) + 0.05  # above the surface
    return v / np.linalg.norm(v, axis=1, keepdims=True)


# (the measured model evaluates a table: test_py_measured.py)
@pytest.mark.parametrize("model", [m.name for m in abrdf.models() if "table" not in m.needs])
def test_float_batch_matches_double_reference(model):
    n = 64 if model == "huang" else 512
    wi, wo = directions(n, 1), directions(n, 2)
    f = abrdf.eval(model, wi, wo)
    d = abrdf.eval(model, wi, wo, precision="double")
    assert f.dtype == np.float32 and d.dtype == np.float64 and f.shape == d.shape == (n, 3)
    assert np.all(np.isfinite(f)) and np.all(f >= 0) and np.all(d >= 0)
    scale = max(float(np.max(d)), 1e-30)
    np.testing.assert_allclose(f, d, rtol=RTOL.get(model, 2e-4), atol=1e-5 * scale)


@pytest.mark.parametrize("model,sets", [
    ("disney_specular", {"r": 0.3}),
    ("disney_specular_aniso", {"r": 0.4, "anisotropic": 0.8, "f0": (0.9, 0.6, 0.3)}),
    ("f_2e", {"n": 300}),
    ("oren_nayar", {"sigma": 0.4, "kd": (0.2, 0.5, 0.7)}),
    ("belcour", {"layer_count": 3, "layer1_kappa": 0, "layer1_eta": 1.2,
                 "layer1_sigma_a": (0.1, 0.5, 2), "layer1_depth": 0.3, "layer2_kappa": 3}),
    ("weidlich_wilkie", {"kd": 0.5, "layer0_eta": 1.0}),
])
def test_double_reference_equals_the_command(cli, model, sets):
    wi, wo = (0.3, 0.0, 1.0), (-0.2, 0.1, 1.0)
    args = ["eval", model, "--wi", "0.3,0,1", "--wo", "-0.2,0.1,1", "--json"]
    for k, v in sets.items():
        args += ["--set", "%s=%s" % (k, ",".join(map(str, v)) if isinstance(v, tuple) else v)]
    ref = cli(*args)["f_r"]
    got = abrdf.eval(model, wi, wo, precision="double", **sets)
    np.testing.assert_allclose(got, ref, rtol=1e-12, atol=0)


def test_shapes_broadcast_and_dtypes():
    b = abrdf.BRDF("blinn_phong", n=50)
    one = b.eval([0.1, 0.2, 1.0], [0.0, -0.1, 1.0])
    assert one.shape == (3,)
    wo = directions(7 * 5, 3).reshape(7, 5, 3)
    many = b.eval([0.1, 0.2, 1.0], wo)  # one light, a grid of views
    assert many.shape == (7, 5, 3)
    np.testing.assert_array_equal(many[2, 3], b.eval([0.1, 0.2, 1.0], wo[2, 3]))
    f32 = b.eval(np.float32([[0.1, 0.2, 1.0]]), np.float32([[0.0, -0.1, 1.0]]))
    np.testing.assert_allclose(f32[0], one, rtol=1e-6)
    ints = b.eval([0, 0, 1], [0, 0, 1])  # integer input is converted
    assert ints.shape == (3,) and ints[0] > 0
    with pytest.raises(ValueError):
        b.eval([0.1, 0.2], [0.0, 0.0, 1.0])
    with pytest.raises(ValueError):
        b.eval(np.zeros((4, 3)), np.zeros((5, 3)))
    with pytest.raises(ValueError):
        b.eval([0, 0, 1], [0, 0, 1], precision="half")


def test_directions_are_normalised_and_degenerate_ones_give_zero():
    b = abrdf.BRDF("disney_specular", r=0.3)
    wi, wo = np.array([0.3, 0.0, 1.0]), np.array([-0.2, 0.1, 1.0])
    for precision in ("float", "double"):
        ref = b.eval(wi, wo, precision)
        for scale in (1e-30, 3.0, 1e30):
            np.testing.assert_allclose(b.eval(wi * scale, wo, precision), ref, rtol=1e-6)
        bad = np.array([[0, 0, 0], [np.nan, 0, 1], [np.inf, 0, 1], [0, 0, -1]], dtype=float)
        out = b.eval(bad, np.tile(wo, (4, 1)), precision)
        assert np.all(out == 0), (precision, out)


def test_threads_give_the_same_result_as_one():
    """A large array split over threads (automatic, or a count that does not divide it) gives
    the result of one thread bit for bit, odd rows (scaled, zero, non-finite, float32) included;
    a bad count is refused."""
    n = 3 * 32768 + 17
    wi, wo = directions(n, 5), directions(n, 6)
    wi[::997] *= 1e25  # beyond the float pass: redone exactly
    wi[1::1009] *= 3.0
    wo[::1013] = 0.0
    wo[5::1019] = np.nan
    b = abrdf.BRDF("disney_specular", r=0.3)
    one = b.eval(wi, wo, threads=1)
    for t in (0, 2, 3, 7):
        np.testing.assert_array_equal(b.eval(wi, wo, threads=t), one)
    np.testing.assert_array_equal(b.eval(wi.astype(np.float32), wo.astype(np.float32), threads=3),
                                  b.eval(wi.astype(np.float32), wo.astype(np.float32), threads=1))
    assert np.all(one[::1013] == 0) and np.all(one[5::1019] == 0)
    # the scaled rows give what their unit rows give
    unit = wi[::997] / np.linalg.norm(wi[::997], axis=1, keepdims=True)
    np.testing.assert_allclose(one[::997], b.eval(unit, wo[::997]), rtol=1e-6)
    np.testing.assert_array_equal(b.eval(wi[:9], wo[:9], threads=np.int64(4)), one[:9])
    for bad in (-1, 65, 2**40, 1.5, True, "2"):
        with pytest.raises(ValueError):
            b.eval(wi[:4], wo[:4], threads=bad)


def test_the_kept_threads_serve_concurrent_calls_and_a_forked_child():
    """The binding's threads are kept between calls: calls from several Python threads at once
    (one owns the threads, the others work alone) each give the one-thread result, and so does
    a child of fork() made after the threads were started (it starts with none, and starts
    its own: it must neither wait for nor count on threads that only its parent has)."""
    n = 4 * 16384 + 5
    wi, wo = directions(n, 9).astype(np.float32), directions(n, 10).astype(np.float32)
    b = abrdf.BRDF("disney_specular", r=0.3)
    one = b.eval(wi, wo, threads=1)
    np.testing.assert_array_equal(b.eval(wi, wo, threads=4), one)  # the threads now exist
    results, errors = [], []

    def worker():
        try:
            for _ in range(5):
                results.append(b.eval(wi, wo, threads=3))
        except Exception as e:  # pragma: no cover - reported below
            errors.append(e)

    pool = [threading.Thread(target=worker) for _ in range(4)]
    for t in pool:
        t.start()
    for t in pool:
        t.join()
    assert not errors and len(results) == 20
    for r in results:
        np.testing.assert_array_equal(r, one)
    # the call returns only when every thread is done with it: an output filled with NaN is
    # whole when the call returns (a 32-lobe material keeps the threads busy for a while)
    mat = abrdf.Lobes([abrdf.BRDF("disney_specular", r=0.1 + 0.02 * k) for k in range(32)])
    whole = mat.eval(wi, wo, threads=1)
    out = np.empty((n, 3), np.float32)
    for _ in range(20):
        out.fill(np.nan)
        mat.eval(wi, wo, threads=4, out=out)
        np.testing.assert_array_equal(out, whole)
    read, write = os.pipe()
    pid = os.fork()
    if pid == 0:  # the child: report through the pipe, never return into pytest
        ok = 0
        try:
            tasks = len(os.listdir("/proc/self/task"))  # Linux: the child's threads
            same = np.array_equal(b.eval(wi, wo, threads=4), one)
            # three workers of its own: the parent's count was not inherited
            ok = int(same) + 2 * int(len(os.listdir("/proc/self/task")) == tasks + 3)
        finally:
            os.write(write, bytes([ok]))
            os._exit(0)
    os.close(write)
    status = None
    for _ in range(600):  # up to 60 s: a child stuck on its parent's threads never answers
        done, status = os.waitpid(pid, os.WNOHANG)
        if done:
            break
        time.sleep(0.1)
    else:
        os.kill(pid, signal.SIGKILL)
        os.waitpid(pid, 0)
        pytest.fail("the forked child did not finish: it waited for its parent's threads")
    assert os.read(read, 1) == b"\x03" and status == 0, "1: the values, 2: the child's threads"
    os.close(read)
    np.testing.assert_array_equal(b.eval(wi, wo, threads=4), one)  # the parent's still serve


def test_the_kept_threads_follow_the_callers_cores():
    """The binding's threads run on the cores the calling thread may use: after a call from a
    thread pinned to one core the workers (threads named abrdf-eval) are on that core, and
    after a call from a thread with every core they are on every core again."""
    if not hasattr(os, "sched_setaffinity") or len(os.sched_getaffinity(0)) < 2:
        pytest.fail("needs Linux and two usable cores")
    n = 4 * 16384
    wi, wo = directions(n, 11).astype(np.float32), directions(n, 12).astype(np.float32)
    b = abrdf.BRDF("lambert")
    b.eval(wi, wo, threads=4)  # the workers exist, whoever started them
    mine = os.sched_getaffinity(0)
    pinned = {min(mine)}

    def cores_of_the_workers():  # they are named abrdf-eval
        found = []
        for task in os.listdir("/proc/self/task"):
            with open(f"/proc/self/task/{task}/comm") as f:
                if f.read().strip() == "abrdf-eval":
                    found.append(os.sched_getaffinity(int(task)))
        return found

    seen = []

    def first():
        os.sched_setaffinity(0, pinned)
        b.eval(wi, wo, threads=4)
        seen.extend(cores_of_the_workers())

    t = threading.Thread(target=first)
    t.start()
    t.join()
    assert len(seen) >= 3 and all(c == pinned for c in seen), seen
    b.eval(wi, wo, threads=4)  # from this thread, with every core
    workers = cores_of_the_workers()
    assert len(workers) >= 3 and all(c == mine for c in workers), workers


# float32 rows go to abrdf_eval_prepared_rows as they are (the library makes them unit);
# float64 rows are converted to float rows first (normalised in double where float cannot hold
# their length), then take the same call
@pytest.mark.parametrize("model", [m.name for m in abrdf.models() if "table" not in m.needs])
def test_float32_rows_give_the_float64_rows_values(model):
    """The same values bit for bit whichever way the rows go: float32 rows (straight into the
    library's loops) against the same numbers as float64 rows (converted), with a chunk holding
    rows of length 2, 3, 1e-20, 1e20, 1 + 4e-7, 1e35 and 1e-35 (float64: normalised in double
    before the conversion) and a zero row, a chunk of unit rows only,
    and a last partial chunk; rows not of unit length give their unit row's values, a zero
    row gives 0."""
    n = 2 * 256 + 45
    wi, wo = directions(n, 7).astype(np.float32), directions(n, 8).astype(np.float32)
    wi[0, 2] = -wi[0, 2]  # below the surface: 0 both ways
    scaled = {300: 2.0, 301: 3.0, 302: 1e-20, 303: 1e20, 304: 1.0 + 4e-7, 305: 1e35, 306: 1e-35}
    for k, scale in scaled.items():
        wi[k] = (wi[k].astype(np.float64) * scale).astype(np.float32)
    wo[400] = 0.0
    b = abrdf.BRDF(model)
    f32 = b.eval(wi, wo, threads=1)
    f64 = b.eval(wi.astype(np.float64), wo.astype(np.float64), threads=1)
    np.testing.assert_array_equal(f32, f64)
    assert np.any(f32 > 0)
    assert np.all(f32[400] == 0)
    ks = list(scaled)
    # the rows made unit by the library's rule (abrdf.h): within 1e-6 of unit squared length
    # as they are, others scaled (a scale rounds the float32 components: these, not unit_wi)
    w64 = wi[ks].astype(np.float64)
    len2 = np.sum(w64 * w64, axis=1, keepdims=True)
    unit = np.where(np.abs(len2 - 1.0) <= 1e-6, w64, w64 / np.sqrt(len2)).astype(np.float32)
    np.testing.assert_allclose(f32[ks], b.eval(unit, wo[ks], threads=1), rtol=2e-5, atol=1e-30)
    # the module function may write over its input: then the rows are laid out first
    w = wi.copy()
    _abrdf.eval_float(b.block, w, wo, w, 1)
    np.testing.assert_array_equal(w, f32)
    # the row of length 2 gives what its unit row gives
    unit = b.eval(wi[300] / np.float32(2.0), wo[300])
    np.testing.assert_array_equal(f32[300], unit)


def test_errors_carry_the_librarys_message():
    with pytest.raises(abrdf.Error) as e:
        abrdf.BRDF("f_2e", n=0.5)  # inside n's own range, outside f_2e's
    assert str(e.value) == "f_2e: n = 0.5 is outside [1, 1e+06]" and e.value.status == -4
    assert isinstance(e.value, ValueError)
    with pytest.raises(abrdf.Error) as e:
        abrdf.BRDF("disney_specular", r=1.5)
    assert "r = 1.5" in str(e.value) and e.value.status == -4
    with pytest.raises(abrdf.Error) as e:
        abrdf.BRDF("lambert", r=0.5)
    assert "lambert does not read parameter 'r'" in str(e.value) and "kd" in str(e.value)
    assert e.value.status == -6
    with pytest.raises(abrdf.Error) as e:
        abrdf.BRDF("lambert", rr=0.5)
    assert "unknown parameter 'rr'" in str(e.value) and e.value.status == -3
    with pytest.raises(abrdf.Error):
        abrdf.BRDF("disney_specular", f0=(0.1, 0.2))
    with pytest.raises(abrdf.Error):
        abrdf.BRDF("weidlich_wilkie", layer_count=1.5)
    with pytest.raises(abrdf.Error):
        abrdf.BRDF("disney_specular", r=math.nan)
    with pytest.raises(TypeError):
        _abrdf.eval_float(abrdf.BRDF("lambert").block, np.zeros((2, 3)), np.zeros((2, 3)),
                          np.zeros((2, 3)))  # out must be float32


def test_params_round_trip():
    b = abrdf.BRDF("disney_specular_aniso", r=0.4, anisotropic=0.8, f0=0.5)
    assert b.params["f0"] == (0.5, 0.5, 0.5)
    assert b.params["r"] == 0.4 and b.model == "disney_specular_aniso"
    again = abrdf.BRDF(b.model, **b.params)
    np.testing.assert_array_equal(again.eval([0.3, 0, 1], [-0.2, 0.1, 1]),
                                  b.eval([0.3, 0, 1], [-0.2, 0.1, 1]))
    assert "anisotropic=0.8" in repr(b)
    assert abrdf.BRDF("weidlich_wilkie", layer_count=2).params["layer_count"] == 2


def test_the_gil_is_released_during_evaluation():
    # While the C loop runs without the GIL, this thread can read the output buffer half
    # written (earlier chunks done, the last not yet); with the GIL held it only ever sees
    # the buffer untouched or complete.
    # marschner: ~20 us per pair, so 40 chunks of 256 pairs take ~0.2 s.
    p = abrdf.BRDF("marschner").block
    n = 40 * 256
    wi = np.ascontiguousarray(directions(n, 4), dtype=np.float32)
    wo = np.ascontiguousarray(directions(n, 5), dtype=np.float32)
    for attempt in range(3):
        out = np.full((n, 3), np.nan, np.float32)
        started, partial = threading.Event(), []
        t = threading.Thread(target=lambda: (started.set(), _abrdf.eval_float(p, wi, wo, out)))
        t.start()
        started.wait()
        while t.is_alive() and not partial:
            if not np.isnan(out[0, 0]) and np.isnan(out[-1, 0]):
                partial.append(True)
        t.join()
        assert not np.isnan(out).any()
        if partial:
            return
    pytest.fail("no half-written output seen in 3 evaluations: the GIL is held")
