"""Renders the picture of the add-on in the README (docs/blender-addon.png): a cube as
the target, the spaceship the add-on found for it beside it, in Blender (Cycles on the
CPU, headless through the `bpy` module).

    python blender/render_example.py docs/blender-addon.png
"""

import math
import pathlib
import sys

import bpy

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import shapegen_addon  # noqa: E402


def main(out):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    shapegen_addon.register()
    scene = bpy.context.scene
    bpy.ops.mesh.primitive_cube_add(size=2.0, location=(0.0, 0.0, 1.0))
    target = bpy.context.active_object
    target.scale = (1.0, 2.5, 0.6)
    s = scene.shapegen
    s.generator, s.target, s.method, s.seconds, s.resolution, s.seed = "spaceship", "VOLUME", "hybrid", 8.0, 40, 1
    bpy.ops.shapegen.search(wait=True)
    result = bpy.data.objects["Shapegen result"]
    result.location.x += 3.5
    glass = bpy.data.materials.new("target")
    glass.diffuse_color = (0.8, 0.3, 0.2, 1.0)
    target.data.materials.append(glass)
    bpy.ops.object.camera_add(location=(9.0, -9.0, 7.0), rotation=(math.radians(60), 0.0, math.radians(45)))
    scene.camera = bpy.context.active_object
    bpy.ops.object.light_add(type="SUN", rotation=(math.radians(40), math.radians(20), math.radians(30)))
    bpy.context.active_object.data.energy = 3.0
    world = bpy.data.worlds.new("world")
    world.color = (0.8, 0.8, 0.85)
    scene.world = world
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = 24
    scene.render.resolution_x, scene.render.resolution_y = 640, 400
    scene.render.filepath = str(pathlib.Path(out).resolve())
    bpy.ops.render.render(write_still=True)


if __name__ == "__main__":
    main(sys.argv[1])
