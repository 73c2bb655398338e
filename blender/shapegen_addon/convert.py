"""Between Blender's axes (Z up, Y north) and shapegen's (Y up, -Z north).

A Blender point (x, y, z) is shapegen's (x, z, -y); both are right-handed, so the
turn keeps every triangle's winding. A lot's points are written [x, y] with y north,
which is Blender's (x, y) on the ground.
"""

import numpy as np


def to_shapegen(points):
    """Blender positions (N x 3) as shapegen's."""
    p = np.asarray(points, dtype=np.float64)
    return np.stack([p[:, 0], p[:, 2], -p[:, 1]], axis=1)


def to_blender(points):
    """shapegen positions (N x 3) as Blender's."""
    p = np.asarray(points, dtype=np.float64)
    return np.stack([p[:, 0], -p[:, 2], p[:, 1]], axis=1)


def triangles(mesh, matrix):
    """The world-space vertices (N x 3, Blender's axes) and triangles (M x 3) of a
    Blender mesh placed by `matrix`."""
    mesh.calc_loop_triangles()
    n = len(mesh.vertices)
    co = np.empty(n * 3, dtype=np.float64)
    mesh.vertices.foreach_get("co", co)
    co = co.reshape(n, 3)
    m = np.array(matrix, dtype=np.float64)
    world = co @ m[:3, :3].T + m[:3, 3]
    tris = np.empty(len(mesh.loop_triangles) * 3, dtype=np.int64)
    mesh.loop_triangles.foreach_get("vertices", tris)
    return world, tris.reshape(-1, 3)
