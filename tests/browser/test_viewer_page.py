"""Browser test of the viewer (issue 8): `sharpmesh view` writes a page, headless
Chromium opens it, the scene loads without a console error and the canvas is
not blank; `sharpmesh render` makes the same picture. Screenshots are kept in
$SHARPMESH_ARTIFACTS for people to look at."""
import os
import pathlib
import re
import shutil
import subprocess

import numpy as np
import pytest
from PIL import Image

CLI = os.environ.get("SHARPMESH_CLI", "")
DATA = pathlib.Path(os.environ.get("SHARPMESH_DATA", ""))
ARTIFACTS = pathlib.Path(os.environ.get("SHARPMESH_ARTIFACTS", "browser-artifacts"))
BROWSER = shutil.which("chromium") or shutil.which("chromium-browser")
FEATURE_RGB = np.array([0xE4, 0x57, 0x2E])  # web/src/viewer.js, the feature lines
BACKGROUND_RGB = np.array([0xF5, 0xF6, 0xF8])


@pytest.fixture(scope="module")
def fandisk_page(tmp_path_factory):
    if not BROWSER:
        pytest.fail("chromium is not installed (scripts/install-deps installs it)")
    folder = tmp_path_factory.mktemp("page")
    mesh = DATA / "meshes" / "fandisk.off"
    subprocess.run([CLI, "sample", str(mesh), "-n", "2000", "-o", str(folder / "points.ply"),
                    "--sharp-edges", str(folder / "edges.txt"), "-q"], check=True)
    subprocess.run([CLI, "view", str(mesh), "--features", str(folder / "edges.txt"), "--points", str(folder / "points.ply"),
                    "-o", str(folder / "fandisk.html"), "-q"], check=True)
    return folder


def run_browser(page, screenshot, size=(1000, 750)):
    """Opens the page headless; returns (the <body> tag after loading, the console log)."""
    run = subprocess.run([BROWSER, "--headless", "--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
                          "--hide-scrollbars", "--no-first-run", "--force-device-scale-factor=1",
                          f"--user-data-dir={page.parent / 'profile'}", f"--window-size={size[0]},{size[1]}",
                          "--virtual-time-budget=30000", "--enable-logging=stderr", "--v=0",
                          f"--screenshot={screenshot}", "--dump-dom", page.as_uri()],
                         capture_output=True, text=True, timeout=180)
    body = re.search(r"<body[^>]*>", run.stdout)
    assert body, f"no page came back from the browser: {run.stderr[-2000:]}"
    return body.group(0), run.stderr


def pixel_statistics(png):
    image = np.asarray(Image.open(png).convert("RGB")).astype(int)
    pixels = image.reshape(-1, 3)
    drawn = np.abs(pixels - BACKGROUND_RGB).sum(axis=1) > 30
    feature = np.abs(pixels - FEATURE_RGB).sum(axis=1) < 60
    return {"size": image.shape[1::-1], "drawn": drawn.mean(), "feature": feature.mean(),
            "colours": len(np.unique(pixels[drawn], axis=0)), "grey_std": image.mean(axis=2).std()}


def test_page_loads_without_errors_and_draws_the_mesh_and_its_lines(fandisk_page):
    ARTIFACTS.mkdir(parents=True, exist_ok=True)
    shot = ARTIFACTS / "viewer-fandisk.png"
    body, log = run_browser(fandisk_page / "fandisk.html", shot)
    assert 'data-status="ready"' in body, body
    assert 'data-errors="0"' in body, body
    console_errors = [line for line in log.splitlines() if "CONSOLE" in line and ("Error" in line or "error" in line)]
    assert not console_errors, console_errors
    stats = pixel_statistics(shot)
    assert stats["size"] == (1000, 750)
    assert 0.1 < stats["drawn"] < 0.9, stats   # the model fills part of the view
    assert stats["colours"] > 100, stats       # shading, not a flat silhouette
    assert stats["feature"] > 0.001, stats     # the feature lines are visible


def test_a_broken_page_is_reported_not_blank(fandisk_page):
    page = fandisk_page / "broken.html"
    text = (fandisk_page / "fandisk.html").read_text()
    page.write_text(text.replace('"indices":"', '"indices":"!!', 1))
    body, _ = run_browser(page, fandisk_page / "broken.png")
    assert 'data-status="ready"' not in body
    assert 'data-errors="0"' not in body


def test_render_writes_the_picture_of_the_page(fandisk_page, tmp_path):
    shot = ARTIFACTS / "render-fandisk-front.png"
    ARTIFACTS.mkdir(parents=True, exist_ok=True)
    subprocess.run([CLI, "render", str(DATA / "meshes" / "fandisk.off"), "--features", str(fandisk_page / "edges.txt"),
                    "--view", "front", "--width", "640", "--height", "480", "-o", str(shot), "-q"], check=True)
    stats = pixel_statistics(shot)
    assert stats["size"] == (640, 480)
    assert stats["drawn"] > 0.05 and stats["feature"] > 0.001, stats


def test_render_fails_cleanly_without_a_browser(fandisk_page, tmp_path):
    out = tmp_path / "shot.png"
    run = subprocess.run([CLI, "render", str(DATA / "meshes" / "cube.off"), "-o", str(out), "--browser", "/nonexistent/chromium"],
                         capture_output=True, text=True)
    assert run.returncode == 2
    assert "browser" in run.stderr.strip().splitlines()[-1]
    assert not out.exists()


def silhouette_overlap(render_png, photo_png):
    """Intersection over union of what the rendering draws and what the photo shows below its sky."""
    image = np.asarray(Image.open(render_png).convert("RGB")).astype(int)
    photo = np.asarray(Image.open(photo_png).convert("RGB").resize(image.shape[1::-1])).astype(int)
    drawn = np.abs(image - BACKGROUND_RGB).sum(axis=2) > 30
    sky = (photo[..., 2] > photo[..., 0] + 20) & (photo[..., 2] >= photo[..., 1])  # make-scene's sky is blue
    return (drawn & ~sky).sum() / (drawn | ~sky).sum()


def test_render_through_an_input_camera_sees_what_its_photo_saw(tmp_path):
    scene = tmp_path / "scene"
    subprocess.run([CLI, "make-scene", str(scene), "--views", "4", "--samples", "2000", "-q"], check=True)
    names = sorted(p.name for p in (scene / "images").iterdir())
    shot = tmp_path / "through.png"
    subprocess.run([CLI, "render", str(scene / "ground_truth.ply"), "--model", str(scene / "sparse"), "--camera", names[1],
                    "--bare", "--wireframe", "off", "--width", "640", "-o", str(shot), "-q"], check=True)
    assert Image.open(shot).size == (640, 480)  # the camera's 320 x 240 shape
    overlaps = {name: silhouette_overlap(shot, scene / "images" / name) for name in names}
    assert overlaps[names[1]] > 0.98, overlaps
    assert all(overlaps[names[1]] > overlaps[other] + 0.02 for other in names if other != names[1]), overlaps
    # With its photograph beside it, at the same height.
    pair = ARTIFACTS / "render-camera-beside-photo.png"
    ARTIFACTS.mkdir(parents=True, exist_ok=True)
    subprocess.run([CLI, "render", str(scene / "ground_truth.ply"), "--model", str(scene / "sparse"), "--camera", names[1],
                    "--photo", "--width", "640", "-o", str(pair), "-q"], check=True)
    assert Image.open(pair).size == (1280, 480)
    run = subprocess.run([CLI, "render", str(scene / "ground_truth.ply"), "--model", str(scene / "sparse"), "--camera", "nope.png",
                          "-o", str(tmp_path / "no.png")], capture_output=True, text=True)
    assert run.returncode == 2 and "nope.png" in run.stderr and not (tmp_path / "no.png").exists()
