"""A simulated airborne laser scanner (issue 44 item 4).

Two parallel flight lines in a random heading flank the district at
`altitude`; each pulse aims at a random ground target from its line's
position across-track, so scan angles reach about 20 degrees and walls
facing the lines are hit sparsely, walls along them hardly at all, as from
a real survey. The first
surface a pulse meets is its return, moved along the ray by the range noise.
A pulse entering a tree crown returns from a random depth inside it and may
go on: up to three returns, the last one from whatever lies below. Writes
LAS 1.2 point format 1 with ASPRS classes (2 ground, 5 high vegetation, 6
building) and return numbers, in a projected frame of metres.
"""
import os
import struct

import numpy as np

GROUND, VEGETATION, BUILDING = 2, 5, 6


def _clip_solid(solid, origins, directions, candidates):
    """Entry distance of the rays `candidates` into a convex solid (inf: missed)."""
    o, d = origins[candidates], directions[candidates]
    no = o @ solid.normals.T  # rays x planes
    nd = d @ solid.normals.T
    with np.errstate(divide="ignore", invalid="ignore"):
        t = (solid.offsets[None, :] - no) / nd
    entering, leaving = nd < 0, nd > 0
    t_in = np.where(entering, t, -np.inf).max(axis=1)
    t_out = np.where(leaving, t, np.inf).min(axis=1)
    # Rays parallel to a plane and outside it miss.
    parallel_out = ((nd == 0) & (no > solid.offsets[None, :])).any(axis=1)
    hit = (t_in <= t_out) & (t_out > 0) & ~parallel_out
    return np.where(hit, np.maximum(t_in, 0), np.inf)


def first_hits(district, origins, directions):
    """Distance to the first solid or ground hit and its class per ray."""
    n = len(origins)
    g0, gx, gy = district.ground
    # Ground plane z = g0 + gx x + gy y.
    normal = np.array((-gx, -gy, 1.0))
    t_best = (g0 - origins @ normal) / (directions @ normal)
    cls = np.full(n, GROUND, dtype=np.uint8)
    slope = np.abs(directions[:, :2] / directions[:, 2:3]).max()
    for solid in district.solids:
        # Rays whose path through the solid's height range passes its box.
        lo_t = (solid.hi[2] - origins[:, 2]) / directions[:, 2]
        xy = origins[:, :2] + lo_t[:, None] * directions[:, :2]
        reach = slope * (solid.hi[2] - solid.lo[2])
        near = np.nonzero((xy[:, 0] > solid.lo[0] - reach) & (xy[:, 0] < solid.hi[0] + reach) &
                          (xy[:, 1] > solid.lo[1] - reach) & (xy[:, 1] < solid.hi[1] + reach))[0]
        if len(near) == 0:
            continue
        t = _clip_solid(solid, origins, directions, near)
        closer = t < t_best[near]
        t_best[near[closer]] = t[closer]
        cls[near[closer]] = GROUND if solid.kind == "ground" else BUILDING
    return t_best, cls


def _crown_entries(district, origins, directions):
    """Entry and exit distances of each ray into its first tree crown (ellipsoids)."""
    n = len(origins)
    t_in, t_out = np.full(n, np.inf), np.full(n, np.inf)
    for centre, radii in district.trees:
        o = (origins - centre) / radii
        d = directions / radii
        a = (d * d).sum(axis=1)
        b = 2 * (o * d).sum(axis=1)
        c = (o * o).sum(axis=1) - 1
        disc = b * b - 4 * a * c
        ok = disc > 0
        root = np.sqrt(np.where(ok, disc, 0))
        enter = (-b - root) / (2 * a)
        leave = (-b + root) / (2 * a)
        better = ok & (enter > 0) & (enter < t_in)
        t_in[better], t_out[better] = enter[better], leave[better]
    return t_in, t_out


def scan(district, rng, density, noise, altitude=300.0):
    """Returns (points, classes, return_number, returns) of every echo."""
    size = district.size
    count = rng.poisson(density * size * size)
    targets = rng.uniform(0, size, (count, 2))
    # Flight lines in any direction relative to the streets, 0.7 tile sides
    # either side of the centre.
    heading = rng.uniform(0, np.pi)
    along, across = np.array((np.cos(heading), np.sin(heading))), np.array((-np.sin(heading), np.cos(heading)))
    centre = np.full(2, size / 2)
    side = np.where(rng.random(count) < 0.5, -0.7 * size, 0.7 * size)
    origins_xy = centre + side[:, None] * across + ((targets - centre) @ along)[:, None] * along
    origins = np.column_stack((origins_xy, np.full(count, altitude)))
    aims = np.column_stack((targets, district.ground_z(targets[:, 0], targets[:, 1])))
    directions = aims - origins
    directions /= np.linalg.norm(directions, axis=1)[:, None]
    t_solid, cls = first_hits(district, origins, directions)
    t_tree_in, t_tree_out = _crown_entries(district, origins, directions)
    in_tree = t_tree_in < t_solid
    # Returns: in a crown, the first at an exponential depth (mean 0.4 m);
    # with probability 0.6 a second deeper one; a last return from the
    # surface below when the pulse gets through (probability 0.5).
    points, classes, numbers, totals = [], [], [], []
    with np.errstate(invalid="ignore"):
        crown = t_tree_out - t_tree_in
    depth1 = np.minimum(rng.exponential(0.4, count), crown)
    second = in_tree & (rng.random(count) < 0.6)
    depth2 = np.minimum(depth1 + rng.exponential(1.0, count), crown)
    through = in_tree & (rng.random(count) < 0.5)
    total = np.where(in_tree, 1 + second + through, 1).astype(np.uint8)
    t_first = np.where(in_tree, t_tree_in + depth1, t_solid)
    cls_first = np.where(in_tree, VEGETATION, cls).astype(np.uint8)
    for t, c, number, mask in ((t_first, cls_first, np.ones(count, np.uint8), np.ones(count, bool)),
                               (t_tree_in + depth2, np.full(count, VEGETATION, np.uint8), np.full(count, 2, np.uint8), second),
                               (t_solid, cls, (1 + second + 1).astype(np.uint8), through)):
        noisy = t[mask] + rng.normal(0, noise, mask.sum())
        points.append(origins[mask] + noisy[:, None] * directions[mask])
        classes.append(c[mask])
        numbers.append(number[mask])
        totals.append(total[mask])
    return np.concatenate(points), np.concatenate(classes), np.concatenate(numbers), np.concatenate(totals)


def write_las(path, points, classes, return_numbers, returns, scale=0.001):
    """LAS 1.2, point format 1 (28-byte records: no colour)."""
    lo, hi = points.min(axis=0), points.max(axis=0)
    offset = np.floor(lo)
    header = bytearray(227)
    header[0:4] = b"LASF"
    header[24], header[25] = 1, 2  # version 1.2
    header[26:58] = b"sharpmesh bench/city".ljust(32, b"\0")
    header[58:90] = b"airborne.py".ljust(32, b"\0")
    struct.pack_into("<HH", header, 90, 1, 2026)
    struct.pack_into("<HIIBHI", header, 94, 227, 227, 0, 1, 28, len(points))
    by_return = [int((return_numbers == r).sum()) for r in range(1, 6)]
    struct.pack_into("<5I", header, 111, *by_return)
    struct.pack_into("<3d", header, 131, scale, scale, scale)
    struct.pack_into("<3d", header, 155, *offset)
    struct.pack_into("<6d", header, 179, hi[0], lo[0], hi[1], lo[1], hi[2], lo[2])
    record = np.dtype([("xyz", "<i4", 3), ("intensity", "<u2"), ("flags", "u1"), ("cls", "u1"), ("angle", "i1"),
                       ("user", "u1"), ("source", "<u2"), ("time", "<f8")])
    data = np.zeros(len(points), dtype=record)
    data["xyz"] = np.round((points - offset) / scale).astype(np.int32)
    data["intensity"] = 100
    data["flags"] = (return_numbers & 7) | ((returns & 7) << 3)
    data["cls"] = classes
    data["source"] = 1
    with open(path + ".tmp", "wb") as f:
        f.write(header)
        f.write(data.tobytes())
    os.replace(path + ".tmp", path)
