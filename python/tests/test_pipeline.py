"""The pipeline from Python: toolbox, features, reconstruction, evaluation,
and a round trip against the command-line tool on the same input."""
import json
import re
import subprocess
import sys
import threading

import numpy as np
import pytest

import sharpmesh as sm


def test_clean_uses_the_cli_names_and_defaults(cube_cloud):
    out = sm.clean(cube_cloud.points, outliers=5, normals="jet", orient=True)
    assert len(out.points) == len(cube_cloud.points) - round(0.05 * len(cube_cloud.points))
    assert out.normals.shape == out.points.shape
    np.testing.assert_allclose(np.linalg.norm(out.normals, axis=1), 1, atol=1e-6)
    with pytest.raises(sm.InvalidArgument, match="smooth"):
        sm.clean(cube_cloud.points, smooth=3)
    # The winding-number repair has nothing to flip on a cube's consistent normals.
    plain = sm.clean(cube_cloud.points, normals="jet", orient=True, winding_repair=False)
    np.testing.assert_array_equal(plain.normals, sm.clean(cube_cloud.points, normals="jet", orient=True).normals)


def test_clean_crease_aware_normals_are_face_normals(cube_cloud):
    # The cube's faces are axis-aligned: a crease-aware normal has one coordinate near +-1.
    jet = sm.clean(cube_cloud.points, normals="jet", orient=True).normals
    shifted = sm.clean(cube_cloud.points, normals="shifted", orient=True).normals
    def off_axis(n):
        return np.mean(np.abs(n).max(axis=1) < np.cos(np.radians(10)))
    assert off_axis(shifted) < 0.01 < off_axis(jet)
    with pytest.raises(sm.InvalidArgument, match="shifted"):
        sm.clean(cube_cloud.points, normals="hough")


def test_features_of_a_cube_are_its_twelve_edges(cube, cube_cloud):
    f = sm.extract_features(cube_cloud.points)
    assert f.point_classes.shape == (len(cube_cloud.points),)
    assert set(np.unique(f.point_classes)) <= {0, 1, 2}
    assert 12 <= len(f.polylines) <= 14
    assert len(f.junctions) == 8 and min(f.junction_degrees) >= 3  # the 8 corners
    ev = sm.eval_features(f.polylines, cube)
    assert ev["recall"] > 0.9 and ev["precision"] > 0.9
    assert ev["recalled_corners"] == ev["truth_corners"] == 8


def test_corner_fitting_is_on_by_default_and_can_be_turned_off(cube_cloud):
    fitted = sm.extract_features(cube_cloud.points)
    thesis = sm.extract_features(cube_cloud.points, fit_corner_points=False)
    assert fitted.report["counts"]["fitted_corner_points"] > 0
    assert thesis.report["counts"]["fitted_corner_points"] == 0
    assert thesis.report["counts"]["corner_points"] == fitted.report["counts"]["corner_points"]
    assert thesis.report["parameters"]["fit_corner_points"] is False


def test_reconstruct_matches_the_cli_on_the_same_input(tmp_path, cli, cube_cloud):
    cloud = tmp_path / "cube.ply"
    sm.write_points(str(cloud), cube_cloud.points)
    subprocess.run([cli, "reconstruct", str(cloud), "-o", str(tmp_path / "cli.ply"), "--sharp-edges", str(tmp_path / "cli.txt"),
                    "--report", str(tmp_path / "cli.json"), "-q"], check=True)
    cli_mesh = sm.read_mesh(str(tmp_path / "cli.ply"))
    cli_edges = sm.read_polylines(str(tmp_path / "cli.txt"))

    result = sm.reconstruct(sm.read_points(str(cloud)).points)
    assert result.mesh.faces.shape == cli_mesh.faces.shape
    np.testing.assert_allclose(result.mesh.vertices, cli_mesh.vertices, atol=1e-9)
    np.testing.assert_array_equal(result.mesh.faces, cli_mesh.faces)
    assert len(result.sharp_edges) == len(cli_edges)
    assert result.report["protection"]["represented_segments"] == result.report["protection"]["protected_segments"]
    topology = sm.check_topology(result.mesh)
    assert topology["closed"] and topology["manifold"] and not topology["self_intersecting"]
    # The same report, but for what only a command line has: its file names,
    # time limit and wall-clock times.
    cli_report = json.loads((tmp_path / "cli.json").read_text())
    for key in ("command", "input", "output", "seconds"):
        del cli_report[key]
    for key in ("features_file", "time_limit_s"):
        del cli_report["parameters"][key]
    del cli_report["self_intersections"]["written_invalid"]
    assert without_timings(cli_report) == without_timings(result.report)


def without_timings(report):
    if isinstance(report, dict):
        # Timings and the process's peak memory measure the run, not its result.
        return {k: without_timings(v) for k, v in report.items() if k not in ("stages", "peak_memory_mib")}
    return report


def test_a_facet_budget_keeps_the_cube_and_its_edges(cube, cube_cloud):
    fine = sm.reconstruct(cube_cloud.points, delta=3.5)
    light = sm.reconstruct(cube_cloud.points, delta=3.5, facets=300)
    assert len(light.mesh.faces) <= 300 < len(fine.mesh.faces)
    assert light.report["decimation"]["output_facets"] == len(light.mesh.faces)
    e, f = sm.evaluate(light.mesh, cube), sm.evaluate(fine.mesh, cube)
    t = e["topology"]
    assert t["closed"] and t["manifold"] and not t["self_intersecting"]
    assert e["sharp_max"] < 2 * f["sharp_max"] and e["hausdorff"] < 2 * f["hausdorff"]
    # The same collapse on its own, from the mesh and its feature edges.
    mesh, report = sm.decimate(fine.mesh, curves=fine.sharp_edges, facets=300)
    assert len(mesh.faces) == report["output_facets"] <= 300 and not report["budget_missed"]
    options = sm.DecimationOptions(facets=300, sharp_angle=0)
    assert sm.decimate(fine.mesh, options=options)[1]["sharp_edges"] == 0  # no curves given, none detected
    with pytest.raises(sm.InvalidArgument, match="budget or a tolerance"):
        sm.decimate(fine.mesh)


def test_every_option_is_a_flag_and_a_keyword(cli):
    help_text = subprocess.run([cli, "reconstruct", "--help"], check=True, capture_output=True, text=True).stdout
    flags = set(re.findall(r"^\s+(?:-[a-z],)?(--[a-z0-9-]+)", help_text, re.M))
    expected = set()
    for name, default in sm.ReconstructOptions().to_dict().items():
        flag = name.replace("_", "-")
        expected.add(f"--no-{flag}" if default is True else f"--{flag}")
        assert getattr(sm.ReconstructOptions(**{name: default}), name) == default
    own = {"--help", "--output", "--no-features", "--features", "--sharp-edges", "--time-limit", "--allow-invalid", "--ascii",
           "--threads", "--quiet", "--report", "--classes",
           # Slabs (sharpmesh/tiled.h): the command's own until Python has reconstruct_tiled.
           "--tiles", "--tile-margin", "--seam-snap", "--seam-merge", "--seam-tolerance"}
    assert flags == expected | own, (flags - expected - own, expected - flags)
    features_help = subprocess.run([cli, "features", "--help"], check=True, capture_output=True, text=True).stdout
    for name in sm.FeatureOptions().to_dict():
        assert name.replace("_", "-") in features_help, name


def test_options_objects_and_keywords_agree(cube_cloud):
    options = sm.ReconstructOptions(delta=6, snapping=False)
    assert repr(options) == "ReconstructOptions(delta=6.0, snapping=False)"
    by_object = sm.reconstruct(cube_cloud.points, options=options, no_features=True)
    by_keywords = sm.reconstruct(cube_cloud.points, delta=6, no_snapping=True, no_features=True)
    np.testing.assert_array_equal(by_object.mesh.faces, by_keywords.mesh.faces)
    assert by_object.report["parameters"] == by_keywords.report["parameters"]
    assert by_object.report["parameters"]["delta"] == 6 and by_object.report["parameters"]["snapping"] is False
    with pytest.raises(sm.InvalidArgument, match="unknown option 'delt'"):
        sm.reconstruct(cube_cloud.points, delt=6)
    with pytest.raises(sm.InvalidArgument, match="spacing_k"):
        sm.ReconstructOptions(spacing_k=2.5)


def test_reconstruct_normals_points_a_cube_outwards_and_reports_the_stage(cube_cloud):
    out = sm.reconstruct_normals(cube_cloud.points, threads=1)
    assert isinstance(out, sm.OrientedNormals)
    points, normals = out.cloud.points, out.cloud.normals
    assert points.shape == normals.shape == cube_cloud.points.shape
    np.testing.assert_allclose(np.linalg.norm(normals, axis=1), 1, atol=1e-6)
    # Outwards from the cube's centre, except at a few edge points.
    outward = np.einsum("ij,ij->i", normals, points - points.mean(axis=0)) > 0
    assert outward.mean() > 0.995
    assert out.report["counts"]["normal_source"] == "cvcm"
    assert out.report["parameters"]["threads"] == 1
    assert out.report["features"]["counts"]["polylines"] >= 12
    jet = sm.reconstruct_normals(cube_cloud.points, no_features=True)
    assert jet.report["counts"]["normal_source"] == "jet" and "features" not in jet.report


def test_reconstruction_is_accurate_and_keeps_the_edges(cube, cube_cloud):
    result = sm.reconstruct(cube_cloud.points, delta=3.5)
    e = sm.evaluate(result.mesh, cube)
    assert e["hausdorff"] < 0.01 * e["diagonal"]
    assert e["sharp_max"] < 0.005 * e["diagonal"]
    fit = result.report["data_fit"]  # every input point on the mesh: no retry
    assert fit["points_off_mesh"] == 0 and fit["points_off_first_mesh"] == 0
    assert 0 < fit["max_distance"]["value"] < result.report["derived"]["average_spacing"]["value"]
    assert 0 < fit["max_distance"]["value"] < fit["off_distance"]["value"]
    baseline = sm.reconstruct(cube_cloud.points, delta=3.5, no_features=True)
    assert baseline.features is None and "protection" not in baseline.report
    assert result.report["counts"]["enclosed_flipped_normals"] == 0  # a consistent cube: nothing to flip
    assert sm.evaluate(baseline.mesh, cube)["sharp_max"] > e["sharp_max"]


def test_given_features_are_protected(cube, cube_cloud):
    edges = sm.sharp_edges(cube)
    result = sm.reconstruct(cube_cloud.points, features=edges)
    assert result.features is None
    assert result.report["protection"]["polylines"] == len(edges)
    with pytest.raises(sm.InvalidArgument):
        sm.reconstruct(cube_cloud.points, features=edges, no_features=True)


def test_progress_is_reported_and_can_cancel(cube_cloud):
    seen = []
    sm.extract_features(cube_cloud.points, progress=lambda stage, fraction: seen.append((stage, fraction)))
    assert seen and all(0 <= f <= 1 for _, f in seen)
    with pytest.raises(sm.Cancelled):
        sm.reconstruct(cube_cloud.points, progress=lambda stage, fraction: False)


def test_an_exception_in_the_callback_reaches_the_caller(cube_cloud):
    def explode(stage, fraction):
        raise KeyError("from the callback")
    with pytest.raises(KeyError, match="from the callback"):
        sm.extract_features(cube_cloud.points, progress=explode)


def test_the_gil_is_released_while_computing(cube_cloud):
    # With a switch interval longer than any run, Python never takes the GIL
    # away from a thread: the main thread runs again while the worker is busy
    # only if the compiled call gives the GIL up itself.
    finished = False

    def compute():
        nonlocal finished
        sm.extract_features(cube_cloud.points)  # no callback
        finished = True

    interval = sys.getswitchinterval()
    sys.setswitchinterval(1000.0)
    try:
        worker = threading.Thread(target=compute)
        worker.start()
        ran_during_the_call = not finished
        worker.join()
    finally:
        sys.setswitchinterval(interval)
    assert finished and ran_during_the_call


def test_bad_parameters_raise_with_the_cli_message(cube_cloud):
    with pytest.raises(sm.InvalidArgument):
        sm.reconstruct(cube_cloud.points, delta=-1)
    with pytest.raises(sm.InvalidArgument):
        sm.extract_features(cube_cloud.points, t1=0)
    with pytest.raises(sm.InvalidInput):
        sm.reconstruct(np.full((100, 3), np.nan))


def test_stereo_on_a_generated_scene(tmp_path, cli):
    scene = tmp_path / "scene"
    subprocess.run([cli, "make-scene", str(scene), "--views", "8", "--width", "320", "--height", "240", "--seed", "1", "-q"],
                   check=True)
    mesh, tracks, report = sm.stereo(str(scene))
    assert report["counts"]["views"] == 8
    assert len(tracks) > 100 and len(mesh.faces) > 200
    truth = sm.read_mesh(str(scene / "ground_truth.ply"))
    scene_size = 2 * report["derived"]["half_diagonal"]
    assert np.median(sm.distances_to_mesh(mesh.vertices, truth)) < 0.01 * scene_size
    assert report["counts"]["fill"]["added"] > 0
    subprocess.run([cli, "stereo", str(scene), "-o", str(tmp_path / "cli.ply"), "--report", str(tmp_path / "cli.json"), "-q"],
                   check=True)
    cli_report = json.loads((tmp_path / "cli.json").read_text())
    for key in ("command", "model", "images", "tracks_input", "output", "seconds"):
        del cli_report[key]
    assert without_timings(cli_report) == without_timings(report)
    _, _, thesis = sm.stereo(str(scene), no_fill=True, outlier_relative=False)
    assert thesis["counts"]["fill"]["added"] == 0 and "soup fill" in [s["name"] for s in thesis["stages"]]
    assert thesis["counts"]["tracks"]["kept"] != report["counts"]["tracks"]["kept"]  # the thesis's global 3-sigma rule
    # Fused depth-map points skip the cone-angle test unless asked.
    fused_path = str(scene / "dense" / "fused.ply")
    _, kept, fused = sm.stereo(str(scene), tracks=fused_path, no_fill=True)
    _, kept_coned, coned = sm.stereo(str(scene), tracks=fused_path, options=sm.StereoOptions(fill=False, cone_angle_on_fused=True))
    assert fused["counts"]["tracks"]["cone_filter_skipped_fused"] and not coned["counts"]["tracks"]["cone_filter_skipped_fused"]
    assert len(kept) > len(kept_coned)
    with pytest.raises(sm.InvalidInput):
        sm.stereo(str(tmp_path / "nowhere"))
