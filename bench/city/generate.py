#!/usr/bin/python3
"""Generates city tiles scanned by a simulated airborne scanner (issue 44).

    generate.py OUT_DIR [--tiles N] [--size METRES] [--first I]

Tile i is made from seed i: a district (scene.py) scanned at a density of
4-20 points per square metre with 2-5 cm of range noise (airborne.py), the
district rotated by a random angle and moved to coordinates like a national
grid's. Writes OUT_DIR/city-NN.las and OUT_DIR/city-NN.npz (the truth, in
the same frame: outer-surface samples 0.1 m apart with a building flag and
normal z; visible edge samples with their kind (1 ridge, 2 eave, 3 parapet, 0 other) and a flag for
those under tree crowns) and OUT_DIR/city-NN.json (the parameters).
Tiles already present are kept.
"""
import argparse
import json
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import airborne  # noqa: E402
import scene  # noqa: E402
import truth  # noqa: E402


def make_tile(out_dir, index, size):
    name = os.path.join(out_dir, "city-%02d" % index)
    if os.path.exists(name + ".json"):
        return
    rng = np.random.default_rng(1000 + index)
    district = scene.make_district(rng, size)
    density = float(rng.uniform(4, 20))
    noise = float(rng.uniform(0.02, 0.05))
    points, classes, numbers, totals = airborne.scan(district, rng, density, noise)
    surface, normal_z, building = truth.surface_samples(district, rng, 0.1)
    edges, kind, covered = truth.edge_samples(district)
    angle = float(rng.uniform(0, 2 * math.pi))
    c, s = math.cos(angle), math.sin(angle)
    shift = np.array((rng.uniform(80000, 90000), rng.uniform(440000, 450000), 0.0))

    def place(p):
        return np.column_stack((c * p[:, 0] - s * p[:, 1], s * p[:, 0] + c * p[:, 1], p[:, 2])) + shift

    airborne.write_las(name + ".las", place(points), classes, numbers, totals)
    np.savez_compressed(name + ".tmp.npz", surface=place(surface), surface_normal_z=normal_z, surface_building=building,
                        edges=place(edges), edges_kind=kind, edges_under_trees=covered)
    os.replace(name + ".tmp.npz", name + ".npz")
    meta = {"size_m": size, "density_per_m2": density, "noise_m": noise, "points": int(len(points)),
            "buildings": sum(s.kind == "building" for s in district.solids), "trees": len(district.trees),
            "rotation_rad": angle, "shift": shift.tolist()}
    with open(name + ".json", "w") as f:
        json.dump(meta, f, indent=1)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("out_dir")
    parser.add_argument("--tiles", type=int, default=30)
    parser.add_argument("--first", type=int, default=0)
    parser.add_argument("--size", type=float, default=100.0, help="tile side [m]")
    args = parser.parse_args()
    os.makedirs(args.out_dir, exist_ok=True)
    for i in range(args.first, args.first + args.tiles):
        make_tile(args.out_dir, i, args.size)
        print("tile %d of %d" % (i - args.first + 1, args.tiles), file=sys.stderr)


if __name__ == "__main__":
    main()
