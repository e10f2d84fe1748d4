"""Procedural city districts with exact ground truth (issue 44 item 4).

A district is a union of convex solids (houses as a box and a roof prism or
hip, flat blocks with parapets, chimneys, dormers, raised pavements) on a
gently sloping ground plane, plus tree crowns. Every solid is a list of
half-spaces n.x <= c, so a ray finds it by clipping (Cyrus-Beck) and the
scanner in airborne.py needs nothing but numpy. Each solid also lists its
sharp edges, tagged by kind: `ridge`, `eave` and `parapet` (a flat roof's
eave: what the thesis's urban evaluation asks for, 8.2) and `other` (hips, rakes, wall corners, parapets,
chimneys, dormers), as segments in the district's frame.
"""
import math

import numpy as np


class Solid:
    """A convex solid: half-spaces (normals, offsets), its bounding box and
    its sharp edges [(kind, a, b)]."""

    def __init__(self, vertices, planes, edges, kind):
        self.normals = np.array([p[0] for p in planes], dtype=float)
        self.offsets = np.array([p[1] for p in planes], dtype=float)
        v = np.asarray(vertices, dtype=float)
        self.lo, self.hi = v.min(axis=0), v.max(axis=0)
        self.edges = edges
        self.kind = kind  # "building" or "ground"


def _plane_through(a, b, c, inside):
    """The half-space bounded by the plane through a, b, c that holds `inside`."""
    n = np.cross(np.subtract(b, a), np.subtract(c, a))
    n = n / np.linalg.norm(n)
    if np.dot(n, inside) - np.dot(n, a) > 0:
        n = -n
    return (n, float(np.dot(n, a)))


def _box_planes(x0, x1, y0, y1, z0, z1):
    return [((-1, 0, 0), -x0), ((1, 0, 0), x1), ((0, -1, 0), -y0), ((0, 1, 0), y1), ((0, 0, -1), -z0), ((0, 0, 1), z1)]


def box(x0, x1, y0, y1, z0, z1, kind="building", edge_kind="other", top_kind=None):
    """An axis-aligned box; its top rim is tagged `top_kind` (eaves of a flat
    roof), its vertical edges `edge_kind`."""
    v = [(x, y, z) for x in (x0, x1) for y in (y0, y1) for z in (z0, z1)]
    top = [((x0, y0, z1), (x1, y0, z1)), ((x1, y0, z1), (x1, y1, z1)), ((x1, y1, z1), (x0, y1, z1)), ((x0, y1, z1), (x0, y0, z1))]
    edges = [(top_kind or edge_kind, np.array(a), np.array(b)) for a, b in top]
    edges += [(edge_kind, np.array((x, y, z0)), np.array((x, y, z1))) for x in (x0, x1) for y in (y0, y1)]
    return Solid(v, _box_planes(x0, x1, y0, y1, z0, z1), edges, kind)


def gabled_house(x0, x1, y0, y1, z0, eave, ridge):
    """Walls up to `eave`, a roof rising to `ridge` over the line y = (y0+y1)/2
    running along x."""
    ym = 0.5 * (y0 + y1)
    v = [(x, y, z) for x in (x0, x1) for y in (y0, y1) for z in (z0, eave)] + [(x0, ym, ridge), (x1, ym, ridge)]
    inside = ((x0 + x1) / 2, ym, (z0 + eave) / 2)
    planes = _box_planes(x0, x1, y0, y1, z0, ridge)[:5]
    planes.append(_plane_through((x0, y0, eave), (x1, y0, eave), (x0, ym, ridge), inside))
    planes.append(_plane_through((x0, y1, eave), (x1, y1, eave), (x0, ym, ridge), inside))
    A = np.array
    edges = [("ridge", A((x0, ym, ridge)), A((x1, ym, ridge))),
             ("eave", A((x0, y0, eave)), A((x1, y0, eave))), ("eave", A((x0, y1, eave)), A((x1, y1, eave)))]
    for x in (x0, x1):
        edges += [("other", A((x, y0, eave)), A((x, ym, ridge))), ("other", A((x, y1, eave)), A((x, ym, ridge)))]
        edges += [("other", A((x, y, z0)), A((x, y, eave))) for y in (y0, y1)]
    return Solid(v, planes, edges, "building")


def hipped_house(x0, x1, y0, y1, z0, eave, ridge):
    """A hip roof: four slopes of one pitch, the ridge along the longer side x."""
    ym = 0.5 * (y0 + y1)
    half = 0.5 * (y1 - y0)
    inset = min(half, 0.5 * (x1 - x0) - 0.01)  # equal pitch on all four sides
    ra, rb = (x0 + inset, ym, ridge), (x1 - inset, ym, ridge)
    v = [(x, y, z) for x in (x0, x1) for y in (y0, y1) for z in (z0, eave)] + [ra, rb]
    inside = ((x0 + x1) / 2, ym, (z0 + eave) / 2)
    planes = _box_planes(x0, x1, y0, y1, z0, ridge)[:5]
    planes.append(_plane_through((x0, y0, eave), (x1, y0, eave), ra, inside))
    planes.append(_plane_through((x0, y1, eave), (x1, y1, eave), ra, inside))
    planes.append(_plane_through((x0, y0, eave), (x0, y1, eave), ra, inside))
    planes.append(_plane_through((x1, y0, eave), (x1, y1, eave), rb, inside))
    A = np.array
    edges = [("ridge", A(ra), A(rb))]
    corners = [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]
    for i, (x, y) in enumerate(corners):
        nx, ny = corners[(i + 1) % 4]
        edges.append(("eave", A((x, y, eave)), A((nx, ny, eave))))
        edges.append(("other", A((x, y, eave)), A(ra if x == x0 else rb)))
        edges.append(("other", A((x, y, z0)), A((x, y, eave))))
    return Solid(v, planes, edges, "building")


def flat_block(rng, x0, x1, y0, y1, z0, height):
    """A flat-roofed block with a parapet: the block, four parapet walls."""
    solids = [box(x0, x1, y0, y1, z0, height)]
    # The block's own top rim lies inside the parapet: only the parapet's
    # outer top rim is an eave.
    solids[0].edges = [e for e in solids[0].edges if e[1][2] != height or e[2][2] != height]
    w, h = rng.uniform(0.25, 0.4), rng.uniform(0.5, 1.0)
    top = height + h
    rim = [box(x0, x1, y0, y0 + w, height, top), box(x0, x1, y1 - w, y1, height, top),
           box(x0, x0 + w, y0 + w, y1 - w, height, top), box(x1 - w, x1, y0 + w, y1 - w, height, top)]
    for part in rim:
        part.edges = [("other", a, b) for _, a, b in part.edges if a[2] == top and b[2] == top]
    A = np.array
    outline = [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]
    inner = [(x0 + w, y0 + w), (x1 - w, y0 + w), (x1 - w, y1 - w), (x0 + w, y1 - w)]
    for i, ((x, y), (u, v)) in enumerate(zip(outline, inner)):
        (nx, ny), (nu, nv) = outline[(i + 1) % 4], inner[(i + 1) % 4]
        rim[0].edges.append(("parapet", A((x, y, top)), A((nx, ny, top))))
        # Where the roof meets the parapet's inner face.
        rim[0].edges.append(("other", A((u, v, height)), A((nu, nv, height))))
    return solids + rim


def chimney(rng, x, y, z_base, z_roof_top):
    s = rng.uniform(0.5, 0.9)
    return box(x - s / 2, x + s / 2, y - s / 2, y + s / 2, z_base, z_roof_top + rng.uniform(0.6, 1.4))


def dormer(x0, x1, y_back, y_front, roof_z, eave, ridge):
    """A gabled dormer on a roof slope that falls towards y_front; `roof_z(y)`
    is the main roof's height. Its walls start under the roof."""
    ym_x = 0.5 * (x0 + x1)
    z_base = min(roof_z(y_back), roof_z(y_front)) - 0.5
    v = [(x, y, z) for x in (x0, x1) for y in (y_back, y_front) for z in (z_base, eave)]
    v += [(ym_x, y_back, ridge), (ym_x, y_front, ridge)]
    inside = (ym_x, 0.5 * (y_back + y_front), 0.5 * (z_base + eave))
    lo_y, hi_y = min(y_back, y_front), max(y_back, y_front)
    planes = _box_planes(x0, x1, lo_y, hi_y, z_base, ridge)[:5]
    planes.append(_plane_through((x0, y_back, eave), (x0, y_front, eave), (ym_x, y_back, ridge), inside))
    planes.append(_plane_through((x1, y_back, eave), (x1, y_front, eave), (ym_x, y_back, ridge), inside))
    A = np.array
    zf = roof_z(y_front)
    edges = [("other", A((ym_x, y_back, ridge)), A((ym_x, y_front, ridge))),
             ("other", A((x0, y_back, eave)), A((x0, y_front, eave))), ("other", A((x1, y_back, eave)), A((x1, y_front, eave))),
             ("other", A((x0, y_front, zf)), A((x1, y_front, zf))),
             ("other", A((x0, y_front, zf)), A((x0, y_front, eave))), ("other", A((x1, y_front, zf)), A((x1, y_front, eave))),
             ("other", A((x0, y_front, eave)), A((ym_x, y_front, ridge))), ("other", A((x1, y_front, eave)), A((ym_x, y_front, ridge))),
             ("other", A((x0, y_back, roof_z(y_back))), A((x0, y_front, zf))),
             ("other", A((x1, y_back, roof_z(y_back))), A((x1, y_front, zf)))]
    return Solid(v, planes, edges, "building")


class District:
    """Solids, tree crowns (centre, radii) and the ground z = g0 + gx x + gy y."""

    def __init__(self, size):
        self.size = size
        self.solids = []
        self.trees = []
        self.ground = (0.0, 0.0, 0.0)

    def ground_z(self, x, y):
        g0, gx, gy = self.ground
        return g0 + gx * x + gy * y


def _row_of_houses(rng, district, x0, x1, y0, depth, z0, facing_street):
    """Attached houses along x from x0 to x1, each its own width and height;
    neighbours differ by at least 0.8 m in eave height so every shared gable
    wall shows a step (an edge), as terraced streets do."""
    x = x0
    previous_eave = None
    while x1 - x > 4.5:
        width = min(rng.uniform(4.5, 8.0), x1 - x)
        eave = rng.uniform(5.0, 9.0)
        if previous_eave is not None and abs(eave - previous_eave) < 0.8:
            eave = previous_eave + (0.8 + rng.uniform(0, 1)) * (1 if rng.random() < 0.5 or previous_eave < 5.8 else -1)
        previous_eave = eave
        pitch = math.radians(rng.uniform(30, 50))
        ridge = eave + 0.5 * depth * math.tan(pitch)
        hipped = rng.random() < 0.25
        house = (hipped_house if hipped and width > 6 else gabled_house)(x, x + width, y0, y0 + depth, z0, eave, ridge)
        district.solids.append(house)
        ym = y0 + depth / 2
        if rng.random() < 0.5:
            cx = rng.uniform(x + 1.0, x + width - 1.0)
            cy = ym + rng.uniform(-0.3, 0.3) * depth / 2
            district.solids.append(chimney(rng, cx, cy, eave, ridge))
        if not hipped and width > 6 and rng.random() < 0.4:
            # A dormer on the street side's slope.
            slope = (ridge - eave) / (depth / 2)
            front = y0 + 0.25 * depth if facing_street < 0 else y0 + 0.75 * depth
            back = ym - 0.05 * depth if facing_street < 0 else ym + 0.05 * depth
            roof_z = (lambda yy, s=slope, r=ridge, m=ym: r - s * abs(yy - m))
            de = min(roof_z(front) + rng.uniform(1.2, 1.8), ridge - 1.2)
            if de > roof_z(front) + 0.8:
                district.solids.append(dormer(x + 1.5, x + width - 1.5, back, front, roof_z, de, de + 0.8))
        x += width


def make_district(rng, size):
    """A district of `size` x `size` metres: streets along x with pavements,
    blocks of terraced houses or flat blocks between them, trees."""
    d = District(size)
    d.ground = (rng.uniform(-1, 1), rng.uniform(-0.01, 0.01), rng.uniform(-0.01, 0.01))
    y = rng.uniform(2, 6)
    while y < size - 12:
        # A street 8-12 m wide, raised pavements 2 m wide on both sides.
        street = rng.uniform(8, 12)
        for py in (y, y + street - 2):
            z = d.ground_z(size / 2, py + 1)
            kerb = box(0, size, py, py + 2, z - 0.5, z + rng.uniform(0.1, 0.2), kind="ground")
            kerb.edges = [("other", a, b) for kind, a, b in kerb.edges if a[2] == b[2] and abs(a[0] - b[0]) > 1]
            d.solids.append(kerb)
        y += street
        block_depth = rng.uniform(9, 16)
        if y + block_depth > size - 1:
            break
        x = rng.uniform(0, 4)
        while x < size - 10:
            length = rng.uniform(18, 45)
            xe = min(x + length, size - rng.uniform(0, 3))
            z0 = d.ground_z((x + xe) / 2, y + block_depth / 2) - 0.5
            if rng.random() < 0.35:
                d.solids += flat_block(rng, x, xe, y, y + block_depth, z0, z0 + 0.5 + rng.uniform(7, 16))
            else:
                _row_of_houses(rng, d, x, xe, y, block_depth, z0, facing_street=-1)
            x = xe + rng.uniform(3, 10)
            # Trees in the gaps between blocks.
            if rng.random() < 0.7 and x < size:
                r = rng.uniform(2, 4)
                tx = x - rng.uniform(1.5, 3)
                ty = y + rng.uniform(r, max(r, block_depth - r))
                d.trees.append((np.array((tx, ty, d.ground_z(tx, ty) + r + rng.uniform(2, 5))), np.array((r, r, r * rng.uniform(0.7, 1.2)))))
        y += block_depth + rng.uniform(1, 4)
    # Street trees on the pavements.
    for _ in range(int(rng.integers(3, 10))):
        tx, ty = rng.uniform(0, size), rng.uniform(0, size)
        r = rng.uniform(1.5, 3.5)
        d.trees.append((np.array((tx, ty, d.ground_z(tx, ty) + r + rng.uniform(2, 4))), np.array((r, r, r))))
    return d
