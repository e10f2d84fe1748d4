"""sharpmesh: point clouds to compact triangle meshes whose sharp edges stay sharp.

Arrays in and out are numpy: points (n, 3), normals (n, 3), faces (m, 3),
polylines as lists of (k, 3) arrays. Options have the names and defaults of
the command-line tool (`sharpmesh COMMAND --help`), with '-' written '_'.
Long functions take `progress=callable(stage, fraction)`; returning False
cancels (sharpmesh.Cancelled). They release the GIL while they compute.

    import sharpmesh as sm
    cloud = sm.read_points("fandisk.xyz")
    result = sm.reconstruct(cloud.points, delta=3.5)
    sm.write_mesh("fandisk.ply", *result.mesh)
    print(len(result.sharp_edges), "feature polylines,", len(result.mesh.faces), "facets")
"""
from ._types import Features, Mesh, OrientedNormals, PointCloud, Reconstruction
from ._core import *  # noqa: F401,F403
from ._core import __version__  # noqa: F401
