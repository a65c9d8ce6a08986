"""GL from Python: the module's headless context, the same maps as the CPU and the GLSL look-up's answers."""
import gc
import threading

import numpy as np
import pytest

import hairshadow as hs
from conftest import SMALL, run_cli, sample_points


@pytest.mark.parametrize("spec", ["dom:3", "occ:32:1", "osm:16:8bit", "fom:7"])
def test_gl_maps_are_the_cpus(small, spec):
    cpu = hs.ShadowMap(spec)
    cpu.build(small, "dir:0,-1,-1", 64)
    gl = hs.ShadowMap(spec, backend="gl", gl_path="compute")
    assert gl.backend == "gl"
    gl.build(small, "dir:0,-1,-1", 64)
    if spec.endswith("8bit"):
        np.testing.assert_array_equal(gl.maps(), cpu.maps())  # integer steps: bit for bit
    else:  # float sums within the documented tolerance (README: 1e-6)
        np.testing.assert_allclose(gl.maps(), cpu.maps(), atol=1e-6, rtol=0)
    points = sample_points(small, 5000)
    # The GLSL look-up computes the CPU query's texel and depth (README, "The GL state contract").
    np.testing.assert_allclose(gl.transmittance(points), cpu.transmittance(points), atol=1e-5, rtol=0)
    np.testing.assert_allclose(gl.transmittance(points, bias=0.003), cpu.transmittance(points, bias=0.003), atol=1e-5, rtol=0)


def test_gl_errors(small):
    gl = hs.ShadowMap("dom:3", backend="gl")
    with pytest.raises(ValueError, match="not built"):
        gl.transmittance(small.points)
    with pytest.raises(ValueError, match="wide lines"):
        gl.build(small, resolution=32, wide=4.0)
    gl.build(small, resolution=32)
    with pytest.raises(ValueError, match="CPU queries"):
        gl.transmittance(small.points, jitter=True)
    with pytest.raises(ValueError, match="depth bias"):
        gl.transmittance(small.points, bias=2.0)
    with pytest.raises(ValueError, match="unknown GL build path"):
        hs.ShadowMap("dom:3", backend="gl", gl_path="mesh")
    with pytest.raises(ValueError, match="one kind of context"):
        hs.ShadowMap("dom:3", backend="gl", context="osmesa")
    with pytest.raises(ValueError, match="belongs to the exact map"):
        gl.fragments(0, 0)
    assert gl.maps().shape == (32, 32, 3) and gl.fragment_count == 0
    caught = []

    def elsewhere():
        try:
            gl.transmittance(small.points)
        except hs.GLError as e:
            caught.append(str(e))

    t = threading.Thread(target=elsewhere)
    t.start()
    t.join()
    assert caught and "thread" in caught[0]
    assert issubclass(hs.GLError, RuntimeError)


def test_compare_and_render_on_gl(tmp_path, small):
    import matplotlib.image as matplotlib_image
    cpu = hs.compare(small, ["dom:3"], resolution=64)[0]
    gl = hs.compare(small, ["dom:3"], resolution=64, backend="gl")[0]
    assert gl["memory_bytes"] > 0
    for key in ("mean_error", "curve_error", "image_error"):
        assert abs(gl[key] - cpu[key]) < 1e-4, key  # the same maps within 1e-6, one look-up in 10^4 apart at most
    picture = hs.render(SMALL, "dom:3", resolution=64, size=48, backend="gl", srgb=True)
    assert picture.shape == (48, 48, 3) and picture.dtype == np.uint8
    run_cli("render", SMALL, "--method", "dom:3", "--res", 64, "--size", 48, "--backend", "gl", "--out", tmp_path / "gl.png")
    png = np.round(matplotlib_image.imread(tmp_path / "gl.png")[:, :, :3] * 255).astype(np.uint8)
    np.testing.assert_array_equal(picture, png)  # the command's GL render


def test_gl_maps_dropped_on_another_thread(small):
    """A GL map whose last reference goes on another thread is deleted at GL's next use on its own."""
    maps = [hs.ShadowMap("dom:3", backend="gl")]
    maps[0].build(small, resolution=32)
    t = threading.Thread(target=maps.clear)
    t.start()
    t.join()
    gc.collect()
    again = hs.ShadowMap("occ:32:1", backend="gl")  # the next use frees the dropped one, on GL's thread
    again.build(small, resolution=32)
    assert again.transmittance(small.points).shape == (small.point_count,)
