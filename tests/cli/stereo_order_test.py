"""`sharpmesh stereo` gives the same mesh, byte for byte, from the same scene
whatever order its model lists cameras, images, tracks and observations in,
and whether the model is COLMAP text or binary.

The shuffled copy renumbers image and point ids, reorders the images' blocks,
the points' lines and each track's observations; the binary copy is written
here from the text (COLMAP's documented layout), independently of the
library's own writer.
usage: stereo_order_test.py SHARPMESH WORK_DIR
"""
import pathlib
import random
import shutil
import struct
import subprocess
import sys

CLI, WORK = sys.argv[1], pathlib.Path(sys.argv[2])
CAMERA_MODELS = {"SIMPLE_PINHOLE": 0, "PINHOLE": 1}


def data_lines(path):
    return [line.split() for line in path.read_text().splitlines() if line.strip() and not line.startswith("#")]


def read_text_model(folder):
    cameras = data_lines(folder / "cameras.txt")
    lines = data_lines(folder / "images.txt")
    images = []
    for header, observations in zip(lines[0::2], lines[1::2]):
        points2d = [(float(observations[k]), float(observations[k + 1]), int(observations[k + 2])) for k in range(0, len(observations), 3)]
        images.append({"id": int(header[0]), "pose": header[1:8], "camera": int(header[8]), "name": header[9], "points2d": points2d})
    points = []
    for p in data_lines(folder / "points3D.txt"):
        track = [(int(p[k]), int(p[k + 1])) for k in range(8, len(p), 2)]
        points.append({"id": int(p[0]), "xyz": p[1:4], "rgb": p[4:7], "error": p[7], "track": track})
    return cameras, images, points


def shuffled(images, points, rng):
    image_ids = {im["id"]: new for im, new in zip(images, rng.sample(range(1, 10 * len(images)), len(images)))}
    point_ids = {p["id"]: new for p, new in zip(points, rng.sample(range(1, 10 * len(points)), len(points)))}
    point_ids[-1] = -1
    images = [dict(im, id=image_ids[im["id"]], points2d=[(x, y, point_ids[pid]) for x, y, pid in im["points2d"]]) for im in images]
    points = [dict(p, id=point_ids[p["id"]], track=rng.sample([(image_ids[i], k) for i, k in p["track"]], len(p["track"])))
              for p in points]
    rng.shuffle(images)
    rng.shuffle(points)
    return images, points


def write_text_model(folder, cameras, images, points):
    folder.mkdir(parents=True)
    (folder / "cameras.txt").write_text("".join(" ".join(c) + "\n" for c in cameras))
    with open(folder / "images.txt", "w") as out:
        for im in images:
            out.write(" ".join([str(im["id"]), *im["pose"], str(im["camera"]), im["name"]]) + "\n")
            out.write(" ".join(f"{x!r} {y!r} {pid}" for x, y, pid in im["points2d"]) + "\n")
    with open(folder / "points3D.txt", "w") as out:
        for p in points:
            track = " ".join(f"{i} {k}" for i, k in p["track"])
            out.write(" ".join([str(p["id"]), *p["xyz"], *p["rgb"], p["error"], track]) + "\n")


def write_binary_model(folder, cameras, images, points):
    folder.mkdir(parents=True)
    with open(folder / "cameras.bin", "wb") as out:
        out.write(struct.pack("<Q", len(cameras)))
        for c in cameras:
            out.write(struct.pack("<IiQQ", int(c[0]), CAMERA_MODELS[c[1]], int(c[2]), int(c[3])))
            out.write(struct.pack(f"<{len(c) - 4}d", *map(float, c[4:])))
    with open(folder / "images.bin", "wb") as out:
        out.write(struct.pack("<Q", len(images)))
        for im in images:
            out.write(struct.pack("<I7dI", im["id"], *map(float, im["pose"]), im["camera"]))
            out.write(im["name"].encode() + b"\0")
            out.write(struct.pack("<Q", len(im["points2d"])))
            for x, y, pid in im["points2d"]:
                out.write(struct.pack("<ddQ", x, y, pid & 0xFFFFFFFFFFFFFFFF))
    with open(folder / "points3D.bin", "wb") as out:
        out.write(struct.pack("<Q", len(points)))
        for p in points:
            out.write(struct.pack("<Q3d3Bd", p["id"], *map(float, p["xyz"]), *map(int, p["rgb"]), float(p["error"])))
            out.write(struct.pack("<Q", len(p["track"])))
            for i, k in p["track"]:
                out.write(struct.pack("<II", i, k))


def stereo(model, output):
    subprocess.run([CLI, "stereo", str(model), "--images", str(WORK / "scene" / "images"), "-o", str(output), "-q"], check=True)
    return output.read_bytes()


def main():
    shutil.rmtree(WORK, ignore_errors=True)
    WORK.mkdir(parents=True)
    subprocess.run([CLI, "make-scene", str(WORK / "scene"), "--views", "6", "--samples", "8000", "-q"], check=True)
    reference = stereo(WORK / "scene" / "sparse", WORK / "reference.ply")
    cameras, images, points = read_text_model(WORK / "scene" / "sparse")
    images, points = shuffled(images, points, random.Random(7))
    write_text_model(WORK / "shuffled_text", cameras, images, points)
    write_binary_model(WORK / "shuffled_binary", cameras, images, points)
    failures = [name for name in ("shuffled_text", "shuffled_binary") if stereo(WORK / name, WORK / f"{name}.ply") != reference]
    if failures:
        sys.exit(f"the mesh differs from the scene's own model's for: {', '.join(failures)}")
    print(f"same mesh ({len(reference)} bytes) from the shuffled text and binary models")


main()
