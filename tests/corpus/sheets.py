"""Open surfaces: sheets with a free boundary, and one-sided "scans" of
closed solids (issue 36 item 1). Each family is a function
(rng, make_solid) -> (metadata, vertices, faces)."""
import math

import numpy as np

import mesh_checks
import solids


def _grid(u, v, point):
    """Triangulates the parameter grid u x v mapped by point(U, V) -> (..., 3)."""
    U, V = np.meshgrid(u, v, indexing="ij")
    vertices = point(U, V).reshape(-1, 3)
    nu, nv = len(u), len(v)
    i, j = np.meshgrid(np.arange(nu - 1), np.arange(nv - 1), indexing="ij")
    a = (i * nv + j).reshape(-1)
    b, c, d = a + nv, a + nv + 1, a + 1
    faces = np.concatenate([np.stack([a, b, c], 1), np.stack([a, c, d], 1)])
    return mesh_checks.compact(vertices, faces)


def hemisphere(rng, make_solid):
    """A spherical cap from 60 to 150 degrees of polar angle."""
    R = rng.uniform(20, 40)
    top = math.radians(rng.uniform(60, 150))
    th = np.linspace(0, top, 120)
    ph = np.linspace(0, 2 * math.pi, 241)
    v, f = _grid(th, ph, lambda T, P: R * np.stack([np.sin(T) * np.cos(P), np.sin(T) * np.sin(P), np.cos(T)], -1))
    return {"cap_degrees": math.degrees(top)}, v, f


def bent_plate(rng, make_solid):
    """A rectangular sheet, flat or bent around a cylinder."""
    L, W = rng.uniform(50, 90), rng.uniform(30, 60)
    bend = rng.uniform(0, 1.5)  # radians of arc over the length
    u = np.linspace(0, L, 200)
    w = np.linspace(0, W, 120)
    if bend < 0.2:
        point = lambda U, V: np.stack([U, V, 0 * U], -1)  # noqa: E731
    else:
        R = L / bend
        point = lambda U, V: np.stack([R * np.sin(U / R), V, R * (1 - np.cos(U / R))], -1)  # noqa: E731
    v, f = _grid(u, w, point)
    return {"bend": bend}, v, f


def wave(rng, make_solid):
    """A height field z = a sin(x/p) cos(y/q) over a rectangle."""
    L, W = rng.uniform(50, 90), rng.uniform(40, 70)
    a, p, q = rng.uniform(3, 10), rng.uniform(8, 20), rng.uniform(8, 20)
    v, f = _grid(np.linspace(0, L, 220), np.linspace(0, W, 180),
                 lambda U, V: np.stack([U, V, a * np.sin(U / p) * np.cos(V / q)], -1))
    return {}, v, f


def open_tube(rng, make_solid):
    R, H = rng.uniform(10, 30), rng.uniform(30, 70)
    sweep = rng.uniform(math.pi, 2 * math.pi)
    v, f = _grid(np.linspace(0, sweep, 240), np.linspace(0, H, 120),
                 lambda T, Z: np.stack([R * np.cos(T), R * np.sin(T), Z], -1))
    return {"sweep_degrees": math.degrees(sweep)}, v, f


def tray(rng, make_solid):
    """An open box: the bottom and four walls, of zero thickness."""
    L, W, H = rng.uniform(40, 70), rng.uniform(30, 60), rng.uniform(10, 30)
    parts = []
    n = 60
    planes = [
        lambda U, V: np.stack([U * L, V * W, 0 * U], -1),
        lambda U, V: np.stack([U * L, 0 * U, V * H], -1),
        lambda U, V: np.stack([U * L, 0 * U + W, V * H], -1),
        lambda U, V: np.stack([0 * U, U * W, V * H], -1),
        lambda U, V: np.stack([0 * U + L, U * W, V * H], -1),
    ]
    t = np.linspace(0, 1, n)
    offset = 0
    vs, fs = [], []
    for plane in planes:
        v, f = _grid(t, t, plane)
        vs.append(v)
        fs.append(f + offset)
        offset += len(v)
    v, f = mesh_checks.compact(np.concatenate(vs), np.concatenate(fs))
    return {}, v, f


def scan_of_solid(rng, make_solid):
    """A closed solid seen from one side: the triangles facing away from a
    random view direction are missing, as in a single-station scan."""
    family = list(solids.FAMILIES)[int(rng.integers(0, len(solids.FAMILIES)))]
    meta, v, f = make_solid(family, int(rng.integers(0, 1_000_000)))
    view = rng.normal(size=3)
    view /= np.linalg.norm(view)
    a, b, c = (v[f[:, k]] for k in range(3))
    n = np.cross(b - a, c - a)
    keep = n @ view > 0.1 * np.linalg.norm(n, axis=1)
    v, f = mesh_checks.compact(v, f[keep])
    return {"solid": family, "view": view.tolist()}, v, f


FAMILIES = {
    "hemisphere": hemisphere,
    "bent-plate": bent_plate,
    "wave": wave,
    "open-tube": open_tube,
    "tray": tray,
    "scan": scan_of_solid,
}
