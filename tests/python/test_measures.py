"""compare, render, bench and the temporal error from Python: the command's numbers, as arrays and dicts."""
import csv

import numpy as np
import pytest

import hairshadow as hs
from conftest import SMALL, run_cli


def test_compare_gives_the_commands_errors(tmp_path, small):
    methods = ["osm:16", "dom:3", "occ:32:1"]
    run_cli("compare", SMALL, "--res", 96, "--methods", ",".join(methods), "--out", tmp_path)
    with open(tmp_path / "compare.csv") as f:
        printed = list(csv.DictReader(f))
    rows = hs.compare(small, methods, "dir:0,-1,-1", 96)
    assert [r["method"] for r in rows] == methods and len(printed) == len(rows)
    for row, line in zip(rows, printed):
        assert row["layers"] == int(line["layers"]) and row["memory_bytes"] == int(line["memory_bytes"])
        for key in ("mean_error", "p95_error", "max_error", "curve_error", "image_error", "image_p99"):
            decimals = len(line[key].partition(".")[2])
            assert abs(row[key] - float(line[key])) <= 0.5 * 10**-decimals + 1e-12, key  # as the command rounds it
    by_path = hs.compare(SMALL, ["dom:3"], resolution=96)
    assert by_path[0]["mean_error"] == rows[1]["mean_error"]


def test_render_is_the_commands_png(tmp_path, small):
    matplotlib_image = pytest.importorskip("matplotlib.image")
    run_cli("render", SMALL, "--method", "dom:3", "--res", 128, "--size", 96, "--out", tmp_path / "r.png")
    png = np.round(matplotlib_image.imread(tmp_path / "r.png")[:, :, :3] * 255).astype(np.uint8)
    picture = hs.render(SMALL, "dom:3", resolution=128, size=96, srgb=True)
    assert picture.shape == (96, 96, 3) and picture.dtype == np.uint8
    np.testing.assert_array_equal(picture, png)
    linear = hs.render(small, "dom:3", resolution=128, size=96)
    assert linear.dtype == np.float32 and linear.shape == (96, 96, 3)
    with pytest.raises(ValueError, match="transparency"):
        hs.render(small, "dom:3", transparency="glass")
    with pytest.raises(FileNotFoundError):
        hs.render(small, "dom:3", mesh="/nonexistent/head.obj")


def test_bench_rows_hash_the_same_maps(small):
    rows = hs.bench(small, ["dom:3", "fom:7"], resolution=64, repeat=3)
    for row in rows:
        m = hs.ShadowMap(row["method"])
        m.build(small, resolution=64)
        assert row["maps_hash"] == m.maps_hash
        assert row["min_ms"] <= row["median_ms"] <= row["max_ms"] and row["fragments"] > 0
    with pytest.raises(ValueError, match="repeat"):
        hs.bench(small, ["dom:3"], repeat=0)


def test_temporal_error_by_hand():
    t = hs.TemporalError()
    exact = np.array([1.0, 0.5], np.float32)
    t.add_frame(np.array([0.9, 0.5], np.float32), exact)  # e = (-0.1, 0)
    t.add_frame(np.array([1.0, 0.7], np.float32), exact)  # e = (0, 0.2)
    assert t.frames == 2
    assert t.mean_error == pytest.approx(0.3 / 4, rel=1e-6)
    assert t.flicker == pytest.approx((0.1 + 0.2) * 2 / 4, rel=1e-6)  # both pairs of the loop
    with pytest.raises(ValueError, match="another number of points"):
        t.add_frame(np.zeros(3, np.float32), np.zeros(3, np.float32))


def test_flicker_of_swaying_hair(small):
    sway = hs.Sway(small, amplitude_degrees=20, period=1.0, seed=3)
    a, b = sway.pose(0.25), sway.pose(0.25)
    np.testing.assert_array_equal(a.points, b.points)  # the same for a seed
    assert not np.array_equal(a.points, small.points)
    method, exact = hs.ShadowMap("osm:4"), hs.ShadowMap("dsm")
    error = hs.TemporalError()
    for frame in range(4):
        posed = sway.pose(frame / 4)
        light = hs.orbit_light("dir:0.6,-1,0.6", frame / 4, 1.0)
        method.build(posed, light, 48)
        exact.build(posed, light, 48)
        error.add_frame(method.transmittance(posed.points), exact.transmittance(posed.points))
    assert error.frames == 4 and error.flicker > 0 and error.mean_error > 0
    turned = hs.orbit_light(hs.Light.directional((1, -1, 0)), 0.25, 1.0)
    np.testing.assert_allclose(turned.direction, (0, -1, -1), atol=1e-6)
    with pytest.raises(ValueError, match="amplitude"):
        hs.Sway(small, amplitude_degrees=120)


def test_lights_read_back_to_the_same_floats():
    for spec in ("dir:0.1,-1,0.3", "point:1e-3,2.5,-7", "spot:0,3,0:0.2,-1,0:37.5"):
        light, again = hs.Light(spec), hs.Light(hs.Light(spec).spec)
        assert (again.type, again.direction, again.position, again.half_angle_degrees) == (
            light.type, light.direction, light.position, light.half_angle_degrees)
    spot = hs.Light.spot((0, 3, 0), (0, -1, 0), 30)
    assert spot.type == "spot" and spot.half_angle_degrees == 30
    with pytest.raises(ValueError, match="bad light spec"):
        hs.Light.directional((0, 0, 0))
    assert hs.Light.directional(np.array([0.0, -1.0, 0.0])).direction == (0, -1, 0)  # a small vector: any real dtype
    with pytest.raises(TypeError, match="float32"):
        hs.Light.directional(np.array(["a", "b", "c"]))
