"""Reading and writing: round trips, shapes, dtypes, errors with the CLI's messages."""
import pathlib

import numpy as np
import pytest

import sharpmesh as sm


def test_point_round_trip_keeps_points_and_normals(tmp_path, cube_cloud):
    normals = np.tile([0.0, 0.0, 1.0], (len(cube_cloud.points), 1))
    for name in ("c.ply", "c.xyz"):
        sm.write_points(str(tmp_path / name), cube_cloud.points, normals)
        back = sm.read_points(str(tmp_path / name))
        assert back.points.shape == cube_cloud.points.shape and back.points.dtype == np.float64
        np.testing.assert_allclose(back.points, cube_cloud.points, atol=1e-6)
        np.testing.assert_allclose(back.normals, normals, atol=1e-6)
    assert not list(tmp_path.glob("*.tmp.*"))


def test_mesh_round_trip_in_every_format(tmp_path, cube):
    for name in ("m.ply", "m.off", "m.obj"):
        sm.write_mesh(str(tmp_path / name), *cube)
        back = sm.read_mesh(str(tmp_path / name))
        assert back.faces.shape == (12, 3) and back.faces.dtype == np.uint32
        np.testing.assert_allclose(back.vertices, cube.vertices)
        np.testing.assert_array_equal(back.faces, cube.faces)


def test_polylines_round_trip(tmp_path):
    lines = [np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0]], float), np.array([[0, 0, 1], [0, 0, 2]], float)]
    sm.write_polylines(str(tmp_path / "p.txt"), lines)
    back = sm.read_polylines(str(tmp_path / "p.txt"))
    assert len(back) == 2
    for a, b in zip(lines, back):
        np.testing.assert_allclose(a, b)


def test_missing_file_is_invalid_input_naming_the_file(tmp_path):
    missing = str(tmp_path / "nowhere.ply")
    with pytest.raises(sm.InvalidInput, match="nowhere.ply"):
        sm.read_points(missing)
    with pytest.raises(ValueError):  # InvalidInput is also a ValueError
        sm.read_mesh(missing)


def test_malformed_file_gives_the_readers_message(tmp_path, cli):
    import subprocess
    bad = tmp_path / "bad.xyz"
    bad.write_text("0 0 0\n1 1 nan\n")
    with pytest.raises(sm.InvalidInput) as caught:
        sm.read_points(str(bad))
    run = subprocess.run([cli, "info", str(bad)], capture_output=True, text=True)
    assert run.returncode == 1
    assert str(caught.value) in run.stderr  # the same message as the command-line tool


def test_wrong_shapes_and_indices_are_value_errors(tmp_path, cube):
    with pytest.raises(ValueError, match=r"\(n, 3\)"):
        sm.average_spacing(np.zeros((10, 2)))
    with pytest.raises(ValueError, match="refers to vertex 8"):
        sm.write_mesh(str(tmp_path / "m.ply"), cube.vertices, np.array([[0, 1, 8]]))
    assert not (tmp_path / "m.ply").exists()


def test_unwritable_destination_leaves_nothing(tmp_path, cube):
    with pytest.raises(sm.Error):
        sm.write_mesh(str(tmp_path / "no" / "such" / "m.ply"), *cube)


LIDAR = pathlib.Path(__file__).resolve().parents[2].parent / "shared" / "data" / "lidar"


@pytest.mark.skipif(not (LIDAR / "ahn3_cropped_2.laz").exists(), reason="no shared LiDAR data")
def test_laz_reads_with_and_without_a_class_filter(tmp_path):
    tile = str(LIDAR / "ahn3_cropped_2.laz")
    everything = sm.read_points(tile)
    ground = sm.read_points(tile, classes=[2])
    ground_and_buildings = sm.read_points(tile, classes=[2, 6])
    assert len(everything.points) == 208432  # the header's count (the tile's README)
    assert 0 < len(ground.points) < len(ground_and_buildings.points) < len(everything.points)
    assert np.isfinite(everything.points).all()
    np.savetxt(tmp_path / "c.xyz", everything.points[:10])
    with pytest.raises(ValueError):
        sm.read_points(str(tmp_path / "c.xyz"), classes=[2])
