"""Ground truth of a district (issue 44 item 4): dense samples of the
buildings' and the ground's outer surface, and the visible sharp edges.

The outer surface of a union of convex solids is every face of every solid
minus what lies strictly inside another solid or under the ground; the same
rule keeps the edges that show (a chimney's foot inside the roof does not).
"""
import numpy as np


def _inside_any(district, points, skip, eps=1e-4):
    inside = np.zeros(len(points), bool)
    for k, solid in enumerate(district.solids):
        if k == skip:
            continue
        box = np.all((points > solid.lo + eps) & (points < solid.hi - eps), axis=1)
        idx = np.nonzero(box)[0]
        if len(idx):
            s = points[idx] @ solid.normals.T - solid.offsets[None, :]
            inside[idx[np.all(s < -eps, axis=1)]] = True
    return inside


def _below_ground(district, points, eps=1e-3):
    return points[:, 2] < district.ground_z(points[:, 0], points[:, 1]) - eps


def _faces(solid):
    """Each bounding plane's polygon: the solid's vertices on it, in angular order."""
    corners = []
    # Vertices: intersections of three planes inside all others.
    n = len(solid.offsets)
    for i in range(n):
        for j in range(i + 1, n):
            for k in range(j + 1, n):
                m = solid.normals[[i, j, k]]
                if abs(np.linalg.det(m)) < 1e-9:
                    continue
                p = np.linalg.solve(m, solid.offsets[[i, j, k]])
                if np.all(solid.normals @ p - solid.offsets < 1e-7):
                    corners.append(p)
    corners = np.unique(np.round(np.array(corners), 9), axis=0)
    faces = []
    for i in range(n):
        on = corners[np.abs(corners @ solid.normals[i] - solid.offsets[i]) < 1e-7]
        if len(on) < 3:
            continue
        c = on.mean(axis=0)
        u = on[0] - c
        u /= np.linalg.norm(u)
        v = np.cross(solid.normals[i], u)
        order = np.argsort(np.arctan2((on - c) @ v, (on - c) @ u))
        faces.append((solid.normals[i], on[order]))
    return faces


def surface_samples(district, rng, spacing):
    """(points, normals_z, is_building): the outer surface sampled about
    `spacing` apart (tree crowns are not part of it)."""
    points, nz, building = [], [], []
    per_area = 1.0 / (spacing * spacing)
    for k, solid in enumerate(district.solids):
        for normal, polygon in _faces(solid):
            for a in range(1, len(polygon) - 1):
                p0, p1, p2 = polygon[0], polygon[a], polygon[a + 1]
                area = 0.5 * np.linalg.norm(np.cross(p1 - p0, p2 - p0))
                count = rng.poisson(area * per_area)
                if count == 0:
                    continue
                r1, r2 = rng.random(count), rng.random(count)
                flip = r1 + r2 > 1
                r1[flip], r2[flip] = 1 - r1[flip], 1 - r2[flip]
                pts = p0 + r1[:, None] * (p1 - p0) + r2[:, None] * (p2 - p0)
                keep = ~_inside_any(district, pts, k) & ~_below_ground(district, pts)
                points.append(pts[keep])
                nz.append(np.full(keep.sum(), normal[2]))
                building.append(np.full(keep.sum(), solid.kind == "building"))
    size = district.size
    count = int(size * size * per_area)
    xy = rng.uniform(0, size, (count, 2))
    ground = np.column_stack((xy, district.ground_z(xy[:, 0], xy[:, 1])))
    keep = ~_inside_any(district, ground, -1)
    points.append(ground[keep])
    nz.append(np.ones(keep.sum()))
    building.append(np.zeros(keep.sum(), bool))
    return np.concatenate(points), np.concatenate(nz), np.concatenate(building)


def edge_samples(district, step=0.25):
    """(points, kind, hidden_by_tree): the solids' sharp edges sampled every
    `step`, where they show; kind 1 ridge, 2 eave, 3 a flat roof's eave (the parapet's top), 0 any
    other edge."""
    points, key = [], []
    for k, solid in enumerate(district.solids):
        for kind, a, b in solid.edges:
            n = max(2, int(np.ceil(np.linalg.norm(b - a) / step)) + 1)
            pts = a + np.linspace(0, 1, n)[:, None] * (b - a)
            keep = ~_inside_any(district, pts, k) & ~_below_ground(district, pts)
            points.append(pts[keep])
            key.append(np.full(keep.sum(), {"ridge": 1, "eave": 2, "parapet": 3}.get(kind, 0), dtype=np.uint8))
        # Where walls meet the ground: the footprint of a solid founded below it.
        if solid.kind == "building" and solid.lo[2] < district.ground_z(solid.lo[0], solid.lo[1]):
            (x0, y0), (x1, y1) = solid.lo[:2], solid.hi[:2]
            for a, b in (((x0, y0), (x1, y0)), ((x1, y0), (x1, y1)), ((x1, y1), (x0, y1)), ((x0, y1), (x0, y0))):
                n = max(2, int(np.ceil(np.hypot(b[0] - a[0], b[1] - a[1]) / step)) + 1)
                xy = np.array(a) + np.linspace(0, 1, n)[:, None] * (np.array(b) - np.array(a))
                pts = np.column_stack((xy, district.ground_z(xy[:, 0], xy[:, 1])))
                keep = ~_inside_any(district, pts, k)
                points.append(pts[keep])
                key.append(np.zeros(keep.sum(), dtype=np.uint8))
    points = np.concatenate(points)
    covered = np.zeros(len(points), bool)
    for centre, radii in district.trees:
        covered |= np.hypot(points[:, 0] - centre[0], points[:, 1] - centre[1]) < radii[0]
    return points, np.concatenate(key), covered
