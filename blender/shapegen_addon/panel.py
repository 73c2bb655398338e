"""The sidebar panel."""

import bpy

from . import operator


class SHAPEGEN_PT_panel(bpy.types.Panel):
    bl_label = "shapegen"
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "shapegen"

    def draw(self, context):
        s = context.scene.shapegen
        col = self.layout.column()
        col.prop(s, "generator")
        col.prop(s, "target")
        col.prop(s, "method")
        col.prop(s, "seconds")
        col.prop(s, "seed")
        col.prop(s, "resolution")
        col.prop(s, "fit")
        col.prop(s, "lot")
        if operator.current is not None and operator.current.running():
            col.label(text=f"generation {operator.current.generation}, best {operator.current.best_fitness or 0:.4f}")
            col.operator("shapegen.stop")
        else:
            col.operator("shapegen.search")
