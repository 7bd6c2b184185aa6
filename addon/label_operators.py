# SPDX-License-Identifier: GPL-3.0-or-later
"""The label operators: Auto Label, Validate Labels and Label Colours (issue 4).

Labels are read and written as labels.py says (DESIGN.md section 3); every
operator is undoable and reports in one sentence per object.
"""

import bpy
import numpy as np
from bpy.props import BoolProperty

from .face_selection import poll_mesh_to_select_in, select_faces_in_edit_mode
from .label_colours import colour_faces, colours_shown, hide_colours
from .labels import read_labels, write_face_maps, write_label_attribute
from .mesh_arrays import read_mesh_arrays
from .polycube_native import auto_labels
from .report import failure
from .settings import LabelSettings
from .validation import details, offending_faces, summary, validate

# Violations listed one by one in the info log; the rest are counted.
_DETAILS_SHOWN = 50


def _selected_meshes(context):
    """The selected mesh objects by name, each mesh once."""
    objects, meshes = [], set()
    for obj in sorted(context.selected_objects, key=lambda o: o.name):
        if obj.type == 'MESH' and obj.data.name not in meshes:
            objects.append(obj)
            meshes.add(obj.data.name)
    return objects


def _poll_object_mode_meshes(cls, context):
    if context.mode != 'OBJECT':
        cls.poll_message_set("Switch to Object Mode first")
        return False
    if not any(obj.type == 'MESH' for obj in context.selected_objects):
        cls.poll_message_set("Select one or more mesh objects")
        return False
    return True


class OBJECT_OT_polycube_auto_label(LabelSettings, bpy.types.Operator):
    """Label every face of the selected meshes automatically: the polycube_label attribute and, \
in Blender 3.x, face maps +X ... -Z"""
    bl_idname = "object.polycube_auto_label"
    bl_label = "Auto Label"
    bl_options = {'REGISTER', 'UNDO'}

    @classmethod
    def poll(cls, context):
        return _poll_object_mode_meshes(cls, context)

    def draw(self, context):
        self.layout.use_property_split = True
        self.layout.prop(self, "compactness")

    def execute(self, context):
        labelled = 0
        for obj in _selected_meshes(context):
            try:
                mesh = read_mesh_arrays(obj.data)
                labels = np.asarray(auto_labels(mesh.vertices, mesh.face_indices, mesh.face_sizes,
                                                compactness=self.compactness), dtype=np.int32)
            except ValueError as error:
                # An error, not a warning: scripts (headless --labels auto) see it as RuntimeError.
                self.report({'ERROR'}, failure(obj.name, "labelled", error))
                continue
            write_label_attribute(obj.data, labels)
            in_user_maps = write_face_maps(obj, labels) if hasattr(obj, "face_maps") else 0
            if colours_shown(obj.data):
                colour_faces(obj.data, labels)
            result = validate(obj, mesh, labels)
            for problem in result["orientation"]:
                self.report({'WARNING'}, f"'{obj.name}': {problem}.")
            self.report({'INFO'}, summary(obj.name, result))
            if in_user_maps:
                self.report({'INFO'}, f"'{obj.name}': {in_user_maps} faces stay in your own face maps; "
                                      f"the polycube_label attribute holds their labels.")
            labelled += 1
        return {'FINISHED'} if labelled else {'CANCELLED'}


class OBJECT_OT_polycube_validate_labels(bpy.types.Operator):
    """Check the active mesh's labels against the polycube conditions; select the faces \
of every violation in Edit Mode"""
    bl_idname = "object.polycube_validate_labels"
    bl_label = "Validate Labels"
    bl_options = {'REGISTER', 'UNDO'}

    @classmethod
    def poll(cls, context):
        return poll_mesh_to_select_in(cls, context, context.active_object)

    def execute(self, context):
        obj = context.active_object
        was_editing = context.mode == 'EDIT_MESH'
        if was_editing:
            bpy.ops.object.mode_set(mode='OBJECT')  # the mesh data catches up with the edits
        try:
            mesh = read_mesh_arrays(obj.data)
            result = validate(obj, mesh, read_labels(obj).values)
        except ValueError as error:
            if was_editing:
                bpy.ops.object.mode_set(mode='EDIT')
            self.report({'ERROR'}, failure(obj.name, "validated", error))
            return {'CANCELLED'}
        for problem in result["orientation"]:
            self.report({'WARNING'}, f"'{obj.name}': {problem}.")
        if result["realisable"]:
            if was_editing:
                bpy.ops.object.mode_set(mode='EDIT')
            self.report({'WARNING'} if result["orientation"] else {'INFO'}, summary(obj.name, result))
            return {'FINISHED'}
        lines = details(result)
        for line in lines[:_DETAILS_SHOWN]:
            self.report({'INFO'}, f"'{obj.name}': {line}.")
        if len(lines) > _DETAILS_SHOWN:
            self.report({'INFO'}, f"'{obj.name}': {len(lines) - _DETAILS_SHOWN} more violations.")
        faces = offending_faces(result)
        select_faces_in_edit_mode(context, obj, faces)
        # Last, so that the status bar shows it.
        self.report({'WARNING'}, summary(obj.name, result, len(faces)))
        return {'FINISHED'}


class OBJECT_OT_polycube_label_colours(bpy.types.Operator):
    """Show the selected meshes' labels as face colours (the polycube_label_colour attribute), \
or hide them again"""
    bl_idname = "object.polycube_label_colours"
    bl_label = "Label Colours"
    bl_options = {'REGISTER', 'UNDO'}

    show: BoolProperty(
        name="Show", description="Show (or refresh) the label colours; off: remove them", default=True)

    @classmethod
    def poll(cls, context):
        return _poll_object_mode_meshes(cls, context)

    def execute(self, context):
        changed = 0
        for obj in _selected_meshes(context):
            if not self.show:
                hide_colours(obj.data)
                changed += 1
                continue
            try:
                colour_faces(obj.data, read_labels(obj).values)
            except ValueError as error:
                self.report({'WARNING'}, failure(obj.name, "coloured", error))
                continue
            changed += 1
        if self.show and changed:
            _show_attribute_colours(context)
        return {'FINISHED'} if changed else {'CANCELLED'}


def _show_attribute_colours(context):
    """Solid shading in this window's 3D views shows the active colour attribute."""
    for area in context.screen.areas if context.screen is not None else ():
        if area.type == 'VIEW_3D':
            area.spaces.active.shading.color_type = 'VERTEX'
