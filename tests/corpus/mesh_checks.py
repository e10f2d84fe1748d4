"""Checks of a triangle mesh given as numpy arrays: the corpus's own
references must be closed (or open where meant), edge-manifold and
consistently oriented before anything is measured against them."""
import numpy as np


def compact(vertices, faces, per_face=None):
    """Merges exact duplicate vertices, drops degenerate faces and unused
    vertices; `per_face` (an array of one value per face) follows the faces."""
    unique, inverse = np.unique(vertices, axis=0, return_inverse=True)
    faces = inverse.reshape(-1)[faces]
    keep = (faces[:, 0] != faces[:, 1]) & (faces[:, 1] != faces[:, 2]) & (faces[:, 0] != faces[:, 2])
    used, remap = np.unique(faces[keep], return_inverse=True)
    if per_face is None:
        return unique[used], remap.reshape(-1, 3)
    return unique[used], remap.reshape(-1, 3), per_face[keep]


def orient(vertices, faces, sign):
    """Orients every edge-connected patch consistently, from its first face,
    then flips each patch whose area-weighted vote of `sign` (per face: +1
    where the face's given orientation is believed outward, -1 where not)
    is negative. Returns the faces."""
    given = faces
    a, b, c = (vertices[faces[:, k]] for k in range(3))
    area = np.linalg.norm(np.cross(b - a, c - a), axis=1)
    faces = faces.copy()
    edges = {}
    for f, (a, b, c) in enumerate(faces):
        for u, v in ((a, b), (b, c), (c, a)):
            edges.setdefault((min(u, v), max(u, v)), []).append(f)
    seen = np.zeros(len(faces), bool)
    patches = []
    for start in range(len(faces)):
        if seen[start]:
            continue
        patch, stack, seen[start] = [], [start], True
        while stack:
            f = stack.pop()
            patch.append(f)
            a, b, c = faces[f]
            for u, v in ((a, b), (b, c), (c, a)):
                for g in edges[(min(u, v), max(u, v))]:
                    if seen[g]:
                        continue
                    x, y, z = faces[g]
                    # g agrees with f when it runs the shared edge the other way.
                    if (u, v) in ((x, y), (y, z), (z, x)):
                        faces[g] = faces[g][::-1]
                    seen[g] = True
                    stack.append(g)
        patch = np.array(patch)
        flipped_from_given = (faces[patch] != given[patch]).any(axis=1)
        votes = np.where(flipped_from_given, -1.0, 1.0) * sign[patch] * area[patch]
        if votes.sum() < 0:
            faces[patch] = faces[patch][:, ::-1]
        patches.append(patch)
    return _orient_by_nesting(vertices, faces, patches)


def _winding_number(point, vertices, faces):
    """Generalized winding number of a closed triangle patch at `point`
    (the solid angles of Van Oosterom and Strackee, 1983)."""
    a, b, c = (vertices[faces[:, k]] - point for k in range(3))
    la, lb, lc = (np.linalg.norm(x, axis=1) for x in (a, b, c))
    numerator = np.einsum("ij,ij->i", a, np.cross(b, c))
    denominator = la * lb * lc + np.einsum("ij,ij->i", a, b) * lc + np.einsum("ij,ij->i", b, c) * la + np.einsum("ij,ij->i", c, a) * lb
    return np.arctan2(numerator, denominator).sum() / (2 * np.pi)


def _orient_by_nesting(vertices, faces, patches):
    """A shell inside an odd number of others bounds a cavity: its faces
    point into it (negative enclosed volume); gmsh's oriented boundaries
    give a cavity's shell the outer orientation (a hollow box with a ball
    inside came out with its volume counted twice)."""
    if len(patches) < 2:
        return faces
    for i, patch in enumerate(patches):
        point = vertices[faces[patch[0]][0]]
        depth = sum(abs(_winding_number(point, vertices, faces[other])) > 0.5 for j, other in enumerate(patches) if j != i)
        a, b, c = (vertices[faces[patch][:, k]] for k in range(3))
        volume = np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6
        if (volume > 0) != (depth % 2 == 0):
            faces[patch] = faces[patch][:, ::-1]
    return faces


def _components(n, faces):
    parent = np.arange(n)

    def find(a):
        while parent[a] != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a

    for a, b, c in faces:
        ra, rb, rc = find(a), find(b), find(c)
        parent[rb] = ra
        parent[find(rc)] = ra
    return len({find(v) for v in np.unique(faces)})


def check(vertices, faces):
    directed = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    undirected = np.sort(directed, axis=1)
    _, counts = np.unique(undirected, axis=0, return_counts=True)
    _, directed_counts = np.unique(directed, axis=0, return_counts=True)
    a, b, c = (vertices[faces[:, k]] for k in range(3))
    volume = float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6)
    area = float(0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1).sum())
    lo, hi = vertices.min(axis=0), vertices.max(axis=0)
    return {
        "closed": bool((counts == 2).all()),
        "boundary_edges": int((counts == 1).sum()),
        "non_manifold_edges": int((counts > 2).sum()),
        "consistently_oriented": bool((directed_counts == 1).all()),
        "components": _components(len(vertices), faces),
        "volume": volume,
        "area": area,
        "diagonal": float(np.linalg.norm(hi - lo)),
    }
