#!/usr/bin/python3
"""Writes docs/city.md and its pictures from bench/city/run's results.

    report.py RESULTS_DIR OUT.md COMMAND
"""
import json
import os
import struct
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from evaluate import read_polylines, resample  # noqa: E402


def median(values):
    values = sorted(v for v in values if v is not None)
    return values[len(values) // 2] if values else float("nan")


def share_at_least(values, bar):
    values = [v for v in values if v is not None]
    return sum(v >= bar for v in values), len(values)


def read_las_xyz(path, stride=1):
    """Points of an uncompressed LAS file (the generated tiles)."""
    raw = open(path, "rb").read()
    start = struct.unpack_from("<I", raw, 96)[0]
    length = struct.unpack_from("<H", raw, 105)[0]
    scale = np.array(struct.unpack_from("<3d", raw, 131))
    offset = np.array(struct.unpack_from("<3d", raw, 155))
    count = (len(raw) - start) // length
    records = np.frombuffer(raw, dtype=np.dtype([("xyz", "<i4", 3), ("rest", "V%d" % (length - 12))]), count=count, offset=start)
    return records["xyz"][::stride] * scale + offset


def tile_picture(results_dir, tile, png):
    """Top view of one tile: its points by height, the true ridges and eaves
    found (blue) and missed (orange), the polylines on a true edge (green)
    and off every one (red)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from scipy.spatial import cKDTree
    truth = np.load(os.path.join(results_dir, "tiles", tile + ".npz"))
    points = read_las_xyz(os.path.join(results_dir, "tiles", tile + ".las"))
    found = resample(read_polylines(os.path.join(results_dir, "work-defaults", tile + ".polylines.txt")), 0.1)
    edges, kind = truth["edges"], truth["edges_kind"]
    origin = points.min(axis=0)
    fig, axes = plt.subplots(1, 2, figsize=(16, 8))
    axes[0].scatter(points[:, 0] - origin[0], points[:, 1] - origin[1], c=points[:, 2], s=0.1, cmap="viridis")
    axes[0].set_title("%s: the points by height" % tile)
    near_truth = cKDTree(edges).query(found)[0] <= 0.5 if len(found) else np.zeros(0, bool)
    near_found = cKDTree(found).query(edges)[0] <= 0.5 if len(found) else np.zeros(len(edges), bool)
    ax = axes[1]
    ax.scatter(edges[kind == 0, 0] - origin[0], edges[kind == 0, 1] - origin[1], s=0.2, c="lightgray")
    for mask, colour in (((kind > 0) & near_found, "tab:blue"), ((kind > 0) & ~near_found, "tab:orange")):
        ax.scatter(edges[mask, 0] - origin[0], edges[mask, 1] - origin[1], s=2, c=colour)
    for mask, colour in ((near_truth, "tab:green"), (~near_truth, "tab:red")):
        ax.scatter(found[mask, 0] - origin[0], found[mask, 1] - origin[1], s=0.5, c=colour)
    ax.set_title("ridges and eaves found (blue) and missed (orange); polylines on an edge (green), off (red)")
    for a in axes:
        a.set_aspect("equal")
        a.set_xlabel("m")
    fig.tight_layout()
    fig.savefig(png, dpi=50)
    plt.close(fig)


def delft_picture(results_dir, png):
    """Top view of the first Delft tile's polylines (ground and buildings)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    path = os.path.join(results_dir, "ahn3_cropped_1.classes.polylines.txt")
    if not os.path.exists(path):
        return False
    lines = read_polylines(path)
    fig, ax = plt.subplots(figsize=(10, 10))
    for line in lines:
        ax.plot(line[:, 0], line[:, 1], lw=0.8, c="k")
    ax.set_aspect("equal")
    ax.set_title("Delft (AHN3 tile 1, classes 2 and 6): feature polylines seen from above")
    ax.set_xlabel("RD x [m]")
    ax.set_ylabel("RD y [m]")
    fig.tight_layout()
    fig.savefig(png, dpi=70)
    plt.close(fig)
    return True


def main():
    results_dir, out_md, command = sys.argv[1:4]
    docs = os.path.dirname(os.path.abspath(out_md))
    runs = {}
    for name in ("defaults", "classes", "no-walls"):
        path = os.path.join(results_dir, name + ".json")
        if os.path.exists(path):
            runs[name] = json.load(open(path))
    lines = ["# Cities from above: roof ridges and eaves as polylines", "",
             "Made by `%s` (bench/city: generate.py, airborne.py, evaluate.py). Thirty districts of 100 m x 100 m, "
             "each from its own seed: terraced gabled and hipped houses whose neighbours differ in height, flat-roofed "
             "blocks with parapets, chimneys, dormers, trees, raised pavements, on gently sloping ground; scanned from "
             "two flight lines 300 m up in a random heading at 4-20 points per square metre with 2-5 cm of range noise, "
             "trees returning up to three echoes, walls hit only by the scan angle. The LAS files carry ASPRS classes "
             "(2 ground, 5 vegetation, 6 building). `features` runs with its defaults on each tile; recall is the share "
             "of the visible true ridges and eaves (not those under a crown) within 0.5 m of a polyline, precision the "
             "share of polyline length within 0.5 m of any true sharp edge (ridges, eaves, hips, rakes, wall corners, "
             "wall feet, parapets, chimneys, dormers, kerbs). Eaves are counted for houses and for flat roofs (the "
             "parapet's outer top rim) apart." % command, "",
             "## Summary", "",
             "| run | recall | ridges | house eaves | flat-roof eaves | precision | tiles with recall >= 0.8 | seconds per tile |",
             "|---|---|---|---|---|---|---|---|"]
    labels = {"defaults": "defaults (walls automatic, every class)", "classes": "`--classes 2,6` (no trees)",
              "no-walls": "`--walls off` (the thesis's features alone)"}
    for name, results in runs.items():
        hit, total = share_at_least([r["recall"] for r in results], 0.8)
        lines.append("| %s | %.2f | %.2f | %.2f | %.2f | %.2f | %d of %d | %.1f |" % (
            labels[name], median(r["recall"] for r in results), median(r["ridge_recall"] for r in results),
            median(r["house_eave_recall"] for r in results), median(r["parapet_recall"] for r in results),
            median(r["precision"] for r in results), hit, total, median(r["seconds_features"] for r in results)))
    lines += ["", "Medians over the tiles. The walls (`--walls`, on by default for clouds one layer thick and wider than "
              "high) give an eave its second face: where a roof ends over a drop, a column of points is added half a "
              "spacing beyond its last point, from the ground up.", ""]
    if "defaults" in runs:
        tile_picture(results_dir, runs["defaults"][0]["tile"], os.path.join(docs, "city.png"))
        lines += ["![a tile from above](city.png)", "", "## Every tile (defaults)", "",
                  "| tile | points per m² | noise (m) | spacing (m) | R (m) | polylines | recall | ridges | house eaves | flat-roof eaves | precision |",
                  "|---|---|---|---|---|---|---|---|---|---|---|"]

        def cell(v):
            return "-" if v is None else "%.2f" % v
        for r in runs["defaults"]:
            lines.append("| %s | %.1f | %.3f | %.2f | %.1f | %d | %.2f | %s | %s | %s | %.2f |" % (
                r["tile"], r["density_per_m2"], r["noise_m"], r["spacing_m"], r["R_m"], r["polylines"], r["recall"],
                cell(r["ridge_recall"]), cell(r["house_eave_recall"]), cell(r["parapet_recall"]), r["precision"]))
    mesh_path = os.path.join(results_dir, "mesh.json")
    if os.path.exists(mesh_path):
        meshes = json.load(open(mesh_path))
        lines += ["", "## Meshes", "",
                  "`reconstruct --classes 2,6` with its defaults, measured against the district's true outer surface "
                  "(sampled 0.1 m apart): from the mesh to the buildings (mesh samples whose nearest true point is a "
                  "building's) and from the roofs to the mesh, 99th percentile and maximum, in metres.", "",
                  "| tile | facets | seconds | peak MiB | mesh to buildings p99 / max | roofs to mesh p99 / max |",
                  "|---|---|---|---|---|---|"]
        for r in meshes:
            if r.get("reconstruct_status", 1) != 0:
                lines.append("| %s | failed (exit %s) | | | | |" % (r["tile"], r.get("reconstruct_status")))
                continue
            lines.append("| %s | %d | %.0f | %.0f | %.2f / %.2f | %.2f / %.2f |" % (
                r["tile"], r["facets"], r["seconds_reconstruct"], r["peak_memory_mib"] or 0, r["mesh_to_buildings_p99_m"],
                r["mesh_to_buildings_max_m"], r["roofs_to_mesh_p99_m"], r["roofs_to_mesh_max_m"]))
    delft = []
    for tile in ("ahn3_cropped_1", "ahn3_cropped_2"):
        for variant, label in (("", "every class"), (".classes", "classes 2, 6")):
            path = os.path.join(results_dir, tile + variant + ".features.json")
            if os.path.exists(path):
                r = json.load(open(path))
                d = r["derived"]
                delft.append("| %s | %s | %d | %d | %.2f | %.1f | %.3f | %d | %.0f | %.0f |" % (
                    tile, label, r["counts"]["points"], r["walls"]["added_points"], d["average_spacing"]["value"], d["R"]["value"],
                    d["noise_estimate"]["value"], r["counts"]["polylines"], r["seconds"], r["peak_memory_mib"]))
    if delft:
        lines += ["", "## Delft (AHN3, real)", "",
                  "`features` on the two AHN3 tiles as they come (LAZ, classes 1 unclassified with the trees, 2 ground, 6 "
                  "building, 9 water, 26 civil structure) and with `--classes 2,6`. No true edges ship with them: the "
                  "picture is the check.", "",
                  "| tile | classes | points (walls included) | wall points added | spacing (m) | R (m) | noise (m) | polylines | seconds | peak MiB |",
                  "|---|---|---|---|---|---|---|---|---|---|"]
        lines += delft
        if delft_picture(results_dir, os.path.join(docs, "city_delft.png")):
            lines += ["", "![Delft polylines](city_delft.png)"]
    with open(out_md, "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
