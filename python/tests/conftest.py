"""Shared fixtures: the CLI binary and the data cache, as ctest passes them."""
import os
import pathlib

import numpy as np
import pytest

import sharpmesh as sm


@pytest.fixture(scope="session")
def cli():
    path = os.environ.get("SHARPMESH_CLI")
    if not path or not os.access(path, os.X_OK):
        pytest.fail("SHARPMESH_CLI must name the sharpmesh binary (ctest sets it)")
    return path


@pytest.fixture(scope="session")
def data():
    path = pathlib.Path(os.environ.get("SHARPMESH_DATA", ""))
    if not (path / "meshes" / "cube.off").exists():
        pytest.fail(f"SHARPMESH_DATA={path} does not hold the test meshes (make data)")
    return path


def box_mesh(size=(1.0, 1.0, 1.0)):
    """An axis-aligned box of 12 triangles, outward-oriented."""
    sx, sy, sz = size
    v = np.array([[x, y, z] for x in (0, sx) for y in (0, sy) for z in (0, sz)], dtype=float)
    f = np.array([[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
                  [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]])
    return sm.Mesh(v, f)


@pytest.fixture(scope="session")
def cube():
    return box_mesh()


@pytest.fixture(scope="session")
def cube_cloud(cube):
    return sm.sample(cube, count=20000, seed=3)
