"""Closed CAD-like solids built with gmsh's OpenCASCADE kernel.

Each family is a function (rng, s) -> dict of metadata, that builds its solid
in the current gmsh model. `s` is the length of one average spacing of a
50,000-point uniform sampling of the part (the corpus's unit for thin
material: plates, bars and slots are given in spacings, issue 36 item 1), so
the same thickness in spacings is reached whatever the part's size.
Every family draws all its random numbers before it builds, in the same
order, so a second build with a corrected `s` makes the same shape.
"""
import math

import gmsh

occ = gmsh.model.occ


def _fuse(objects):
    """Union of a list of volume tags: one volume per connected part."""
    if len(objects) == 1:
        return objects
    out, _ = occ.fuse([(3, objects[0])], [(3, t) for t in objects[1:]])
    return [t for d, t in out if d == 3]


def _cut(obj, tools):
    out, _ = occ.cut([(3, t) for t in obj], [(3, t) for t in tools])
    return [t for d, t in out if d == 3]


def _edges_of(volume):
    surfaces = gmsh.model.getBoundary([(3, volume)], combined=False, oriented=False)
    curves = gmsh.model.getBoundary(surfaces, combined=False, oriented=False)
    return sorted(set(abs(t) for _, t in curves))


def plate(rng, s):
    t = rng.uniform(1, 8)
    L, W = rng.uniform(60, 100), rng.uniform(30, 70)
    occ.addBox(0, 0, 0, L, W, t * s)
    return {"thin": t}


def ribbed_block(rng, s):
    """A base block carrying parallel ribs (fins) of a few spacings."""
    t = rng.uniform(1.5, 8)
    ribs = int(rng.integers(2, 6))
    L, W, H = rng.uniform(60, 90), rng.uniform(40, 70), rng.uniform(8, 15)
    rib_h = rng.uniform(10, 25)
    pitch = L / (ribs + 1)
    parts = [occ.addBox(0, 0, 0, L, W, H)]
    for i in range(ribs):
        parts.append(occ.addBox(pitch * (i + 1) - 0.5 * t * s, 0, H - 1, t * s, W, rib_h + 1))
    _fuse(parts)
    return {"thin": t}


def frame(rng, s):
    """A cube frame: the twelve edges of a cube as square bars."""
    t = rng.uniform(2, 8)
    L = rng.uniform(40, 70)
    b = t * s
    outer = occ.addBox(0, 0, 0, L, L, L)
    tools = [occ.addBox(b, b, -1, L - 2 * b, L - 2 * b, L + 2),
             occ.addBox(b, -1, b, L - 2 * b, L + 2, L - 2 * b),
             occ.addBox(-1, b, b, L + 2, L - 2 * b, L - 2 * b)]
    _cut([outer], tools)
    return {"thin": t}


def thin_disk(rng, s):
    t = rng.uniform(1, 8)
    R = rng.uniform(30, 50)
    occ.addCylinder(0, 0, 0, 0, 0, t * s, R)
    return {"thin": t}


def cone_roof(rng, s):
    """A thin conical roof on columns (a shell: cone minus a lower cone)."""
    t = rng.uniform(2, 8)
    R, h, H = rng.uniform(30, 45), rng.uniform(10, 25), rng.uniform(20, 40)
    columns = int(rng.integers(3, 7))
    r_col = rng.uniform(2, 4)
    # The shell's thickness along the normal is t: the offset of the lower
    # cone is vertical, t / cos(slope).
    dz = t * s * math.hypot(R, h) / R
    roof = _cut([occ.addCone(0, 0, H, 0, 0, h, R, 0)], [occ.addCone(0, 0, H - dz, 0, 0, h, R, 0)])
    parts = roof
    for i in range(columns):
        a = 2 * math.pi * i / columns
        rc = 0.7 * R
        parts = parts + [occ.addCylinder(rc * math.cos(a), rc * math.sin(a), 0, 0, 0, H + 0.35 * h, r_col)]
    _fuse(parts)
    return {"thin": t}


def slotted_block(rng, s):
    """A block with slots of 1-6 spacings: through the height but open on
    one side only (so the block stays in one piece), or blind from the top."""
    w = rng.uniform(1, 6)
    slots = int(rng.integers(1, 4))
    L, W, H = rng.uniform(50, 80), rng.uniform(30, 50), rng.uniform(15, 30)
    blind = rng.uniform() < 0.5
    depth = rng.uniform(0.3, 0.7) * H
    tools = []
    for i in range(slots):
        x = L * (i + 1) / (slots + 1) - 0.5 * w * s
        z0 = H - depth if blind else -1
        tools.append(occ.addBox(x, -1, z0, w * s, (W + 2) if blind else 0.7 * W, H + 2))
    _cut([occ.addBox(0, 0, 0, L, W, H)], tools)
    return {"thin": w, "gap": True}


def holed_plate(rng, s):
    """A plate with through-holes 1-6 spacings in diameter."""
    d = rng.uniform(1.5, 6)
    L, W, T = rng.uniform(50, 80), rng.uniform(40, 60), rng.uniform(5, 15)
    holes = int(rng.integers(2, 7))
    xs = rng.uniform(0.15, 0.85, holes)
    ys = rng.uniform(0.15, 0.85, holes)
    tools = [occ.addCylinder(x * L, y * W, -1, 0, 0, T + 2, 0.5 * d * s) for x, y in zip(xs, ys)]
    _cut([occ.addBox(0, 0, 0, L, W, T)], tools)
    return {"thin": d, "gap": True}


def boss_pocket(rng, s):
    L, W, H = rng.uniform(50, 80), rng.uniform(40, 60), rng.uniform(10, 20)
    r_boss, h_boss = rng.uniform(5, 12), rng.uniform(5, 15)
    pw, pd = rng.uniform(8, 20), rng.uniform(3, 0.8 * H)
    body = _fuse([occ.addBox(0, 0, 0, L, W, H), occ.addCylinder(0.3 * L, 0.5 * W, H - 1, 0, 0, h_boss + 1, r_boss)])
    _cut(body, [occ.addBox(0.6 * L, 0.3 * W, H - pd, pw, pw, pd + 1)])
    return {}


def chamfered_block(rng, s):
    """Box with every edge chamfered; the chamfer face is 1-3 spacings wide."""
    c = rng.uniform(1, 3)
    L, W, H = rng.uniform(30, 70), rng.uniform(30, 70), rng.uniform(20, 50)
    box = occ.addBox(0, 0, 0, L, W, H)
    occ.synchronize()
    edges = _edges_of(box)
    # A chamfer of face width c s has legs c s / sqrt(2).
    # OpenCASCADE measures a chamfer's legs on one face next to each edge.
    faces = [int(gmsh.model.getAdjacencies(1, e)[0][0]) for e in edges]
    occ.chamfer([box], edges, faces, [c * s / math.sqrt(2)])
    return {"thin": c}


def filleted_block(rng, s):
    r = rng.uniform(2, 10)
    L, W, H = rng.uniform(30, 70), rng.uniform(30, 70), rng.uniform(20, 50)
    box = occ.addBox(0, 0, 0, L, W, H)
    some = rng.uniform() < 0.5
    occ.synchronize()
    edges = _edges_of(box)
    # Some of the edges, or all of them.
    if some:
        edges = edges[: len(edges) // 3 + 1]
    occ.fillet([box], edges, [r])
    return {}


def curved_minus_box(rng, s):
    """Cylinder or sphere minus a box: curved and flat faces meeting."""
    R = rng.uniform(20, 35)
    sphere = rng.uniform() < 0.5
    a = rng.uniform(0.3, 0.8) * R
    body = occ.addSphere(0, 0, 0, R) if sphere else occ.addCylinder(0, 0, -R, 0, 0, 2 * R, R)
    tool = occ.addBox(R - a, -2 * R, -2 * R, 4 * R, 4 * R, 4 * R) if sphere else occ.addBox(-a, -2 * R, 0, 4 * R, 4 * R, 4 * R)
    _cut([body], [tool])
    return {}


def box_minus_cylinders(rng, s):
    L, W, H = rng.uniform(40, 70), rng.uniform(30, 60), rng.uniform(20, 40)
    n = int(rng.integers(1, 4))
    tools = []
    for _ in range(n):
        r = rng.uniform(4, 0.3 * min(W, H))
        axis = int(rng.integers(0, 3))
        c = [rng.uniform(0.25, 0.75) * L, rng.uniform(0.25, 0.75) * W, rng.uniform(0.25, 0.75) * H]
        length = [L + 20, W + 20, H + 20][axis]
        start = list(c)
        start[axis] = -10
        direction = [0, 0, 0]
        direction[axis] = length
        tools.append(occ.addCylinder(*start, *direction, r))
    _cut([occ.addBox(0, 0, 0, L, W, H)], tools)
    return {}


def several_components(rng, s):
    """Two to four disjoint solids (boxes, spheres, cylinders)."""
    n = int(rng.integers(2, 5))
    made = 0
    for i in range(n):
        x = i * 45.0
        kind = int(rng.integers(0, 3))
        size = rng.uniform(12, 20)
        if kind == 0:
            occ.addBox(x, 0, 0, size, rng.uniform(10, 20), rng.uniform(10, 20))
        elif kind == 1:
            occ.addSphere(x + size, 10, 10, 0.6 * size)
        else:
            occ.addCylinder(x + size, 10, 0, 0, 0, rng.uniform(10, 25), 0.5 * size)
        made += 1
    return {"components": made}


def nested_shells(rng, s):
    """A hollow box (an inner cavity: a second shell) with a ball inside."""
    L = rng.uniform(40, 60)
    wall = rng.uniform(3, 8)
    hollow = _cut([occ.addBox(0, 0, 0, L, L, L)], [occ.addBox(wall * s, wall * s, wall * s, L - 2 * wall * s, L - 2 * wall * s, L - 2 * wall * s)])
    occ.addSphere(0.5 * L, 0.5 * L, 0.5 * L, rng.uniform(0.15, 0.3) * L)
    return {"thin": wall, "components": 3}


def gear(rng, s):
    teeth = int(rng.integers(8, 20))
    R, T = rng.uniform(25, 40), rng.uniform(6, 15)
    depth, width = rng.uniform(3, 6), rng.uniform(0.3, 0.5)
    parts = [occ.addCylinder(0, 0, 0, 0, 0, T, R)]
    tooth_w = width * 2 * math.pi * R / teeth
    for i in range(teeth):
        b = occ.addBox(R - 1, -0.5 * tooth_w, 0, depth + 1, tooth_w, T)
        occ.rotate([(3, b)], 0, 0, 0, 0, 0, 1, 2 * math.pi * i / teeth)
        parts.append(b)
    body = _fuse(parts)
    _cut(body, [occ.addCylinder(0, 0, -1, 0, 0, T + 2, rng.uniform(0.15, 0.35) * R)])
    return {}


def hinge(rng, s):
    """Two leaves and knuckles around a pin axis."""
    L, W, T = rng.uniform(50, 80), rng.uniform(20, 35), rng.uniform(2, 6) * s
    knuckles = int(rng.integers(3, 6))
    r = rng.uniform(4, 7)
    parts = [occ.addBox(0, -W, -0.5 * T, L, W, T), occ.addBox(0, 0, -0.5 * T, L, W, T)]
    step = L / knuckles
    for i in range(knuckles):
        parts.append(occ.addCylinder(i * step + 0.5, 0, 0, step - 1.0, 0, 0, r))
    body = _fuse(parts)
    _cut(body, [occ.addCylinder(-1, 0, 0, L + 2, 0, 0, 0.4 * r)])
    return {"thin": T / s}


def l_bracket(rng, s):
    """An angle bracket with a web and holes: flanges a few spacings thick."""
    t = rng.uniform(2, 8)
    L, W, H = rng.uniform(40, 70), rng.uniform(30, 50), rng.uniform(30, 50)
    parts = [occ.addBox(0, 0, 0, L, W, t * s), occ.addBox(0, 0, 0, t * s, W, H)]
    body = _fuse(parts)
    holes = [occ.addCylinder(0.6 * L, 0.5 * W, -1, 0, 0, t * s + 2, rng.uniform(3, 6)),
             occ.addCylinder(-1, 0.5 * W, 0.6 * H, t * s + 2, 0, 0, rng.uniform(3, 6))]
    _cut(body, holes)
    return {"thin": t}


def tube(rng, s):
    """A thick-walled pipe: the wall 2-8 spacings."""
    t = rng.uniform(2, 8)
    R, H = rng.uniform(15, 30), rng.uniform(30, 70)
    _cut([occ.addCylinder(0, 0, 0, 0, 0, H, R)], [occ.addCylinder(0, 0, -1, 0, 0, H + 2, R - t * s)])
    return {"thin": t}


FAMILIES = {
    "plate": plate,
    "ribs": ribbed_block,
    "frame": frame,
    "disk": thin_disk,
    "cone-roof": cone_roof,
    "slots": slotted_block,
    "holes": holed_plate,
    "boss-pocket": boss_pocket,
    "chamfer": chamfered_block,
    "fillet": filleted_block,
    "curved-minus-box": curved_minus_box,
    "box-minus-cylinders": box_minus_cylinders,
    "components": several_components,
    "nested": nested_shells,
    "gear": gear,
    "hinge": hinge,
    "bracket": l_bracket,
    "tube": tube,
}
