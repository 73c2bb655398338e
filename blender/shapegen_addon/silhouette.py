"""A target object's silhouette through the scene's camera, as a mask and the camera
matrices a shapegen scene takes."""

import numpy as np

# shapegen's axes to Blender's: (x, y, z) -> (x, -z, y).
TO_BLENDER = np.array([[1, 0, 0, 0], [0, 0, -1, 0], [0, 1, 0, 0], [0, 0, 0, 1]], dtype=np.float64)


def camera_matrices(camera, depsgraph, width, height, placement):
    """World to view and view to clip (OpenGL) of `camera` for a `width` x `height`
    image, the world being where the generator builds (`placement` maps the target
    there), both as 4 x 4 row-major nested lists."""
    view = np.array(camera.matrix_world.inverted(), dtype=np.float64)
    projection = np.array(camera.calc_matrix_camera(depsgraph, x=width, y=height), dtype=np.float64)
    back = np.eye(4)
    back[:3, :3] /= placement.scale
    back[:3, 3] = -placement.offset / placement.scale
    return (view @ TO_BLENDER @ back), projection


def mask(vertices, faces, view, projection, width, height):
    """The pixels whose centres the triangles cover (H x W booleans, row 0 at the top),
    the vertices in the space `view` takes."""
    clip = np.c_[vertices, np.ones(len(vertices))] @ (projection @ view).T
    w = clip[:, 3:4]
    ndc = clip[:, :2] / np.where(np.abs(w) < 1e-12, 1e-12, w)
    px = np.c_[(ndc[:, 0] + 1) * 0.5 * width, (1 - ndc[:, 1]) * 0.5 * height]
    out = np.zeros((height, width), dtype=bool)
    ys, xs = np.mgrid[0:height, 0:width] + 0.5
    for a, b, c in faces:
        if min(w[a, 0], w[b, 0], w[c, 0]) <= 0:
            continue
        pa, pb, pc = px[a], px[b], px[c]
        x0, x1 = int(max(np.floor(min(pa[0], pb[0], pc[0])), 0)), int(min(np.ceil(max(pa[0], pb[0], pc[0])), width))
        y0, y1 = int(max(np.floor(min(pa[1], pb[1], pc[1])), 0)), int(min(np.ceil(max(pa[1], pb[1], pc[1])), height))
        if x0 >= x1 or y0 >= y1:
            continue
        X, Y = xs[y0:y1, x0:x1], ys[y0:y1, x0:x1]
        def edge(p, q):
            return (q[0] - p[0]) * (Y - p[1]) - (q[1] - p[1]) * (X - p[0])
        e0, e1, e2 = edge(pa, pb), edge(pb, pc), edge(pc, pa)
        inside = ((e0 >= 0) & (e1 >= 0) & (e2 >= 0)) | ((e0 <= 0) & (e1 <= 0) & (e2 <= 0))
        out[y0:y1, x0:x1] |= inside
    return out
