#!/usr/bin/env python3
"""Meshes side by side, coloured by their distance to the reference with one
common scale, each rendered by `sharpmesh render` (headless Chromium) and
labelled with its facet count and Hausdorff distance.

side_by_side.py SHARPMESH REFERENCE OUT.png SCALE LABEL=MESH[,FEATURES] ...
SCALE: distance at the red end of the ramp, data units (shared by all panels).
"""
import json
import pathlib
import subprocess
import sys
import tempfile

from PIL import Image, ImageDraw, ImageFont


def main():
    binary, reference, out, scale = sys.argv[1], sys.argv[2], pathlib.Path(sys.argv[3]), float(sys.argv[4])
    panels = [arg.split("=", 1) for arg in sys.argv[5:]]
    width, height, band = 640, 520, 56
    font = ImageFont.load_default()
    sheet = Image.new("RGB", (width * len(panels), height + band), "white")
    with tempfile.TemporaryDirectory() as scratch:
        for i, (label, files) in enumerate(panels):
            mesh, *features = files.split(",")
            shot, report = pathlib.Path(scratch) / f"{i}.png", pathlib.Path(scratch) / f"{i}.json"
            extra = ["--features", features[0]] if features else []
            subprocess.run([binary, "render", mesh, "--reference", reference, "--distance-scale", str(scale), "--bare",
                            "--width", str(width), "--height", str(height), "-o", str(shot), "-q", *extra], check=True)
            evaluation = pathlib.Path(scratch) / f"{i}.eval.json"
            subprocess.run([binary, "eval", mesh, "--reference", reference, "--json", str(evaluation), "-q"], check=True)
            e = json.loads(evaluation.read_text())["evaluation"]
            sheet.paste(Image.open(shot), (i * width, band))
            text = f"{label}\n{e['facets']:,} facets, Hausdorff {e['hausdorff']['U']:.2f} U"
            ImageDraw.Draw(sheet).multiline_text((i * width + 12, 8), text, fill=(29, 35, 48), font=font, spacing=6)
    ImageDraw.Draw(sheet).text((12, height + band - 18), f"colour: distance to the reference, blue 0 to red {scale:.3g} (data units)",
                               fill=(90, 98, 114), font=font)
    sheet.save(out)
    print(f"side_by_side: {len(panels)} meshes -> {out}")


if __name__ == "__main__":
    main()
