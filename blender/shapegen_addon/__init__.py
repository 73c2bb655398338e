"""shapegen for Blender: search a generator's models for one that fills the selected
mesh (or matches its silhouette in the active camera), and keep it as a mesh object
with one material per part.

The search runs in a background thread (the shapegen package releases Python's lock
while it searches), so the interface goes on; the current best model appears in the
scene as it improves, as the object "Shapegen result". Esc or "Stop" ends the search
after its generation. Needs the `shapegen` Python package in Blender's Python (see the
README's "Blender add-on").
"""

bl_info = {
    "name": "shapegen",
    "author": "shapegen",
    "version": (0, 1, 0),
    "blender": (4, 2, 0),
    "location": "View3D > Sidebar > shapegen",
    "description": "Search a procedural generator's models for one that meets a goal",
    "category": "Add Mesh",
}

import bpy

from . import operator, panel

classes = (operator.Settings, operator.SHAPEGEN_OT_search, operator.SHAPEGEN_OT_stop, panel.SHAPEGEN_PT_panel)


def register():
    for cls in classes:
        bpy.utils.register_class(cls)
    bpy.types.Scene.shapegen = bpy.props.PointerProperty(type=operator.Settings)


def unregister():
    del bpy.types.Scene.shapegen
    for cls in reversed(classes):
        bpy.utils.unregister_class(cls)
