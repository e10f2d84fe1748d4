#!/usr/bin/python3
"""Generates the project's own corpus of reference meshes (issue 36 item 1).

    generate.py OUT_DIR [--per-family N] [--open N] [--only NAME,...]

Closed solids come from gmsh's OpenCASCADE kernel (families in solids.py),
open surfaces from sheets.py; every model is built from seeded random
parameters, so the corpus is the same on every machine. Each model is
written as OUT_DIR/NAME.off (shared vertices, outward-facing triangles)
with OUT_DIR/NAME.json: family, closed or open, the thinnest material in
average spacings of a 50,000-point sampling, and the component count.
Models already present (same generator version) are kept.
"""
import argparse
import hashlib
import json
import math
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

import gmsh  # noqa: E402

import mesh_checks  # noqa: E402
import sheets  # noqa: E402
import solids  # noqa: E402

# Part of every model's metadata: a change of the generator's sources makes
# every model again.
VERSION = hashlib.sha1(b"".join(open(os.path.join(HERE, f), "rb").read()
                                for f in ("generate.py", "solids.py", "sheets.py", "mesh_checks.py"))).hexdigest()[:12]

REFERENCE_POINTS = 50_000


def spacing_for(area, n=REFERENCE_POINTS):
    # Mean distance to the 6 nearest of n uniform samples: about
    # 0.77 sqrt(area / n) (estimated_area_from_spacing, src/pipeline).
    return 0.77 * math.sqrt(area / n)



def _mesh_current_model(s):
    """Triangulates the current gmsh model finely against the spacing s and
    returns (vertices, faces) with outward-facing triangles."""
    gmsh.option.setNumber("Mesh.MeshSizeMax", 3.0 * s)
    gmsh.option.setNumber("Mesh.MeshSizeMin", 0.05 * s)
    # 24 segments per full turn: tessellation creases stay under 15 degrees,
    # below every sharp-edge threshold the evaluation uses.
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 24)
    gmsh.option.setNumber("Mesh.Algorithm", 6)
    gmsh.model.mesh.generate(2)
    tags, coords, _ = gmsh.model.mesh.getNodes()
    index = {int(t): i for i, t in enumerate(tags)}
    vertices = coords.reshape(-1, 3)
    # gmsh's triangles follow each surface's own parametrisation; the
    # volumes' oriented boundaries say which of them face outwards.
    faces, signs = [], []
    for _, volume in gmsh.model.getEntities(3):
        for dim, surface in gmsh.model.getBoundary([(3, volume)], combined=False, oriented=True):
            types, _, nodes = gmsh.model.mesh.getElements(2, abs(surface))
            for kind, conn in zip(types, nodes):
                if kind != 2:
                    continue
                tri = np.array([index[int(t)] for t in conn]).reshape(-1, 3)
                faces.append(tri)
                signs.append(np.full(len(tri), 1.0 if surface > 0 else -1.0))
    vertices, faces, signs = mesh_checks.compact(vertices, np.concatenate(faces), np.concatenate(signs))
    return vertices, mesh_checks.orient(vertices, faces, signs)


def _build_solid(family, seed, s):
    rng = np.random.default_rng(seed)
    gmsh.model.add(f"{family}-{seed}")
    meta = solids.FAMILIES[family](rng, s)
    solids.occ.synchronize()
    area = sum(gmsh.model.occ.getMass(2, t) for _, t in gmsh.model.getEntities(2))
    return meta, area


def make_solid(family, seed):
    gmsh.clear()
    _, area = _build_solid(family, seed, 1.0)
    s = spacing_for(area)
    for _ in range(2):  # the part's area barely depends on its thin dimensions
        gmsh.clear()
        meta, area = _build_solid(family, seed, s)
        s_next = spacing_for(area)
        if abs(s_next - s) < 0.02 * s:
            break
        s = s_next
    vertices, faces = _mesh_current_model(s)
    meta["spacing_50k"] = spacing_for(area)
    return meta, vertices, faces


def write(out, name, meta, vertices, faces):
    report = mesh_checks.check(vertices, faces)
    meta.update(name=name, version=VERSION, faces=int(len(faces)), **report)
    meta.setdefault("components", report["components"])
    if meta["closed"] and report["components"] != meta["components"]:
        raise RuntimeError(f"{name}: {report['components']} components, expected {meta['components']}")
    tmp = os.path.join(out, name + ".off.tmp")
    with open(tmp, "w") as f:
        f.write(f"OFF\n{len(vertices)} {len(faces)} 0\n")
        np.savetxt(f, vertices, fmt="%.9g")
        np.savetxt(f, np.hstack([np.full((len(faces), 1), 3), faces]), fmt="%d")
    os.replace(tmp, os.path.join(out, name + ".off"))
    with open(os.path.join(out, name + ".json"), "w") as f:
        json.dump(meta, f, indent=1)


def up_to_date(out, name):
    try:
        with open(os.path.join(out, name + ".json")) as f:
            return json.load(f).get("version") == VERSION and os.path.exists(os.path.join(out, name + ".off"))
    except (OSError, ValueError):
        return False


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out")
    parser.add_argument("--per-family", type=int, default=10, help="closed solids per family")
    parser.add_argument("--open", type=int, default=6, help="open surfaces per open family")
    parser.add_argument("--only", default="", help="comma-separated model names to make (default: all)")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    only = set(filter(None, args.only.split(",")))
    jobs = [(f"{family}-{i:02d}", "closed", family, 1000 * k + i) for k, family in enumerate(solids.FAMILIES) for i in range(args.per_family)]
    jobs += [(f"{family}-{i:02d}", "open", family, 500_000 + 1000 * k + i) for k, family in enumerate(sheets.FAMILIES) for i in range(args.open)]
    gmsh.initialize(readConfigFiles=False)
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.option.setNumber("General.NumThreads", 1)
    made = 0
    try:
        for name, kind, family, seed in jobs:
            if only and name not in only:
                continue
            if up_to_date(args.out, name):
                continue
            if kind == "closed":
                meta, vertices, faces = make_solid(family, seed)
                meta.update(family=family, kind="closed", seed=seed)
            else:
                meta, vertices, faces = sheets.FAMILIES[family](np.random.default_rng(seed), lambda fam, sd: make_solid(fam, sd))
                meta.update(family=family, kind="open", seed=seed)
            write(args.out, name, meta, vertices, faces)
            made += 1
            print(f"corpus: {name} ({meta['faces']} triangles)", file=sys.stderr, flush=True)
    finally:
        gmsh.finalize()
    print(f"corpus: {made} models made in {args.out}", file=sys.stderr)


if __name__ == "__main__":
    main()
