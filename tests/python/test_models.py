"""Models in and out of Python: loaded, procedural, from numpy arrays, and their arrays as views."""
import gc
import threading

import numpy as np
import pytest

import hairshadow as hs
from conftest import RATBOY, SINTEL, run_cli


def test_loaded_model_matches_the_command(sintel):
    info = dict(line.split(":", 1) for line in run_cli("info", SINTEL).splitlines() if ":" in line)
    assert int(info["strands"]) == sintel.strand_count == 11400
    assert int(info["points"]) == sintel.point_count and int(info["segments"]) == sintel.segment_count
    assert sintel.points.shape == (sintel.point_count, 3) and sintel.points.dtype == np.float32
    assert sintel.strand_offsets[0] == 0 and sintel.strand_offsets[-1] == sintel.point_count


def test_arrays_are_views_of_the_model_not_copies(sintel):
    a, b = sintel.points, sintel.points
    assert np.shares_memory(a, b)  # the same memory twice: the model's own
    assert not a.flags.writeable
    with pytest.raises(ValueError):
        a[0, 0] = 1.0
    assert np.shares_memory(sintel.strand_offsets, sintel.strand_offsets)


def test_model_from_arrays_round_trip(tmp_path):
    rng = np.random.default_rng(3)
    points = rng.random((30, 3), dtype=np.float32)
    lengths = np.array([10, 12, 8])
    thickness = np.full(30, 0.01, np.float32)
    colors = rng.random((30, 3), dtype=np.float32)
    m = hs.Model(points, strand_lengths=lengths, thickness=thickness, colors=colors)
    assert m.strand_count == 3 and m.point_count == 30 and m.segment_count == 27
    np.testing.assert_array_equal(m.points, points)
    np.testing.assert_array_equal(m.strand_offsets, [0, 10, 22, 30])
    np.testing.assert_array_equal(m.colors, colors)
    assert m.transparency is None
    points[0, 0] = 99.0  # the model copied its input
    assert m.points[0, 0] != 99.0
    same = hs.Model(m.points, strand_offsets=m.strand_offsets, thickness=m.thickness, colors=m.colors)
    np.testing.assert_array_equal(same.points, m.points)
    path = tmp_path / "m.hair"
    hs.save(m, str(path))
    back = hs.load(str(path))
    np.testing.assert_array_equal(back.points, m.points)
    np.testing.assert_array_equal(back.strand_offsets, m.strand_offsets)


def test_points_can_be_moved_and_are_checked(small):
    m = small.copy()
    moved = m.points + np.float32(0.5)
    m.points = moved
    np.testing.assert_array_equal(m.points, moved)
    bad = moved.copy()
    bad[5, 1] = np.nan
    with pytest.raises(ValueError, match="non-finite"):
        m.points = bad
    np.testing.assert_array_equal(m.points, moved)  # the model kept its points
    with pytest.raises(ValueError, match=r"shape \(%d, 3\)" % m.point_count):
        m.points = moved[:-1]
    with pytest.raises(ValueError, match="outside"):
        m.transparency = np.full(m.point_count, 2.0, np.float32)
    assert m.transparency is None


def test_procedural_is_deterministic_and_takes_the_short_form():
    a = hs.procedural("procedural:wavy:strands=50:seed=4")
    b = hs.procedural("wavy:strands=50:seed=4")
    np.testing.assert_array_equal(a.points, b.points)
    with pytest.raises(ValueError, match="bad model spec"):
        hs.procedural("wavy:strands=-3")


def test_every_format_the_library_reads(tmp_path, small):
    ratboy = hs.load(str(RATBOY))
    assert ratboy.strand_count > 0
    for ext in (".hair", ".data", ".tfx"):
        path = tmp_path / f"m{ext}"
        hs.save(small, str(path))
        assert hs.load(str(path)).point_count == small.point_count


def test_wrong_arrays_name_what_was_expected():
    with pytest.raises(TypeError, match="float32"):
        hs.Model(np.zeros((4, 3)), strand_lengths=[4])
    with pytest.raises(ValueError, match=r"shape \(n, 3\)"):
        hs.Model(np.zeros((4, 2), np.float32), strand_lengths=[4])
    with pytest.raises(ValueError, match="one of the two"):
        hs.Model(np.zeros((4, 3), np.float32))
    with pytest.raises(ValueError, match="one of the two"):
        hs.Model(np.zeros((4, 3), np.float32), strand_lengths=[4], strand_offsets=[0, 4])
    with pytest.raises(ValueError, match="more than"):
        hs.Model(np.zeros((4, 3), np.float32), strand_lengths=[3, 3])
    with pytest.raises(ValueError, match="negative"):
        hs.Model(np.zeros((4, 3), np.float32), strand_lengths=[-1, 5])
    with pytest.raises(TypeError, match="integer"):
        hs.Model(np.zeros((4, 3), np.float32), strand_lengths=[1.5, 2.5])
    with pytest.raises(ValueError, match="no segment"):
        hs.Model(np.zeros((4, 3), np.float32), strand_lengths=[4])
    with pytest.raises(TypeError, match="float32"):
        hs.Model("points", strand_lengths=[4])


def test_file_errors_are_os_errors(tmp_path):
    with pytest.raises(FileNotFoundError, match="no such file") as missing:
        hs.load(str(tmp_path / "missing.hair"))
    assert missing.value.filename == str(tmp_path / "missing.hair")
    garbage = tmp_path / "garbage.hair"
    garbage.write_bytes(b"HAIR" + b"\xff" * 40)
    with pytest.raises(OSError) as caught:
        hs.load(str(garbage))
    assert not isinstance(caught.value, FileNotFoundError)
    unknown = tmp_path / "model.xyz"
    unknown.write_text("1 2 3\n")
    with pytest.raises(OSError, match="unknown model format") as caught:
        hs.load(str(unknown))
    assert not isinstance(caught.value, FileNotFoundError) and str(unknown) in str(caught.value)


def test_views_follow_assignments_and_outlive_the_model():
    m = hs.procedural("straight:strands=20:seed=2")
    points, offsets = m.points, m.strand_offsets
    moved = points + np.float32(1.0)
    m.points = moved
    np.testing.assert_array_equal(points, moved)  # the same memory, new values
    m.thickness = np.full(m.point_count, 0.02, np.float32)
    thickness = m.thickness
    m.thickness = np.full(m.point_count, 0.03, np.float32)
    assert thickness[0] == np.float32(0.03)
    with pytest.raises(ValueError, match="cannot be removed"):
        m.thickness = None
    with pytest.raises(TypeError, match="float32"):
        m.thickness = np.full(m.point_count, 0.05)  # float64: refused, the model kept its thickness
    assert m.thickness[0] == np.float32(0.03)
    with pytest.raises(ValueError, match="negative"):
        m.thickness = np.full(m.point_count, -1.0, np.float32)
    assert m.thickness[0] == np.float32(0.03)
    del m
    gc.collect()
    assert points.sum() == moved.sum() and offsets[-1] == len(points)  # the views keep the model


def test_a_model_is_not_changed_while_a_build_reads_it(sintel):
    model = sintel.copy()
    m = hs.ShadowMap("dom:3")
    done = threading.Event()

    def build():
        for _ in range(4):
            m.build(model, resolution=2048, threads=1)
        done.set()

    worker = threading.Thread(target=build)
    worker.start()
    refused = 0
    while not done.is_set():
        try:
            model.points = model.points  # the same values: harmless where it lands
        except ValueError as e:
            assert "being read" in str(e)
            refused += 1
    worker.join()
    assert refused > 0
