# SPDX-License-Identifier: GPL-3.0-or-later
"""Showing faces to the user: Edit Mode with exactly those faces selected."""

import bpy
import numpy as np

from .mesh_arrays import face_of_corner


def poll_mesh_to_select_in(cls, context, obj):
    """Shared poll of the operators that end in Edit Mode with faces selected:
    `obj` is a mesh and Blender is in Object or Edit Mode."""
    if obj is None or obj.type != 'MESH':
        cls.poll_message_set("Make a mesh object active")
        return False
    if context.mode not in {'OBJECT', 'EDIT_MESH'}:
        cls.poll_message_set("Switch to Object Mode or Edit Mode first")
        return False
    return True


def select_faces_in_edit_mode(context, obj, faces):
    """Enter Edit Mode on `obj` alone, face select, with `faces` (ids) selected and
    nothing else; the other selected objects stay selected. Call in Object Mode."""
    mesh = obj.data
    face_selected = np.zeros(len(mesh.polygons), dtype=bool)
    face_selected[np.asarray(faces, dtype=np.int64)] = True
    corner_selected = face_selected[face_of_corner(mesh)]
    # Vertices and edges of the selected faces, so that Edit Mode sees a consistent selection.
    for elements, corner_key in ((mesh.vertices, "vertex_index"), (mesh.edges, "edge_index")):
        corners = np.empty(len(mesh.loops), dtype=np.int32)
        mesh.loops.foreach_get(corner_key, corners)
        selected = np.zeros(len(elements), dtype=bool)
        selected[corners[corner_selected]] = True
        elements.foreach_set("select", selected)
    mesh.polygons.foreach_set("select", face_selected)
    # Edit Mode takes in every selected mesh: enter it with `obj` alone, then give
    # the other objects their selection back.
    others = [other for other in context.selected_objects if other != obj]
    for other in others:
        other.select_set(False)
    obj.select_set(True)
    context.view_layer.objects.active = obj
    context.tool_settings.mesh_select_mode = (False, False, True)
    bpy.ops.object.mode_set(mode='EDIT')
    for other in others:
        other.select_set(True)
