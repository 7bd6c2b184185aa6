# SPDX-License-Identifier: GPL-3.0-or-later
"""Subdivide before deforming: a refined copy, the object `<name> polycube`.

The user's object keeps its vertex count and its shape keys; the copy gets the
refined mesh (OpenSubdiv, native `refine`), each child face keeping its parent's
label (in the `polycube_label` attribute), material and smooth flag. The copy
is placed beside the object, along world X, so both stay visible. Running again
replaces the copy's mesh (not its place) instead of making another copy.
"""

import bpy
import numpy as np
from mathutils import Matrix, Vector

from .labels import Labels, write_label_attribute
from .mesh_arrays import new_mesh, read_mesh_arrays
from .polycube_native import refine

COPY_SUFFIX = " polycube"
SOURCE_PROPERTY = "polycube_subdivided_from"


def source_object(obj):
    """The object a subdivided copy was made from; the object itself otherwise."""
    source = bpy.data.objects.get(obj.get(SOURCE_PROPERTY, ""))
    return source if source is not None and source.type == 'MESH' and source != obj else obj


def check_copy_name(obj):
    """ValueError if the name of obj's copy is taken by an object that is not its copy."""
    name = obj.name + COPY_SUFFIX
    copy = bpy.data.objects.get(name)
    if copy is not None and copy.get(SOURCE_PROPERTY) != obj.name:
        raise ValueError(f"an object named '{name}' exists already and is not its subdivided copy")


def refine_mesh(mesh, labels, levels, scheme):
    """The native refinement of MeshArrays `mesh` carrying `labels` (Labels). Touches no
    Blender data: may run on a worker thread."""
    return refine(mesh.vertices, mesh.face_indices, mesh.face_sizes, labels.values,
                  levels=levels, scheme=scheme.lower())


def subdivided_copy(obj, refined, labels, levels, scheme):
    """(copy, its MeshArrays, its Labels) from refine_mesh's result for the object's mesh
    and Labels; ValueError, with nothing created, if it cannot be made."""
    check_copy_name(obj)
    name = obj.name + COPY_SUFFIX
    copy = bpy.data.objects.get(name)
    parents = np.asarray(refined["parent_face"])
    data = new_mesh(name, refined["vertices"], refined["face_indices"], refined["face_sizes"])
    try:
        if len(data.polygons) != len(parents):
            raise ValueError("its subdivision holds faces Blender cannot keep (degenerate faces)")
        arrays = read_mesh_arrays(data)
    except ValueError:
        bpy.data.meshes.remove(data)
        raise
    carry_face_flags(obj.data, data, parents)
    values = np.asarray(refined["labels"], dtype=np.int32)
    write_label_attribute(data, values)

    if copy is None:
        copy = bpy.data.objects.new(name, data)
        for collection in obj.users_collection:
            collection.objects.link(copy)
        copy[SOURCE_PROPERTY] = obj.name
        copy.matrix_world = Matrix.Translation((_beside(obj), 0.0, 0.0)) @ obj.matrix_world
    else:
        # The copy stays where it is (the user may have moved it).
        old = copy.data
        copy.data = data
        if old.users == 0:
            bpy.data.meshes.remove(old)
    how = f"{scheme.lower()} x{levels}"
    return copy, arrays, Labels(values, f"{labels.source}, subdivided ({how})")


def _beside(obj):
    """How far along world X a copy of `obj` goes so that the two do not overlap:
    its world width and a quarter of it as a gap."""
    corners = np.array([obj.matrix_world @ Vector(corner) for corner in obj.bound_box])
    width = float(np.ptp(corners[:, 0])) if len(corners) else 0.0
    return 1.25 * width if width > 0 else 1.0


def remove_copy(copy):
    """Take a copy made for a run that failed away again."""
    data = copy.data
    bpy.data.objects.remove(copy)
    if data.users == 0:
        bpy.data.meshes.remove(data)


def carry_face_flags(source, target, parents):
    for material in source.materials:
        target.materials.append(material)
    for name, dtype in (("material_index", np.int32), ("use_smooth", bool)):
        values = np.empty(len(source.polygons), dtype=dtype)
        source.polygons.foreach_get(name, values)
        target.polygons.foreach_set(name, values[parents])
