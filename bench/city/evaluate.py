#!/usr/bin/python3
"""Measures sharp-edge polylines and meshes of city tiles against their truth
(issue 44 item 4).

    evaluate.py TILE.npz [--polylines P.txt] [--mesh M.ply] [--tolerance 0.5]

Prints one JSON object:
- recall: the share of visible ridge and eave samples (truth.edge_samples,
  those under tree crowns left out) within `tolerance` of a polyline, also
  for ridges, eaves, and of the eaves those of houses and of flat roofs
  (parapets) apart;
- precision: the share of polyline length within `tolerance` of any visible
  sharp edge of the district (ridges, eaves, hips, rakes, wall corners,
  parapets, chimneys, dormers, kerbs);
- for a mesh: distances from the mesh (sampled 0.1 m apart) to the
  district's outer surface and back, for the buildings (mesh samples whose
  nearest truth sample is a building's; roofs: building truth facing up)
  as the 99th percentile and the maximum, in metres.
"""
import argparse
import json
import struct
import sys

import numpy as np
from scipy.spatial import cKDTree


def read_polylines(path):
    lines = []
    with open(path) as f:
        for row in f:
            v = row.split()
            if not v:
                continue
            n = int(v[0])
            lines.append(np.array(v[1:1 + 3 * n], dtype=float).reshape(n, 3))
    return lines


def resample(lines, step):
    out = []
    for line in lines:
        for a, b in zip(line[:-1], line[1:]):
            n = max(1, int(np.ceil(np.linalg.norm(b - a) / step)))
            out.append(a + np.linspace(0, 1, n, endpoint=False)[:, None] * (b - a))
    return np.concatenate(out) if out else np.zeros((0, 3))


def read_ply_mesh(path):
    with open(path, "rb") as f:
        header = []
        while True:
            line = f.readline().decode("ascii", "replace").strip()
            header.append(line)
            if line == "end_header":
                break
        body = f.read()
    fmt = next(h.split()[1] for h in header if h.startswith("format"))
    nv = next(int(h.split()[2]) for h in header if h.startswith("element vertex"))
    nf = next(int(h.split()[2]) for h in header if h.startswith("element face"))
    vertex_props = []
    in_vertex = False
    for h in header:
        if h.startswith("element"):
            in_vertex = h.startswith("element vertex")
        elif h.startswith("property") and in_vertex:
            vertex_props.append(h.split()[1])
    sizes = {"float": 4, "float32": 4, "double": 8, "float64": 8, "uchar": 1, "uint8": 1, "int": 4, "uint": 4}
    if fmt == "ascii":
        rows = body.decode().split("\n")
        v = np.array([r.split()[:3] for r in rows[:nv]], dtype=float)
        f = np.array([r.split()[1:4] for r in rows[nv:nv + nf]], dtype=np.int64)
        return v, f
    vdt = np.dtype([("p%d" % i, "<f4" if sizes[t] == 4 and t.startswith("f") else "<f8" if t in ("double", "float64") else
                     "u1" if sizes[t] == 1 else "<i4") for i, t in enumerate(vertex_props)])
    v = np.frombuffer(body, dtype=vdt, count=nv)
    v = np.column_stack([v["p0"], v["p1"], v["p2"]]).astype(float)
    fdt = np.dtype([("n", "u1"), ("i", "<i4", 3)])
    f = np.frombuffer(body, dtype=fdt, count=nf, offset=nv * vdt.itemsize)
    return v, f["i"].astype(np.int64)


def sample_mesh(vertices, faces, spacing, rng):
    a, b, c = vertices[faces[:, 0]], vertices[faces[:, 1]], vertices[faces[:, 2]]
    area = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1)
    count = rng.poisson(area / (spacing * spacing))
    idx = np.repeat(np.arange(len(faces)), count)
    r1, r2 = rng.random(len(idx)), rng.random(len(idx))
    flip = r1 + r2 > 1
    r1[flip], r2[flip] = 1 - r1[flip], 1 - r2[flip]
    pts = a[idx] + r1[:, None] * (b[idx] - a[idx]) + r2[:, None] * (c[idx] - a[idx])
    return np.concatenate((pts, vertices))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("truth")
    parser.add_argument("--polylines")
    parser.add_argument("--mesh")
    parser.add_argument("--tolerance", type=float, default=0.5, help="[m]")
    args = parser.parse_args()
    t = np.load(args.truth)
    result = {}
    if args.polylines:
        lines = read_polylines(args.polylines)
        found = resample(lines, 0.1)
        edges, kind, covered = t["edges"], t["edges_kind"], t["edges_under_trees"]
        wanted = (kind > 0) & ~covered
        near_found = np.zeros(len(edges), bool)
        near_truth = np.zeros(len(found), bool)
        if len(found):
            near_found = cKDTree(found).query(edges, distance_upper_bound=args.tolerance)[0] <= args.tolerance
            near_truth = cKDTree(edges).query(found, distance_upper_bound=args.tolerance)[0] <= args.tolerance
        share = lambda mask: float(near_found[mask].mean()) if mask.any() else None  # noqa: E731
        result.update(polylines=len(lines), polyline_length_m=round(0.1 * len(found), 1),
                      recall=share(wanted), ridge_recall=share(wanted & (kind == 1)), eave_recall=share(wanted & (kind >= 2)),
                      house_eave_recall=share(wanted & (kind == 2)), parapet_recall=share(wanted & (kind == 3)),
                      precision=float(near_truth.mean()) if len(found) else 0.0)
    if args.mesh:
        vertices, faces = read_ply_mesh(args.mesh)
        samples = sample_mesh(vertices, faces, 0.1, np.random.default_rng(0))
        surface, building, normal_z = t["surface"], t["surface_building"], t["surface_normal_z"]
        distance, nearest = cKDTree(surface).query(samples)
        on_building = building[nearest]
        to_mesh = cKDTree(samples).query(surface[building & (normal_z > 0.3)])[0]
        result.update(
            facets=int(len(faces)),
            mesh_to_buildings_p99_m=float(np.percentile(distance[on_building], 99)) if on_building.any() else None,
            mesh_to_buildings_max_m=float(distance[on_building].max()) if on_building.any() else None,
            roofs_to_mesh_p99_m=float(np.percentile(to_mesh, 99)),
            roofs_to_mesh_max_m=float(to_mesh.max()),
            mesh_to_surface_median_m=float(np.median(distance)))
    json.dump(result, sys.stdout)
    print()


if __name__ == "__main__":
    main()
