"""The settings, and the operators that start and stop a search."""

import time

import bpy
import numpy as np

from . import model, silhouette
from .convert import to_shapegen, triangles
from .place import Placement
from .search import Background

# The search under way, if any (one at a time).
current = None


try:
    import shapegen
except ImportError as err:
    raise ImportError(
        "the shapegen add-on needs the `shapegen` Python package in Blender's Python; "
        "install its wheel with Blender's python -m pip (README, \"The Blender add-on\")"
    ) from err

# A fixed list: Blender (4.2 as a Python module) crashes at exit after an enum whose
# items come from a function.
GENERATORS = [(g, g, f"the {g} generator") for g in shapegen.generators()]

METHODS = [(m, m, f"search with {m}") for m in ("hybrid", "ga", "smc", "sosmc", "rjmcmc", "random")]


class Settings(bpy.types.PropertyGroup):
    generator: bpy.props.EnumProperty(name="Generator", items=GENERATORS)
    target: bpy.props.EnumProperty(
        name="Target",
        items=[
            ("VOLUME", "Volume", "fill the selected mesh"),
            ("SILHOUETTE", "Silhouette", "match the selected mesh as the active camera sees it"),
        ],
    )
    method: bpy.props.EnumProperty(name="Method", items=METHODS)
    seconds: bpy.props.FloatProperty(name="Seconds", default=10.0, min=0.1)
    seed: bpy.props.IntProperty(name="Seed", default=1, min=0)
    resolution: bpy.props.IntProperty(name="Resolution", default=48, min=4, max=256,
                                      description="voxels along the target's longest side; pixels of the silhouette's height")
    fit: bpy.props.BoolProperty(name="Fit to generator", default=True,
                                description="search with the target moved and scaled onto the generator's typical model, and bring the result back")
    lot: bpy.props.PointerProperty(name="Lot", type=bpy.types.Object,
                                   description="buildings on a lot: a mesh (its selected face, or its first) or a curve (its first spline)")


def lot_points(obj):
    """The lot an object gives, as [x, y] points on the ground (Blender's x and y)."""
    m = np.array(obj.matrix_world, dtype=np.float64)
    if obj.type == "MESH":
        mesh = obj.data
        faces = [p for p in mesh.polygons if p.select] or list(mesh.polygons)
        if not faces:
            raise ValueError(f"the lot `{obj.name}` has no face")
        co = [mesh.vertices[i].co for i in faces[0].vertices]
    elif obj.type == "CURVE" and obj.data.splines:
        spline = obj.data.splines[0]
        co = [p.co.xyz for p in (spline.bezier_points or spline.points)]
    else:
        raise ValueError(f"the lot `{obj.name}` must be a mesh with a face or a curve")
    pts = np.array([list(c) for c in co], dtype=np.float64)
    world = pts @ m[:3, :3].T + m[:3, 3]
    return world[:, :2]


def make_scene(context, settings):
    """The shapegen scene of the panel's settings and the selected object, and the
    placement that maps the target to where the generator builds."""
    obj = context.active_object
    if obj is None or obj.type != "MESH":
        raise ValueError("select the target: a mesh object")
    generator = shapegen.generator(settings.generator)
    depsgraph = context.evaluated_depsgraph_get()
    mesh = obj.evaluated_get(depsgraph).to_mesh()
    try:
        vertices, faces = triangles(mesh, obj.matrix_world)
    finally:
        obj.evaluated_get(depsgraph).to_mesh_clear()
    if len(faces) == 0:
        raise ValueError(f"the target `{obj.name}` has no faces")
    vertices = to_shapegen(vertices)
    placement = Placement(vertices, generator, fit=settings.fit)
    extra = {"optimizer": {"method": settings.method}}
    if settings.lot is not None:
        lot = lot_points(settings.lot)
        ground = to_shapegen(np.c_[lot, np.zeros(len(lot))])
        placed = placement.forward(ground)
        extra["lot"] = {"points": np.c_[placed[:, 0], -placed[:, 2]].tolist()}
    if settings.target == "VOLUME":
        scene = shapegen.volume_scene(
            generator.name, placement.forward(vertices), faces,
            resolution=settings.resolution, settings=extra,
        )
    else:
        camera = context.scene.camera
        if camera is None:
            raise ValueError("a silhouette target is seen through the scene's camera: add one")
        render = context.scene.render
        height = settings.resolution * 2
        width = max(1, round(height * render.resolution_x / render.resolution_y))
        view, projection = silhouette.camera_matrices(camera, depsgraph, width, height, placement)
        image = silhouette.mask(placement.forward(vertices), faces, view, projection, width, height)
        if not image.any():
            raise ValueError(f"the camera does not see `{obj.name}`")
        camera_table = {"view": view.tolist(), "projection": projection.tolist(),
                        "width": width, "height": height}
        scene = shapegen.silhouette_scene(generator.name, image, camera_table, settings=extra)
    return scene, placement


class Shown:
    """Puts each new best model in the Blender scene, brought back from where the
    generator builds."""

    def __init__(self, scene, placement):
        self.scene, self.placement = scene, placement

    def __call__(self, genome):
        m = self.scene.model(genome)
        return model.show(_Placed(m, self.placement))


class _Placed:
    """A model with its vertices moved back by a placement."""

    def __init__(self, m, placement):
        self.vertices = placement.back(m.vertices)
        self.faces, self.parts = m.faces, m.parts
        self.part_names, self.part_colors = m.part_names, m.part_colors


class SHAPEGEN_OT_search(bpy.types.Operator):
    """Search the generator's models for one that meets the target"""

    bl_idname = "shapegen.search"
    bl_label = "Search"
    bl_options = {"REGISTER", "UNDO"}

    wait: bpy.props.BoolProperty(
        name="Wait", default=False,
        description="run to the end before returning (scripts, and Blender without its interface)",
    )

    def execute(self, context):
        global current
        settings = context.scene.shapegen
        try:
            scene, placement = make_scene(context, settings)
        except Exception as err:
            self.report({"ERROR"}, str(err))
            return {"CANCELLED"}
        self.show = Shown(scene, placement)
        current = Background(
            scene, seed=settings.seed, seconds=settings.seconds, generations=10**9
        ).start()
        if self.wait or bpy.app.background:
            while current.running():
                self._update()
                time.sleep(0.05)
            return self._finish()
        self.timer = context.window_manager.event_timer_add(0.25, window=context.window)
        context.window_manager.modal_handler_add(self)
        return {"RUNNING_MODAL"}

    def _update(self):
        best = current.latest()
        if best is not None:
            self.show(best)

    def _finish(self):
        self._update()
        if current.error is not None:
            self.report({"ERROR"}, str(current.error))
            return {"CANCELLED"}
        r = current.result
        self.report({"INFO"}, f"best fitness {r.best_fitness:.4f} after {r.generations} generations ({r.stopped})")
        return {"FINISHED"}

    def modal(self, context, event):
        if event.type == "ESC":
            current.stop()
        if event.type == "TIMER":
            self._update()
            for area in context.screen.areas:
                area.tag_redraw()
            if not current.running():
                context.window_manager.event_timer_remove(self.timer)
                return self._finish()
        return {"PASS_THROUGH"}


class SHAPEGEN_OT_stop(bpy.types.Operator):
    """Stop the search after its generation; the best model so far stays"""

    bl_idname = "shapegen.stop"
    bl_label = "Stop"

    def execute(self, context):
        if current is not None:
            current.stop()
        return {"FINISHED"}
