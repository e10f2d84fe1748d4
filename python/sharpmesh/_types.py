"""Result types of the sharpmesh module: named tuples of numpy arrays."""
from typing import List, NamedTuple, Optional

import numpy as np


class PointCloud(NamedTuple):
    """Points (n, 3) float64, with optional normals (n, 3) and colours (n, 3) uint8."""
    points: np.ndarray
    normals: Optional[np.ndarray] = None
    colors: Optional[np.ndarray] = None


class Mesh(NamedTuple):
    """A triangle mesh: vertices (n, 3) float64 and faces (m, 3) uint32."""
    vertices: np.ndarray
    faces: np.ndarray


class Features(NamedTuple):
    """Sharp features of a point cloud (thesis 7.2).

    polylines: list of (k, 3) arrays running between junctions or darts
    (closed loops repeat their first point); junctions (j, 3) with their
    types ('dart', 'cusp' or 'corner') and degrees; per input point its class
    (0 smooth, 1 edge, 2 corner), edge direction, unoriented CVCM normal and
    eigenvalue ratios; report: radii, counts and stage timings.
    """
    polylines: List[np.ndarray]
    junctions: np.ndarray
    junction_types: List[str]
    junction_degrees: np.ndarray
    point_classes: np.ndarray
    directions: np.ndarray
    normals: np.ndarray
    ratio01: np.ndarray
    ratio12: np.ndarray
    report: dict


class OrientedNormals(NamedTuple):
    """The result of reconstruct_normals(): the cloud without duplicated
    points, with the oriented unit normals reconstruct() starts Poisson
    from, and a report of the normals stage."""
    cloud: PointCloud
    report: dict


class Reconstruction(NamedTuple):
    """The result of reconstruct(): the mesh, the mesh edges that represent
    the protected features (polylines), the features extracted (None when
    given or disabled) and a report like the CLI's --report."""
    mesh: Mesh
    sharp_edges: List[np.ndarray]
    features: Optional[Features]
    report: dict
