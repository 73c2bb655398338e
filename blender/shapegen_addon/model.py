"""A shapegen model as a Blender mesh object, one material per part."""

import bpy
import numpy as np

from .convert import to_blender

RESULT = "Shapegen result"


def material(name, colour):
    """The material `shapegen <name>`, made with the part's colour when missing."""
    full = f"shapegen {name}"
    mat = bpy.data.materials.get(full)
    if mat is None:
        mat = bpy.data.materials.new(full)
        mat.diffuse_color = (*(float(c) for c in colour), 1.0)
    return mat


def show(model, name=RESULT, collection=None):
    """Puts `model` (a shapegen.Model) in the scene as the mesh object `name`, replacing
    that object's mesh when it exists; returns the object."""
    vertices = to_blender(model.vertices)
    faces = np.asarray(model.faces, dtype=np.int64)
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(vertices.tolist(), [], faces.tolist())
    used = sorted(set(int(p) for p in np.unique(model.parts)))
    slot = {part: i for i, part in enumerate(used)}
    colours = model.part_colors
    for part in used:
        mesh.materials.append(material(model.part_names[part], colours[part]))
    indices = np.array([slot[int(p)] for p in model.parts], dtype=np.int64)
    if len(indices):
        mesh.polygons.foreach_set("material_index", indices)
    mesh.update()
    obj = bpy.data.objects.get(name)
    if obj is None:
        obj = bpy.data.objects.new(name, mesh)
        (collection or bpy.context.scene.collection).objects.link(obj)
    else:
        old = obj.data
        obj.data = mesh
        if old.users == 0:
            bpy.data.meshes.remove(old)
    return obj
