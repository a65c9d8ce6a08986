"""Shadow maps from Python: every registered method, the same answers as the command, arrays in and out."""
import numpy as np
import pytest

import hairshadow as hs
from conftest import SINTEL, run_cli, sample_points


@pytest.mark.parametrize("spec", hs.methods())
def test_every_registered_method_builds_and_answers(small, spec):
    m = hs.ShadowMap(spec)
    assert not m.built
    m.build(small, "dir:0,-1,-1", 48)
    assert m.built and m.resolution == 48 and m.spec == spec
    t = m.transmittance(small.points)
    assert t.dtype == np.float32 and t.shape == (small.point_count,)
    assert np.all((t >= 0) & (t <= 1))
    assert t.min() < 1.0  # the hair shadows itself
    k = m.maps()
    assert k.shape[:2] == (48, 48) and k.dtype == np.float32 and m.map_layout.startswith("[y, x, ")


@pytest.mark.parametrize("spec", ["dom:3", "occ:128:4", "fom:7", "avsm", "dsm"])
def test_transmittance_equals_the_command_query(tmp_path, sintel, spec):
    points = sample_points(sintel, 2000)
    path = tmp_path / "points.txt"
    np.savetxt(path, points, fmt="%.9g")
    printed = np.array(run_cli("query", SINTEL, "--method", spec, "--res", 256, "--light", "dir:0,-1,-1", "--points", path).split(), np.float32)
    m = hs.ShadowMap(spec)
    m.build(sintel, hs.Light("dir:0,-1,-1"), 256)
    t = m.transmittance(np.loadtxt(path, dtype=np.float32))
    np.testing.assert_allclose(t, printed, atol=5.1e-7, rtol=0)  # the command prints 6 decimals


def test_query_options_as_the_command(tmp_path, sintel):
    points = sample_points(sintel, 500, seed=5)
    path = tmp_path / "points.txt"
    np.savetxt(path, points, fmt="%.9g")
    printed = np.array(run_cli("query", SINTEL, "--method", "osm:16", "--res", 128, "--points", path, "--bias", 0.01, "--filter", "--jitter").split(),
                       np.float32)
    m = hs.ShadowMap("osm:16")
    m.build(sintel, resolution=128)
    t = m.transmittance(np.loadtxt(path, dtype=np.float32), box_filter=True, jitter=True, bias=0.01)
    np.testing.assert_allclose(t, printed, atol=5.1e-7, rtol=0)


def test_curve_along_a_ray_is_the_point_query(small):
    m = hs.ShadowMap("dom:3")
    m.build(small, "point:0,3,1", 64)
    space = m.light_space
    points = sample_points(small, 300)
    projected = space.project(points)
    inside = (projected[:, 3] > 0) & (projected[:, 0] >= 0) & (projected[:, 1] >= 0) & (projected[:, 0] < 64) & (projected[:, 1] < 64)
    assert inside.sum() > 250
    t = m.transmittance(points)
    for p, expected in zip(projected[inside][:50], t[inside][:50]):
        assert m.transmittance_at(int(p[0]), int(p[1]), [p[2]])[0] == expected
    x, y = int(projected[0, 0]), int(projected[0, 1])
    depths = np.linspace(0, 1, 65, dtype=np.float32)
    curve = m.transmittance_at(x, y, depths)
    np.testing.assert_array_equal(m.transmittance_at(x, y, depths.astype(np.float64)), curve)  # a few depths: any real dtype
    assert np.all(np.diff(curve) <= 0)  # light only ever lost along a ray
    np.testing.assert_allclose(np.exp(-m.optical_depth_at(x, y, depths)), curve, rtol=1e-6)
    with pytest.raises(ValueError, match="outside the 64x64"):
        m.transmittance_at(64, 0, depths)


def test_world_point_inverts_project(small):
    space = hs.LightSpace("spot:0,3,0:0,-1,0:40", small, 128)
    points = sample_points(small, 20)
    for p, q in zip(points, space.project(points)):
        np.testing.assert_allclose(space.world_point(q[0], q[1], q[2]), p, atol=1e-4)


def test_exact_fragments(small):
    m = hs.ShadowMap("dsm")
    m.build(small, resolution=32)
    found = 0
    for y in range(32):
        for x in range(32):
            depths, optical = m.fragments(x, y)
            if len(depths) == 0:
                continue
            found += 1
            assert np.all(np.diff(depths) >= 0) and np.all(np.diff(optical) >= 0)
            assert m.optical_depth_at(x, y, [1.0])[0] == optical[-1]
    assert found > 20
    compressed = hs.ShadowMap("dsm:0.01")
    compressed.build(small, resolution=32)
    for y in range(32):
        for x in range(32):
            depths, t = compressed.fragments(x, y)
            if len(depths) < 3:
                continue
            assert np.all((t >= 0) & (t <= 1)) and np.all(np.diff(t) <= 0) and np.all(np.diff(depths) >= 0)
            alone = np.ones(len(depths), bool)  # a vertex not sharing its depth (a step has two)
            alone[1:] &= depths[1:] != depths[:-1]
            alone[:-1] &= depths[:-1] != depths[1:]
            np.testing.assert_allclose(compressed.transmittance_at(x, y, depths[alone]), t[alone], atol=1e-6)
            exact_t = m.transmittance_at(x, y, np.linspace(0, 1, 200))
            assert np.all(np.abs(compressed.transmittance_at(x, y, np.linspace(0, 1, 200)) - exact_t) <= 0.01 + 1e-6)  # Lokovic-Veach's bound
    with pytest.raises(ValueError, match="belongs to the exact map"):
        dom = hs.ShadowMap("dom:3")
        dom.build(small, resolution=8)
        dom.fragments(0, 0)


def test_stored_maps_and_rebuilds(small):
    m = hs.ShadowMap("osm:8")
    m.build(small, resolution=40)
    maps = m.maps()
    assert maps.shape == (40, 40, 8)
    assert np.all(np.diff(maps, axis=2) >= 0)  # optical depth through each layer's end grows
    h, size = m.maps_hash, m.memory_bytes
    m.build(small, resolution=40)
    assert m.maps_hash == h and m.memory_bytes == size
    m.build(small, "dir:1,-1,0", 40)
    assert m.maps_hash != h


def test_map_errors(small):
    with pytest.raises(ValueError, match="unknown method 'nope'"):
        hs.ShadowMap("nope:3")
    with pytest.raises(ValueError, match="bad method spec"):
        hs.ShadowMap("dom:0")
    with pytest.raises(ValueError, match="unknown backend"):
        hs.ShadowMap("dom:3", backend="vulkan")
    with pytest.raises(ValueError, match="CPU-only"):
        hs.ShadowMap("dsm", backend="gl")
    m = hs.ShadowMap("dom:3")
    with pytest.raises(ValueError, match="not built"):
        m.transmittance(small.points)
    with pytest.raises(ValueError, match="not built"):
        m.maps()
    with pytest.raises(ValueError, match="resolution 0"):
        m.build(small, resolution=0)
    with pytest.raises(ValueError, match="resolution"):
        m.build(small, resolution=1 << 20)
    with pytest.raises(ValueError, match="bad light spec"):
        m.build(small, "sun:1,2", 16)
    with pytest.raises(TypeError, match="light"):
        m.build(small, 42, 16)
    m.build(small, resolution=16)
    with pytest.raises(TypeError, match="float32"):
        m.transmittance(np.zeros((3, 3)))
    with pytest.raises(ValueError, match=r"shape \(n, 3\)"):
        m.transmittance(np.zeros((3, 4), np.float32))
    with pytest.raises(ValueError, match="depth bias"):
        m.transmittance(small.points, bias=float("nan"))
    strided = np.zeros((6, 3), np.float32)[::2]  # not contiguous: copied, still answered
    assert m.transmittance(strided).shape == (3,)
    assert m.transmittance(np.zeros((0, 3), np.float32)).shape == (0,)
